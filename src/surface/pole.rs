//! Poles: a degenerate edge (the apex of a cone, the pole of a sphere or revolved face) is a
//! segment in (u,v) whose points are all one 3-D point. The front needs it cut into pieces as
//! long as the neighbouring spacing asks for, and each zero-length piece needs its own ideal
//! point: the point at 3-D distance δ from the pole, straight into the face in (u,v).

use crate::geometry::{orient2d, Surface};
use glam::{DVec2, DVec3};

/// Bisection steps of the ring search for a front point (the bracket shrinks by 2⁻⁶⁰).
const BISECT: usize = 60;
/// Bisection steps when only the ring's length is wanted (to count pieces): 2⁻²⁴ of the
/// bracket is far below what rounding the length to whole pieces can see, at 40% of the
/// evaluations (a sphere's two poles took 0.7 ms, serial before its parts are meshed).
const BISECT_FOR_LENGTH: usize = 24;
/// Samples along a pole segment to measure the ring at distance δ around the pole.
const RING_SAMPLES: usize = 24;

/// The point at 3-D distance `delta` from `pole` on the line through `from` in (u,v) direction
/// `dir` (unit, pointing into the face): the first crossing, by expansion then bisection.
/// `None` when the line leaves the parameter domain first.
pub fn ring_point(
    surface: &dyn Surface,
    pole: DVec3,
    from: DVec2,
    dir: DVec2,
    delta: f64,
) -> Option<(DVec2, DVec3)> {
    ring_point_to(surface, pole, from, dir, delta, BISECT)
}

/// [`ring_point`] with `bisect` steps of bisection.
fn ring_point_to(
    surface: &dyn Surface,
    pole: DVec3,
    from: DVec2,
    dir: DVec2,
    delta: f64,
    bisect: usize,
) -> Option<(DVec2, DVec3)> {
    let b = surface.bounds();
    let inside = |uv: DVec2| {
        let ok =
            |x: f64, (lo, hi): (f64, f64), per: Option<f64>| per.is_some() || (x >= lo && x <= hi);
        ok(uv.x, b.u, b.u_period) && ok(uv.y, b.v, b.v_period)
    };
    let at = |s: f64| from + dir * s;
    let gap = |s: f64| surface.point(at(s)).distance(pole) - delta;
    // First step from the metric one step away from the pole (its own metric may vanish).
    let e = b.extent().max_element().max(1e-300);
    let probe = 1e-6 * e;
    let speed = surface.point(at(probe)).distance(pole) / probe;
    let mut hi = if speed.is_finite() && speed > 0.0 {
        delta / speed
    } else {
        1e-3 * e
    };
    let mut lo = 0.0;
    let mut tries = 0;
    loop {
        if !inside(at(hi)) {
            // Shrink back to the domain's edge once, then give up.
            let mut s = hi;
            for _ in 0..BISECT {
                s = 0.5 * (lo + s);
                if inside(at(s)) {
                    break;
                }
            }
            if !inside(at(s)) || gap(s) < 0.0 {
                return None;
            }
            hi = s;
            break;
        }
        if gap(hi) >= 0.0 {
            break;
        }
        lo = hi;
        hi *= 2.0;
        tries += 1;
        if tries > 60 {
            return None;
        }
    }
    for _ in 0..bisect {
        let m = 0.5 * (lo + hi);
        if gap(m) < 0.0 {
            lo = m;
        } else {
            hi = m;
        }
    }
    let uv = at(hi);
    Some((uv, surface.point(uv)))
}

/// Into-the-face unit direction of pole segment `a → b` (the face is on its left).
pub fn inward(a: DVec2, b: DVec2) -> Option<DVec2> {
    (b - a).perp().try_normalize()
}

/// Does `c` lie strictly between the rays that leave the pole piece `a → b` into the face
/// (square to it in (u,v))? Only such a vertex may stand in for the piece's ring point: a
/// vertex beside the piece (the next node along the edge leaving the pole) already has a fan
/// triangle of its own, and when both end pieces of a short ring take theirs, the pieces
/// between are left without a ring point and the fan collapses into one flat triangle
/// through the axis.
pub fn within_piece(a: DVec2, b: DVec2, c: DVec2) -> bool {
    let across = (b - a).perp();
    // Right of the ray from a (on b's side) and left of the ray from b (on a's side).
    orient2d(a, a + across, c) < 0.0 && orient2d(b, b + across, c) > 0.0
}

/// Largest turn around the pole's axis one piece may cover. A piece's fan triangle spans the
/// chord between its two ring points; a piece covering half a turn or more (a sharp tip whose
/// ring is shorter than δ, cut by a symmetry plane) makes that triangle flat through the axis
/// — lying in the neighbouring face and inverted against its own.
const MAX_PIECE_TURN: f64 = std::f64::consts::FRAC_PI_2;

/// How many pieces the pole segment `a → b` needs: the length of the ring of points at
/// distance `delta` around the pole, divided by `delta`, and enough that no piece turns more
/// than [`MAX_PIECE_TURN`] around the axis (at least one).
pub fn pieces(surface: &dyn Surface, pole: DVec3, a: DVec2, b: DVec2, delta: f64) -> usize {
    let Some(dir) = inward(a, b) else { return 1 };
    let mut ring = Vec::with_capacity(RING_SAMPLES + 1);
    let mut axis = DVec3::ZERO;
    for k in 0..=RING_SAMPLES {
        let from = a.lerp(b, k as f64 / RING_SAMPLES as f64);
        match ring_point_to(surface, pole, from, dir, delta, BISECT_FOR_LENGTH) {
            Some((uv, p)) => {
                ring.push(p);
                axis += surface.normal(uv);
            }
            None => return 1,
        }
    }
    let length: f64 = ring.windows(2).map(|w| w[0].distance(w[1])).sum();
    let by_length = ((length / delta).round() as usize).max(1);
    let by_turn = ring_turn(&ring, pole, axis)
        .map_or(1, |turn| (turn / MAX_PIECE_TURN).ceil() as usize)
        .max(1);
    by_length.max(by_turn)
}

/// How far the ring turns around the pole, seen along `axis` (the summed surface normals at
/// the ring): the sum of the angles between successive ring points projected on the plane
/// across the axis. `None` when the axis is undefined (normals cancel).
fn ring_turn(ring: &[DVec3], pole: DVec3, axis: DVec3) -> Option<f64> {
    let axis = axis.try_normalize()?;
    let across = |p: DVec3| {
        let d = p - pole;
        d - axis * d.dot(axis)
    };
    Some(
        ring.windows(2)
            .map(|w| {
                let (x, y) = (across(w[0]), across(w[1]));
                if x.length_squared() == 0.0 || y.length_squared() == 0.0 {
                    0.0
                } else {
                    x.angle_between(y)
                }
            })
            .sum(),
    )
}
