//! Recovery of a missing surface triangle `abc` whose three edges exist.
//!
//! Around edge `ab` the tets form a ring `c_0 … c_{n-1}`; the face is present iff `c` is in
//! the ring. Otherwise the half-plane of the triangle at `ab` lies in exactly one wedge
//! `(a, b, c_i, c_{i+1})` (exact: `c` is strictly between the half-planes through `c_i` and
//! `c_{i+1}`), and the wedge's far edge `c_i c_{i+1}` crosses the open triangle: the edges
//! `ac` and `bc` exist, so they cannot enter that tet, which forces its section by the
//! triangle's plane to lie inside the triangle. A vertex on the wedge's boundary half-plane
//! lies inside the triangle. The crossing edge is removed by edge removal, asking the ring
//! for the triangle `abc` when `a`, `b`, `c` are all in it (then the face appears at once);
//! the three edges of the triangle give three starting wedges. When flips fail, a Steiner
//! point is put in the triangle (where the crossing edge meets its plane, kept away from
//! the triangle's edges), splitting it into three.

use crate::volume::delaunay::predicates::orient;
use crate::volume::delaunay::{Keep, INF};

use super::edges::remove_edge_deep;
use super::{Ctx, RecoveryError};

/// What blocks triangle `abc` at its edge `ab`.
enum Block {
    /// The face is there: tet and face index.
    Present(u32, u8),
    /// This edge crosses the open triangle.
    Edge(u32, u32),
    /// This vertex lies inside the triangle.
    Vertex(u32),
}

fn block_at(ctx: &mut Ctx, a: u32, b: u32, c: u32) -> Option<Block> {
    if let Some((t, f)) = ctx.dt.find_face_near(a, b, c) {
        return Some(Block::Present(t, f));
    }
    let (_, ring) = ctx.dt.tets_around_edge(a, b)?;
    let p = |v: u32| ctx.dt.point(v);
    let (pa, pb, pc) = (p(a), p(b), p(c));
    let n = ring.len();
    for i in 0..n {
        let (x, y) = (ring[i], ring[(i + 1) % n]);
        if x == INF || y == INF {
            continue;
        }
        let s1 = orient(&pa, &pb, &p(x), &pc);
        let s2 = orient(&pa, &pb, &pc, &p(y));
        if s1 > 0.0 && s2 > 0.0 {
            return Some(Block::Edge(x, y));
        }
        if s1 == 0.0 && s2 > 0.0 {
            return Some(Block::Vertex(x));
        }
        if s2 == 0.0 && s1 > 0.0 {
            return Some(Block::Vertex(y));
        }
    }
    None
}

/// How a missing triangle was dealt with.
pub(super) enum FaceResult {
    /// The triangle is a face, now constrained.
    Present,
    /// The triangle was split at this vertex into three; their edges and faces are new work.
    Split(u32),
}

/// Recover triangle `k` of the surface (its edges are present).
pub(super) fn recover_face(ctx: &mut Ctx, k: u32) -> Result<FaceResult, RecoveryError> {
    const ROUNDS: usize = 16;
    let [a, b, c] = ctx.surface.tris[k as usize];
    let mut last_cross = None;
    for _ in 0..ROUNDS {
        let mut progress = false;
        for (x, y, z) in [(a, b, c), (b, c, a), (c, a, b)] {
            match block_at(ctx, x, y, z) {
                None => {}
                Some(Block::Present(t, f)) => {
                    ctx.dt
                        .set_constrained(t, f, true)
                        .map_err(|e| ctx.face_error(k, &e.to_string()))?;
                    return Ok(FaceResult::Present);
                }
                Some(Block::Vertex(v)) => {
                    if ctx.surface.is_vertex(v) {
                        let why = format!(
                            "surface vertex {v} at {} lies inside it (seen from edge {x}-{y})",
                            crate::geometry::Xyz(glam::DVec3::from_array(ctx.dt.point(v)))
                        );
                        return Err(ctx.face_error(k, &why));
                    }
                    ctx.surface.split_triangle(k, v);
                    return Ok(FaceResult::Split(v));
                }
                Some(Block::Edge(u, w)) => {
                    last_cross = Some((u, w));
                    if ctx.surface.protects(&[u, w]) {
                        return Err(ctx.face_error(k, "a surface edge crosses it"));
                    }
                    if remove_edge_deep(ctx, u, w, Keep::Triangle(a, b, c)) {
                        progress = true;
                        break;
                    }
                }
            }
        }
        if !progress {
            break;
        }
    }
    if let Some((t, f)) = ctx.dt.find_face_near(a, b, c) {
        ctx.dt
            .set_constrained(t, f, true)
            .map_err(|e| ctx.face_error(k, &e.to_string()))?;
        return Ok(FaceResult::Present);
    }
    if last_cross.is_none() {
        for (x, y, z) in [(a, b, c), (b, c, a), (c, a, b)] {
            if let Some(Block::Edge(u, w)) = block_at(ctx, x, y, z) {
                last_cross = Some((u, w));
                break;
            }
        }
    }
    steiner_in_face(ctx, k, last_cross)
}

