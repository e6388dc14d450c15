//! Exact 2-D tests in the parameter plane, all through `orient2d`.

use crate::geometry::orient2d;
use glam::DVec2;

/// Do segments p1–p2 and q1–q2 intersect (touching and overlapping count)?
pub fn segments_cross(p1: DVec2, p2: DVec2, q1: DVec2, q2: DVec2) -> bool {
    let d1 = orient2d(q1, q2, p1);
    let d2 = orient2d(q1, q2, p2);
    let d3 = orient2d(p1, p2, q1);
    let d4 = orient2d(p1, p2, q2);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |a: DVec2, b: DVec2, p: DVec2, d: f64| {
        d == 0.0 && p.cmpge(a.min(b)).all() && p.cmple(a.max(b)).all()
    };
    on(q1, q2, p1, d1) || on(q1, q2, p2, d2) || on(p1, p2, q1, d3) || on(p1, p2, q2, d4)
}

/// Is `p` inside or on the boundary of the counter-clockwise triangle a, b, c?
pub fn inside_or_on(a: DVec2, b: DVec2, c: DVec2, p: DVec2) -> bool {
    orient2d(a, b, p) >= 0.0 && orient2d(b, c, p) >= 0.0 && orient2d(c, a, p) >= 0.0
}
