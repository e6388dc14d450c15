//! A missing segment lying in a planar part of the hull (a symmetry plane beside a wing root).
//!
//! There the crossing edges are hull edges in that plane, and recovering the segment is the
//! 2-D constrained-triangulation problem: flip the crossing edges away, in any order that
//! works (Lawson). The flips from the segment's two ends (`edges.rs`) see only the
//! first crossing from each end, and there both quads can be non-convex: next to a wing's
//! root chord the symmetry plane's layer points stand in straight columns, so the edge from
//! an upper-surface node to a column point has the column's collinear neighbours as its
//! quad. Splitting the segment then only makes new chord pieces beside the same columns,
//! and the Steiner points pile up where the crossing edge meets the chord. Here every hull
//! edge crossing the segment is tried, from the middle outwards as much as from the ends,
//! until the segment is an edge or nothing more can be flipped.

use crate::volume::delaunay::predicates::orient;
use crate::volume::delaunay::INF;

use super::Ctx;
use std::collections::VecDeque;

/// Flips allowed per crossing edge found at the start (a flip may make a new crossing).
const FLIPS_PER_CROSSING: usize = 4;

/// Whether `ab` lies in a planar part of the hull; then flip the hull edges crossing it
/// away (Sloan's queue: a crossing edge that cannot go yet goes to the back, a new diagonal
/// that still crosses joins at the back, so no pair of flips undoes itself). True when `ab`
/// is an edge afterwards. `remove_crossing_edge` is the edge removal of the end flips.
pub(super) fn recover_in_hull_plane(
    ctx: &mut Ctx,
    a: u32,
    b: u32,
    remove_crossing_edge: fn(&mut Ctx, u32, u32, u32, u32) -> bool,
) -> bool {
    let Some(w) = off_plane_point(ctx, a, b) else {
        return false;
    };
    let mut queue: VecDeque<(u32, u32)> = crossing_hull_edges(ctx, a, b, w).into();
    let mut budget = FLIPS_PER_CROSSING * queue.len();
    // Edges tried in a row without a flip: a whole queue of them means stuck.
    let mut refused = 0;
    while let Some((x, y)) = queue.pop_front() {
        if ctx.dt.has_edge(a, b) {
            return true;
        }
        if budget == 0 || refused > queue.len() {
            break;
        }
        if !ctx.dt.has_edge(x, y) {
            continue;
        }
        if !remove_crossing_edge(ctx, x, y, a, b) {
            queue.push_back((x, y));
            refused += 1;
            continue;
        }
        budget -= 1;
        refused = 0;
        // The queue keeps its order; crossings the flip made join at the back.
        let now = crossing_hull_edges(ctx, a, b, w);
        queue.retain(|e| now.contains(e));
        for e in now {
            if !queue.contains(&e) {
                queue.push_back(e);
            }
        }
    }
    ctx.dt.has_edge(a, b)
}

/// Where on `ab` (0..1, open) the hull edge `xy` crosses it, when `ab` lies in a planar part
/// of the hull: the split point whose halves no longer cross `xy` (the exact signs decide
/// whether it crosses; the parameter itself is approximate).
pub(super) fn crossing_parameter(ctx: &mut Ctx, a: u32, b: u32, x: u32, y: u32) -> Option<f64> {
    let w = off_plane_point(ctx, a, b)?;
    let dt = &ctx.dt;
    let (pa, pb, px, py, pw) = (
        dt.point(a),
        dt.point(b),
        dt.point(x),
        dt.point(y),
        dt.point(w),
    );
    let sx = orient(&pa, &pb, &px, &pw);
    let sy = orient(&pa, &pb, &py, &pw);
    if sx * sy >= 0.0 {
        return None;
    }
    let s = sx / (sx - sy);
    let q = [0, 1, 2].map(|i| px[i] + s * (py[i] - px[i]));
    let d = [0, 1, 2].map(|i| pb[i] - pa[i]);
    let dd: f64 = d.iter().map(|c| c * c).sum();
    let t = (0..3).map(|i| (q[i] - pa[i]) * d[i]).sum::<f64>() / dd;
    (t > 0.0 && t < 1.0).then_some(t)
}

/// A vertex off the plane of a hull face at `a` that also holds `b` (the finite apex behind
/// that face); `None` when no hull face at `a` is coplanar with `b` (the segment does not
/// run in the hull).
fn off_plane_point(ctx: &mut Ctx, a: u32, b: u32) -> Option<u32> {
    let pb = ctx.dt.point(b);
    for t in ctx.dt.tets_around_vertex(a) {
        if !ctx.dt.is_ghost(t) {
            continue;
        }
        let v = ctx.dt.tet(t);
        let Some(i) = v.iter().position(|&x| x == INF) else {
            continue;
        };
        let face: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| v[k]).collect();
        let p = face.iter().map(|&x| ctx.dt.point(x)).collect::<Vec<_>>();
        if orient(&p[0], &p[1], &p[2], &pb) != 0.0 {
            continue;
        }
        let (inner, _) = ctx.dt.neighbor(t, i as u8);
        let apex = ctx.dt.tet(inner).into_iter().find(|x| !face.contains(x))?;
        return (apex != INF).then_some(apex);
    }
    None
}

/// The hull edges in `ab`'s plane (`w` off it) whose interiors cross the open segment `ab`.
fn crossing_hull_edges(ctx: &Ctx, a: u32, b: u32, w: u32) -> Vec<(u32, u32)> {
    let dt = &ctx.dt;
    let (pa, pb, pw) = (dt.point(a), dt.point(b), dt.point(w));
    let mut out: Vec<(u32, u32)> = Vec::new();
    for t in dt.ghost_ids() {
        let v = dt.tet(t);
        let face: Vec<u32> = v.iter().copied().filter(|&x| x != INF).collect();
        let p: Vec<[f64; 3]> = face.iter().map(|&x| dt.point(x)).collect();
        if orient(&p[0], &p[1], &p[2], &pa) != 0.0 || orient(&p[0], &p[1], &p[2], &pb) != 0.0 {
            continue;
        }
        for k in 0..3 {
            let (x, y) = (face[k], face[(k + 1) % 3]);
            if x == a || x == b || y == a || y == b {
                continue;
            }
            let (px, py) = (p[k], p[(k + 1) % 3]);
            let sx = orient(&pa, &pb, &px, &pw);
            let sy = orient(&pa, &pb, &py, &pw);
            let ta = orient(&px, &py, &pa, &pw);
            let tb = orient(&px, &py, &pb, &pw);
            if sx * sy < 0.0 && ta * tb < 0.0 {
                let e = (x.min(y), x.max(y));
                if !out.contains(&e) {
                    out.push(e);
                }
            }
        }
    }
    // Middle first: the crossings at the ends are the ones the end flips already refused.
    let mid = [
        0.5 * (pa[0] + pb[0]),
        0.5 * (pa[1] + pb[1]),
        0.5 * (pa[2] + pb[2]),
    ];
    let d2 = |e: &(u32, u32)| {
        let (p, q) = (dt.point(e.0), dt.point(e.1));
        (0..3)
            .map(|i| (0.5 * (p[i] + q[i]) - mid[i]).powi(2))
            .sum::<f64>()
    };
    out.sort_by(|e, f| d2(e).total_cmp(&d2(f)));
    out
}
