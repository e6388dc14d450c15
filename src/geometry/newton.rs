//! Generic Newton methods that give every [`Curve`], [`Curve2d`] and [`Surface`] a projection
//! and a circle intersection. They start from the caller's hint when it is good and fall back
//! to coarse sampling of the parameter domain when it is not, and they say `None` rather than
//! return a point that does not satisfy the equations.

use super::{Circle, CircleHint, CircleHit, Curve, Curve2d, Range1, Surface, SurfaceBounds};
use glam::{DMat2, DMat3, DVec2, DVec3};

const MAX_ITER: usize = 60;
/// Relative parameter step below which an iteration has converged.
const STEP_TOL: f64 = 1e-13;
/// Samples per direction for the fallback start.
const SAMPLES: usize = 24;

/// Closest parameter on a 3-D curve: Newton on `C'(t)·(C(t) − p) = 0`.
pub fn closest_parameter_3d<C: Curve + ?Sized>(
    curve: &C,
    p: DVec3,
    hint: Option<f64>,
) -> Option<f64> {
    let range = curve.range();
    let eval = |t: f64| {
        let d = curve.derivs(t);
        (d.p - p, d.d1, d.d2)
    };
    closest_on_curve(range, curve.period(), hint, eval, |r| r.length_squared())
}

/// Closest parameter on a pcurve: Newton on `c'(t)·(c(t) − p) = 0`.
pub fn closest_parameter_2d<C: Curve2d + ?Sized>(
    curve: &C,
    p: DVec2,
    hint: Option<f64>,
) -> Option<f64> {
    let eval = |t: f64| {
        let (c, d1, d2) = curve.derivs(t);
        ((c - p).extend(0.0), d1.extend(0.0), d2.extend(0.0))
    };
    closest_on_curve(curve.range(), None, hint, eval, |r| r.length_squared())
}

fn closest_on_curve(
    range: Range1,
    period: Option<f64>,
    hint: Option<f64>,
    eval: impl Fn(f64) -> (DVec3, DVec3, DVec3),
    dist2: impl Fn(DVec3) -> f64,
) -> Option<f64> {
    let len = range.1 - range.0;
    if !(len.is_finite() && len > 0.0) {
        return Some(range.0);
    }
    let fold = |t: f64| match period {
        Some(per) => range.0 + (t - range.0).rem_euclid(per),
        None => t.clamp(range.0, range.1),
    };
    let newton = |mut t: f64| -> Option<f64> {
        for _ in 0..MAX_ITER {
            let (r, d1, d2) = eval(t);
            let f = d1.dot(r);
            let mut fp = d2.dot(r) + d1.length_squared();
            if fp <= 0.0 {
                // Not a minimum locally: fall back to the Gauss-Newton curvature.
                fp = d1.length_squared();
            }
            if fp <= 0.0 {
                return None;
            }
            let next = fold(t - f / fp);
            let step = (next - t).abs();
            t = next;
            if step <= STEP_TOL * len {
                return Some(t);
            }
        }
        None
    };
    let mut best: Option<(f64, f64)> = None;
    let consider = |best: &mut Option<(f64, f64)>, t: Option<f64>| {
        if let Some(t) = t {
            let d = dist2(eval(t).0);
            if best.is_none_or(|(_, bd)| d < bd) {
                *best = Some((t, d));
            }
        }
    };
    if let Some(h) = hint {
        consider(&mut best, newton(fold(h)));
        if let Some((_, d)) = best {
            if d <= (1e-10 * curve_scale(&eval, range)).powi(2) {
                return best.map(|b| b.0);
            }
        }
    }
    // Sampled starts: the three best samples, so a bad hint never decides the answer.
    let mut samples: Vec<(f64, f64)> = (0..=SAMPLES)
        .map(|i| {
            let t = range.0 + len * i as f64 / SAMPLES as f64;
            (t, dist2(eval(t).0))
        })
        .collect();
    samples.select_nth_unstable_by(3, |a, b| a.1.total_cmp(&b.1));
    for &(t, _) in samples.iter().take(3) {
        consider(&mut best, newton(t));
    }
    best.map(|b| b.0)
}

fn curve_scale(eval: &impl Fn(f64) -> (DVec3, DVec3, DVec3), range: Range1) -> f64 {
    let mid = 0.5 * (range.0 + range.1);
    let (_, d1, _) = eval(mid);
    (d1.length() * (range.1 - range.0)).max(1e-300)
}

