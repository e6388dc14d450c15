//! The spacing integral I(t) = ∫ |C'(t)| / δ(C(t)) dt along one curve, tabulated so it can be
//! inverted: node k of n sits where I(t) = k·I_total/n.
//!
//! The curve is walked in steps of half the local spacing (in arc length), each integrated by
//! Simpson's rule. Steps that follow δ cannot miss a dip of it: the spacing function grows at
//! a bounded rate away from every source (the curvature and proximity limits at 0.25 per unit
//! length), so over half a spacing it changes by a few percent at most, and a step whose
//! density changes by more than half is halved. A fixed subdivision refined where halves
//! disagree needed about 50 spacing queries per segment on nist_ctc_01, and could step over a
//! narrow dip whose Gauss points all lay outside it; the walk needs about four.

use crate::geometry::Curve;
use glam::DVec3;

/// Step length as a fraction of the local spacing.
const STEP: f64 = 0.5;
/// At least this many steps per curve, so its shape is followed even where δ is large.
const MIN_STEPS: usize = 4;
/// A step whose end densities differ by more than this fraction of the larger is halved.
const MAX_CHANGE: f64 = 0.5;
/// Halvings allowed per step, and steps allowed per curve (a spacing of nearly zero, or a
/// parameter speed of nearly zero, must not loop forever).
const MAX_HALVINGS: u32 = 30;
const MAX_STEPS: usize = 1 << 22;

/// One Simpson step: its parameter interval and the density at its start, middle and end.
#[derive(Clone, Copy, Debug)]
struct Step {
    t0: f64,
    t1: f64,
    f0: f64,
    fm: f64,
    f1: f64,
}

impl Step {
    /// ∫ of the density's quadratic interpolant from t0 to t0 + s·(t1 − t0), s in [0, 1].
    fn partial(&self, s: f64) -> f64 {
        let h = self.t1 - self.t0;
        // q(s) = f0 + b s + c s², through (0, f0), (½, fm), (1, f1).
        let b = -3.0 * self.f0 + 4.0 * self.fm - self.f1;
        let c = 2.0 * self.f0 - 4.0 * self.fm + 2.0 * self.f1;
        h * (self.f0 * s + b * s * s / 2.0 + c * s * s * s / 3.0)
    }

    fn whole(&self) -> f64 {
        (self.t1 - self.t0) * (self.f0 + 4.0 * self.fm + self.f1) / 6.0
    }
}

pub struct SpacingIntegral {
    range: (f64, f64),
    steps: Vec<Step>,
    /// The integral up to the start of each step, and the total at the end.
    cumulative: Vec<f64>,
}

impl SpacingIntegral {
    pub fn new(curve: &dyn Curve, range: (f64, f64), spacing: impl Fn(DVec3) -> f64) -> Self {
        let density = |t: f64| -> (f64, f64) {
            let d = curve.derivs(t);
            let delta = spacing(d.p);
            (d.d1.length() / delta, delta / d.d1.length().max(1e-300))
        };
        let (a, b) = range;
        let max_dt = (b - a) / MIN_STEPS as f64;
        let mut steps = Vec::new();
        let mut cumulative = vec![0.0];
        let (mut t, (mut f, mut dt_per_spacing)) = (a, density(a));
        while t < b && steps.len() < MAX_STEPS {
            let mut dt = (STEP * dt_per_spacing).min(max_dt).min(b - t);
            let mut halvings = 0;
            let step = loop {
                let t1 = if dt >= b - t { b } else { t + dt };
                let (fm, _) = density(0.5 * (t + t1));
                let (f1, next_dt) = density(t1);
                let change = (f1 - f).abs().max((fm - f).abs());
                if change <= MAX_CHANGE * f.max(f1).max(fm) || halvings >= MAX_HALVINGS {
                    dt_per_spacing = next_dt;
                    break Step {
                        t0: t,
                        t1,
                        f0: f,
                        fm,
                        f1,
                    };
                }
                dt *= 0.5;
                halvings += 1;
            };
            let last = *cumulative.last().unwrap_or(&0.0);
            cumulative.push(last + step.whole());
            t = step.t1;
            f = step.f1;
            steps.push(step);
        }
        SpacingIntegral {
            range,
            steps,
            cumulative,
        }
    }

    /// ∫ ds/δ over the whole range.
    pub fn total(&self) -> f64 {
        *self.cumulative.last().unwrap_or(&0.0)
    }

    /// Parameters of n + 1 nodes at equal increments of the integral, ends included.
    pub fn equal_increments(&self, n: usize) -> Vec<f64> {
        let (Some(first), Some(last)) = (self.steps.first(), self.steps.last()) else {
            return vec![self.range.0; n + 1];
        };
        let total = self.total();
        let mut out = Vec::with_capacity(n + 1);
        out.push(first.t0);
        for k in 1..n {
            out.push(self.invert(total * k as f64 / n as f64));
        }
        out.push(last.t1);
        out
    }

    /// t with I(t) = target: find the step, then Newton (safeguarded by bisection) on its
    /// quadratic density, which costs no spacing query.
    fn invert(&self, target: f64) -> f64 {
        let i = self
            .cumulative
            .partition_point(|&c| c < target)
            .clamp(1, self.steps.len())
            - 1;
        let step = &self.steps[i];
        let want = target - self.cumulative[i];
        let (mut lo, mut hi) = (0.0, 1.0);
        let mut s = (want / step.whole().max(1e-300)).clamp(0.0, 1.0);
        for _ in 0..60 {
            let g = step.partial(s) - want;
            if g > 0.0 {
                hi = s;
            } else {
                lo = s;
            }
            let b = -3.0 * step.f0 + 4.0 * step.fm - step.f1;
            let c = 2.0 * step.f0 - 4.0 * step.fm + 2.0 * step.f1;
            let slope = (step.t1 - step.t0) * (step.f0 + b * s + c * s * s);
            let next = if slope > 0.0 {
                s - g / slope
            } else {
                0.5 * (lo + hi)
            };
            let next = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if (next - s).abs() <= 1e-12 {
                s = next;
                break;
            }
            s = next;
        }
        step.t0 + s * (step.t1 - step.t0)
    }
}
