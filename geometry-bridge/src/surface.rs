//! `OccSurface`: a face's surface as owned deep copies, one per thread using it at once.

use cxx::UniquePtr;

use crate::ffi::bridge as ffi;
use crate::pool::CopyPool;

/// Point and derivatives of a surface at (u, v).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceDerivs {
    pub p: [f64; 3],
    pub du: [f64; 3],
    pub dv: [f64; 3],
    pub duu: [f64; 3],
    pub duv: [f64; 3],
    pub dvv: [f64; 3],
}

/// A point where a circle meets a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircleHit {
    pub uv: [f64; 2],
    /// Circle parameter: angle from the circle's x axis about its axis.
    pub theta: f64,
    pub point: [f64; 3],
}

/// The (untrimmed) surface of one face, located in model space.
///
/// Thread safety by construction: the C++ object is a deep copy (Geom_Surface::Copy) that
/// nothing else references, and a call uses a copy no other thread is using at that moment
/// (see [`crate::pool`]): threads sharing one handle neither race nor queue.
pub struct OccSurface {
    geom: CopyPool<ffi::SurfaceGeom>,
    u_range: [f64; 2],
    v_range: [f64; 2],
    u_period: Option<f64>,
    v_period: Option<f64>,
    elementary: bool,
}

fn period(x: f64) -> Option<f64> {
    (x > 0.0).then_some(x)
}

impl OccSurface {
    pub(crate) fn new(g: UniquePtr<ffi::SurfaceGeom>) -> Self {
        let mut info = [0.0; 7];
        ffi::surface_info(&g, &mut info);
        Self {
            geom: CopyPool::new(g, ffi::surface_clone),
            u_range: [info[0], info[1]],
            v_range: [info[2], info[3]],
            u_period: period(info[4]),
            v_period: period(info[5]),
            elementary: info[6] != 0.0,
        }
    }

    /// An independent deep copy (a handle of its own; sharing one handle is as fast).
    pub fn try_clone(&self) -> Option<Self> {
        let g = self.geom.with(|g| ffi::surface_clone(g)).ok()?;
        Some(Self::new(g))
    }

    /// Parameter range of the face (BRepTools::UVBounds), not of the untrimmed surface.
    pub fn u_range(&self) -> [f64; 2] {
        self.u_range
    }

    pub fn v_range(&self) -> [f64; 2] {
        self.v_range
    }

    /// A plane, cylinder, cone, sphere or torus (Geom_ElementarySurface): closed forms, so
    /// OCCT's intersections with it are cheap and exact.
    pub fn is_elementary(&self) -> bool {
        self.elementary
    }

    pub fn u_period(&self) -> Option<f64> {
        self.u_period
    }

    pub fn v_period(&self) -> Option<f64> {
        self.v_period
    }

    pub fn point(&self, u: f64, v: f64) -> Option<[f64; 3]> {
        self.derivs(u, v).map(|d| d.p)
    }

    /// Point and first and second derivatives (Geom_Surface::D2); None where OCCT cannot
    /// evaluate (e.g. an offset surface's singular point).
    pub fn derivs(&self, u: f64, v: f64) -> Option<SurfaceDerivs> {
        let mut o = [0.0; 18];
        self.geom.with(|g| ffi::surface_d2(g, u, v, &mut o)).ok()?;
        let at = |i: usize| [o[i], o[i + 1], o[i + 2]];
        Some(SurfaceDerivs {
            p: at(0),
            du: at(3),
            dv: at(6),
            duu: at(9),
            duv: at(12),
            dvv: at(15),
        })
    }

    /// Closest (u, v) to `p` (ShapeAnalysis_Surface::ValueOfUV, or NextValueOfUV starting from
    /// `hint`).
    pub fn project(&self, p: [f64; 3], hint: Option<[f64; 2]>) -> Option<[f64; 2]> {
        self.project_with_distance(p, hint).map(|(uv, _)| uv)
    }

    /// As `project`, also returning the distance from `p` to the surface point found.
    pub fn project_with_distance(
        &self,
        p: [f64; 3],
        hint: Option<[f64; 2]>,
    ) -> Option<([f64; 2], f64)> {
        let h = hint.unwrap_or([0.0; 2]);
        let input = [p[0], p[1], p[2], h[0], h[1]];
        let mut o = [0.0; 3];
        self.geom
            .with(|g| ffi::surface_project(g.pin_mut(), &input, hint.is_some(), &mut o))
            .ok()?;
        Some(([o[0], o[1]], o[2]))
    }

    /// Points where the circle (centre, unit axis, x axis in its plane, radius) meets the
    /// untrimmed surface (GeomAPI_IntCS); None if OCCT fails. Points outside the face's trim
    /// are included: the caller decides about trimming.
    pub fn intersect_circle(
        &self,
        centre: [f64; 3],
        axis: [f64; 3],
        x_axis: [f64; 3],
        radius: f64,
    ) -> Option<Vec<CircleHit>> {
        let c = [
            centre[0], centre[1], centre[2], axis[0], axis[1], axis[2], x_axis[0], x_axis[1],
            x_axis[2], radius,
        ];
        let flat = self
            .geom
            .with(|g| ffi::surface_intersect_circle(g, &c))
            .ok()?;
        Some(
            flat.chunks_exact(6)
                .map(|h| CircleHit {
                    uv: [h[0], h[1]],
                    theta: h[2],
                    point: [h[3], h[4], h[5]],
                })
                .collect(),
        )
    }
}
