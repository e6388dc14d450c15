//! Pcurves for edges that lie on a surface without one (native faces): the edge is sampled and
//! each sample projected onto the surface, each projection starting from the previous one, so
//! the result follows the edge continuously even across a periodic seam.

use crate::geometry::{Curve, PolyCurve2d, Surface, SurfaceBounds};
use glam::DVec2;

/// Samples per edge for a projected pcurve.
const SAMPLES: usize = 64;

/// Where an edge leaves the surface it is said to lie on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OffSurface {
    pub t: f64,
    pub distance: f64,
}

/// Project `curve` over `range` onto `surface`; fails when a sample is further than `tol`
/// from the surface (the edge does not lie on that face).
pub fn project_pcurve(
    surface: &dyn Surface,
    curve: &dyn Curve,
    range: (f64, f64),
    tol: f64,
) -> Result<PolyCurve2d, OffSurface> {
    let bounds = surface.bounds();
    let mut params = Vec::with_capacity(SAMPLES + 1);
    let mut points: Vec<DVec2> = Vec::with_capacity(SAMPLES + 1);
    for i in 0..=SAMPLES {
        let t = range.0 + (range.1 - range.0) * i as f64 / SAMPLES as f64;
        let p = curve.point(t);
        let hint = points.last().copied();
        let uv = surface.closest_uv(p, hint).ok_or(OffSurface {
            t,
            distance: f64::INFINITY,
        })?;
        let uv = match hint {
            Some(prev) => unwrap_near(uv, prev, &bounds),
            None => uv,
        };
        let distance = surface.point(uv).distance(p);
        if distance > tol {
            return Err(OffSurface { t, distance });
        }
        params.push(t);
        points.push(uv);
    }
    Ok(PolyCurve2d { params, points })
}

/// Shift `uv` by whole periods so it is as close as possible to `reference`.
pub fn unwrap_near(uv: DVec2, reference: DVec2, bounds: &SurfaceBounds) -> DVec2 {
    let shift = |x: f64, r: f64, period: Option<f64>| match period {
        Some(p) if p > 0.0 => x + ((r - x) / p).round() * p,
        _ => x,
    };
    DVec2::new(
        shift(uv.x, reference.x, bounds.u_period),
        shift(uv.y, reference.y, bounds.v_period),
    )
}
