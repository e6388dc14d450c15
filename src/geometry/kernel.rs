//! How a foreign kernel's answers are used, the same for the built-in OpenCASCADE adapter and
//! for plugins: a kernel's closest point is taken when it lies on the curve or surface (within
//! [`ON_SURFACE`] of its size), else the generic Newton runs too and the closer answer wins; a
//! kernel that intersects the whole circle at once has its hits chosen by
//! [`nearest_hit`](super::circle::nearest_hit), after a Newton search near the front's hint
//! (which usually lands first).

use super::circle::nearest_hit;
use super::{newton, Circle, CircleHint, CircleHit, Curve, Range1, Surface};
use glam::{DVec2, DVec3};

/// Relative distance under which a projection is taken as lying on the curve or surface
/// (CAD edges lie on their faces to about this, relative to the model size); farther answers
/// are double-checked by the generic Newton.
pub const ON_SURFACE: f64 = 1e-7;

/// The closer of two (answer, distance) pairs.
fn closer<T>(a: Option<(T, f64)>, b: Option<(T, f64)>) -> Option<T> {
    match (a, b) {
        (Some(a), Some(b)) => Some(if b.1 < a.1 { b.0 } else { a.0 }),
        (a, b) => a.or(b).map(|x| x.0),
    }
}

fn mid(r: Range1) -> f64 {
    0.5 * (r.0 + r.1)
}

/// The closest parameter of `curve` to `p`, from the kernel's answer `kernel` (a parameter,
/// when it found one).
pub fn closest_parameter<C: Curve + ?Sized>(
    curve: &C,
    p: DVec3,
    hint: Option<f64>,
    kernel: Option<f64>,
) -> Option<f64> {
    let r = curve.range();
    let at = |t: f64| curve.point(t);
    let scale = at(r.0)
        .distance(at(mid(r)))
        .max(at(r.1).distance(at(mid(r))))
        .max(1e-300);
    let kernel = kernel
        .filter(|t| t.is_finite())
        .map(|t| (t, at(t).distance(p)));
    if let Some((t, d)) = kernel {
        if d <= ON_SURFACE * scale {
            return Some(t);
        }
    }
    let newton = newton::closest_parameter_3d(curve, p, hint).map(|t| (t, at(t).distance(p)));
    closer(kernel, newton)
}

/// Size of a surface's patch in space: the longest diagonal of its parameter rectangle.
fn surface_scale<S: Surface + ?Sized>(s: &S) -> f64 {
    let b = s.bounds();
    let c = |u, v| s.point(DVec2::new(u, v));
    c(b.u.0, b.v.0)
        .distance(c(b.u.1, b.v.1))
        .max(c(b.u.1, b.v.0).distance(c(b.u.0, b.v.1)))
        .max(1e-300)
}

/// The closest (u,v) of `surface` to `p`, from the kernel's answer `kernel`: folded into the
/// bounds and polished by a few local Gauss–Newton steps, then kept if it lies on the surface.
pub fn closest_uv<S: Surface + ?Sized>(
    surface: &S,
    p: DVec3,
    hint: Option<DVec2>,
    kernel: Option<DVec2>,
) -> Option<DVec2> {
    let b = surface.bounds();
    let dist = |uv: DVec2| surface.point(uv).distance(p);
    let kernel = kernel
        .filter(|uv| uv.is_finite())
        .map(|uv| b.normalise(uv))
        .map(|uv| match newton::project_local(surface, p, uv) {
            Some(q) if dist(q) < dist(uv) => (q, dist(q)),
            _ => (uv, dist(uv)),
        });
    if let Some((uv, d)) = kernel {
        if d <= ON_SURFACE * surface_scale(surface) {
            return Some(uv);
        }
    }
    let newton = newton::closest_uv(surface, p, hint).map(|uv| (uv, dist(uv)));
    closer(kernel, newton)
}

/// A point of `surface` on `circle` near the hint: Newton from the hint first; then the
/// kernel's hits on the whole circle (`whole`: `None` when the kernel does not intersect this
/// surface), the nearest within the window; none there while the kernel found some means there
/// is no such point; no hits at all, a Newton search across the window.
pub fn intersect_circle<S: Surface + ?Sized>(
    surface: &S,
    circle: &Circle,
    hint: &CircleHint,
    whole: impl FnOnce() -> Option<Vec<CircleHit>>,
) -> Option<CircleHit> {
    if let Some(hit) = newton::intersect_circle_near_hint(surface, circle, hint) {
        return Some(hit);
    }
    let Some(hits) = whole() else {
        return newton::intersect_circle(surface, circle, hint);
    };
    match nearest_hit(&hits, &surface.bounds(), hint) {
        Some(hit) => Some(CircleHit {
            point: surface.point(hit.uv),
            ..hit
        }),
        // The kernel saw the whole circle: hits outside the window or the face's range mean
        // there is no ideal point here, and a Newton search would not find one either.
        None if !hits.is_empty() => None,
        // Kernels miss some tangential and near-degenerate meetings: search from the hint.
        None => newton::intersect_circle(surface, circle, hint),
    }
}
