//! The geometry traits for the native Ferguson types of `tetrafoil-native`.

use super::{Curve, CurveDerivs, Range1, Surface, SurfaceBounds, SurfaceDerivs};
use glam::{DVec2, DVec3};
use tetrafoil_native::{FergusonCurve, FergusonPatch, FergusonSurface, SurfaceDerivatives};

impl Curve for FergusonCurve {
    fn range(&self) -> Range1 {
        FergusonCurve::range(self)
    }
    fn point(&self, t: f64) -> DVec3 {
        FergusonCurve::point(self, t)
    }
    fn derivs(&self, t: f64) -> CurveDerivs {
        let (p, d1, d2) = FergusonCurve::derivs(self, t);
        CurveDerivs { p, d1, d2 }
    }
}

fn convert(d: SurfaceDerivatives) -> SurfaceDerivs {
    SurfaceDerivs {
        p: d.p,
        du: d.du,
        dv: d.dv,
        duu: d.duu,
        duv: d.duv,
        dvv: d.dvv,
    }
}

impl Surface for FergusonPatch {
    fn bounds(&self) -> SurfaceBounds {
        SurfaceBounds::rect((0.0, 1.0), (0.0, 1.0))
    }
    fn point(&self, uv: DVec2) -> DVec3 {
        FergusonPatch::point(self, uv.x, uv.y)
    }
    fn derivs(&self, uv: DVec2) -> SurfaceDerivs {
        convert(FergusonPatch::derivs(self, uv.x, uv.y))
    }
}

impl Surface for FergusonSurface {
    fn bounds(&self) -> SurfaceBounds {
        let (u, v) = FergusonSurface::bounds(self);
        SurfaceBounds::rect(u, v)
    }
    fn point(&self, uv: DVec2) -> DVec3 {
        FergusonSurface::point(self, uv.x, uv.y)
    }
    fn derivs(&self, uv: DVec2) -> SurfaceDerivs {
        convert(FergusonSurface::derivs(self, uv.x, uv.y))
    }
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }
}
