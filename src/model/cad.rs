//! A [`Model`] from a CAD model read by `tetrafoil-occt`: the CAD topology as it is (ids are
//! the CAD's 0-based ids), OCCT geometry behind the root traits, then validation and automatic
//! orientation exactly as for a case file.
//!
//! - vertices and edges one to one; degenerate edges (poles) get `curve: None`;
//! - faces with their names from the file (STEP/XDE), loops of edge uses each carrying its
//!   OCCT pcurve (a seam's two uses carry its two pcurves), re-parametrised to the edge's own
//!   parameter when OCCT's pcurve range differs from the edge's;
//! - one region per solid, named after the solid, with its shells; faces shared by touching
//!   solids exist once and appear in both regions' shells.
//!
//! Orientation is not taken from the file: [`Model::orient`] computes it (tests compare it with
//! OCCT's).

use super::{
    orient::OrientError, Edge, EdgeUse, EntityRef, Face, FaceUse, Loop, Model, Region, Shell,
    Vertex,
};
use crate::geometry::occt::ReparamPcurve;
use crate::geometry::Curve2d;
use glam::DVec3;
use std::sync::Arc;
use tetrafoil_occt::{CadError, CadModel};

/// Why a CAD model could not become a [`Model`].
#[derive(Debug, thiserror::Error)]
pub enum CadImportError {
    #[error(transparent)]
    Cad(#[from] CadError),
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
}

/// Build, validate and orient the model of a CAD file. A file without any solid gives
/// `CadError::NoSolid` (the caller may sew and retry).
pub fn model_from_cad(cad: &CadModel) -> Result<Model, CadImportError> {
    let mut model = import_cad(cad)?;
    let file = cad.file().to_string();
    let edges = &cad.topology().edges;
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
    let errors = model.validation_errors();
    if !errors.is_empty() {
        return Err(CadImportError::Invalid { file, errors });
    }
    model
        .orient()
        .map_err(|source| CadImportError::Orient { file, source })?;
    Ok(model)
}

/// The model of a CAD file as read: no validation, no orientation (every `FaceUse` is
/// forward). For tests and tools that want to look before orienting.
pub fn import_cad(cad: &CadModel) -> Result<Model, CadImportError> {
    let t = cad.topology();
    let file = cad.file().to_string();
    if t.solids.is_empty() {
        return Err(CadError::NoSolid {
            file,
            faces: t.faces.len(),
            open_shells: t.shells.iter().filter(|s| !s.closed).count(),
        }
        .into());
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
        ..Model::default()
    };
    for (i, e) in t.edges.iter().enumerate() {
        let curve = if e.degenerate {
            None
        } else {
            match cad.curve(i)? {
                Some(c) => Some(Arc::new(c) as Arc<dyn crate::geometry::Curve>),
                None => {
                    return Err(CadImportError::Entity {
                        file,
                        entity: EntityRef::Edge(i, None),
                        message: "has no 3-D curve and is not degenerate".into(),
                    })
                }
            }
        };
        model.edges.push(Edge {
            name: None,
            curve,
            range: (e.t_range[0], e.t_range[1]),
            start: e.v0,
            end: e.v1,
        });
    }
    for (f, face) in t.faces.iter().enumerate() {
        let surface = Arc::new(cad.surface(f)?);
        let mut loops = Vec::with_capacity(face.loops.len());
        for (l, lp) in face.loops.iter().enumerate() {
            let mut uses = Vec::with_capacity(lp.len());
            for (k, u) in lp.iter().enumerate() {
                let pc = cad.pcurve(f, l, k)?;
                uses.push(EdgeUse {
                    edge: u.edge,
                    reversed: u.reversed,
                    pcurve: Some(edge_parametrised(pc, model.edges[u.edge].range)),
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
        let shells = s
            .shells
            .iter()
            .map(|&sh| Shell {
                faces: t.shells[sh]
                    .faces
                    .iter()
                    .map(|&(face, _)| FaceUse {
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
