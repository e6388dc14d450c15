//! A [`Model`] from a CAD model read by `tetrafoil-occt`: OCCT's topology and geometry as a
//! [`ForeignSource`] (ids are the CAD's 0-based ids; pcurves re-parametrised to the edge's own
//! parameter when OCCT's range differs), imported, validated and oriented by
//! [`super::foreign`] as any kernel's model is.

use super::foreign::{
    import_foreign, model_from_foreign, ForeignEdge, ForeignFace, ForeignSolid, ForeignSource,
    ForeignTopology, ForeignUse, ForeignVertex, ImportError,
};
use super::Model;
use crate::geometry::occt::ReparamPcurve;
use crate::geometry::{Curve, Curve2d, Surface};
use glam::DVec3;
use std::sync::Arc;
use tetrafoil_occt::CadModel;

/// Why a CAD model could not become a [`Model`].
pub type CadImportError = ImportError;

/// Build, validate and orient the model of a CAD file. A file without any solid gives
/// [`ImportError::NoSolid`] (the caller may sew and retry).
pub fn model_from_cad(cad: &CadModel) -> Result<Model, CadImportError> {
    model_from_foreign(&OcctSource::new(cad)?)
}

/// The model of a CAD file as read: no validation, no orientation (every `FaceUse` is
/// forward). For tests and tools that want to look before orienting.
pub fn import_cad(cad: &CadModel) -> Result<Model, CadImportError> {
    import_foreign(&OcctSource::new(cad)?)
}

/// A CAD model read by OpenCASCADE as a [`ForeignSource`].
struct OcctSource<'a> {
    cad: &'a CadModel,
    topology: ForeignTopology,
}

impl<'a> OcctSource<'a> {
    fn new(cad: &'a CadModel) -> Result<Self, ImportError> {
        let t = cad.topology();
        if t.solids.is_empty() {
            return Err(ImportError::NoSolid {
                file: cad.file().to_string(),
                faces: t.faces.len(),
                open_shells: t.shells.iter().filter(|s| !s.closed).count(),
            });
        }
        let topology = ForeignTopology {
            vertices: (t.vertices.iter())
                .map(|v| ForeignVertex {
                    point: v.point,
                    tolerance: v.tolerance,
                })
                .collect(),
            edges: (t.edges.iter())
                .map(|e| ForeignEdge {
                    v0: e.v0,
                    v1: e.v1,
                    degenerate: e.degenerate,
                    t_range: e.t_range,
                    tolerance: e.tolerance,
                })
                .collect(),
            faces: (t.faces.iter())
                .map(|f| ForeignFace {
                    name: f.name.clone(),
                    loops: (f.loops.iter())
                        .map(|lp| {
                            (lp.iter())
                                .map(|u| ForeignUse {
                                    edge: u.edge,
                                    reversed: u.reversed,
                                })
                                .collect()
                        })
                        .collect(),
                })
                .collect(),
            solids: (t.solids.iter())
                .map(|s| ForeignSolid {
                    name: s.name.clone(),
                    shells: (s.shells.iter())
                        .map(|&sh| t.shells[sh].faces.iter().map(|f| f.0).collect())
                        .collect(),
                })
                .collect(),
        };
        Ok(OcctSource { cad, topology })
    }
}

impl ForeignSource for OcctSource<'_> {
    fn file(&self) -> &str {
        self.cad.file()
    }
    fn topology(&self) -> &ForeignTopology {
        &self.topology
    }
    fn curve(&self, edge: usize) -> Result<Arc<dyn Curve>, String> {
        match self.cad.curve(edge).map_err(|e| e.to_string())? {
            Some(c) => Ok(Arc::new(c)),
            None => Err(format!(
                "{}: edge {edge}: has no 3-D curve and is not degenerate",
                self.cad.file()
            )),
        }
    }
    fn surface(&self, face: usize) -> Result<Arc<dyn Surface>, String> {
        Ok(Arc::new(self.cad.surface(face).map_err(|e| e.to_string())?))
    }
    fn pcurve(&self, face: usize, lp: usize, k: usize) -> Result<Option<Arc<dyn Curve2d>>, String> {
        let pc = self.cad.pcurve(face, lp, k).map_err(|e| e.to_string())?;
        let edge = self.topology.faces[face].loops[lp][k].edge;
        let range = self.topology.edges[edge].t_range;
        Ok(Some(edge_parametrised(pc, (range[0], range[1]))))
    }
}

/// The pcurve as a function of the edge parameter: OCCT's own when its range is the edge's
/// (the usual "same parameter" case), else linearly re-parametrised.
fn edge_parametrised(pc: tetrafoil_occt::OccPcurve, edge: (f64, f64)) -> Arc<dyn Curve2d> {
    let own = Curve2d::range(&pc);
    let tol = 1e-9 * (edge.1 - edge.0).abs().max(1.0);
    if (own.0 - edge.0).abs() <= tol && (own.1 - edge.1).abs() <= tol {
        Arc::new(pc)
    } else {
        Arc::new(ReparamPcurve {
            inner: pc,
            edge_range: edge,
        })
    }
}

/// Names of the faces and edges that keep a CAD model from being a set of solids: every
/// free edge with the face using it (at most `limit` of them).
pub fn open_boundary_diagnosis(cad: &CadModel, limit: usize) -> String {
    let t = cad.topology();
    let mut users: Vec<Vec<usize>> = vec![Vec::new(); t.edges.len()];
    for (f, face) in t.faces.iter().enumerate() {
        for u in face.loops.iter().flatten() {
            users[u.edge].push(f);
        }
    }
    let face_name = |f: usize| match &t.faces[f].name {
        Some(n) => format!("face {f} '{n}'"),
        None => format!("face {f}"),
    };
    let mut lines: Vec<String> = t
        .free_edges
        .iter()
        .take(limit)
        .map(|&e| {
            let faces: Vec<String> = users[e].iter().map(|&f| face_name(f)).collect();
            let at = |v: usize| crate::geometry::Xyz(DVec3::from_array(t.vertices[v].point));
            let edge = &t.edges[e];
            format!(
                "edge {e} (from {} to {}) is used only by {}",
                at(edge.v0),
                at(edge.v1),
                faces.join(", ")
            )
        })
        .collect();
    if t.free_edges.len() > limit {
        lines.push(format!(
            "... and {} more free edges",
            t.free_edges.len() - limit
        ));
    }
    format!(
        "{} faces, {} shells ({} open), {} free edges{}{}",
        t.faces.len(),
        t.shells.len(),
        t.shells.iter().filter(|s| !s.closed).count(),
        t.free_edges.len(),
        if lines.is_empty() { "" } else { ":\n  " },
        lines.join("\n  ")
    )
}
