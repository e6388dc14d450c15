//! Simple pcurves: straight segments and polylines in a face's parameter plane. Native patch
//! boundaries are straight lines in (u,v), and a polyline carries sampled pcurves.

use super::{Curve2d, Range1};
use glam::DVec2;

/// Straight segment `a → b` in the parameter plane, over the parameter range `range`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line2d {
    pub a: DVec2,
    pub b: DVec2,
    pub range: Range1,
}

impl Curve2d for Line2d {
    fn range(&self) -> Range1 {
        self.range
    }
    fn point(&self, t: f64) -> DVec2 {
        let s = (t - self.range.0) / (self.range.1 - self.range.0);
        self.a.lerp(self.b, s)
    }
    fn derivs(&self, t: f64) -> (DVec2, DVec2, DVec2) {
        let d = (self.b - self.a) / (self.range.1 - self.range.0);
        (self.point(t), d, DVec2::ZERO)
    }
}

/// Piecewise linear curve through `points` at increasing parameters `params`.
#[derive(Clone, Debug, PartialEq)]
pub struct PolyCurve2d {
    pub params: Vec<f64>,
    pub points: Vec<DVec2>,
}

impl PolyCurve2d {
    fn segment(&self, t: f64) -> usize {
        let n = self.params.len();
        match self.params.partition_point(|&p| p <= t) {
            0 => 0,
            i if i >= n => n - 2,
            i => i - 1,
        }
    }
}

impl Curve2d for PolyCurve2d {
    fn range(&self) -> Range1 {
        (self.params[0], self.params[self.params.len() - 1])
    }
    fn point(&self, t: f64) -> DVec2 {
        self.derivs(t).0
    }
    fn derivs(&self, t: f64) -> (DVec2, DVec2, DVec2) {
        let i = self.segment(t);
        let (t0, t1) = (self.params[i], self.params[i + 1]);
        let d = (self.points[i + 1] - self.points[i]) / (t1 - t0);
        (self.points[i] + d * (t - t0), d, DVec2::ZERO)
    }
}
