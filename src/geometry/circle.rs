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
