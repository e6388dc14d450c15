//! Surface meshing: every face is triangulated by an advancing front in its parameter plane,
//! with quality judged in 3-D and intersections tested exactly in (u,v); then diagonal swaps
//! and smoothing. Faces are meshed in parallel; edges shared by faces already carry identical
//! nodes (from the curve mesh), so the shells come out watertight.

mod advance;
mod boundary;
mod fallback;
mod front;
mod geometry2d;
mod improve;
mod pole;
pub mod quality;
mod schedule;
mod split;

pub use boundary::FaceVertex;
pub use quality::{surface_quality, SurfaceQuality};

use crate::curve::CurveMesh;
use crate::geometry::Surface;
use crate::model::{EdgeId, FaceId, Model};
use crate::progress::Reporter;
use crate::sizing::SizingField;
use glam::DVec3;

#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    #[error(
        "{face}: the node at {} of {edge} cannot be placed in the face's parameter plane",
        crate::geometry::Xyz(*.at)
    )]
    Boundary {
        face: String,
        edge: String,
        at: DVec3,
    },
    #[error(
        "{face}: the advancing front cannot close near (u,v) = ({}, {}), xyz = {}",
        crate::geometry::Coord(*.u),
        crate::geometry::Coord(*.v),
        crate::geometry::Xyz(*.xyz)
    )]
    Stuck {
        face: String,
        u: f64,
        v: f64,
        xyz: DVec3,
    },
    #[error("surface meshing {0}")]
    Cancelled(#[from] crate::progress::Cancelled),
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
    /// Parts each face was cut into and meshed concurrently (1: meshed whole; 0: failed).
    pub face_parts: Vec<usize>,
    /// Faces the advancing front could not close, meshed by the constrained-Delaunay
    /// fallback instead (every face with `delaunay_only`).
    pub delaunay_faces: Vec<FaceId>,
}

impl SurfaceMesh {
    /// Faces meshed in more than one part.
    pub fn split_faces(&self) -> usize {
        self.face_parts.iter().filter(|&&p| p > 1).count()
    }
}

/// Options for [`mesh_surfaces`].
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceOptions<'a> {
    /// Go on after a face fails; the failures are returned beside the mesh.
    pub keep_going: bool,
    /// Mesh every face whole, never in parts (see [`split`]): for comparisons.
    pub whole_faces: bool,
    /// Mesh every face by the constrained-Delaunay fallback (see [`fallback`]), whole: for
    /// tests and comparisons.
    pub delaunay_only: bool,
    /// Told `"surfaces"` progress (meshing jobs done of jobs: whole faces and parts of split
    /// faces); asked between jobs whether to stop.
    pub progress: Reporter<'a>,
}

/// Mesh every face; the error of the first face that fails, unless `keep_going`.
pub fn mesh_surfaces(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    options: SurfaceOptions,
) -> Result<(SurfaceMesh, Vec<SurfaceError>), SurfaceError> {
    let per_face = schedule::mesh_faces(model, curves, sizing, options);
    options.progress.check()?;
    let mut mesh = SurfaceMesh {
        points: curves.points.clone(),
        face_parts: vec![0; model.faces.len()],
        ..Default::default()
    };
    let mut failures = Vec::new();
    for (f, res) in per_face.into_iter().enumerate() {
        let tri = match res {
            Ok((t, meshed)) => {
                mesh.face_parts[f] = meshed.parts;
                if meshed.by_delaunay {
                    mesh.delaunay_faces.push(f);
                }
                t
            }
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

/// Swaps (never of a `slit` edge), smoothing of the vertices from `fixed` on, swaps.
fn improve_all(
    tri: &mut advance::FaceTriangulation,
    surface: &dyn Surface,
    fixed: usize,
    slits: &[[usize; 2]],
) {
    improve::swap_diagonals(tri, slits);
    improve::smooth(tri, surface, fixed);
    improve::swap_diagonals(tri, slits);
}
