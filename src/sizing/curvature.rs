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
/// At most this many finer samples per direction of one coarse step or cell.
const MAX_SUBDIVISIONS: usize = 32;

pub struct CurvatureLimit {
    samples: GradedSamples,
}

impl CurvatureLimit {
    /// Sample the model; `segments_per_circle` is n, `min_size` floors the limit (a sharp corner
    /// of a B-spline would otherwise ask for δ → 0).
    pub fn from_model(model: &Model, segments_per_circle: f64, min_size: f64) -> Self {
        use rayon::prelude::*;
        // r₁ at least the sample's own δ: one element's width of plateau around the curved
        // spot before the grading starts, which the front follows more evenly.
        let sample = |p: DVec3, kappa: f64, r1: f64| {
            (kappa.is_finite() && kappa > 0.0).then(|| {
                let delta = (std::f64::consts::TAU / (segments_per_circle * kappa)).max(min_size);
                GradedSample {
                    point: p,
                    delta,
                    r1: r1.max(delta),
                }
            })
        };
        let on_edges = model.edges.par_iter().flat_map_iter(|e| {
            let mut out = Vec::new();
            if let Some(c) = &e.curve {
                let (t0, t1) = e.range;
                let step = (t1 - t0) / EDGE_SAMPLES as f64;
                let step_len = arc_estimate(c.as_ref(), e.range) / EDGE_SAMPLES as f64;
                for i in 0..=EDGE_SAMPLES {
                    let t = t0 + step * i as f64;
                    let Some(first) = curve_sample(c.as_ref(), t, 0.5 * step_len, &sample) else {
                        continue;
                    };
                    // A step much longer than the spacing it asks for is sampled again finer,
                    // so the fine spacing is asked for along the edge, not in a ball of half a
                    // coarse step around each sample.
                    let m = subdivisions(step_len, first.delta);
                    if m == 1 || i == EDGE_SAMPLES {
                        out.push(first);
                        continue;
                    }
                    let fine_len = step_len / m as f64;
                    out.extend((0..m).filter_map(|k| {
                        let t = t + step * k as f64 / m as f64;
                        curve_sample(c.as_ref(), t, 0.5 * fine_len, &sample)
                    }));
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
        let on_faces = (0..model.faces.len() * FACE_SAMPLES)
            .into_par_iter()
            .flat_map_iter(|row| {
                let (f, i) = (row / FACE_SAMPLES, row % FACE_SAMPLES);
                let polys = &polys[f];
                let s = model.faces[f].surface.as_ref();
                let b = s.bounds();
                let cell = b.extent() / FACE_SAMPLES as f64;
                let mut out = Vec::new();
                for j in 0..FACE_SAMPLES {
                    let corner = DVec2::new(b.u.0, b.v.0) + cell * DVec2::new(i as f64, j as f64);
                    face_cell_samples(s, corner, cell, polys, &sample, &mut out);
                }
                out
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

/// Finer samples per coarse step (per direction) where the step is longer than twice the
/// spacing its sample asks for: about one sample per δ, at most [`MAX_SUBDIVISIONS`].
fn subdivisions(step_len: f64, delta: f64) -> usize {
    if step_len <= 2.0 * delta {
        1
    } else {
        ((step_len / delta).ceil() as usize).clamp(1, MAX_SUBDIVISIONS)
    }
}

/// The sample of curve `c` at `t`, asking within `r1`.
fn curve_sample(
    c: &dyn Curve,
    t: f64,
    r1: f64,
    sample: &impl Fn(DVec3, f64, f64) -> Option<GradedSample>,
) -> Option<GradedSample> {
    let d = c.derivs(t);
    let speed = d.d1.length();
    (speed > 0.0)
        .then(|| sample(d.p, d.d1.cross(d.d2).length() / speed.powi(3), r1))
        .flatten()
}

/// Samples of one cell of a face's (u,v) grid (lower corner, extent): its centre, or, where
/// the cell is much larger in 3-D than the spacing the centre asks for (a fillet along a long
/// edge), a finer grid over the cell, so a sample's radius r₁ stays about its own δ and the
/// fine spacing does not spread half a coarse cell onto the faces around. Samples outside the
/// trimming loops are dropped.
fn face_cell_samples(
    s: &dyn Surface,
    corner: DVec2,
    cell: DVec2,
    polys: &[Vec<DVec2>],
    sample: &impl Fn(DVec3, f64, f64) -> Option<GradedSample>,
    out: &mut Vec<GradedSample>,
) {
    let at = |uv: DVec2, extent: DVec2| {
        let d = s.derivs(uv);
        let (hu, hv) = (d.du.length() * extent.x, d.dv.length() * extent.y);
        let r1 = 0.5 * (hu * hu + hv * hv).sqrt();
        (sample(d.p, principal_curvature_of(&d), r1), hu, hv)
    };
    let inside = |uv: DVec2| polys.is_empty() || inside_face(polys, uv);
    let centre = corner + 0.5 * cell;
    let (first, hu, hv) = at(centre, cell);
    let Some(first) = first else { return };
    let (mu, mv) = (subdivisions(hu, first.delta), subdivisions(hv, first.delta));
    if mu == 1 && mv == 1 {
        // The inside test (a winding number over the loops) only for a sample that asks for
        // something: none on a plane.
        if inside(centre) {
            out.push(first);
        }
        return;
    }
    let fine = cell / DVec2::new(mu as f64, mv as f64);
    for a in 0..mu {
        for b in 0..mv {
            let uv = corner + fine * DVec2::new(a as f64 + 0.5, b as f64 + 0.5);
            if let (Some(x), _, _) = at(uv, fine) {
                if inside(uv) {
                    out.push(x);
                }
            }
        }
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
