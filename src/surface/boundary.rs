//! The initial front of one face: the curve-mesh nodes of its loops placed in the face's
//! parameter plane through the pcurves, as directed segments with the face on their left.

use super::SurfaceError;
use crate::curve::CurveMesh;
use crate::model::{FaceId, Model};
use glam::{DVec2, DVec3};

/// A vertex of one face's mesh. The same global node may appear twice with different (u,v)
/// (both sides of a seam).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceVertex {
    pub uv: DVec2,
    pub xyz: DVec3,
    /// Global node id; `None` for a vertex created inside the face.
    pub node: Option<usize>,
}

/// Vertices and directed boundary segments (face on the left) of one face.
pub struct Boundary {
    pub vertices: Vec<FaceVertex>,
    pub segments: Vec<[usize; 2]>,
}

/// Build the boundary of `face` from the curve mesh. Loops are oriented (outer
/// counter-clockwise, holes clockwise), so the face is on the left of every segment.
pub fn face_boundary(
    model: &Model,
    curves: &CurveMesh,
    face: FaceId,
) -> Result<Boundary, SurfaceError> {
    let f = &model.faces[face];
    let bounds = f.surface.bounds();
    let mut b = Boundary {
        vertices: Vec::new(),
        segments: Vec::new(),
    };
    for lp in f.loops.iter().filter(|l| !l.uses.is_empty()) {
        let first = b.vertices.len();
        for u in &lp.uses {
            let em = &curves.edges[u.edge];
            let n = em.nodes.len();
            // Walk the edge's nodes in loop direction, all but the last (the next use's first).
            for k in 0..n - 1 {
                let i = if u.reversed { n - 1 - k } else { k };
                let t = em.params[i];
                let uv = model
                    .use_uv(face, u, t)
                    .ok_or_else(|| SurfaceError::Boundary {
                        face: model.face_ref(face).to_string(),
                        edge: model.edge_ref(u.edge).to_string(),
                        at: curves.points[em.nodes[i]],
                    })?;
                let uv = match b.vertices.last() {
                    Some(prev) if b.vertices.len() > first => {
                        crate::model::unwrap_near(uv, prev.uv, &bounds)
                    }
                    _ => uv,
                };
                b.vertices.push(FaceVertex {
                    uv,
                    xyz: curves.points[em.nodes[i]],
                    node: Some(em.nodes[i]),
                });
            }
        }
        let last = b.vertices.len();
        for k in first..last {
            let next = if k + 1 == last { first } else { k + 1 };
            b.segments.push([k, next]);
        }
    }
    Ok(b)
}
