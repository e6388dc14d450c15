//! The geometry traits for the OpenCASCADE handles of `tetrafoil-occt`.
//!
//! Projection uses OCCT's own algorithms (ShapeAnalysis_Curve / ShapeAnalysis_Surface) and the
//! circle–surface intersection uses GeomAPI_IntCS on a `Geom_Circle`; [`super::kernel`] decides
//! what to keep of them (the same way as for plugins).
//!
//! # Evaluation failures
//!
//! OCCT may refuse to evaluate at a parameter (an offset surface at a singular point, a curve
//! evaluated outside its definition): the bridge returns `None` there. The traits return plain
//! values, so the adapters never panic and never return NaN: they evaluate instead at a point
//! nudged towards the middle of the parameter domain (the bridge's `derivs_nudged`), and if
//! that fails too return the origin with zero derivatives. A zero derivative makes Newton iterations stop (`None`) rather than wander,
//! and the orientation integrals count such a point as a pole (zero area element).

use super::kernel;
use super::{
    Circle, CircleHint, CircleHit, Curve, Curve2d, CurveDerivs, Range1, Surface, SurfaceBounds,
    SurfaceDerivs,
};
use glam::{DVec2, DVec3};
use tetrafoil_occt::{OccCurve, OccPcurve, OccSurface};

fn v3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
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
        match self.derivs_nudged(t) {
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
    /// OCCT's projection (ShapeAnalysis_Curve), checked by [`kernel::closest_parameter`].
    fn closest_parameter(&self, p: DVec3, hint: Option<f64>) -> Option<f64> {
        let occt = OccCurve::project(self, p.to_array(), hint)
            .filter(|(_, d)| d.is_finite())
            .map(|(t, _)| t);
        kernel::closest_parameter(self, p, hint, occt)
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
        match self.derivs_nudged(t) {
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

impl Curve2d for ReparamPcurve {
    fn range(&self) -> Range1 {
        self.edge_range
    }
    fn point(&self, t: f64) -> DVec2 {
        self.derivs(t).0
    }
    fn derivs(&self, t: f64) -> (DVec2, DVec2, DVec2) {
        let (e0, e1) = self.edge_range;
        let (s, k) = self.inner.edge_parameter([e0, e1], t);
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

impl Surface for OccSurface {
    fn bounds(&self) -> SurfaceBounds {
        bounds_of(self)
    }
    fn point(&self, uv: DVec2) -> DVec3 {
        Surface::derivs(self, uv).p
    }
    fn derivs(&self, uv: DVec2) -> SurfaceDerivs {
        match self.derivs_nudged(uv.x, uv.y) {
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
    /// OCCT's projection (ShapeAnalysis_Surface, from the hint when given), checked by
    /// [`kernel::closest_uv`].
    fn closest_uv(&self, p: DVec3, hint: Option<DVec2>) -> Option<DVec2> {
        let occt = OccSurface::project(self, p.to_array(), hint.map(|h| h.to_array()))
            .map(DVec2::from_array);
        kernel::closest_uv(self, p, hint, occt)
    }
    /// GeomAPI_IntCS on the circle, through [`kernel::intersect_circle`].
    fn intersect_circle(&self, circle: &Circle, hint: &CircleHint) -> Option<CircleHit> {
        // On a plane, cylinder, cone, sphere or torus GeomAPI_IntCS is closed-form and cheap,
        // so it sees the whole circle; on other surfaces it sorts boxes over the whole surface
        // on every call (1-2 ms on trimmed B-spline faces) and over the corpus none of its hits
        // was ever kept (outside the window or the face), so the Newton search from
        // projections across the window answers instead (ONERA domain surfaces 0.83 s → 0.38 s).
        let whole = || {
            self.is_elementary().then(|| {
                OccSurface::intersect_circle(
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
                .collect()
            })
        };
        kernel::intersect_circle(self, circle, hint, whole)
    }
}
