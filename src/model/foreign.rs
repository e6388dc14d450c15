//! A [`Model`] from a foreign kernel (OpenCASCADE, a plugin): the kernel's topology as plain
//! data ([`ForeignTopology`], ids are the kernel's 0-based ids) and its geometry behind the
//! root traits ([`ForeignSource`]), then validation and automatic orientation exactly as for a
//! case file.
//!
//! - vertices and edges one to one; degenerate edges (poles) get `curve: None`;
//! - faces with their names from the file, loops of edge uses each carrying the kernel's
//!   pcurve (a seam's two uses carry its two pcurves); a use without one gets the edge's curve
//!   projected onto the surface, as native faces do;
//! - one region per solid, named after the solid, with its shells; faces shared by touching
//!   solids exist once and appear in both regions' shells.
//!
//! Orientation is not taken from the file: [`Model::orient`] computes it.

use super::{
    orient::OrientError, Edge, EdgeUse, EntityRef, Face, FaceUse, Loop, Model, Region, Shell,
    Vertex,
};
use crate::geometry::{Curve, Curve2d, FaultLog, Surface, Xyz};
use glam::DVec3;
use std::sync::Arc;

/// A vertex as the kernel gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct ForeignVertex {
    pub point: [f64; 3],
    pub tolerance: f64,
}

/// An edge from `v0` (at `t_range[0]`) to `v1`; a degenerate one (a pole) has no curve.
#[derive(Clone, Debug, PartialEq)]
pub struct ForeignEdge {
    pub v0: usize,
    pub v1: usize,
    pub degenerate: bool,
    pub t_range: [f64; 2],
    pub tolerance: f64,
}

/// One traversal of an edge by a face loop; `reversed` runs it from `t_range[1]` to `[0]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ForeignUse {
    pub edge: usize,
    pub reversed: bool,
}

/// A face: its name and loops of edge uses, each in chain order.
#[derive(Clone, Debug, PartialEq)]
pub struct ForeignFace {
    pub name: Option<String>,
    pub loops: Vec<Vec<ForeignUse>>,
}

/// A solid: its shells, as indices into [`ForeignTopology::shells`].
#[derive(Clone, Debug, PartialEq)]
pub struct ForeignSolid {
    pub name: Option<String>,
    pub shells: Vec<usize>,
}

/// A kernel's model as plain data. Shells are lists of faces; a shell or face in no solid is
/// what a surface set (to sew) or construction geometry beside a part looks like.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ForeignTopology {
    pub vertices: Vec<ForeignVertex>,
    pub edges: Vec<ForeignEdge>,
    pub faces: Vec<ForeignFace>,
    pub shells: Vec<Vec<usize>>,
    pub solids: Vec<ForeignSolid>,
}

impl ForeignTopology {
    /// How many times the faces `faces` use each edge (a seam twice).
    fn edge_uses(&self, faces: impl IntoIterator<Item = usize>) -> Vec<usize> {
        let mut n = vec![0; self.edges.len()];
        for f in faces {
            for u in self.faces[f].loops.iter().flatten() {
                n[u.edge] += 1;
            }
        }
        n
    }

    /// Edges that are not degenerate and that one face use alone bounds: an open boundary.
    pub fn free_edges(&self) -> Vec<usize> {
        let n = self.edge_uses(0..self.faces.len());
        (0..n.len())
            .filter(|&e| n[e] == 1 && !self.edges[e].degenerate)
            .collect()
    }

    /// Whether every non-degenerate edge of shell `s` is used exactly twice by its faces.
    pub fn shell_closed(&self, s: usize) -> bool {
        let n = self.edge_uses(self.shells[s].iter().copied());
        (0..n.len()).all(|e| n[e] == 0 || n[e] == 2 || self.edges[e].degenerate)
    }

    /// Faces in no solid's shells, in id order.
    pub fn faces_outside_solids(&self) -> Vec<usize> {
        let mut inside = vec![false; self.faces.len()];
        for s in &self.solids {
            for &sh in &s.shells {
                for &f in &self.shells[sh] {
                    inside[f] = true;
                }
            }
        }
        (0..self.faces.len()).filter(|&f| !inside[f]).collect()
    }

    /// The largest edge tolerance the file gives.
    pub fn max_edge_tolerance(&self) -> f64 {
        self.edges.iter().map(|e| e.tolerance).fold(0.0, f64::max)
    }