/// Barycentric coordinates of `x` in triangle `abc` (by signed areas projected on the
/// triangle's normal), floating point: only used to place a point, never to decide a sign.
fn barycentric(a: [f64; 3], b: [f64; 3], c: [f64; 3], x: [f64; 3]) -> [f64; 3] {
    let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let n = cross(sub(b, a), sub(c, a));
    let nn = dot(n, n);
    [
        dot(n, cross(sub(b, x), sub(c, x))) / nn,
        dot(n, cross(sub(c, x), sub(a, x))) / nn,
        dot(n, cross(sub(a, x), sub(b, x))) / nn,
    ]
}

/// Split triangle `k` with a new vertex: where the crossing edge meets its plane (or the
/// centroid), with every barycentric coordinate kept at least `MIN` so that the three new
/// triangles are not slivers.
fn steiner_in_face(
    ctx: &mut Ctx,
    k: u32,
    cross: Option<(u32, u32)>,
) -> Result<FaceResult, RecoveryError> {
    const MIN: f64 = 0.15;
    let [a, b, c] = ctx.surface.tris[k as usize];
    let (pa, pb, pc) = (ctx.dt.point(a), ctx.dt.point(b), ctx.dt.point(c));
    let mut lams = Vec::new();
    if let Some((u, w)) = cross {
        let (pu, pw) = (ctx.dt.point(u), ctx.dt.point(w));
        let hu = orient(&pa, &pb, &pc, &pu);
        let hw = orient(&pa, &pb, &pc, &pw);
        if (hu > 0.0) != (hw > 0.0) && hu != hw {
            let s = hu / (hu - hw);
            let x = [
                pu[0] + s * (pw[0] - pu[0]),
                pu[1] + s * (pw[1] - pu[1]),
                pu[2] + s * (pw[2] - pu[2]),
            ];
            let mut l = barycentric(pa, pb, pc, x).map(|v| v.max(MIN));
            let sum: f64 = l.iter().sum();
            l.iter_mut().for_each(|v| *v /= sum);
            lams.push(l);
        }
    }
    lams.extend([
        [1.0 / 3.0; 3],
        [0.4, 0.3, 0.3],
        [0.3, 0.4, 0.3],
        [0.3, 0.3, 0.4],
    ]);
    let hint = ctx.dt.vertex_tet(a);
    for l in lams {
        let m = [0, 1, 2].map(|i| l[0] * pa[i] + l[1] * pb[i] + l[2] * pc[i]);
        let surface = &ctx.surface;
        let protect = |s: &[u32]| surface.protects(s);
        if let Ok(out) = ctx.dt.insert_split(m, hint, &protect) {
            let v = out.vertex;
            ctx.report.steiner_on_faces += 1;
            ctx.surface.split_triangle(k, v);
            let surface = &ctx.surface;
            let protect = |s: &[u32]| surface.protects(s);
            ctx.report.flips += ctx.dt.flip_around(v, &protect, 256);
            return Ok(FaceResult::Split(v));
        }
    }
    Err(ctx.face_error(k, "no Steiner point could be inserted in it"))
}
