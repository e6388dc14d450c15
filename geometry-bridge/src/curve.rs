//! `OccCurve` (an edge's 3-D curve) and `OccPcurve` (an edge use's curve in its face's
//! parameter plane): owned deep copies, one per thread using them at once, like `OccSurface`.

use cxx::UniquePtr;

use crate::ffi::bridge as ffi;
use crate::pool::CopyPool;

/// Point and derivatives of a 3-D curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveDerivs {
    pub p: [f64; 3],
    pub d1: [f64; 3],
    pub d2: [f64; 3],
}

/// Point and derivatives of a pcurve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcurveDerivs {
    pub p: [f64; 2],
    pub d1: [f64; 2],
    pub d2: [f64; 2],
}

/// An edge's 3-D curve over the edge's range, located in model space.
pub struct OccCurve {
    geom: CopyPool<ffi::CurveGeom>,
    range: [f64; 2],
    period: Option<f64>,
}

impl OccCurve {
    pub(crate) fn new(g: UniquePtr<ffi::CurveGeom>) -> Self {
        let mut r = [0.0; 3];
        ffi::curve_range(&g, &mut r);
        Self {
            geom: CopyPool::new(g, ffi::curve_clone),
            range: [r[0], r[1]],
            period: (r[2] > 0.0).then_some(r[2]),
        }
    }

    /// An independent deep copy (a handle of its own; sharing one handle is as fast).
    pub fn try_clone(&self) -> Option<Self> {
        self.geom.with(|g| ffi::curve_clone(g)).ok().map(Self::new)
    }

    pub fn range(&self) -> [f64; 2] {
        self.range
    }

    pub fn period(&self) -> Option<f64> {
        self.period
    }

    pub fn point(&self, t: f64) -> Option<[f64; 3]> {
        self.derivs(t).map(|d| d.p)
    }

    pub fn derivs(&self, t: f64) -> Option<CurveDerivs> {
        let mut o = [0.0; 9];
        self.geom.with(|g| ffi::curve_d2(g, t, &mut o)).ok()?;
        Some(CurveDerivs {
            p: [o[0], o[1], o[2]],
            d1: [o[3], o[4], o[5]],
            d2: [o[6], o[7], o[8]],
        })
    }

    /// Closest parameter within the range (ShapeAnalysis_Curve::Project, or NextProject from
    /// `hint`), with the distance to it.
    pub fn project(&self, p: [f64; 3], hint: Option<f64>) -> Option<(f64, f64)> {
        let mut o = [0.0; 2];
        self.geom
            .with(|g| ffi::curve_project(g, &p, hint.is_some(), hint.unwrap_or(0.0), &mut o))
            .ok()?;
        Some((o[0], o[1]))
    }
}

/// The pcurve of one edge use. Parametrised like the edge (increasing from `range[0]` to
/// `range[1]`); a reversed use traverses it backwards. A seam's two uses give its two pcurves.
pub struct OccPcurve {
    geom: CopyPool<ffi::PcurveGeom>,
    range: [f64; 2],
}

impl OccPcurve {
    pub(crate) fn new(g: UniquePtr<ffi::PcurveGeom>) -> Self {
        let mut r = [0.0; 2];
        ffi::pcurve_range(&g, &mut r);
        Self {
            geom: CopyPool::new(g, ffi::pcurve_clone),
            range: r,
        }
    }

    /// An independent deep copy (a handle of its own; sharing one handle is as fast).
    pub fn try_clone(&self) -> Option<Self> {
        self.geom.with(|g| ffi::pcurve_clone(g)).ok().map(Self::new)
    }

    pub fn range(&self) -> [f64; 2] {
        self.range
    }

    pub fn point(&self, t: f64) -> Option<[f64; 2]> {
        self.derivs(t).map(|d| d.p)
    }

    pub fn derivs(&self, t: f64) -> Option<PcurveDerivs> {
        let mut o = [0.0; 6];
        self.geom.with(|g| ffi::pcurve_d2(g, t, &mut o)).ok()?;
        Some(PcurveDerivs {
            p: [o[0], o[1]],
            d1: [o[2], o[3]],
            d2: [o[4], o[5]],
        })
    }
}
