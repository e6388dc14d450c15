//! The geometry interface: every geometric question the mesher asks goes through the traits
//! [`Curve`], [`Curve2d`] and [`Surface`]. Native (Ferguson) and foreign (OpenCASCADE, or any
//! kernel loaded as a [`plugin`]) entities all implement them, so one model can mix them.
//!
//! Projection and circle–surface intersection have generic Newton defaults (in [`newton`]) that
//! work for any implementor; a foreign kernel may override them with its own algorithms.

mod circle;
mod faults;
pub mod kernel;
mod linear;
pub mod native;
pub mod newton;
#[cfg(feature = "occt")]
pub mod occt;
pub mod plugin;
mod xyz;

pub use circle::{Circle, CircleHint, CircleHit};
pub use faults::FaultLog;
pub use linear::{Line2d, PolyCurve2d};
pub use xyz::{Coord, Xyz};

use glam::{DVec2, DVec3};

/// A closed parameter interval `[lo, hi]`.
pub type Range1 = (f64, f64);

/// Value, first and second derivatives of a curve at one parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveDerivs {
    pub p: DVec3,
    pub d1: DVec3,
    pub d2: DVec3,
}

/// Value, first and second derivatives of a surface at one (u,v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceDerivs {
    pub p: DVec3,
    pub du: DVec3,
    pub dv: DVec3,
    pub duu: DVec3,
    pub duv: DVec3,
    pub dvv: DVec3,
}

impl SurfaceDerivs {
    /// Unnormalised normal `Su × Sv` (its length is the area element).
    pub fn normal_raw(&self) -> DVec3 {
        self.du.cross(self.dv)
    }

    /// First fundamental form `(E, F, G)`: maps a (u,v) step to its squared 3-D length.
    pub fn first_form(&self) -> (f64, f64, f64) {
        (
            self.du.dot(self.du),
            self.du.dot(self.dv),
            self.dv.dot(self.dv),
        )
    }
}

/// A 3-D curve `C(t)`, `t` in [`Curve::range`].
pub trait Curve: Send + Sync {
    fn range(&self) -> Range1;
    /// Period of the parameter when the curve is closed and periodic (a full circle).
    fn period(&self) -> Option<f64> {
        None
    }
    fn point(&self, t: f64) -> DVec3;
    /// Value, first and second derivative.
    fn derivs(&self, t: f64) -> CurveDerivs;
    /// Parameter of the point of the curve closest to `p`; `hint` is a nearby parameter.
    /// `None` when the iteration does not converge.
    fn closest_parameter(&self, p: DVec3, hint: Option<f64>) -> Option<f64> {
        newton::closest_parameter_3d(self, p, hint)
    }
}

/// A curve in a face's parameter plane (a pcurve): `c(t) = (u(t), v(t))`.
pub trait Curve2d: Send + Sync {
    fn range(&self) -> Range1;
    fn point(&self, t: f64) -> DVec2;
    /// Value, first and second derivative.
    fn derivs(&self, t: f64) -> (DVec2, DVec2, DVec2);
    fn closest_parameter(&self, p: DVec2, hint: Option<f64>) -> Option<f64> {
        newton::closest_parameter_2d(self, p, hint)
    }
}

/// Parameter rectangle of a surface and its periodicity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceBounds {
    pub u: Range1,
    pub v: Range1,
    /// Period in u when the surface closes on itself in u (cylinder, torus).
    pub u_period: Option<f64>,
    pub v_period: Option<f64>,
}

impl SurfaceBounds {
    pub fn rect(u: Range1, v: Range1) -> Self {
        SurfaceBounds {
            u,
            v,
            u_period: None,
            v_period: None,
        }
    }

    /// Clamp (non-periodic directions) or wrap into the base interval (periodic directions).
    pub fn normalise(&self, uv: DVec2) -> DVec2 {
        DVec2::new(
            fold(uv.x, self.u, self.u_period),
            fold(uv.y, self.v, self.v_period),
        )
    }

    /// Size of the parameter rectangle, used to scale tolerances.
    pub fn extent(&self) -> DVec2 {
        DVec2::new(self.u.1 - self.u.0, self.v.1 - self.v.0)
    }
}

fn fold(x: f64, (lo, hi): Range1, period: Option<f64>) -> f64 {
    match period {
        Some(p) if p > 0.0 => lo + (x - lo).rem_euclid(p),
        _ => x.clamp(lo, hi),
    }
}

/// A parametric surface `S(u,v)`.
pub trait Surface: Send + Sync {
    fn bounds(&self) -> SurfaceBounds;
    fn point(&self, uv: DVec2) -> DVec3;
    /// Value, first and second derivatives.
    fn derivs(&self, uv: DVec2) -> SurfaceDerivs;
    /// (u,v) of the point of the surface closest to `p`; `hint` is a nearby (u,v).
    /// `None` when the iteration does not converge.
    fn closest_uv(&self, p: DVec3, hint: Option<DVec2>) -> Option<DVec2> {
        newton::closest_uv(self, p, hint)
    }
    /// A point of the surface on `circle`, near the angle and (u,v) of `hint`.
    /// `None` when there is none within the hint's angular window.
    fn intersect_circle(&self, circle: &Circle, hint: &CircleHint) -> Option<CircleHit> {
        newton::intersect_circle(self, circle, hint)
    }
    /// Unit normal `Su × Sv / |Su × Sv|` (zero at a degenerate point such as a pole).
    fn normal(&self, uv: DVec2) -> DVec3 {
        self.derivs(uv).normal_raw().normalize_or_zero()
    }
    /// The concrete surface, for callers that must tell native from foreign geometry in a
    /// mixed model (a repaired CAD face); `None` when the type does not say.
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        None
    }
}

/// Exact sign of the orientation of `c` relative to the directed line `a → b` (positive when
/// `c` is to the left), by robust's adaptive predicate.
pub fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let k = |p: DVec2| robust::Coord { x: p.x, y: p.y };
    robust::orient2d(k(a), k(b), k(c))
}
