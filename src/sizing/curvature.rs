//! The curvature limit: δ ≤ 2πR/n for the local radius of curvature R of the model's curves
//! and surfaces, so that n segments resolve a full circle whatever the global size. The model
//! is sampled once; each sample is a graded source (see [`super::graded`]).

use super::graded::{GradedSample, GradedSamples};
use crate::geometry::{Curve, Surface};
use crate::model::Model;
use glam::{DVec2, DVec3};

/// Samples per edge and per face direction.
const EDGE_SAMPLES: usize = 64;
const FACE_SAMPLES: usize = 32;

pub struct CurvatureLimit {
    samples: GradedSamples,
}

impl CurvatureLimit {
    /// Sample the model; `segments_per_circle` is n, `min_size` floors the limit (a sharp corner
    /// of a B-spline would otherwise ask for δ → 0).
    pub fn from_model(model: &Model, segments_per_circle: f64, min_size: f64) -> Self {
        use rayon::prelude::*;
        let sample = |p: DVec3, kappa: f64, r1: f64| {
            (kappa.is_finite() && kappa > 0.0).then(|| GradedSample {
                point: p,
                delta: (std::f64::consts::TAU / (segments_per_circle * kappa)).max(min_size),
                r1,
            })
        };
        let on_edges = model.edges.par_iter().flat_map_iter(|e| {
            let mut out = Vec::new();
            if let Some(c) = &e.curve {
                let (t0, t1) = e.range;
                let step_len = arc_estimate(c.as_ref(), e.range) / EDGE_SAMPLES as f64;
                for i in 0..=EDGE_SAMPLES {
                    let t = t0 + (t1 - t0) * i as f64 / EDGE_SAMPLES as f64;
                    let d = c.derivs(t);
                    let speed = d.d1.length();
                    if speed > 0.0 {
                        let kappa = d.d1.cross(d.d2).length() / speed.powi(3);
                        out.extend(sample(d.p, kappa, 0.5 * step_len));
                    }
                }
            }
            out
        });
        // One task per row of a face's sample grid, not per face: a model with one dominant
        // face (a revolved sphere) would otherwise keep one thread busy and the rest idle.
        let polys: Vec<Vec<Vec<DVec2>>> = (0..model.faces.len())
            .into_par_iter()
            .map(|f| model.loop_polygons_rough(f).unwrap_or_default())
            .collect();
        let on_faces = (0..model.faces.len() * (FACE_SAMPLES + 1))
            .into_par_iter()
            .flat_map_iter(|row| {
                let (f, i) = (row / (FACE_SAMPLES + 1), row % (FACE_SAMPLES + 1));
                let polys = &polys[f];
                let s = model.faces[f].surface.as_ref();
                let b = s.bounds();
                let e = b.extent();
                (0..=FACE_SAMPLES).filter_map(move |j| {
                    let uv = DVec2::new(
                        b.u.0 + e.x * i as f64 / FACE_SAMPLES as f64,
                        b.v.0 + e.y * j as f64 / FACE_SAMPLES as f64,
                    );
                    let d = s.derivs(uv);
                    let h = (d.du.length() * e.x).max(d.dv.length() * e.y) / FACE_SAMPLES as f64;
                    // The inside test (a winding number over the loops) only for a sample that
                    // asks for something: none on a plane.
                    sample(d.p, principal_curvature_of(&d), 0.5 * h)
                        .filter(|_| polys.is_empty() || inside_face(polys, uv))
                })
            });
        let samples: Vec<GradedSample> = on_edges.chain(on_faces).collect();
        CurvatureLimit {
            samples: GradedSamples::new(samples),
        }
    }

    /// The curvature limit at `p`, or `None` when the model has no curvature.
    pub fn spacing(&self, p: DVec3) -> Option<f64> {
        self.spacing_below(p, f64::INFINITY)
    }

    /// The curvature limit at `p` when it is below `cap`, else `None`. The cap (the spacing
    /// already known from other contributions) prunes the search: only samples that could beat
    /// it are visited, which is most of the cost of a spacing query.
    pub fn spacing_below(&self, p: DVec3, cap: f64) -> Option<f64> {
        self.samples.spacing_below(p, cap)
    }

    /// [`Self::spacing_below`] grading away from the samples at `rate` per unit distance.
    pub fn spacing_below_at(&self, p: DVec3, cap: f64, rate: f64) -> Option<f64> {
        self.samples.spacing_below_at(p, cap, rate)
    }
}

pub(super) fn arc_estimate(c: &dyn Curve, (t0, t1): (f64, f64)) -> f64 {
    let n = 32;
    (0..n)
        .map(|i| {
            let a = t0 + (t1 - t0) * i as f64 / n as f64;
            let b = t0 + (t1 - t0) * (i + 1) as f64 / n as f64;
            c.point(a).distance(c.point(b))
        })
        .sum()
}

/// Largest |principal curvature| from the first and second fundamental forms.
pub fn max_principal_curvature(s: &dyn Surface, uv: DVec2) -> f64 {
    principal_curvature_of(&s.derivs(uv))
}

/// [`max_principal_curvature`] from the derivatives at the point.
fn principal_curvature_of(d: &crate::geometry::SurfaceDerivs) -> f64 {
    let n = d.normal_raw();
    let len = n.length();
    // A pole, or next to one: the first fundamental form is nearly singular and the curvature
    // from it is noise (a Rhino B-spline sphere gave radii of 1e-3 there, and 9x the triangles).
    let longest = d.du.length().max(d.dv.length());
    if len <= 1e-4 * longest * longest {
        return 0.0;
    }
    let n = n / len;
    let (e, f, g) = d.first_form();
    let (l, m, nn) = (d.duu.dot(n), d.duv.dot(n), d.dvv.dot(n));
    let det1 = e * g - f * f;
    let k_gauss = (l * nn - m * m) / det1;
    let h_mean = (e * nn - 2.0 * f * m + g * l) / (2.0 * det1);
    let disc = (h_mean * h_mean - k_gauss).max(0.0).sqrt();
    (h_mean + disc).abs().max((h_mean - disc).abs())
}

/// Is `uv` inside the face: inside the outer loop and outside every hole (even–odd rule on the
/// loop polygons, with the exact orient2d for the crossing side test).
pub fn inside_face(polys: &[Vec<DVec2>], uv: DVec2) -> bool {
    polys.iter().filter(|p| winding_contains(p, uv)).count() % 2 == 1
}

fn winding_contains(poly: &[DVec2], q: DVec2) -> bool {
    let n = poly.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a.y > q.y) != (b.y > q.y) {
            // Crossing to the right of q when q is on the left of the upward edge.
            let side = crate::geometry::orient2d(a, b, q);
            if (side > 0.0) == (b.y > a.y) {
                inside = !inside;
            }
        }
    }
    inside
}
