//! Surface meshing: every face is triangulated by an advancing front in its parameter plane,
//! with quality judged in 3-D and intersections tested exactly in (u,v); then diagonal swaps
//! and smoothing. Faces are meshed in parallel; edges shared by faces already carry identical
//! nodes (from the curve mesh), so the shells come out watertight.

mod advance;
mod boundary;
mod front;
mod geometry2d;
mod improve;
mod pole;
pub mod quality;

pub use boundary::FaceVertex;
pub use quality::{surface_quality, SurfaceQuality};

use crate::curve::CurveMesh;
use crate::model::{EdgeId, FaceId, Model};
use crate::sizing::SizingField;
use glam::DVec3;
use rayon::prelude::*;

#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    #[error("{face}: the node at {at:?} of {edge} cannot be placed in the face's parameter plane")]
    Boundary {
        face: String,
        edge: String,
        at: DVec3,
    },
    #[error(
        "{face}: the advancing front cannot close near (u,v) = ({u:.6}, {v:.6}), xyz = {xyz:?}"
    )]
    Stuck {
        face: String,
        u: f64,
        v: f64,
        xyz: DVec3,
    },
}

/// All faces' triangles on shared nodes. Triangles run counter-clockwise in their face's
/// (u,v), i.e. their normal follows the surface normal `Su × Sv`.
#[derive(Clone, Debug, Default)]
pub struct SurfaceMesh {
    /// Curve-mesh nodes first, then the nodes created inside faces.
    pub points: Vec<DVec3>,
    pub triangles: Vec<[usize; 3]>,
    /// Face of each triangle.
    pub face_of: Vec<FaceId>,
    /// Segments of the embedded edges (free curves inside a region, on no face), on the
    /// curve-mesh nodes: the volume mesh must have them as edges.
    pub segments: Vec<[usize; 2]>,
    /// Edge of each segment.
    pub segment_edge: Vec<EdgeId>,
}

/// Options for [`mesh_surfaces`].
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceOptions {
    /// Go on after a face fails; the failures are returned beside the mesh.
    pub keep_going: bool,
}

/// Mesh every face; the error of the first face that fails, unless `keep_going`.
pub fn mesh_surfaces(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    options: SurfaceOptions,
) -> Result<(SurfaceMesh, Vec<SurfaceError>), SurfaceError> {
    // Largest faces first (by boundary nodes), one face per task, so a big face started last
    // does not leave the other threads idle at the end.
    let mut order: Vec<FaceId> = (0..model.faces.len()).collect();
    order.sort_by_key(|&f| std::cmp::Reverse(boundary_nodes(model, curves, f)));
    let mut per_face: Vec<(FaceId, Result<advance::FaceTriangulation, SurfaceError>)> = order
        .into_par_iter()
        .with_max_len(1)
        .map(|f| (f, mesh_face(model, curves, sizing, f)))
        .collect();
    per_face.sort_by_key(|(f, _)| *f);
    let per_face = per_face.into_iter().map(|(_, r)| r);
    let mut mesh = SurfaceMesh {
        points: curves.points.clone(),
        ..Default::default()
    };
    let mut failures = Vec::new();
    for (f, res) in per_face.enumerate() {
        let tri = match res {
            Ok(t) => t,
            Err(e) if options.keep_going => {
                failures.push(e);
                continue;
            }
            Err(e) => return Err(e),
        };
        // Vertices enter the mesh when a kept triangle uses them (a retry may orphan some).
        let mut ids: Vec<Option<usize>> = vec![None; tri.vertices.len()];
        for t in &tri.triangles {
            let node = |k: usize| tri.vertices[k].node.unwrap_or(usize::MAX - k);
            let n = t.map(node);
            // Two corners on one node (both sides of a pole) make a zero-area sliver: drop it.
            if n[0] == n[1] || n[1] == n[2] || n[2] == n[0] {
                continue;
            }
            let g = t.map(|k| {
                *ids[k].get_or_insert_with(|| match tri.vertices[k].node {
                    Some(n) => n,
                    None => {
                        mesh.points.push(tri.vertices[k].xyz);
                        mesh.points.len() - 1
                    }
                })
            });
            mesh.triangles.push(g);
            mesh.face_of.push(f);
        }
    }
    let mut embedded: Vec<EdgeId> = model
        .regions
        .iter()
        .flat_map(|r| r.embedded_edges.iter().copied())
        .collect();
    embedded.sort_unstable();
    embedded.dedup();
    for e in embedded {
        let Some(edge) = curves.edges.get(e) else {
            continue;
        };
        for w in edge.nodes.windows(2) {
            if w[0] != w[1] {
                mesh.segments.push([w[0], w[1]]);
                mesh.segment_edge.push(e);
            }
        }
    }
    Ok((mesh, failures))
}

/// Triangulate one face.
fn mesh_face(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    face: FaceId,
) -> Result<advance::FaceTriangulation, SurfaceError> {
    let surface = model.faces[face].surface.as_ref();
    let boundary = boundary::face_boundary(model, curves, sizing, face)?;
    let fixed = boundary.vertices.len();
    let mut tri = advance::advance(surface, sizing, boundary).map_err(|s| SurfaceError::Stuck {
        face: model.face_ref(face).to_string(),
        u: s.uv.x,
        v: s.uv.y,
        xyz: s.xyz,
    })?;
    improve::swap_diagonals(&mut tri);
    improve::smooth(&mut tri, surface, fixed);
    improve::swap_diagonals(&mut tri);
    Ok(tri)
}

/// Curve-mesh nodes on a face's loops: a cheap measure of its meshing work.
fn boundary_nodes(model: &Model, curves: &CurveMesh, face: FaceId) -> usize {
    model.faces[face]
        .loops
        .iter()
        .flat_map(|l| &l.uses)
        .map(|u| curves.edges.get(u.edge).map_or(0, |m| m.nodes.len()))
        .sum()
}
