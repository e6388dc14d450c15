//! The triangles of each face while refinement splits them, and the one way a node joins a
//! model edge: the curve mesh, the edge's segments and the triangles of every face on the edge
//! are split together, so faces sharing the edge stay conforming. Used by the edge stage of
//! `surface.rs` and by the column feet of `feet.rs`.

use crate::curve::CurveMesh;
use crate::model::{EdgeId, FaceId};
use crate::surface::SurfaceMesh;
use glam::DVec3;

/// A face's triangles during refinement.
pub(super) struct FaceTris {
    pub tris: Vec<[usize; 3]>,
}

/// Node `p` (at parameter `t` of edge `e`'s curve) between the edge's nodes `k` and `k + 1`:
/// the curve mesh, the triangles of every face on the edge and the edge's segment are split.
#[allow(clippy::too_many_arguments)]
pub(super) fn insert_edge_node(
    mesh: &mut SurfaceMesh,
    curves: &mut CurveMesh,
    faces: &mut [FaceTris],
    faces_of_edge: &[FaceId],
    e: EdgeId,
    k: usize,
    t: f64,
    p: DVec3,
) {
    let (na, nb) = (curves.edges[e].nodes[k], curves.edges[e].nodes[k + 1]);
    let m = mesh.points.len();
    mesh.points.push(p);
    curves.edges[e].nodes.insert(k + 1, m);
    curves.edges[e].params.insert(k + 1, t);
    for &f in faces_of_edge {
        split_edge(&mut faces[f].tris, na, nb, m);
    }
    for seg in mesh.segments.iter_mut().zip(mesh.segment_edge.iter()) {
        let (s2, &se) = seg;
        if se == e && ((s2[0] == na && s2[1] == nb) || (s2[0] == nb && s2[1] == na)) {
            let old = *s2;
            *s2 = [old[0], m];
            mesh.segments.push([m, old[1]]);
            mesh.segment_edge.push(e);
            break;
        }
    }
}

pub(super) fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Split every triangle with edge `ab` at node `m`, keeping orientation.
pub(super) fn split_edge(tris: &mut Vec<[usize; 3]>, a: usize, b: usize, m: usize) {
    let mut add = Vec::new();
    for t in tris.iter_mut() {
        for i in 0..3 {
            let (p, q, r) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
            if (p == a && q == b) || (p == b && q == a) {
                *t = [p, m, r];
                add.push([m, q, r]);
                break;
            }
        }
    }
    tris.extend(add);
}
