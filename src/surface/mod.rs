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
mod split;

pub use boundary::FaceVertex;
pub use quality::{surface_quality, SurfaceQuality};

use crate::curve::CurveMesh;
use crate::geometry::Surface;
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
    /// Parts each face was cut into and meshed concurrently (1: meshed whole; 0: failed).
    pub face_parts: Vec<usize>,
}

impl SurfaceMesh {
    /// Faces meshed in more than one part.
    pub fn split_faces(&self) -> usize {
        self.face_parts.iter().filter(|&&p| p > 1).count()
    }
}

/// Options for [`mesh_surfaces`].
#[derive(Clone, Copy, Debug, Default)]
pub struct SurfaceOptions {
    /// Go on after a face fails; the failures are returned beside the mesh.
    pub keep_going: bool,
    /// Mesh every face whole, never in parts (see [`split`]): for comparisons.
    pub whole_faces: bool,
}

/// Mesh every face; the error of the first face that fails, unless `keep_going`.
pub fn mesh_surfaces(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    options: SurfaceOptions,
) -> Result<(SurfaceMesh, Vec<SurfaceError>), SurfaceError> {
    // Largest faces first (by boundary nodes), handed out one at a time in that order.
    let mut order: Vec<FaceId> = (0..model.faces.len()).collect();
    order.sort_by_key(|&f| std::cmp::Reverse(boundary_nodes(model, curves, f)));
    let mut per_face = in_order(&order, |f| mesh_face(model, curves, sizing, f, options));
    per_face.sort_by_key(|(f, _)| *f);
    let per_face = per_face.into_iter().map(|(_, r)| r);
    let mut mesh = SurfaceMesh {
        points: curves.points.clone(),
        face_parts: vec![0; model.faces.len()],
        ..Default::default()
    };
    let mut failures = Vec::new();
    for (f, res) in per_face.enumerate() {
        let tri = match res {
            Ok((t, parts)) => {
                mesh.face_parts[f] = parts;
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

/// `work` on every item, the items handed out in their order to whichever thread is free
/// (one worker per thread pulling from a shared cursor), so the largest jobs start first
/// and small ones fill in at the end. An indexed parallel iterator splits the list in
/// halves instead: with two threads one took the two largest faces in turn while the other
/// ran out of work (cylinder_catia_trimmed.igs: 1.5x on two threads instead of 2). Not
/// `par_bridge`: a thread waiting in a split face's nested join may pick up another bridge
/// job, which then returns at once and leaves its thread without faces.
fn in_order<T: Send>(items: &[FaceId], work: impl Fn(FaceId) -> T + Sync) -> Vec<(FaceId, T)> {
    let cursor = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(Vec::with_capacity(items.len()));
    rayon::scope(|scope| {
        for _ in 0..rayon::current_num_threads() {
            scope.spawn(|_| loop {
                let k = cursor.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(&item) = items.get(k) else { break };
                let result = work(item);
                done.lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .push((item, result));
            });
        }
    });
    done.into_inner().unwrap_or_else(|e| e.into_inner())
}

/// Triangulate one face: in parts meshed concurrently when it is large (see [`split`]),
/// whole otherwise or when a part fails. Also returns the number of parts.
fn mesh_face(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    face: FaceId,
    options: SurfaceOptions,
) -> Result<(advance::FaceTriangulation, usize), SurfaceError> {
    let surface = model.faces[face].surface.as_ref();
    let boundary = boundary::face_boundary(model, curves, sizing, face)?;
    let plan = (!options.whole_faces)
        .then(|| split::plan(surface, sizing, &boundary))
        .flatten();
    if let Some(plan) = plan {
        let parts = plan.parts.len();
        if let Some(tri) = mesh_parts(surface, sizing, plan) {
            return Ok((tri, parts));
        }
    }
    let fixed = boundary.vertices.len();
    let mut tri = advance::advance(surface, sizing, boundary).map_err(|s| SurfaceError::Stuck {
        face: model.face_ref(face).to_string(),
        u: s.uv.x,
        v: s.uv.y,
        xyz: s.xyz,
    })?;
    improve_all(&mut tri, surface, fixed);
    Ok((tri, 1))
}

/// Swaps, smoothing of the vertices from `fixed` on, swaps.
fn improve_all(tri: &mut advance::FaceTriangulation, surface: &dyn Surface, fixed: usize) {
    improve::swap_diagonals(tri);
    improve::smooth(tri, surface, fixed);
    improve::swap_diagonals(tri);
}

/// Mesh and improve the parts of a split face concurrently, with the cut nodes fixed; merge
/// them on the shared cut nodes and improve once more around the cuts. `None` if a part
/// fails. (An OCCT surface makes a copy of itself for each thread calling it at once.)
fn mesh_parts(
    surface: &dyn Surface,
    sizing: &SizingField,
    plan: split::Plan,
) -> Option<advance::FaceTriangulation> {
    let meshed: Vec<Option<advance::FaceTriangulation>> = plan
        .parts
        .par_iter()
        .with_max_len(1)
        .map(|part| {
            let fixed = part.pool_ids.len();
            let mut tri = advance::advance(surface, sizing, part.boundary.clone()).ok()?;
            improve_all(&mut tri, surface, fixed);
            Some(tri)
        })
        .collect();
    let pool = plan.vertices.len();
    let mut tri = advance::FaceTriangulation {
        vertices: plan.vertices,
        triangles: Vec::new(),
    };
    for (part, m) in plan.parts.iter().zip(meshed) {
        let m = m?;
        let mut ids = part.pool_ids.clone();
        for v in &m.vertices[ids.len()..] {
            ids.push(tri.vertices.len());
            tri.vertices.push(*v);
        }
        tri.triangles
            .extend(m.triangles.iter().map(|t| t.map(|k| ids[k])));
    }
    let near_cut: Vec<bool> = (0..tri.vertices.len())
        .map(|v| (plan.first_cut..pool).contains(&v))
        .collect();
    improve::swap_diagonals_near(&mut tri, &near_cut);
    improve::smooth_vertices(&mut tri, surface, |v| near_cut[v]);
    improve::swap_diagonals_near(&mut tri, &near_cut);
    Some(tri)
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
