//! Piecewise cubic Hermite (Ferguson) curves.

use glam::DVec3;

use crate::error::NativeError;
use crate::hermite::{basis, estimate_tangents, interval};

/// Piecewise cubic Hermite (Ferguson) curve through a sequence of points.
///
/// The parameter is the cumulative chord length, starting at 0 at the first
/// point, so the range is `[0, total chord length]`. Chord length keeps the
/// parameter speed close to 1 (exactly 1 on straight runs), which makes
/// parameter distances meaningful as approximate arc lengths for meshing.
///
/// Segment `k` spans `[t_k, t_{k+1}]` with length `h = t_{k+1} - t_k`; with the
/// local coordinate `s = (t - t_k) / h` it is
/// `C = H0(s) P_k + H1(s) P_{k+1} + h (H2(s) T_k + H3(s) T_{k+1})`,
/// so the stored tangents `T_k` are derivatives with respect to `t` itself.
#[derive(Clone, Debug, PartialEq)]
pub struct FergusonCurve {
    params: Vec<f64>,
    points: Vec<DVec3>,
    tangents: Vec<DVec3>,
}

impl FergusonCurve {
    /// Interpolates `points` with estimated tangents, giving a C¹ curve.
    ///
    /// Interior tangents are Bessel (chord-weighted three-point) estimates, end
    /// tangents come from the parabola through the first/last three points. Two
    /// points give a straight line with parameter speed `|C'| = 1`.
    ///
    /// Errors: fewer than two points, non-finite coordinates, or consecutive
    /// coincident points (zero chord).
    pub fn interpolate(points: &[DVec3]) -> Result<Self, NativeError> {
        let params = chord_params(points)?;
        let tangents = estimate_tangents(&params, points);
        Ok(Self {
            params,
            points: points.to_vec(),
            tangents,
        })
    }

    /// Interpolates `points` with user-given tangents, one per point.
    ///
    /// Each tangent is the full derivative `dC/dt` with respect to the chord
    /// length parameter `t`: its direction is the curve direction and its
    /// magnitude the parameter speed (use unit vectors for a speed of about 1;
    /// larger magnitudes make the curve "fuller" near that node).
    ///
    /// Errors as for [`FergusonCurve::interpolate`], plus
    /// [`NativeError::LengthMismatch`] if the slice lengths differ and
    /// [`NativeError::NonFinite`] for a non-finite tangent.
    pub fn with_tangents(points: &[DVec3], tangents: &[DVec3]) -> Result<Self, NativeError> {
        if points.len() < 2 {
            return Err(NativeError::TooFewPoints {
                needed: 2,
                got: points.len(),
            });
        }
        if tangents.len() != points.len() {
            return Err(NativeError::LengthMismatch {
                expected: points.len(),
                got: tangents.len(),
            });
        }
        if let Some(index) = tangents.iter().position(|t| !t.is_finite()) {
            return Err(NativeError::NonFinite { index });
        }
        let params = chord_params(points)?;
        Ok(Self {
            params,
            points: points.to_vec(),
            tangents: tangents.to_vec(),
        })
    }

    /// Parameter range `(0, total chord length)`.
    pub fn range(&self) -> (f64, f64) {
        (self.params[0], self.params[self.params.len() - 1])
    }

    /// Node parameters (cumulative chord lengths), one per point.
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// Interpolated points.
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// Node tangents `dC/dt` (estimated or as given).
    pub fn tangents(&self) -> &[DVec3] {
        &self.tangents
    }

    /// Point at parameter `t`; outside the range the end segment's cubic is
    /// extrapolated.
    pub fn point(&self, t: f64) -> DVec3 {
        self.derivs(t).0
    }

    /// `(C, C', C'')` at `t`, derivatives with respect to `t` (analytic).
    pub fn derivs(&self, t: f64) -> (DVec3, DVec3, DVec3) {
        let k = interval(&self.params, t);
        let h = self.params[k + 1] - self.params[k];
        let s = (t - self.params[k]) / h;
        let (f, d1, d2) = basis(s);
        let (p0, p1) = (self.points[k], self.points[k + 1]);
        let (t0, t1) = (self.tangents[k] * h, self.tangents[k + 1] * h);
        let c = p0 * f[0] + p1 * f[1] + t0 * f[2] + t1 * f[3];
        let dc = (p0 * d1[0] + p1 * d1[1] + t0 * d1[2] + t1 * d1[3]) / h;
        let ddc = (p0 * d2[0] + p1 * d2[1] + t0 * d2[2] + t1 * d2[3]) / (h * h);
        (c, dc, ddc)
    }
}

/// Validates `points` and returns their cumulative chord lengths.
fn chord_params(points: &[DVec3]) -> Result<Vec<f64>, NativeError> {
    if points.len() < 2 {
        return Err(NativeError::TooFewPoints {
            needed: 2,
            got: points.len(),
        });
    }
    if let Some(index) = points.iter().position(|p| !p.is_finite()) {
        return Err(NativeError::NonFinite { index });
    }
    let mut params = Vec::with_capacity(points.len());
    let mut t = 0.0;
    params.push(t);
    for (index, w) in points.windows(2).enumerate() {
        let chord = w[0].distance(w[1]);
        // Also rejects chords so short that the sum does not increase.
        if t + chord <= t {
            return Err(NativeError::CoincidentPoints { index });
        }
        t += chord;
        if !t.is_finite() {
            // Finite but huge coordinates whose distances overflow.
            return Err(NativeError::NonFinite { index: index + 1 });
        }
        params.push(t);
    }
    Ok(params)
}