/// Rough size of a surface in space, from its derivatives at the centre of its bounds.
pub fn surface_scale<S: Surface + ?Sized>(surface: &S, b: &SurfaceBounds) -> f64 {
    let c = DVec2::new(0.5 * (b.u.0 + b.u.1), 0.5 * (b.v.0 + b.v.1));
    let d = surface.derivs(c);
    let e = b.extent();
    (d.du.length() * e.x + d.dv.length() * e.y).max(1e-300)
}

/// Closest (u,v) on a surface: Newton on the gradient of `|S(u,v) − p|²`, with the full
/// Hessian where it is positive definite and Gauss–Newton where it is not.
pub fn closest_uv<S: Surface + ?Sized>(
    surface: &S,
    p: DVec3,
    hint: Option<DVec2>,
) -> Option<DVec2> {
    let b = surface.bounds();
    let extent = b.extent();
    let newton = |mut uv: DVec2| -> Option<DVec2> {
        for _ in 0..MAX_ITER {
            let d = surface.derivs(uv);
            let r = d.p - p;
            let g = DVec2::new(d.du.dot(r), d.dv.dot(r));
            let (e, f, gg) = d.first_form();
            let full = DMat2::from_cols(
                DVec2::new(e + d.duu.dot(r), f + d.duv.dot(r)),
                DVec2::new(f + d.duv.dot(r), gg + d.dvv.dot(r)),
            );
            let gauss = DMat2::from_cols(DVec2::new(e, f), DVec2::new(f, gg));
            let h = if full.x_axis.x > 0.0 && full.determinant() > 0.0 {
                full
            } else {
                gauss
            };
            let det = h.determinant();
            if !(det.is_finite() && det.abs() > 0.0) {
                return None;
            }
            let step = -(h.inverse() * g);
            let next = b.normalise(uv + step);
            let moved = next - uv;
            uv = next;
            if moved.x.abs() <= STEP_TOL * extent.x.max(1e-300)
                && moved.y.abs() <= STEP_TOL * extent.y.max(1e-300)
            {
                return Some(uv);
            }
        }
        None
    };
    let dist2 = |uv: DVec2| surface.point(uv).distance_squared(p);
    let mut best: Option<(DVec2, f64)> = None;
    let consider = |best: &mut Option<(DVec2, f64)>, uv: Option<DVec2>| {
        if let Some(uv) = uv {
            let d = dist2(uv);
            if best.is_none_or(|(_, bd)| d < bd) {
                *best = Some((uv, d));
            }
        }
    };
    if let Some(h) = hint {
        consider(&mut best, newton(b.normalise(h)));
        if let Some((_, d)) = best {
            if d <= (1e-10 * surface_scale(surface, &b)).powi(2) {
                return best.map(|x| x.0);
            }
        }
    }
    let mut samples = Vec::with_capacity((SAMPLES + 1) * (SAMPLES + 1));
    for i in 0..=SAMPLES {
        for j in 0..=SAMPLES {
            let uv = DVec2::new(
                b.u.0 + extent.x * i as f64 / SAMPLES as f64,
                b.v.0 + extent.y * j as f64 / SAMPLES as f64,
            );
            samples.push((uv, dist2(uv)));
        }
    }
    samples.select_nth_unstable_by(3, |a, b| a.1.total_cmp(&b.1));
    for &(uv, _) in samples.iter().take(3) {
        consider(&mut best, newton(uv));
    }
    best.map(|x| x.0)
}

/// Local projection: Gauss–Newton steps on `|S(u,v) − p|²` from `start`, no global search.
/// For points known to be close to `S(start)` (smoothing moves); `None` if it does not settle.
pub fn project_local<S: Surface + ?Sized>(surface: &S, p: DVec3, start: DVec2) -> Option<DVec2> {
    let b = surface.bounds();
    let extent = b.extent();
    let mut uv = b.normalise(start);
    for _ in 0..12 {
        let d = surface.derivs(uv);
        let r = d.p - p;
        let (e, f, g) = d.first_form();
        let h = DMat2::from_cols(DVec2::new(e, f), DVec2::new(f, g));
        if h.determinant().abs() <= 0.0 {
            return None;
        }
        let step = -(h.inverse() * DVec2::new(d.du.dot(r), d.dv.dot(r)));
        let next = b.normalise(uv + step);
        let moved = (next - uv).abs();
        uv = next;
        if moved.x <= 1e-12 * extent.x && moved.y <= 1e-12 * extent.y {
            return Some(uv);
        }
    }
    Some(uv)
}

