//! C¹ networks of bicubic Ferguson patches interpolating a point grid.

use glam::DVec3;

use crate::error::NativeError;
use crate::hermite::{estimate_tangents, interval};
use crate::patch::{FergusonPatch, SurfaceDerivatives};

/// C¹ network of bicubic Ferguson patches interpolating `grid[i][j]`
/// (`i = 0..nu` along u, `j = 0..nv` along v, `nu, nv >= 2`).
///
/// Choices, all made so that neighbouring patches share their edge data
/// exactly (hence C¹):
/// * **Parameters.** `u_0 = 0` and `u_{i+1} - u_i` is the chord length between
///   grid lines `i` and `i+1` averaged over all `j` (likewise for `v`). One
///   parameter vector per direction keeps the patch layout a tensor product and
///   is robust against single degenerate grid lines (e.g. a collapsed tip).
/// * **Tangents.** `Pu[i][j]` is the tangent estimate of [`crate::FergusonCurve`]
///   (Bessel inside, quadratic end condition) applied to the grid line `j`
///   with the shared parameters `u_i`; likewise `Pv`. Each node has one tangent
///   used by all patches meeting there.
/// * **Twists.** `Puv` is the same estimate applied along `v` to the
///   u-tangents. Since the estimate is linear and parameters are shared, this
///   equals the estimate along `u` of the v-tangents, so the choice is
///   symmetric; it is exact for data that is quadratic in each parameter.
///
/// Patch `(i, j)` spans `[u_i, u_{i+1}] × [v_j, v_{j+1}]`; it is stored on the
/// unit square with tangents scaled by the interval lengths `hu`, `hv` (twist by
/// `hu·hv`), and evaluation applies the chain rule, so derivatives are exact
/// with respect to the global `(u, v)`.
#[derive(Clone, Debug, PartialEq)]
pub struct FergusonSurface {
    grid: Vec<Vec<DVec3>>,
    u_params: Vec<f64>,
    v_params: Vec<f64>,
    /// Patch `(i, j)` at `patches[i * (nv - 1) + j]`, in local unit coordinates.
    patches: Vec<FergusonPatch>,
}

impl FergusonSurface {
    /// Interpolates a rectangular grid of points.
    ///
    /// Errors: fewer than two rows or columns ([`NativeError::TooFewPoints`]),
    /// rows of different lengths ([`NativeError::RaggedGrid`]), non-finite
    /// points ([`NativeError::NonFiniteGrid`]) and two entirely coincident
    /// consecutive grid lines ([`NativeError::CoincidentGridLines`]).
    pub fn interpolate(grid: &[Vec<DVec3>]) -> Result<Self, NativeError> {
        check_grid(grid)?;
        let (nu, nv) = (grid.len(), grid[0].len());
        let u_params = averaged_chords(nu, nv, 'u', |i, j| grid[i][j])?;
        let v_params = averaged_chords(nv, nu, 'v', |j, i| grid[i][j])?;
        Ok(Self::build(grid, u_params, v_params))
    }

    /// Interpolates a rectangular grid at given parameters: `grid[i][j]` is the point at
    /// `(u_params[i], v_params[j])`. For a patch network that keeps another surface's
    /// parameterisation (a CAD face replaced by a fit to its samples keeps its pcurves).
    ///
    /// Errors: as [`Self::interpolate`], plus parameters that do not match the grid's size
    /// ([`NativeError::LengthMismatch`]) or are not finite and strictly increasing
    /// ([`NativeError::BadParams`]).
    pub fn interpolate_with_params(
        grid: &[Vec<DVec3>],
        u_params: &[f64],
        v_params: &[f64],
    ) -> Result<Self, NativeError> {
        check_grid(grid)?;
        for (axis, params, n) in [('u', u_params, grid.len()), ('v', v_params, grid[0].len())] {
            if params.len() != n {
                return Err(NativeError::LengthMismatch {
                    expected: n,
                    got: params.len(),
                });
            }
            if let Some(index) = params
                .windows(2)
                .position(|w| !(w[0].is_finite() && w[1].is_finite() && w[1] > w[0]))
            {
                return Err(NativeError::BadParams { axis, index });
            }
        }
        Ok(Self::build(grid, u_params.to_vec(), v_params.to_vec()))
    }