    /// "face 3 'name'" or "face 3".
    pub fn face_label(&self, f: usize) -> String {
        match &self.faces[f].name {
            Some(n) => format!("face {f} '{n}'"),
            None => format!("face {f}"),
        }
    }

    /// Names of the faces and edges that keep the model from being a set of solids: every
    /// free edge with the faces using it (at most `limit` of them).
    pub fn open_boundary_diagnosis(&self, limit: usize) -> String {
        let mut users: Vec<Vec<usize>> = vec![Vec::new(); self.edges.len()];
        for (f, face) in self.faces.iter().enumerate() {
            for u in face.loops.iter().flatten() {
                users[u.edge].push(f);
            }
        }
        let free = self.free_edges();
        let at = |v: usize| Xyz(DVec3::from_array(self.vertices[v].point));
        let mut lines: Vec<String> = (free.iter().take(limit))
            .map(|&e| {
                let faces: Vec<String> = users[e].iter().map(|&f| self.face_label(f)).collect();
                let edge = &self.edges[e];
                format!(
                    "edge {e} (from {} to {}) is used only by {}",
                    at(edge.v0),
                    at(edge.v1),
                    faces.join(", ")
                )
            })
            .collect();
        if free.len() > limit {
            lines.push(format!("... and {} more free edges", free.len() - limit));
        }
        let open = (0..self.shells.len())
            .filter(|&s| !self.shell_closed(s))
            .count();
        format!(
            "{} faces, {} shells ({open} open), {} free edges{}{}",
            self.faces.len(),
            self.shells.len(),
            free.len(),
            if lines.is_empty() { "" } else { ":\n  " },
            lines.join("\n  ")
        )
    }
}

/// What a kernel answers for one open file: the topology, and the geometry of each entity as
/// trait objects. Errors are the kernel's messages.
pub trait ForeignSource {
    /// The file, as messages name it.
    fn file(&self) -> &str;
    fn topology(&self) -> &ForeignTopology;
    /// The 3-D curve of a non-degenerate edge.
    fn curve(&self, edge: usize) -> Result<Arc<dyn Curve>, String>;
    fn surface(&self, face: usize) -> Result<Arc<dyn Surface>, String>;
    /// The pcurve of use `k` of loop `lp` of `face`, in the edge's parameter; `None` when the
    /// kernel gives none (it is then projected).
    fn pcurve(&self, face: usize, lp: usize, k: usize) -> Result<Option<Arc<dyn Curve2d>>, String>;
    /// Where the kernel's query failures are recorded (a plugin's); the model keeps it.
    fn faults(&self) -> FaultLog {
        FaultLog::default()
    }
}

/// Why a kernel's model could not become a [`Model`].
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    #[error("{0}")]
    Kernel(String),
    #[error("{file}: contains no solid ({faces} faces, {open_shells} open shells)")]
    NoSolid {
        file: String,
        faces: usize,
        open_shells: usize,
    },
    #[error("{file}: {entity}: {message}")]
    Entity {
        file: String,
        entity: EntityRef,
        message: String,
    },
    #[error("{file}: the model is not valid:\n  {}", .errors.join("\n  "))]
    Invalid { file: String, errors: Vec<String> },
    #[error("{file}: {source}")]
    Orient { file: String, source: OrientError },
    #[error("{0}")]
    Geometry(String),
}

/// Build, validate and orient the model of a kernel's file. A file without any solid gives
/// [`ImportError::NoSolid`] (the caller may sew and retry).
pub fn model_from_foreign(source: &dyn ForeignSource) -> Result<Model, ImportError> {
    let mut model = import_foreign(source)?;
    let file = source.file().to_string();
    let edges = &source.topology().edges;
    let tolerance = |e: usize| edges.get(e).map_or(0.0, |x| x.tolerance);
    for m in super::coincident::merge_coincident_stretches(&mut model, &tolerance) {
        log::warn!(
            "{file}: {}: {} runs along {} from {} for {:.4} within {:.2e} (their tolerance {:.2e}): \
             the slit is closed, the stretch is {} of its own (geometry moves by at most {:.2e} in area)",
            model.face_ref(m.face),
            model.edge_ref(m.cut),
            model.edge_ref(m.kept),
            model.vertex_ref(m.vertex),
            m.length,
            m.gap,
            m.tolerance,
            model.edge_ref(m.new_edge),
            m.gap * m.length
        );
    }
    // A kernel's failed query is the cause of whatever went wrong after it: it comes first.
    let fault = |model: &Model| model.faults.first().map(ImportError::Geometry);
    let errors = model.validation_errors();
    if let Some(e) = fault(&model) {
        return Err(e);
    }
    if !errors.is_empty() {
        return Err(ImportError::Invalid { file, errors });
    }
    let oriented = model.orient();
    if let Some(e) = fault(&model) {
        return Err(e);
    }
    oriented.map_err(|source| ImportError::Orient { file, source })?;
    Ok(model)
}

