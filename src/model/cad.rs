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
use std::borrow::Borrow;
use std::sync::Arc;
use tetrafoil_occt::CadModel;

/// Why a CAD model could not become a [`Model`].
pub type CadImportError = ImportError;

/// Build, validate and orient the model of a CAD file. A file without any solid gives
/// [`ImportError::NoSolid`] (the caller may sew and retry).
pub fn model_from_cad(cad: &CadModel) -> Result<Model, CadImportError> {
    model_from_foreign(&OcctSource::new(cad))
}

/// The model of a CAD file as read: no validation, no orientation (every `FaceUse` is
/// forward). For tests and tools that want to look before orienting.
pub fn import_cad(cad: &CadModel) -> Result<Model, CadImportError> {
    import_foreign(&OcctSource::new(cad))
}

/// A CAD model read by OpenCASCADE (owned or borrowed) as a [`ForeignSource`].
pub struct OcctSource<C: Borrow<CadModel>> {
    cad: C,
    topology: ForeignTopology,
}

impl<C: Borrow<CadModel>> OcctSource<C> {
    pub fn new(cad: C) -> Self {
        let t = cad.borrow().topology();
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
            shells: (t.shells.iter())
                .map(|sh| sh.faces.iter().map(|f| f.0).collect())
                .collect(),
            solids: (t.solids.iter())
                .map(|s| ForeignSolid {
                    name: s.name.clone(),
                    shells: s.shells.clone(),
                })
                .collect(),
        };
        OcctSource { cad, topology }
    }

    /// The CAD model.
    pub fn cad(&self) -> &CadModel {
        self.cad.borrow()
    }

    /// The CAD model, given back.
    pub fn into_cad(self) -> C {
        self.cad
    }
}

impl<C: Borrow<CadModel>> ForeignSource for OcctSource<C> {
    fn file(&self) -> &str {
        self.cad().file()
    }
    fn topology(&self) -> &ForeignTopology {
        &self.topology
    }
    fn curve(&self, edge: usize) -> Result<Arc<dyn Curve>, String> {
        match self.cad().curve(edge).map_err(|e| e.to_string())? {
            Some(c) => Ok(Arc::new(c)),
            None => Err(format!(
                "{}: edge {edge}: has no 3-D curve and is not degenerate",
                self.file()
            )),
        }
    }
    fn surface(&self, face: usize) -> Result<Arc<dyn Surface>, String> {
        Ok(Arc::new(
            self.cad().surface(face).map_err(|e| e.to_string())?,
        ))
    }
    fn pcurve(&self, face: usize, lp: usize, k: usize) -> Result<Option<Arc<dyn Curve2d>>, String> {
        let pc = self.cad().pcurve(face, lp, k).map_err(|e| e.to_string())?;
        let edge = self.topology.faces[face].loops[lp][k].edge;
        let range = self.topology.edges[edge].t_range;
        Ok(Some(edge_parametrised(pc, (range[0], range[1]))))
    }
}

/// The pcurve as a function of the edge parameter: OCCT's own when its range is the edge's
/// (the usual "same parameter" case), else linearly re-parametrised.
fn edge_parametrised(pc: tetrafoil_occt::OccPcurve, edge: (f64, f64)) -> Arc<dyn Curve2d> {
    if pc.same_parameter([edge.0, edge.1]) {
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
    OcctSource::new(cad).topology.open_boundary_diagnosis(limit)
}
