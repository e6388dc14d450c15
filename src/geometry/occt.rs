//! The geometry traits for the OpenCASCADE handles of `tetrafoil-occt`.
//!
//! Projection uses OCCT's own algorithms (ShapeAnalysis_Curve / ShapeAnalysis_Surface) and the
//! circle–surface intersection uses GeomAPI_IntCS on a `Geom_Circle`; each falls back to the
//! generic Newton methods of [`super::newton`] when OCCT finds nothing or a worse answer.
//!
//! # Evaluation failures
//!
//! OCCT may refuse to evaluate at a parameter (an offset surface at a singular point, a curve
//! evaluated outside its definition): the bridge returns `None` there. The traits return plain
//! values, so the adapters never panic and never return NaN: they evaluate instead at a point
//! nudged towards the middle of the parameter domain (fractions 1e-9, 1e-7, 1e-5, 1e-3, 0.1,
//! 0.5 of the way, then the middle itself), and if all of those fail return the origin with
//! zero derivatives. A zero derivative makes Newton iterations stop (`None`) rather than wander,
//! and the orientation integrals count such a point as a pole (zero area element).

use super::circle::nearest_hit;
use super::newton;
use super::{
    Circle, CircleHint, CircleHit, Curve, Curve2d, CurveDerivs, Range1, Surface, SurfaceBounds,
    SurfaceDerivs,
};
use glam::{DVec2, DVec3};
use tetrafoil_occt::{OccCurve, OccPcurve, OccSurface};

/// Fractions of the way to the domain's middle tried when OCCT cannot evaluate at a point.
const NUDGES: [f64; 6] = [1e-9, 1e-7, 1e-5, 1e-3, 0.1, 0.5];

fn v3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// Evaluate `f` at `x`, else at points nudged towards `mid`, else at `mid`.
fn robust_eval<X: Copy, T>(
    x: X,
    mid: X,
    lerp: impl Fn(X, X, f64) -> X,
    f: impl Fn(X) -> Option<T>,
) -> Option<T> {
    f(x).or_else(|| NUDGES.iter().find_map(|&s| f(lerp(x, mid, s))))
        .or_else(|| f(mid))
}

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

fn finite3(a: [f64; 3]) -> bool {
    a.iter().all(|x| x.is_finite())
}

impl Curve for OccCurve {
    fn range(&self) -> Range1 {
        let [a, b] = OccCurve::range(self);
        (a, b)
    }
    fn period(&self) -> Option<f64> {
        OccCurve::period(self)
    }
    fn point(&self, t: f64) -> DVec3 {
        Curve::derivs(self, t).p
    }
    fn derivs(&self, t: f64) -> CurveDerivs {
        let m = mid(Curve::range(self));
        let eval = |t: f64| {
            OccCurve::derivs(self, t).filter(|d| finite3(d.p) && finite3(d.d1) && finite3(d.d2))
        };
        match robust_eval(t, m, |a, b, s| a + s * (b - a), eval) {
            Some(d) => CurveDerivs {
                p: v3(d.p),
                d1: v3(d.d1),
                d2: v3(d.d2),
            },
            None => CurveDerivs {
                p: DVec3::ZERO,
                d1: DVec3::ZERO,
                d2: DVec3::ZERO,
            },
        }
    }
    /// OCCT's projection (ShapeAnalysis_Curve); when it finds nothing, or a point farther
    /// than [`ON_SURFACE`] × the curve's size from `p`, the generic Newton runs too and the
    /// closer answer wins.
    fn closest_parameter(&self, p: DVec3, hint: Option<f64>) -> Option<f64> {
        let r = Curve::range(self);
        let at = |t: f64| Curve::point(self, t);
        let scale = at(r.0)
            .distance(at(mid(r)))
            .max(at(r.1).distance(at(mid(r))))
            .max(1e-300);
        let occt = OccCurve::project(self, p.to_array(), hint)
            .filter(|(t, d)| t.is_finite() && d.is_finite())
            .map(|(t, _)| (t, at(t).distance(p)));
        if let Some((t, d)) = occt {
            if d <= ON_SURFACE * scale {
                return Some(t);
            }
        }
        let newton = newton::closest_parameter_3d(self, p, hint).map(|t| (t, at(t).distance(p)));
        closer(occt, newton)
    }
}

