//! Edge flips inside the surface: the edges a Steiner point adds inside an original (flat)
//! triangle are artificial — any triangulation of that triangle is as good a boundary — so
//! they may be swapped like in a 2-D mesh. Without this, splitting edge `ab` of triangle
//! `abc` adds the long edge `mc`, whose own split adds another long edge, and the pieces
//! degenerate into needles along the original edges. Two uses:
//!
//! * a missing artificial edge whose quad's other diagonal is an edge of the tetrahedra is
//!   simply swapped to it (no Steiner point);
//! * after a Steiner point, the triangles around it are made 2-D Delaunay within their
//!   original triangle (Lawson), so the pieces stay well shaped — except that an edge
//!   present in the tetrahedra is never swapped for a missing one.
//!
//! Convexity of the quad is decided exactly (`orient` against a point off the plane); the
//! in-circle choice only picks between two valid triangulations, so floating point is fine.

use crate::volume::delaunay::predicates::orient;

use super::Ctx;

fn sub(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    [p[0] - q[0], p[1] - q[1], p[2] - q[2]]
}

fn cross(u: [f64; 3], v: [f64; 3]) -> [f64; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

fn dot(u: [f64; 3], v: [f64; 3]) -> f64 {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}

/// Is the quad `a c b d` (diagonal `ab`, `c` and `d` on either side) strictly convex? Decided
/// by exact orientations against a point `q` off the common plane.
fn convex(ctx: &Ctx, a: u32, b: u32, c: u32, d: u32) -> bool {
    let [pa, pb, pc, pd] = [a, b, c, d].map(|v| ctx.dt.point(v));
    let n = cross(sub(pb, pa), sub(pc, pa));
    let s = dot(n, n).sqrt().max(f64::MIN_POSITIVE);
    let l = dot(sub(pb, pa), sub(pb, pa)).sqrt();
    let q = [0, 1, 2].map(|i| pa[i] + n[i] / s * l);
    let side = |x: &[f64; 3], y: &[f64; 3], z: &[f64; 3]| orient(x, y, z, &q);
    let (c1, d1) = (side(&pa, &pb, &pc), side(&pa, &pb, &pd));
    let (a1, b1) = (side(&pc, &pd, &pa), side(&pc, &pd, &pb));
    c1 * d1 < 0.0 && a1 * b1 < 0.0
}

/// Is `w` strictly inside the circumcircle of the (flat) triangle `x y z`? Floating point.
fn in_circle(ctx: &Ctx, x: u32, y: u32, z: u32, w: u32) -> bool {
    let [px, py, pz, pw] = [x, y, z, w].map(|v| ctx.dt.point(v));
    let (u, v) = (sub(py, px), sub(pz, px));
    let n = cross(u, v);
    let nn = dot(n, n);
    if nn == 0.0 {
        return false;
    }
    // Circumcentre: x + ((|u|² v − |v|² u) × n) / (2 |n|²).
    let t = sub(
        [0, 1, 2].map(|i| dot(u, u) * v[i]),
        [0, 1, 2].map(|i| dot(v, v) * u[i]),
    );
    let c = cross(t, n);
    let o = [0, 1, 2].map(|i| px[i] + c[i] / (2.0 * nn));
    let r2 = dot(sub(px, o), sub(px, o));
    dot(sub(pw, o), sub(pw, o)) < r2 * (1.0 - 1e-12)
}

/// Swap the missing artificial edge `ab` to the other diagonal if that one is an edge of the
/// tetrahedralisation. Returns whether it did.
pub(super) fn swap_to_existing(ctx: &mut Ctx, a: u32, b: u32) -> bool {
    let Some(q @ (_, _, c, d)) = ctx.surface.quad(a, b) else {
        return false;
    };
    if !ctx.dt.has_edge(c, d) || !convex(ctx, a, b, c, d) {
        return false;
    }
    ctx.surface.flip(a, b, q);
    true
}

/// Lawson flips of the surface around the new vertex `m`; returns the new edges (to be
/// recovered).
pub(super) fn delaunay_around(ctx: &mut Ctx, m: u32) -> Vec<(u32, u32)> {
    let mut stack: Vec<(u32, u32)> = ctx
        .surface
        .edges_at(m)
        .into_iter()
        .flat_map(|(v, _)| ctx.surface.edges_at(v))
        .filter(|&(x, y)| x != m && y != m)
        .collect();
    let mut new = Vec::new();
    let mut budget = 64;
    while let Some((a, b)) = stack.pop() {
        if budget == 0 {
            break;
        }
        let Some(q @ (_, _, c, d)) = ctx.surface.quad(a, b) else {
            continue;
        };
        if c != m && d != m {
            continue;
        }
        if !in_circle(ctx, a, b, c, d) || !convex(ctx, a, b, c, d) {
            continue;
        }
        if ctx.dt.has_edge(a, b) && !ctx.dt.has_edge(c, d) {
            continue;
        }
        budget -= 1;
        ctx.surface.flip(a, b, q);
        new.push((c, d));
        let w = if c == m { d } else { c };
        stack.push((a, w));
        stack.push((w, b));
    }
    new
}
