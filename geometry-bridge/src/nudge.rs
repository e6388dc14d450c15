//! Evaluation that answers wherever it can. OCCT may refuse to evaluate at a parameter (an
//! offset surface at a singular point, a curve evaluated just outside its definition) or
//! answer a non-finite value; the answer is then taken at a point nudged towards the middle of
//! the parameter domain (fractions 1e-9, 1e-7, 1e-5, 1e-3, 0.1, 0.5 of the way, then the
//! middle itself). `None` only when every one of those fails. The core's OCCT adapter and the
//! OCCT plugin both evaluate this way.

use crate::{CurveDerivs, OccCurve, OccPcurve, OccSurface, PcurveDerivs, SurfaceDerivs};

/// Fractions of the way to the domain's middle tried when OCCT cannot evaluate at a point.
const NUDGES: [f64; 6] = [1e-9, 1e-7, 1e-5, 1e-3, 0.1, 0.5];

/// `f` at `x`, else at points nudged towards `mid`, else at `mid`.
fn nudged<X: Copy, T>(
    x: X,
    mid: X,
    lerp: impl Fn(X, X, f64) -> X,
    f: impl Fn(X) -> Option<T>,
) -> Option<T> {
    f(x).or_else(|| NUDGES.iter().find_map(|&s| f(lerp(x, mid, s))))
        .or_else(|| f(mid))
}

fn lerp(a: f64, b: f64, s: f64) -> f64 {
    a + s * (b - a)
}

fn finite<const N: usize>(a: &[[f64; N]]) -> bool {
    a.iter().flatten().all(|x| x.is_finite())
}

impl OccCurve {
    /// Point and derivatives at `t`, nudged inwards where OCCT refuses.
    pub fn derivs_nudged(&self, t: f64) -> Option<CurveDerivs> {
        let [a, b] = self.range();
        let eval = |t| self.derivs(t).filter(|d| finite(&[d.p, d.d1, d.d2]));
        nudged(t, 0.5 * (a + b), lerp, eval)
    }
}

impl OccPcurve {
    /// Point and derivatives at `t` (the pcurve's own parameter), nudged inwards where OCCT
    /// refuses.
    pub fn derivs_nudged(&self, t: f64) -> Option<PcurveDerivs> {
        let [a, b] = self.range();
        let eval = |t| self.derivs(t).filter(|d| finite(&[d.p, d.d1, d.d2]));
        nudged(t, 0.5 * (a + b), lerp, eval)
    }

    /// The pcurve's own parameter at the edge parameter `t`, and its rate `ds/dt`: the pcurve
    /// maps linearly onto the edge's range when OCCT's pcurve range differs from the edge's
    /// (an edge that is not "same parameter"; exact at the ends, close inside).
    pub fn edge_parameter(&self, edge: [f64; 2], t: f64) -> (f64, f64) {
        let [a, b] = self.range();
        let k = (b - a) / (edge[1] - edge[0]);
        (a + (t - edge[0]) * k, k)
    }

    /// Whether the pcurve is parametrised like an edge over `edge` (within 1e-9).
    pub fn same_parameter(&self, edge: [f64; 2]) -> bool {
        let own = self.range();
        let tol = 1e-9 * (edge[1] - edge[0]).abs().max(1.0);
        (own[0] - edge[0]).abs() <= tol && (own[1] - edge[1]).abs() <= tol
    }
}

impl OccSurface {
    /// Point and derivatives at (u, v), nudged inwards where OCCT refuses.
    pub fn derivs_nudged(&self, u: f64, v: f64) -> Option<SurfaceDerivs> {
        let ([u0, u1], [v0, v1]) = (self.u_range(), self.v_range());
        let mid = [0.5 * (u0 + u1), 0.5 * (v0 + v1)];
        let eval = |uv: [f64; 2]| {
            self.derivs(uv[0], uv[1])
                .filter(|d| finite(&[d.p, d.du, d.dv, d.duu, d.duv, d.dvv]))
        };
        let lerp2 = |a: [f64; 2], b: [f64; 2], s| [lerp(a[0], b[0], s), lerp(a[1], b[1], s)];
        nudged([u, v], mid, lerp2, eval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nudging_moves_inwards_then_gives_up() {
        let f = |x: f64| (x > 0.5).then_some(x);
        assert_eq!(nudged(0.0, 1.0, lerp, f), Some(1.0));
        let near = nudged(0.4, 1.0, lerp, f);
        assert!((near.unwrap() - 0.7).abs() < 1e-12);
        assert!(nudged(0.0, 1.0, lerp, |_: f64| None::<f64>).is_none());
    }
}