impl Curve2d for OccPcurve {
    fn range(&self) -> Range1 {
        let [a, b] = OccPcurve::range(self);
        (a, b)
    }
    fn point(&self, t: f64) -> DVec2 {
        Curve2d::derivs(self, t).0
    }
    fn derivs(&self, t: f64) -> (DVec2, DVec2, DVec2) {
        let m = mid(Curve2d::range(self));
        let ok = |a: [f64; 2]| a.iter().all(|x| x.is_finite());
        let eval = |t: f64| OccPcurve::derivs(self, t).filter(|d| ok(d.p) && ok(d.d1) && ok(d.d2));
        match robust_eval(t, m, |a, b, s| a + s * (b - a), eval) {
            Some(d) => (
                DVec2::from_array(d.p),
                DVec2::from_array(d.d1),
                DVec2::from_array(d.d2),
            ),
            None => (DVec2::ZERO, DVec2::ZERO, DVec2::ZERO),
        }
    }
}

/// A pcurve whose own parameter differs from its edge's: maps the edge parameter linearly
/// onto the pcurve's range (OCCT edges that are not "same parameter"). The map is exact at the
/// ends and close inside; [`crate::model::Model::use_uv`] refines interior points by projection.
pub struct ReparamPcurve {
    pub inner: OccPcurve,
    /// The edge's range: the parameter callers use.
    pub edge_range: Range1,
}

impl ReparamPcurve {
    fn map(&self, t: f64) -> (f64, f64) {
        let (a, b) = Curve2d::range(&self.inner);
        let (e0, e1) = self.edge_range;
        let k = (b - a) / (e1 - e0);
        (a + (t - e0) * k, k)
    }
}

impl Curve2d for ReparamPcurve {
    fn range(&self) -> Range1 {
        self.edge_range
    }
    fn point(&self, t: f64) -> DVec2 {
        Curve2d::point(&self.inner, self.map(t).0)
    }
    fn derivs(&self, t: f64) -> (DVec2, DVec2, DVec2) {
        let (s, k) = self.map(t);
        let (p, d1, d2) = Curve2d::derivs(&self.inner, s);
        (p, d1 * k, d2 * k * k)
    }
}

fn bounds_of(s: &OccSurface) -> SurfaceBounds {
    let [u0, u1] = s.u_range();
    let [v0, v1] = s.v_range();
    SurfaceBounds {
        u: (u0, u1),
        v: (v0, v1),
        u_period: s.u_period(),
        v_period: s.v_period(),
    }
}

/// Size of the face's patch in space: the longest diagonal of its parameter rectangle.
fn surface_scale(s: &OccSurface, b: &SurfaceBounds) -> f64 {
    let c = |u, v| Surface::point(s, DVec2::new(u, v));
    c(b.u.0, b.v.0)
        .distance(c(b.u.1, b.v.1))
        .max(c(b.u.1, b.v.0).distance(c(b.u.0, b.v.1)))
        .max(1e-300)
}

