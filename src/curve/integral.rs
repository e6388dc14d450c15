//! The spacing integral I(t) = ∫ |C'(t)| / δ(C(t)) dt along one curve, tabulated on adaptively
//! refined pieces so it can be inverted: node k of n sits where I(t) = k·I_total/n.

use crate::geometry::Curve;
use glam::DVec3;

const GL3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];
/// Initial pieces before adaptive refinement.
const START_PIECES: usize = 16;
const MAX_DEPTH: u32 = 10;
/// Accepted error of the whole integral, relative: a tenth of a segment on a 100-segment edge,
/// below what rounding to whole segments needs (1e-4 cost a third more spacing queries on
/// nist_ctc_01 for the same nodes). Each piece gets the share of it that its width has of the
/// range, so the spacing's kinks (a min over sources) do not drive every piece to the full
/// depth.
const REL_TOL: f64 = 1e-3;
/// Floor of the accepted error per piece, in segments.
const ABS_TOL: f64 = 1e-9;

pub struct SpacingIntegral<'a, F: Fn(DVec3) -> f64> {
    curve: &'a dyn Curve,
    spacing: F,
    /// Piece boundaries in t and the integral up to each boundary.
    knots: Vec<f64>,
    cumulative: Vec<f64>,
}

impl<'a, F: Fn(DVec3) -> f64> SpacingIntegral<'a, F> {
    pub fn new(curve: &'a dyn Curve, range: (f64, f64), spacing: F) -> Self {
        let mut s = SpacingIntegral {
            curve,
            spacing,
            knots: vec![range.0],
            cumulative: vec![0.0],
        };
        let h = (range.1 - range.0) / START_PIECES as f64;
        let pieces: Vec<(f64, f64, f64)> = (0..START_PIECES)
            .map(|k| {
                let a = range.0 + h * k as f64;
                let b = if k + 1 == START_PIECES {
                    range.1
                } else {
                    a + h
                };
                (a, b, s.gauss(a, b))
            })
            .collect();
        let estimate: f64 = pieces.iter().map(|p| p.2.abs()).sum();
        let width = (range.1 - range.0).abs().max(1e-300);
        for (a, b, whole) in pieces {
            let tol = (REL_TOL * estimate * (b - a).abs() / width).max(ABS_TOL);
            s.refine(a, b, whole, 0, tol);
        }
        s
    }

    /// Integrand |C'(t)|/δ(C(t)).
    fn density(&self, t: f64) -> f64 {
        let d = self.curve.derivs(t);
        d.d1.length() / (self.spacing)(d.p)
    }

    fn gauss(&self, a: f64, b: f64) -> f64 {
        let (m, r) = (0.5 * (a + b), 0.5 * (b - a));
        GL3.iter()
            .map(|&(x, w)| w * r * self.density(m + r * x))
            .sum()
    }

    /// Split [a,b] until the two halves agree with the whole, then record it.
    /// `tol` is the error accepted on [a,b]; each half gets half of it.
    fn refine(&mut self, a: f64, b: f64, whole: f64, depth: u32, tol: f64) {
        let m = 0.5 * (a + b);
        let (left, right) = (self.gauss(a, m), self.gauss(m, b));
        let split = left + right;
        if depth < MAX_DEPTH && (split - whole).abs() > tol {
            let half = (0.5 * tol).max(ABS_TOL);
            self.refine(a, m, left, depth + 1, half);
            self.refine(m, b, right, depth + 1, half);
        } else {
            let last = *self.cumulative.last().unwrap_or(&0.0);
            self.knots.push(b);
            self.cumulative.push(last + split);
        }
    }

    /// ∫ ds/δ over the whole range.
    pub fn total(&self) -> f64 {
        *self.cumulative.last().unwrap_or(&0.0)
    }

    /// Parameters of n + 1 nodes at equal increments of the integral, ends included.
    pub fn equal_increments(&self, n: usize) -> Vec<f64> {
        let total = self.total();
        let mut out = Vec::with_capacity(n + 1);
        out.push(self.knots[0]);
        for k in 1..n {
            out.push(self.invert(total * k as f64 / n as f64));
        }
        out.push(*self.knots.last().unwrap_or(&self.knots[0]));
        out
    }

    /// t with I(t) = target: find the piece, then Newton with a bisection safeguard.
    fn invert(&self, target: f64) -> f64 {
        let i = self
            .cumulative
            .partition_point(|&c| c < target)
            .clamp(1, self.knots.len() - 1);
        let (mut lo, mut hi) = (self.knots[i - 1], self.knots[i]);
        let base = self.cumulative[i - 1];
        let mut t = lo + (hi - lo) * (target - base) / (self.cumulative[i] - base).max(1e-300);
        for _ in 0..50 {
            let f = base + self.gauss(self.knots[i - 1], t) - target;
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let d = self.density(t);
            let next = if d > 0.0 { t - f / d } else { 0.5 * (lo + hi) };
            let next = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            // 1e-10 of a piece places nodes far below any mesh tolerance; at 1e-14 the kinks
            // of δ (min of sources, linear grading) left Newton to bisection, and inversion
            // took 60% of the curve stage on nist_ctc_01.
            if (next - t).abs() <= 1e-10 * (self.knots[i] - self.knots[i - 1]).abs() {
                return next;
            }
            t = next;
        }
        t
    }
}
