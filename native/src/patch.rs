//! Single bicubic Ferguson (Coons–Hermite) patches.

use glam::DVec3;

use crate::hermite::basis;

/// Value and derivatives of a surface at (u,v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceDerivatives {
    pub p: DVec3,
    pub du: DVec3,
    pub dv: DVec3,
    pub duu: DVec3,
    pub duv: DVec3,
    pub dvv: DVec3,
}

/// Bicubic Ferguson (Coons–Hermite) patch on `[0,1]²`.
///
/// Defined by corner points `P[i][j]` (i along u, j along v), u-tangents
/// `Pu[i][j]`, v-tangents `Pv[i][j]` and twist vectors `Puv[i][j]`, all with
/// respect to the unit-square parameters. It is the tensor product of the cubic
/// Hermite basis: `P(u,v) = Σ_ab H_a(u) H_b(v) G[a][b]` with the 4×4 geometry
/// matrix `G = [[P, Pv], [Pu, Puv]]`. The twists only affect the interior, so
/// patches sharing edge data join with C¹ continuity whatever the twists.
#[derive(Clone, Debug, PartialEq)]
pub struct FergusonPatch {
    /// `g[a][b]`: a, b index the Hermite basis `[value@0, value@1, slope@0, slope@1]`
    /// in u and v respectively.
    g: [[DVec3; 4]; 4],
}

impl FergusonPatch {
    /// Patch from corner points, u- and v-tangents and twists (each indexed `[i][j]`).
    pub fn new(
        p: [[DVec3; 2]; 2],
        pu: [[DVec3; 2]; 2],
        pv: [[DVec3; 2]; 2],
        puv: [[DVec3; 2]; 2],
    ) -> Self {
        let mut g = [[DVec3::ZERO; 4]; 4];
        for i in 0..2 {
            for j in 0..2 {
                g[i][j] = p[i][j];
                g[i + 2][j] = pu[i][j];
                g[i][j + 2] = pv[i][j];
                g[i + 2][j + 2] = puv[i][j];
            }
        }
        Self { g }
    }

    /// Bilinear patch through four corners, handy for flat faces.
    ///
    /// Tangents are the edge differences and the twist is the constant twist of
    /// the bilinear surface, `P11 - P10 - P01 + P00`, so the patch is *exactly*
    /// `Σ (1-u|u)(1-v|v) P[i][j]` (the twist is zero for parallelograms; a zero
    /// twist on a general quad would give a different, non-bilinear surface).
    pub fn bilinear(p: [[DVec3; 2]; 2]) -> Self {
        let pu = [[p[1][0] - p[0][0], p[1][1] - p[0][1]]; 2];
        let pv = [
            [p[0][1] - p[0][0], p[0][1] - p[0][0]],
            [p[1][1] - p[1][0], p[1][1] - p[1][0]],
        ];
        let twist = p[1][1] - p[1][0] - p[0][1] + p[0][0];
        Self::new(p, pu, pv, [[twist; 2]; 2])
    }

    /// Point at `(u, v)`; values outside `[0,1]²` extrapolate the bicubic.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let (fu, _, _) = basis(u);
        let (fv, _, _) = basis(v);
        combine(&self.g, &fu, &fv)
    }

    /// Point and analytic first and second derivatives at `(u, v)`.
    pub fn derivs(&self, u: f64, v: f64) -> SurfaceDerivatives {
        let (fu, du, duu) = basis(u);
        let (fv, dv, dvv) = basis(v);
        SurfaceDerivatives {
            p: combine(&self.g, &fu, &fv),
            du: combine(&self.g, &du, &fv),
            dv: combine(&self.g, &fu, &dv),
            duu: combine(&self.g, &duu, &fv),
            duv: combine(&self.g, &du, &dv),
            dvv: combine(&self.g, &fu, &dvv),
        }
    }
}

/// `Σ_ab a[i] b[j] g[i][j]`.
fn combine(g: &[[DVec3; 4]; 4], a: &[f64; 4], b: &[f64; 4]) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for (row, &wa) in g.iter().zip(a) {
        for (&gij, &wb) in row.iter().zip(b) {
            sum += gij * (wa * wb);
        }
    }
    sum
}
