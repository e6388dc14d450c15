//! `[[replace_face]]`: a CAD face's surface replaced by a native Ferguson patch network fitted
//! to samples of it (a repair of a bad CAD surface). The fit interpolates the CAD surface on a
//! uniform grid over the face's (u,v) bounds *at the CAD parameters*, so the face's (u,v)
//! plane, and with it its OCCT pcurves, carry over; its edges stay CAD edges.

use crate::geometry::{Curve2d, Surface};
use crate::model::{project_pcurve, FaceId, Model};
use glam::{DVec2, DVec3};
use std::sync::Arc;
use tetrafoil_native::FergusonSurface;

/// Samples per edge use when checking that a kept pcurve still maps onto its edge.
const PCURVE_CHECKS: usize = 9;

/// How well the native fit follows the CAD surface.
pub(super) struct Fit {
    /// Largest distance between fit and CAD surface at the grid cells' centres.
    pub max_deviation: f64,
}

pub(super) fn replace_face(
    model: &mut Model,
    face: FaceId,
    samples: usize,
    tol: f64,
) -> Result<Fit, String> {
    let cad = model.faces[face].surface.clone();
    let b = cad.bounds();
    if !(b.u.1 > b.u.0 && b.v.1 > b.v.0) {
        return Err(format!("empty (u,v) bounds {:?} x {:?}", b.u, b.v));
    }
    let us = linspace(b.u, samples);
    let vs = linspace(b.v, samples);
    let grid: Vec<Vec<DVec3>> = us
        .iter()
        .map(|&u| vs.iter().map(|&v| cad.point(DVec2::new(u, v))).collect())
        .collect();
    let native = FergusonSurface::interpolate_with_params(&grid, &us, &vs)
        .map_err(|e| format!("cannot fit a native surface to it: {e}"))?;
    let mut max_deviation: f64 = 0.0;
    for i in 0..samples - 1 {
        for j in 0..samples - 1 {
            let uv = DVec2::new(0.5 * (us[i] + us[i + 1]), 0.5 * (vs[j] + vs[j + 1]));
            let d = Surface::point(&native, uv).distance(cad.point(uv));
            max_deviation = max_deviation.max(d);
        }
    }
    let native: Arc<dyn Surface> = Arc::new(native);
    reproject_pcurves(
        model,
        face,
        native.as_ref(),
        10.0 * tol + 4.0 * max_deviation,
    )?;
    model.faces[face].surface = native;
    Ok(Fit { max_deviation })
}

fn linspace((a, b): (f64, f64), n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| {
            if k + 1 == n {
                b
            } else {
                a + (b - a) * k as f64 / (n - 1) as f64
            }
        })
        .collect()
}

/// Keeps each use's pcurve where it still lands on its edge on the new surface (the usual
/// case: same (u,v) plane); projects the edge anew where it does not.
fn reproject_pcurves(
    model: &mut Model,
    face: FaceId,
    surface: &dyn Surface,
    tol: f64,
) -> Result<(), String> {
    let mut loops = std::mem::take(&mut model.faces[face].loops);
    let result = (|| {
        for u in loops.iter_mut().flat_map(|l| l.uses.iter_mut()) {
            let edge = &model.edges[u.edge];
            let Some(curve) = &edge.curve else { continue };
            let fits = u.pcurve.as_ref().is_some_and(|pc| {
                (0..PCURVE_CHECKS).all(|k| {
                    let t = edge.range.0
                        + (edge.range.1 - edge.range.0) * k as f64 / (PCURVE_CHECKS - 1) as f64;
                    surface.point(pc.point(t)).distance(curve.point(t)) <= tol
                })
            });
            if !fits {
                let pc =
                    project_pcurve(surface, curve.as_ref(), edge.range, tol).map_err(|off| {
                        format!(
                            "{} is {:.3e} from the fitted surface at parameter {}",
                            model.edge_ref(u.edge),
                            off.distance,
                            off.t
                        )
                    })?;
                u.pcurve = Some(Arc::new(pc) as Arc<dyn Curve2d>);
            }
        }
        Ok(())
    })();
    model.faces[face].loops = loops;
    result
}