    /// The patch network through a checked grid at checked parameters.
    fn build(grid: &[Vec<DVec3>], u_params: Vec<f64>, v_params: Vec<f64>) -> Self {
        let (nu, nv) = (grid.len(), grid[0].len());

        // pu[i][j]: tangent of the u-line j at node i.
        let mut pu = vec![vec![DVec3::ZERO; nv]; nu];
        for j in 0..nv {
            let line: Vec<DVec3> = (0..nu).map(|i| grid[i][j]).collect();
            for (i, t) in estimate_tangents(&u_params, &line).into_iter().enumerate() {
                pu[i][j] = t;
            }
        }
        let pv: Vec<Vec<DVec3>> = grid
            .iter()
            .map(|line| estimate_tangents(&v_params, line))
            .collect();
        let puv: Vec<Vec<DVec3>> = pu
            .iter()
            .map(|line| estimate_tangents(&v_params, line))
            .collect();

        let mut patches = Vec::with_capacity((nu - 1) * (nv - 1));
        for i in 0..nu - 1 {
            let hu = u_params[i + 1] - u_params[i];
            for j in 0..nv - 1 {
                let hv = v_params[j + 1] - v_params[j];
                let corner = |a: &[Vec<DVec3>], scale: f64| {
                    [
                        [a[i][j] * scale, a[i][j + 1] * scale],
                        [a[i + 1][j] * scale, a[i + 1][j + 1] * scale],
                    ]
                };
                patches.push(FergusonPatch::new(
                    corner(grid, 1.0),
                    corner(&pu, hu),
                    corner(&pv, hv),
                    corner(&puv, hu * hv),
                ));
            }
        }

        Self {
            grid: grid.to_vec(),
            u_params,
            v_params,
            patches,
        }
    }

    /// Parameters `u_i` of the grid lines `i` (starting at 0).
    pub fn u_params(&self) -> &[f64] {
        &self.u_params
    }

    /// Parameters `v_j` of the grid lines `j` (starting at 0).
    pub fn v_params(&self) -> &[f64] {
        &self.v_params
    }

    /// `((u0, u1), (v0, v1))`, the parameter rectangle covered by the grid.
    pub fn bounds(&self) -> ((f64, f64), (f64, f64)) {
        let (u, v) = (&self.u_params, &self.v_params);
        ((u[0], u[u.len() - 1]), (v[0], v[v.len() - 1]))
    }

    /// Point at `(u, v)`; outside the bounds the border patch is extrapolated.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (patch, s, r, _, _) = self.locate(u, v);
        patch.point(s, r)
    }

    /// Point and analytic derivatives with respect to the global `(u, v)`.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivatives {
        let (patch, s, r, hu, hv) = self.locate(u, v);
        let d = patch.derivs(s, r);
        SurfaceDerivatives {
            p: d.p,
            du: d.du / hu,
            dv: d.dv / hv,
            duu: d.duu / (hu * hu),
            duv: d.duv / (hu * hv),
            dvv: d.dvv / (hv * hv),
        }
    }

    /// The interpolated grid, `grid[i][j]`.
    pub fn grid(&self) -> &[Vec<DVec3>] {
        &self.grid
    }

    /// Patch containing `(u, v)` with local coordinates and interval lengths.
    fn locate(&self, u: f64, v: f64) -> (&FergusonPatch, f64, f64, f64, f64) {
        let i = interval(&self.u_params, u);
        let j = interval(&self.v_params, v);
        let hu = self.u_params[i + 1] - self.u_params[i];
        let hv = self.v_params[j + 1] - self.v_params[j];
        let s = (u - self.u_params[i]) / hu;
        let r = (v - self.v_params[j]) / hv;
        let patch = &self.patches[i * (self.v_params.len() - 1) + j];
        (patch, s, r, hu, hv)
    }
}

/// At least 2 × 2 points, rows of one length, finite points.
fn check_grid(grid: &[Vec<DVec3>]) -> Result<(), NativeError> {
    let nu = grid.len();
    if nu < 2 {
        return Err(NativeError::TooFewPoints { needed: 2, got: nu });
    }
    let nv = grid[0].len();
    if nv < 2 {
        return Err(NativeError::TooFewPoints { needed: 2, got: nv });
    }
    for (row, line) in grid.iter().enumerate() {
        if line.len() != nv {
            return Err(NativeError::RaggedGrid {
                row,
                expected: nv,
                got: line.len(),
            });
        }
        if let Some(col) = line.iter().position(|p| !p.is_finite()) {
            return Err(NativeError::NonFiniteGrid { row, col });
        }
    }
    Ok(())
}

/// Cumulative chord lengths between the `n` lines of a grid, each chord averaged
/// over the `m` points of the lines; `at(k, l)` is point `l` of line `k`.
fn averaged_chords(
    n: usize,
    m: usize,
    axis: char,
    at: impl Fn(usize, usize) -> DVec3,
) -> Result<Vec<f64>, NativeError> {
    let mut params = Vec::with_capacity(n);
    let mut t = 0.0;
    params.push(t);
    for index in 0..n - 1 {
        let sum: f64 = (0..m)
            .map(|l| at(index, l).distance(at(index + 1, l)))
            .sum();
        let next = t + sum / m as f64;
        if !next.is_finite() {
            // Finite but huge coordinates whose distances overflow.
            let (row, col) = if axis == 'u' {
                (index + 1, 0)
            } else {
                (0, index + 1)
            };
            return Err(NativeError::NonFiniteGrid { row, col });
        }
        if next <= t {
            return Err(NativeError::CoincidentGridLines { axis, index });
        }
        t = next;
        params.push(t);
    }
    Ok(params)
}
