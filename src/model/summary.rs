//! A topology summary for `tetrafoil check`: counts and per-region shells.

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

impl Model {
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