/// A point of the surface on the circle near `hint`: Newton on `S(u,v) − C(θ) = 0` in the
/// three unknowns (u, v, θ). Starts from the projection of `C(θ₀)`; if that fails, from a few
/// other angles in the hint's window. The answer is checked against both equations.
pub fn intersect_circle<S: Surface + ?Sized>(
    surface: &S,
    circle: &Circle,
    hint: &CircleHint,
) -> Option<CircleHit> {
    intersect_circle_with(surface, circle, hint, true)
}

/// Newton from the hint's (u,v) and angle only: no projection, no other starts. Cheap, and
/// right nearly always on the advancing front, whose hint is a neighbour's (u,v); adapters
/// with an expensive global intersection (OCCT) try this first.
pub fn intersect_circle_near_hint<S: Surface + ?Sized>(
    surface: &S,
    circle: &Circle,
    hint: &CircleHint,
) -> Option<CircleHit> {
    intersect_circle_with(surface, circle, hint, false)
}

fn intersect_circle_with<S: Surface + ?Sized>(
    surface: &S,
    circle: &Circle,
    hint: &CircleHint,
    search: bool,
) -> Option<CircleHit> {
    let b = surface.bounds();
    let scale = surface_scale(surface, &b).max(circle.radius);
    let tol = 1e-11 * scale;
    let solve = |uv0: DVec2, theta0: f64| -> Option<CircleHit> {
        let (mut uv, mut theta) = (uv0, theta0);
        let mut last = f64::INFINITY;
        let mut growing = 0;
        for iteration in 0..MAX_ITER {
            let d = surface.derivs(uv);
            let f = d.p - circle.point(theta);
            // From a good start Newton converges in a handful of steps; one that keeps
            // growing or is still far after a dozen is not going to (measured on the ONERA
            // wing: two thirds of the failing solves ran all MAX_ITER steps).
            let residual = f.length();
            if residual > last {
                growing += 1;
                if growing >= 3 {
                    return None;
                }
            }
            last = residual;
            if iteration >= 12 && residual > 1e-6 * scale {
                return None;
            }
            // At a pole the parameters need not settle: the point already has.
            if residual <= 1e-3 * tol {
                break;
            }
            let j = DMat3::from_cols(d.du, d.dv, -circle.tangent(theta));
            let det = j.determinant();
            if !(det.is_finite() && det.abs() > 1e-300) {
                return None;
            }
            let step = -(j.inverse() * f);
            let next = b.normalise(uv + DVec2::new(step.x, step.y));
            theta += step.z;
            let moved = (next - uv).abs();
            uv = next;
            if f.length() <= tol
                && moved.x <= 1e-10 * b.extent().x
                && moved.y <= 1e-10 * b.extent().y
            {
                break;
            }
        }
        let point = surface.point(uv);
        if point.distance(circle.point(theta)) > 1e-9 * scale {
            return None;
        }
        let dtheta = wrap_angle(theta - hint.theta);
        if dtheta.abs() > hint.max_dtheta {
            return None;
        }
        Some(CircleHit {
            uv,
            theta: hint.theta + dtheta,
            point,
        })
    };
    let start = |theta: f64| {
        surface
            .closest_uv(circle.point(theta), Some(hint.uv))
            .unwrap_or(hint.uv)
    };
    // The caller's (u,v) is usually close: try it before paying for a projection.
    if let Some(hit) = solve(b.normalise(hint.uv), hint.theta) {
        return Some(hit);
    }
    if !search {
        return None;
    }
    // From each angle, start at the local projection from the hint's (u,v) (a few Newton
    // steps); only where that does not settle, at the surface's own projection, which may
    // search the whole surface (OCCT's fills a grid of distances on every call: 60% of the
    // spring's surface time when every start paid for one).
    [0.0, 1.0, -1.0, 2.0, -2.0].into_iter().find_map(|k| {
        let theta = hint.theta + k * hint.max_dtheta / 3.0;
        let uv =
            project_local(surface, circle.point(theta), hint.uv).unwrap_or_else(|| start(theta));
        solve(uv, theta)
    })
}

/// Angle folded into (−π, π].
fn wrap_angle(a: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let r = a.rem_euclid(two_pi);
    if r > std::f64::consts::PI {
        r - two_pi
    } else {
        r
    }
}
