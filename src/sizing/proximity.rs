//! The proximity limit: δ ≤ w/n where a face is only w wide, so n elements span it. A face
//! narrower than the spacing (a fillet strip, the side of a thin wall, the ligament between a
//! hole and an edge) otherwise gets boundary nodes δ apart on both sides and only needles
//! between them, and in the volume the two sides of a thin wall can cross.
//!
//! Each face's loops are sampled in 3-D; a sample p finds the nearest point q of the same face's
//! sample polyline that faces it across the face: q lies within 60° of p's inward direction (the surface normal
//! crossed with the loop's tangent: the face is on the loop's left) and p within 60° of q's.
//! Samples of the same loop must also be far apart along it (more than `ALONG_RATIO` times their
//! distance), so a corner's two edges do not count as a gap unless the corner is sharper than
//! about 23°. Each gap becomes a graded sample (see [`super::graded`]).

use super::curvature::arc_estimate;
use super::graded::{GradedSample, GradedSamples};
use crate::model::{FaceId, Model};
use glam::DVec3;
use rstar::{primitives::GeomWithData, RTree};

/// Samples per edge use.
const EDGE_SAMPLES: usize = 32;
/// Two samples of one loop face each other only if the loop between them is this many times
/// longer than their distance: 1/sin(θ/2) for a corner of angle θ, so corners sharper than
/// about 23° count as gaps (they force small angles anyway) and blunter ones do not.
const ALONG_RATIO: f64 = 5.0;
/// cos 60°: how far off the inward direction the other side may lie.
const FACING_COS: f64 = 0.5;

/// A point of a face's boundary with the direction into the face.
struct BoundarySample {
    p: DVec3,
    /// Unit vector into the face, in its tangent plane; zero at a pole.
    inward: DVec3,
    /// Which loop, and the arc length along it.
    lp: usize,
    s: f64,
    /// Distance to the neighbouring samples along the loop.
    step: f64,
}

pub struct ProximityLimit {
    samples: GradedSamples,
    /// Gaps narrower than `cells` × the size floor: what the mesh cannot resolve there is
    /// forced by the floor (point and the radius it covers).
    floored: RTree<GeomWithData<[f64; 3], f64>>,
    /// The largest radius in `floored`.
    floored_reach: f64,
}

impl ProximityLimit {
    /// Find the gaps narrower than `max_width` on every face: `cells` is n in δ ≤ w/n and
    /// `min_size` floors δ.
    pub fn from_model(model: &Model, cells: f64, min_size: f64, max_width: f64) -> Self {
        use rayon::prelude::*;
        let gaps: Vec<(DVec3, f64, f64)> = (0..model.faces.len())
            .into_par_iter()
            .flat_map_iter(|f| face_gaps(model, f, max_width))
            .collect();
        let floored: Vec<_> = gaps
            .iter()
            .filter(|(_, w, _)| w / cells < min_size)
            .map(|&(p, w, step)| GeomWithData::new(p.to_array(), w.max(0.5 * step)))
            .collect();
        let samples = gaps.into_iter().map(|(p, w, step)| GradedSample {
            point: p,
            delta: (w / cells).max(min_size),
            r1: 0.5 * step,
        });
        ProximityLimit {
            samples: GradedSamples::new(samples),
            floored_reach: floored.iter().map(|g| g.data).fold(0.0, f64::max),
            floored: RTree::bulk_load(floored),
        }
    }

    /// Is there a gap narrower than the size floor allows within `radius` of `p` (plus the
    /// gap's own extent)?
    pub fn floored_near(&self, p: DVec3, radius: f64) -> bool {
        self.floored
            .nearest_neighbor_iter_with_distance_2(&p.to_array())
            .take_while(|(_, d2)| d2.sqrt() <= radius + self.floored_reach)
            .any(|(g, d2)| d2.sqrt() <= radius + g.data)
    }

    /// Number of boundary samples that found a gap.
    pub fn len(&self) -> usize {
        self.samples.len()
    }

    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// The proximity limit at `p` when it is below `cap`, else `None`.
    pub fn spacing_below(&self, p: DVec3, cap: f64) -> Option<f64> {
        self.samples.spacing_below(p, cap)
    }

    /// [`Self::spacing_below`] grading away from the samples at `rate` per unit distance.
    pub fn spacing_below_at(&self, p: DVec3, cap: f64, rate: f64) -> Option<f64> {
        self.samples.spacing_below_at(p, cap, rate)
    }
}

