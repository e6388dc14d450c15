//! The spacing a flow domain's body asks for: δ on every body face, graded outwards as the
//! curvature limit is, so a far field many body lengths away is meshed coarse while the body
//! keeps the spacing it would have alone (`case/farfield.rs`).

use super::curvature::inside_face;
use super::graded::GradedSample;
use crate::model::Model;
use glam::DVec2;
use rayon::prelude::*;

/// Samples per side of each face's (u, v) grid.
const GRID: usize = 32;

/// Samples asking for `delta` on each of `faces`: the centres of a grid over the face's
/// parameter box that lie inside it, each asking over half its cell's diagonal (at least δ),
/// so the samples cover the face between them.
pub fn body_samples(model: &Model, faces: &[usize], delta: f64) -> Vec<GradedSample> {
    faces
        .par_iter()
        .flat_map_iter(|&f| {
            let polys = model.loop_polygons_rough(f).unwrap_or_default();
            let s = model.faces[f].surface.as_ref();
            let b = s.bounds();
            let cell = b.extent() / GRID as f64;
            let mut out = Vec::new();
            for i in 0..GRID {
                for j in 0..GRID {
                    let uv = DVec2::new(b.u.0, b.v.0)
                        + cell * DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
                    if !polys.is_empty() && !inside_face(&polys, uv) {
                        continue;
                    }
                    let d = s.derivs(uv);
                    let (hu, hv) = (d.du.length() * cell.x, d.dv.length() * cell.y);
                    out.push(GradedSample {
                        point: d.p,
                        delta,
                        r1: (0.5 * hu.hypot(hv)).max(delta),
                    });
                }
            }
            out
        })
        .collect()
}