impl Surface for OccSurface {
    fn bounds(&self) -> SurfaceBounds {
        bounds_of(self)
    }
    fn point(&self, uv: DVec2) -> DVec3 {
        Surface::derivs(self, uv).p
    }
    fn derivs(&self, uv: DVec2) -> SurfaceDerivs {
        let b = bounds_of(self);
        let m = DVec2::new(mid(b.u), mid(b.v));
        let eval = |uv: DVec2| {
            OccSurface::derivs(self, uv.x, uv.y).filter(|d| {
                [d.p, d.du, d.dv, d.duu, d.duv, d.dvv]
                    .iter()
                    .all(|a| finite3(*a))
            })
        };
        match robust_eval(uv, m, |a, b, s| a.lerp(b, s), eval) {
            Some(d) => SurfaceDerivs {
                p: v3(d.p),
                du: v3(d.du),
                dv: v3(d.dv),
                duu: v3(d.duu),
                duv: v3(d.duv),
                dvv: v3(d.dvv),
            },
            None => SurfaceDerivs {
                p: DVec3::ZERO,
                du: DVec3::ZERO,
                dv: DVec3::ZERO,
                duu: DVec3::ZERO,
                duv: DVec3::ZERO,
                dvv: DVec3::ZERO,
            },
        }
    }
    /// OCCT's projection (ShapeAnalysis_Surface, from the hint when given), folded into the
    /// face's bounds and polished by a few local Gauss–Newton steps. When OCCT finds nothing, or
    /// a point farther than [`ON_SURFACE`] × the face's size from `p`, the generic Newton
    /// projection runs too and the closer answer wins.
    fn closest_uv(&self, p: DVec3, hint: Option<DVec2>) -> Option<DVec2> {
        let b = bounds_of(self);
        let dist = |uv: DVec2| Surface::point(self, uv).distance(p);
        let occt = OccSurface::project(self, p.to_array(), hint.map(|h| h.to_array()))
            .map(DVec2::from_array)
            .filter(|uv| uv.is_finite())
            .map(|uv| b.normalise(uv))
            .map(|uv| match newton::project_local(self, p, uv) {
                Some(q) if dist(q) < dist(uv) => (q, dist(q)),
                _ => (uv, dist(uv)),
            });
        if let Some((uv, d)) = occt {
            if d <= ON_SURFACE * surface_scale(self, &b) {
                return Some(uv);
            }
        }
        let newton = newton::closest_uv(self, p, hint).map(|uv| (uv, dist(uv)));
        closer(occt, newton)
    }
    /// GeomAPI_IntCS on the circle: of the hits inside the face's parameter range, the one
    /// nearest the hint's angle within its window; the generic Newton when there is none.
    fn intersect_circle(&self, circle: &Circle, hint: &CircleHint) -> Option<CircleHit> {
        // Newton from the front's hint usually lands first. When it does not: on a plane,
        // cylinder, cone, sphere or torus GeomAPI_IntCS is closed-form and cheap, so it sees
        // the whole circle; on other surfaces it sorts boxes over the whole surface on every
        // call (1-2 ms on trimmed B-spline faces) and over the corpus none of its hits was ever
        // kept (outside the window or the face), so the Newton search from projections across
        // the window answers instead (ONERA domain surfaces 0.83 s → 0.38 s).
        if let Some(hit) = newton::intersect_circle_near_hint(self, circle, hint) {
            return Some(hit);
        }
        if !self.is_elementary() {
            return newton::intersect_circle(self, circle, hint);
        }
        let b = bounds_of(self);
        let hits: Vec<CircleHit> = OccSurface::intersect_circle(
            self,
            circle.centre.to_array(),
            circle.axis().to_array(),
            circle.x_axis.to_array(),
            circle.radius,
        )
        .unwrap_or_default()
        .iter()
        .map(|h| CircleHit {
            uv: DVec2::from_array(h.uv),
            theta: h.theta,
            point: v3(h.point),
        })
        .collect();
        match nearest_hit(&hits, &b, hint) {
            Some(hit) => Some(CircleHit {
                point: Surface::point(self, hit.uv),
                ..hit
            }),
            // IntCS saw the whole circle: hits outside the window or the face's range mean
            // there is no ideal point here, and a Newton search would not find one either.
            None if !hits.is_empty() => None,
            // IntCS misses some tangential and near-degenerate meetings: search from the hint.
            None => newton::intersect_circle(self, circle, hint),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::circle::wrap_angle;
    use super::*;

    #[test]
    fn angles_wrap_into_half_open_interval() {
        let pi = std::f64::consts::PI;
        assert!((wrap_angle(3.0 * pi) - pi).abs() < 1e-12);
        assert!((wrap_angle(-0.5) + 0.5).abs() < 1e-12);
        assert!((wrap_angle(2.0 * pi + 0.25) - 0.25).abs() < 1e-12);
    }
    #[test]
    fn robust_eval_nudges_then_gives_up() {
        let f = |x: f64| (x > 0.5).then_some(x);
        let r = robust_eval(0.0, 1.0, |a, b, s| a + s * (b - a), f);
        assert_eq!(r, Some(1.0));
        let near = robust_eval(0.4, 1.0, |a, b, s| a + s * (b - a), f);
        assert!((near.unwrap() - 0.7).abs() < 1e-12);
        let none = robust_eval(0.0, 1.0, |a, b, s| a + s * (b - a), |_: f64| None::<f64>);
        assert!(none.is_none());
    }
}
