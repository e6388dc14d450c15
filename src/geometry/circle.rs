//! The 3-D circle of the advancing front's ideal point: all points at distance δ from both ends
//! of a front segment lie on a circle around the segment's midpoint, in the plane normal to it.

use glam::{DVec2, DVec3};

/// A circle in space: `centre + radius (cos θ x_axis + sin θ y_axis)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle {
    pub centre: DVec3,
    pub radius: f64,
    /// Unit vector in the circle's plane, θ = 0.
    pub x_axis: DVec3,
    /// Unit vector in the plane, θ = π/2; `axis = x_axis × y_axis`.
    pub y_axis: DVec3,
}

impl Circle {
    /// Circle with the given centre, unit `axis` and radius; `x_hint` picks θ = 0 (its part
    /// normal to the axis is used; any vector not parallel to the axis will do).
    pub fn new(centre: DVec3, axis: DVec3, radius: f64, x_hint: DVec3) -> Option<Circle> {
        let axis = axis.try_normalize()?;
        let x_axis = (x_hint - axis * x_hint.dot(axis))
            .try_normalize()
            .or_else(|| axis.any_orthonormal_vector().try_normalize())?;
        let y_axis = axis.cross(x_axis);
        Some(Circle {
            centre,
            radius,
            x_axis,
            y_axis,
        })
    }

    /// The circle of points at distance `delta` from both `a` and `b`; `None` when
    /// `delta < |ab|/2` (no such point) or `a == b`. θ = 0 points along `toward`.
    pub fn equidistant(a: DVec3, b: DVec3, delta: f64, toward: DVec3) -> Option<Circle> {
        let half = 0.5 * a.distance(b);
        if half <= 0.0 || delta < half {
            return None;
        }
        let radius = (delta * delta - half * half).sqrt();
        Circle::new(0.5 * (a + b), b - a, radius, toward)
    }

    pub fn axis(&self) -> DVec3 {
        self.x_axis.cross(self.y_axis)
    }

    pub fn point(&self, theta: f64) -> DVec3 {
        self.centre + self.radius * (theta.cos() * self.x_axis + theta.sin() * self.y_axis)
    }

    /// dC/dθ.
    pub fn tangent(&self, theta: f64) -> DVec3 {
        self.radius * (-theta.sin() * self.x_axis + theta.cos() * self.y_axis)
    }
}

/// Where to look for a circle–surface intersection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircleHint {
    /// A (u,v) near the expected intersection.
    pub uv: DVec2,
    /// Expected angle on the circle.
    pub theta: f64,
    /// Solutions with |θ − theta| beyond this are rejected (the paper's bounded arc).
    pub max_dtheta: f64,
}

/// A point where the surface meets the circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircleHit {
    pub uv: DVec2,
    pub theta: f64,
    pub point: DVec3,
}

/// Of a kernel's hits on the whole circle, the one nearest the hint's angle within its window
/// and inside the face's parameter range (ties: nearest the hint's (u,v)); its angle is taken
/// as the hint's plus the wrapped difference and its (u,v) folded into `bounds`. Kernels that
/// intersect the whole circle at once (OpenCASCADE, plugins) share this choice.
pub fn nearest_hit(
    hits: &[CircleHit],
    bounds: &super::SurfaceBounds,
    hint: &CircleHint,
) -> Option<CircleHit> {
    let finite = |h: &&CircleHit| h.uv.is_finite() && h.point.is_finite() && h.theta.is_finite();
    let inside = |x: f64, (lo, hi): (f64, f64), period: Option<f64>| {
        let slack = 1e-9 * (hi - lo).abs().max(1e-300);
        period.is_some() || (x >= lo - slack && x <= hi + slack)
    };
    hits.iter()
        .filter(finite)
        .filter(|h| inside(h.uv.x, bounds.u, bounds.u_period))
        .filter(|h| inside(h.uv.y, bounds.v, bounds.v_period))
        .map(|h| (h, wrap_angle(h.theta - hint.theta)))
        .filter(|(_, dt)| dt.abs() <= hint.max_dtheta)
        .min_by(|a, b| {
            a.1.abs().total_cmp(&b.1.abs()).then_with(|| {
                let d = |h: &CircleHit| h.uv.distance_squared(hint.uv);
                d(a.0).total_cmp(&d(b.0))
            })
        })
        .map(|(h, dt)| CircleHit {
            uv: bounds.normalise(h.uv),
            theta: hint.theta + dt,
            point: h.point,
        })
}

/// Angle folded into (−π, π].
pub fn wrap_angle(a: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let r = a.rem_euclid(two_pi);
    if r > std::f64::consts::PI {
        r - two_pi
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::wrap_angle;

    #[test]
    fn angles_wrap_into_half_open_interval() {
        let pi = std::f64::consts::PI;
        assert!((wrap_angle(3.0 * pi) - pi).abs() < 1e-12);
        assert!((wrap_angle(-0.5) + 0.5).abs() < 1e-12);
        assert!((wrap_angle(2.0 * pi + 0.25) - 0.25).abs() < 1e-12);
    }
}