/// The model of a kernel's file as read: no validation, no orientation (every `FaceUse` is
/// forward). For tests and tools that want to look before orienting.
pub fn import_foreign(source: &dyn ForeignSource) -> Result<Model, ImportError> {
    let t = source.topology();
    let file = source.file().to_string();
    if t.solids.is_empty() {
        return Err(ImportError::NoSolid {
            file,
            faces: t.faces.len(),
            open_shells: (0..t.shells.len()).filter(|&s| !t.shell_closed(s)).count(),
        });
    }
    let mut model = Model {
        vertices: t
            .vertices
            .iter()
            .map(|v| Vertex {
                name: None,
                point: DVec3::from_array(v.point),
            })
            .collect(),
        faults: source.faults(),
        ..Model::default()
    };
    for (i, e) in t.edges.iter().enumerate() {
        let curve = if e.degenerate {
            None
        } else {
            Some(source.curve(i).map_err(ImportError::Kernel)?)
        };
        model.edges.push(Edge {
            name: None,
            curve,
            range: (e.t_range[0], e.t_range[1]),
            start: e.v0,
            end: e.v1,
        });
    }
    let extent = diagonal(&model);
    for (f, face) in t.faces.iter().enumerate() {
        let surface = source.surface(f).map_err(ImportError::Kernel)?;
        let mut loops = Vec::with_capacity(face.loops.len());
        for (l, lp) in face.loops.iter().enumerate() {
            let mut uses = Vec::with_capacity(lp.len());
            for (k, u) in lp.iter().enumerate() {
                let pcurve = match source.pcurve(f, l, k).map_err(ImportError::Kernel)? {
                    Some(pc) => pc,
                    None => projected(&model, &t.edges[u.edge], u.edge, &*surface, extent)
                        .map_err(|message| ImportError::Entity {
                            file: file.clone(),
                            entity: EntityRef::Face(f, face.name.clone()),
                            message,
                        })?,
                };
                uses.push(EdgeUse {
                    edge: u.edge,
                    reversed: u.reversed,
                    pcurve: Some(pcurve),
                });
            }
            loops.push(Loop { uses, vertex: None });
        }
        model.faces.push(Face {
            name: face.name.clone(),
            surface,
            loops,
        });
    }
    for s in &t.solids {
        let shells = (s.shells.iter())
            .map(|&sh| Shell {
                faces: (t.shells[sh].iter())
                    .map(|&face| FaceUse {
                        face,
                        reversed: false,
                    })
                    .collect(),
                volume: 0.0,
            })
            .collect();
        model.regions.push(Region {
            name: s.name.clone(),
            shells,
            embedded_faces: Vec::new(),
            embedded_edges: Vec::new(),
        });
    }
    Ok(model)
}

/// The bounding-box diagonal of the model's vertices.
fn diagonal(model: &Model) -> f64 {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for v in &model.vertices {
        lo = lo.min(v.point);
        hi = hi.max(v.point);
    }
    if model.vertices.is_empty() {
        0.0
    } else {
        lo.distance(hi)
    }
}

/// A use's pcurve when the kernel gives none: the edge's curve projected onto the surface,
/// within a thousand times the edge's tolerance or 1e-6 of the model.
fn projected(
    model: &Model,
    edge: &ForeignEdge,
    e: usize,
    surface: &dyn Surface,
    extent: f64,
) -> Result<Arc<dyn Curve2d>, String> {
    let curve = model.edges[e].curve.as_deref().ok_or_else(|| {
        format!("degenerate edge {e} has no pcurve from the kernel, and a pole cannot be projected")
    })?;
    let tol = (1e3 * edge.tolerance).max(1e-6 * extent);
    let range = (edge.t_range[0], edge.t_range[1]);
    super::project_pcurve(surface, curve, range, tol)
        .map(|pc| Arc::new(pc) as Arc<dyn Curve2d>)
        .map_err(|off| {
            format!(
                "edge {e} leaves the surface at t = {:.6} ({}) by {:.3e}: it has no pcurve from \
                 the kernel and does not lie on the face",
                off.t,
                Xyz(curve.point(off.t)),
                off.distance
            )
        })
}
