//! A topology summary for `tetrafoil check`: counts, per-region shells, and (`--faces`) each
//! face's id, marker and extent, to pick refinement sources by id in a model whose faces
//! have no names.

use super::Model;
use serde::Serialize;

#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Summary {
    pub regions: usize,
    pub shells: usize,
    pub faces: usize,
    pub edges: usize,
    pub vertices: usize,
    pub degenerate_edges: usize,
    pub embedded_faces: usize,
    pub embedded_edges: usize,
    pub region_details: Vec<RegionSummary>,
}

#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct RegionSummary {
    pub name: String,
    /// Faces per shell, outer shell first.
    pub shell_faces: Vec<usize>,
    /// Enclosed volume per shell (positive), outer first.
    pub shell_volumes: Vec<f64>,
}

/// One face: its id (what a case file's `faces = [...]` takes), marker name, and the box of
/// its boundary.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct FaceSummary {
    pub id: usize,
    pub name: String,
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Model {
    /// Every face's [`FaceSummary`]; the box is that of points along its edges (8 per edge).
    pub fn face_summaries(&self) -> Vec<FaceSummary> {
        (0..self.faces.len())
            .map(|f| {
                let mut min = [f64::INFINITY; 3];
                let mut max = [f64::NEG_INFINITY; 3];
                let uses = self.faces[f].loops.iter().flat_map(|l| &l.uses);
                for u in uses {
                    let (t0, t1) = self.edges[u.edge].range;
                    for k in 0..=8 {
                        let p = self.edge_point(u.edge, t0 + (t1 - t0) * k as f64 / 8.0);
                        for a in 0..3 {
                            min[a] = min[a].min(p[a]);
                            max[a] = max[a].max(p[a]);
                        }
                    }
                }
                FaceSummary {
                    id: f,
                    name: self.face_marker(f),
                    min,
                    max,
                }
            })
            .collect()
    }

    pub fn summary(&self) -> Summary {
        Summary {
            regions: self.regions.len(),
            shells: self.regions.iter().map(|r| r.shells.len()).sum(),
            faces: self.faces.len(),
            edges: self.edges.len(),
            vertices: self.vertices.len(),
            degenerate_edges: self.edges.iter().filter(|e| e.is_degenerate()).count(),
            embedded_faces: self.regions.iter().map(|r| r.embedded_faces.len()).sum(),
            embedded_edges: self.regions.iter().map(|r| r.embedded_edges.len()).sum(),
            region_details: self
                .regions
                .iter()
                .enumerate()
                .map(|(i, r)| RegionSummary {
                    name: r.name.clone().unwrap_or_else(|| format!("region_{i}")),
                    shell_faces: r.shells.iter().map(|s| s.faces.len()).collect(),
                    shell_volumes: r.shells.iter().map(|s| s.volume).collect(),
                })
                .collect(),
        }
    }
}
