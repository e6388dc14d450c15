//! Surface mesh quality as a CFD user judges it: the share of triangles with a minimum angle
//! of at least 25° and of edges whose length is within [0.6, 1.5]·δ at their midpoint.
//!
//! Some small angles are not the mesher's to avoid, and are counted apart: a triangle at a CAD
//! corner sharper than 25° (its angle there is the corner's), and a triangle in a gap of a face
//! narrower than the size floor lets the proximity limit resolve (see
//! [`crate::sizing::ProximityLimit`]).

use super::SurfaceMesh;
use crate::mesh::quality::triangle_min_angle;
use crate::model::{FaceId, Model, VertexId};
use crate::sizing::SizingField;
use std::collections::HashSet;

/// Below this minimum angle a triangle counts as poor.
pub const GOOD_ANGLE_DEG: f64 = 25.0;

#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct SurfaceQuality {
    pub triangles: usize,
    /// Smallest angle of any triangle, degrees.
    pub min_angle: f64,
    /// Triangles with a minimum angle below 25°, forced ones included.
    pub below_25deg: usize,
    /// Of those: at a CAD corner sharper than 25°.
    pub forced_by_corner: usize,
    /// Of those (and not at such a corner): in a gap narrower than the size floor.
    pub forced_by_size_floor: usize,
    pub edges: usize,
    /// Edges with length in [0.6, 1.5]·δ(midpoint).
    pub edges_in_range: usize,
}

impl SurfaceQuality {
    /// Share of triangles that are good or forced.
    pub fn angle_share(&self) -> f64 {
        let unforced = self.below_25deg - self.forced_by_corner - self.forced_by_size_floor;
        1.0 - unforced as f64 / self.triangles.max(1) as f64
    }

    pub fn length_share(&self) -> f64 {
        self.edges_in_range as f64 / self.edges.max(1) as f64
    }
}

/// Measure `mesh` (whose first nodes are the model's vertices, as the curve mesh numbers them)
/// against `sizing`.
pub fn surface_quality(model: &Model, mesh: &SurfaceMesh, sizing: &SizingField) -> SurfaceQuality {
    let sharp = sharp_corners(model);
    let nv = model.vertices.len();
    let p = |i: usize| mesh.points[i];
    let mut q = SurfaceQuality {
        triangles: mesh.triangles.len(),
        min_angle: if mesh.triangles.is_empty() {
            0.0
        } else {
            180.0
        },
        ..Default::default()
    };
    for (t, &f) in mesh.triangles.iter().zip(&mesh.face_of) {
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let angle = triangle_min_angle(a, b, c);
        q.min_angle = q.min_angle.min(angle);
        if angle >= GOOD_ANGLE_DEG {
            continue;
        }
        q.below_25deg += 1;
        if t.iter().any(|&v| v < nv && sharp.contains(&(f, v))) {
            q.forced_by_corner += 1;
            continue;
        }
        let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
        if let Some(prox) = &sizing.proximity {
            if prox.floored_near((a + b + c) / 3.0, longest) {
                q.forced_by_size_floor += 1;
            }
        }
    }
    let mut edges: Vec<(usize, usize)> = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    q.edges = edges.len();
    q.edges_in_range = edges
        .iter()
        .filter(|&&(i, j)| {
            let d = sizing.spacing(0.5 * (p(i) + p(j)));
            (0.6 * d..=1.5 * d).contains(&p(i).distance(p(j)))
        })
        .count();
    q
}

/// (face, vertex) pairs where the face's corner is sharper than 25°: the angle inside the face
/// between the loop's incoming and outgoing edges, signed by the surface normal so a re-entrant
/// corner is not mistaken for a sharp one. Corners at degenerate edges (poles) are skipped.
pub fn sharp_corners(model: &Model) -> HashSet<(FaceId, VertexId)> {
    let mut out = HashSet::new();
    for (f, face) in model.faces.iter().enumerate() {
        for l in &face.loops {
            let n = l.uses.len();
            for i in 0..n {
                let (u_in, u_out) = (&l.uses[i], &l.uses[(i + 1) % n]);
                let (Some(c_in), Some(c_out)) = (
                    &model.edges[u_in.edge].curve,
                    &model.edges[u_out.edge].curve,
                ) else {
                    continue;
                };
                let end_param = |u: &crate::model::EdgeUse, at_end: bool| {
                    let r = model.edges[u.edge].range;
                    if at_end != u.reversed {
                        r.1
                    } else {
                        r.0
                    }
                };
                let sign = |u: &crate::model::EdgeUse| if u.reversed { -1.0 } else { 1.0 };
                let t_in = c_in.derivs(end_param(u_in, true)).d1 * sign(u_in);
                let s_out = end_param(u_out, false);
                let t_out = c_out.derivs(s_out).d1 * sign(u_out);
                let Some(uv) = model.use_uv(f, u_out, s_out) else {
                    continue;
                };
                let normal = face.surface.derivs(uv).normal_raw();
                let (Some(t_in), Some(t_out), Some(normal)) = (
                    t_in.try_normalize(),
                    t_out.try_normalize(),
                    normal.try_normalize(),
                ) else {
                    continue;
                };
                // Left turn φ from t_in to t_out; the face is on the left, so its corner is π − φ.
                let turn = normal.dot(t_in.cross(t_out)).atan2(t_in.dot(t_out));
                let corner = (std::f64::consts::PI - turn).to_degrees();
                if corner < GOOD_ANGLE_DEG {
                    out.insert((f, model.use_vertices(u_out).0));
                }
            }
        }
    }
    out
}
