//! Point, line and triangle sources with the FELISA law: the spacing is δ₁ within distance r₁
//! of the source, doubles at r₂, and keeps growing exponentially beyond.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Where a source acts from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum SourceShape {
    Point(DVec3),
    Line(DVec3, DVec3),
    Triangle([DVec3; 3]),
}

/// A source: a shape and its FELISA parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Source {
    pub shape: SourceShape,
    /// Spacing within `r1` of the shape.
    pub delta1: f64,
    pub r1: f64,
    /// Distance at which the spacing has doubled; must exceed `r1`.
    pub r2: f64,
}

impl Source {
    /// The spacing this source asks for at `p`.
    pub fn spacing(&self, p: DVec3) -> f64 {
        felisa(self.shape.distance(p), self.delta1, self.r1, self.r2)
    }
}

/// δ(d) = δ₁ for d ≤ r₁, δ₁ · 2^((d − r₁)/(r₂ − r₁)) beyond.
pub fn felisa(d: f64, delta1: f64, r1: f64, r2: f64) -> f64 {
    if d <= r1 {
        delta1
    } else {
        delta1 * ((d - r1) / (r2 - r1) * std::f64::consts::LN_2).exp()
    }
}

impl SourceShape {
    /// Euclidean distance from `p` to the shape.
    pub fn distance(&self, p: DVec3) -> f64 {
        match self {
            SourceShape::Point(a) => a.distance(p),
            SourceShape::Line(a, b) => distance_to_segment(p, *a, *b),
            SourceShape::Triangle(t) => distance_to_triangle(p, t),
        }
    }
}

pub fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + s * ab)
}

/// Distance to a triangle: to its plane when the foot falls inside, else to the nearest side.
pub fn distance_to_triangle(p: DVec3, t: &[DVec3; 3]) -> f64 {
    let (a, b, c) = (t[0], t[1], t[2]);
    let n = (b - a).cross(c - a);
    let n2 = n.length_squared();
    if n2 > 0.0 {
        let foot = p - n * ((p - a).dot(n) / n2);
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(x, y)| (y - x).cross(foot - x).dot(n) >= 0.0);
        if inside {
            return p.distance(foot);
        }
    }
    distance_to_segment(p, a, b)
        .min(distance_to_segment(p, b, c))
        .min(distance_to_segment(p, c, a))
}