/// (point, width, sample step) for each boundary sample of `face` that faces another sample
/// closer than `max_width`.
fn face_gaps(model: &Model, face: FaceId, max_width: f64) -> Vec<(DVec3, f64, f64)> {
    let (samples, loop_lengths) = boundary_samples(model, face);
    let tree = RTree::bulk_load(
        samples
            .iter()
            .enumerate()
            .map(|(i, b)| GeomWithData::new(b.p.to_array(), i))
            .collect(),
    );
    let scale = samples
        .iter()
        .map(|b| b.p.abs().max_element())
        .fold(1.0, f64::max);
    let mut gaps = Vec::new();
    for a in &samples {
        if a.inward == DVec3::ZERO {
            continue;
        }
        // A range query, not a nearest-first walk: most candidates (the sample's neighbours
        // along its own edge) are rejected, and the walk paid a heap step for each.
        let facing = tree
            .locate_within_distance(a.p.to_array(), max_width * max_width)
            .filter_map(|q| {
                let b = &samples[q.data];
                if b.inward == DVec3::ZERO {
                    return None;
                }
                // The other side is the polyline through b, not b alone: where the gap is
                // much narrower than the sample step (a corner of 1°), the nearest sample
                // lies off to the side and would fail the facing test.
                let c = closest_on_polyline(&samples, q.data, a.p);
                let d = a.p.distance(c);
                if d <= 1e-9 * scale || d >= max_width {
                    return None;
                }
                if a.lp == b.lp {
                    let along = (a.s - b.s).abs();
                    let along = along.min(loop_lengths[a.lp] - along);
                    if along < ALONG_RATIO * d {
                        return None;
                    }
                }
                let dir = (c - a.p) / d;
                (dir.dot(a.inward) >= FACING_COS && -dir.dot(b.inward) >= FACING_COS).then_some(d)
            })
            .fold(f64::INFINITY, f64::min);
        if facing.is_finite() {
            gaps.push((a.p, facing, a.step));
        }
    }
    gaps
}

/// The point nearest `p` on the two segments of the loop's sample polyline that meet at
/// sample `i` (a segment whose other end is on another loop is left out).
fn closest_on_polyline(samples: &[BoundarySample], i: usize, p: DVec3) -> DVec3 {
    let b = &samples[i];
    let mut best = b.p;
    let neighbours = [i.checked_sub(1), Some(i + 1)];
    for j in neighbours.into_iter().flatten() {
        let Some(n) = samples.get(j).filter(|n| n.lp == b.lp) else {
            continue;
        };
        let e = n.p - b.p;
        let t = ((p - b.p).dot(e) / e.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        let c = b.p + t * e;
        if c.distance_squared(p) < best.distance_squared(p) {
            best = c;
        }
    }
    best
}

/// Samples along every loop of `face`, and each loop's length.
fn boundary_samples(model: &Model, face: FaceId) -> (Vec<BoundarySample>, Vec<f64>) {
    let f = &model.faces[face];
    let surface = f.surface.as_ref();
    let mut out: Vec<BoundarySample> = Vec::new();
    let mut lengths = Vec::new();
    for (lp, l) in f.loops.iter().enumerate() {
        let mut s = 0.0;
        let mut prev: Option<DVec3> = None;
        for u in &l.uses {
            let e = &model.edges[u.edge];
            let Some(c) = &e.curve else { continue };
            let (t0, t1) = e.range;
            let step = arc_estimate(c.as_ref(), e.range) / EDGE_SAMPLES as f64;
            for i in 0..EDGE_SAMPLES {
                let k = if u.reversed { EDGE_SAMPLES - i } else { i };
                let t = t0 + (t1 - t0) * k as f64 / EDGE_SAMPLES as f64;
                let d = c.derivs(t);
                if let Some(q) = prev {
                    s += q.distance(d.p);
                }
                prev = Some(d.p);
                let tangent = if u.reversed { -d.d1 } else { d.d1 };
                let uv = match &u.pcurve {
                    Some(pc) => Some(pc.point(t)),
                    None => surface.closest_uv(d.p, None),
                };
                let inward = uv
                    .map(|uv| surface.derivs(uv).normal_raw().cross(tangent))
                    .and_then(|n| n.try_normalize())
                    .unwrap_or(DVec3::ZERO);
                out.push(BoundarySample {
                    p: d.p,
                    inward,
                    lp,
                    s,
                    step,
                });
            }
        }
        if let (Some(q), Some(first)) = (prev, out.iter().find(|b| b.lp == lp)) {
            s += q.distance(first.p);
        }
        lengths.push(s);
    }
    (out, lengths)
}
