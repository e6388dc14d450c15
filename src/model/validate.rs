//! The validation pass: everything about a model's topology that would make meshing fail or
//! give a bad mesh, reported by entity id and name.

use super::{EntityRef, Model};
use std::collections::HashMap;

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// Meshing cannot go on.
    Error,
    /// Suspicious but meshable.
    Warning,
}

/// One finding.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub entity: EntityRef,
    pub message: String,
}

impl std::fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let level = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        write!(f, "{level}: {}: {}", self.entity, self.message)
    }
}

impl Model {
    /// Open loops, edges used by one face of a closed shell (or by more than two), and
    /// unreferenced vertices, edges and faces.
    pub fn validate(&self) -> Vec<Diagnostic> {
        let mut out = Vec::new();
        let error = |entity, message: String| Diagnostic {
            severity: Severity::Error,
            entity,
            message,
        };
        // Loops must close: each use ends where the next starts.
        for (f, face) in self.faces.iter().enumerate() {
            for (l, lp) in face.loops.iter().enumerate() {
                let n = lp.uses.len();
                for i in 0..n {
                    let (_, end) = self.use_vertices(&lp.uses[i]);
                    let (next_start, _) = self.use_vertices(&lp.uses[(i + 1) % n]);
                    if end != next_start {
                        out.push(error(
                            self.face_ref(f),
                            format!(
                                "loop {l} is open: {} ends at {} but the next use, {}, starts at {}",
                                self.edge_ref(lp.uses[i].edge),
                                self.vertex_ref(end),
                                self.edge_ref(lp.uses[(i + 1) % n].edge),
                                self.vertex_ref(next_start)
                            ),
                        ));
                    }
                }
                if n == 0 && lp.vertex.is_none() {
                    out.push(error(self.face_ref(f), format!("loop {l} is empty")));
                }
            }
        }
        // Every edge of a closed shell is used exactly twice (a seam twice by one face).
        for (r, region) in self.regions.iter().enumerate() {
            for (s, shell) in region.shells.iter().enumerate() {
                let mut count: HashMap<usize, Vec<usize>> = HashMap::new();
                for fu in &shell.faces {
                    for lp in &self.faces[fu.face].loops {
                        for u in &lp.uses {
                            count.entry(u.edge).or_default().push(fu.face);
                        }
                    }
                }
                let mut edges: Vec<_> = count.into_iter().collect();
                edges.sort_by_key(|(e, _)| *e);
                for (e, faces) in edges {
                    if self.edges[e].is_degenerate() {
                        continue;
                    }
                    let names: Vec<String> = faces
                        .iter()
                        .map(|&f| self.face_ref(f).to_string())
                        .collect();
                    if faces.len() == 1 {
                        out.push(error(
                            self.edge_ref(e),
                            format!(
                                "used by only one face ({}) of closed shell {s} of {}: the shell is open",
                                names[0],
                                self.region_ref(r)
                            ),
                        ));
                    } else if faces.len() > 2 {
                        out.push(error(
                            self.edge_ref(e),
                            format!(
                                "used {} times in shell {s} of {} ({}): non-manifold",
                                faces.len(),
                                self.region_ref(r),
                                names.join(", ")
                            ),
                        ));
                    }
                }
            }
            if region.shells.is_empty() {
                out.push(error(self.region_ref(r), "region has no faces".into()));
            }
        }
        self.unreferenced(&mut out);
        out
    }

    /// The error-level findings of [`Model::validate`], as messages naming their entities.
    pub fn validation_errors(&self) -> Vec<String> {
        self.validate()
            .into_iter()
            .filter(|d| d.severity == Severity::Error)
            .map(|d| d.to_string())
            .collect()
    }

    fn unreferenced(&self, out: &mut Vec<Diagnostic>) {
        let mut vertex_used = vec![false; self.vertices.len()];
        let mut edge_used = vec![false; self.edges.len()];
        let mut face_used = vec![false; self.faces.len()];
        for e in &self.edges {
            vertex_used[e.start] = true;
            vertex_used[e.end] = true;
        }
        for face in &self.faces {
            for lp in &face.loops {
                if let Some(v) = lp.vertex {
                    vertex_used[v] = true;
                }
                for u in &lp.uses {
                    edge_used[u.edge] = true;
                }
            }
        }
        for region in &self.regions {
            for fu in region.shells.iter().flat_map(|s| &s.faces) {
                face_used[fu.face] = true;
            }
            for &f in &region.embedded_faces {
                face_used[f] = true;
            }
            for &e in &region.embedded_edges {
                edge_used[e] = true;
            }
        }
        let warn = |entity, what: &str| Diagnostic {
            severity: Severity::Warning,
            entity,
            message: format!("not used by any {what}"),
        };
        for (v, used) in vertex_used.iter().enumerate() {
            if !used {
                out.push(warn(self.vertex_ref(v), "edge or loop"));
            }
        }
        for (e, used) in edge_used.iter().enumerate() {
            if !used {
                out.push(warn(self.edge_ref(e), "face loop or region"));
            }
        }
        for (f, used) in face_used.iter().enumerate() {
            if !used {
                out.push(warn(self.face_ref(f), "region"));
            }
        }
    }
}
