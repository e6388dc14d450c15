//! Interior points by the centroid method (seed paper, "Volume mesh generation"): the centroid
//! of every tet is a candidate; it is kept when no point lies closer than a fraction of the
//! spacing δ there, and it keeps the same distance from the plane of any boundary face of its
//! tet. Accepted points go in as one batch through the kernel (whose cavities never cross the
//! recovered boundary); the next round looks only at the tets that batch created. Rounds stop
//! when nothing is accepted.
//!
//! Speed: δ is evaluated once per point (at insertion) and interpolated at centroids as the
//! mean of the tet's corners, or the sources' spacing at the centroid itself where that is
//! below half of it (a source in the open, a wake's line source, is seen by no corner until
//! points reach it); the nearest old point of a centroid is looked for among the
//! corners of its tet and of the tet's face neighbours (the Delaunay neighbourhood), and only
//! this round's accepted points sit in a spatial tree; the new tets inherit their region from
//! the old tets around the cavity instead of a full reclassification.

use super::boundary::OUTSIDE;
use super::delaunay::Delaunay;
use crate::progress::Reporter;
use crate::sizing::SizingField;
use glam::DVec3;
use rayon::prelude::*;
use rstar::RTree;

/// A candidate closer than `SPACING_FRACTION · δ` to an existing point is refused. With 0.7,
/// the points settle at edge lengths close to δ (measured on uniform boxes: mean edge ≈ δ).
pub const SPACING_FRACTION: f64 = 0.7;
/// A candidate closer than `BOUNDARY_FRACTION · δ` to the plane of a boundary face of its tet
/// is refused: it would make a flat tet against the surface.
pub const BOUNDARY_FRACTION: f64 = 0.4;
/// Safety bound; uniform fields need about a dozen rounds.
const MAX_ROUNDS: usize = 200;

/// What the interior-point stage did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct InteriorReport {
    pub rounds: usize,
    pub points: usize,
    /// Candidates the kernel refused (exactly on a recovered boundary face).
    pub refused_on_boundary: usize,
}

/// Where interior points must not go (point, δ there): the zone directional refinement fills
/// with its own layers.
pub type KeepOut<'a> = dyn Fn(DVec3, f64) -> bool + Sync + 'a;

/// Insert interior points until every tet meets the spacing; `region_of` (per tet slot) is
/// kept up to date.
pub fn insert_interior_points(
    dt: &mut Delaunay,
    sizing: &SizingField,
    region_of: &mut Vec<u32>,
    side: &dyn Fn(&Delaunay, u32, u8) -> Option<u32>,
    keep_out: Option<&KeepOut<'_>>,
    progress: Reporter<'_>,
) -> InteriorReport {
    let mut report = InteriorReport::default();
    let mut delta: Vec<f64> = (0..dt.num_points() as u32)
        .into_par_iter()
        .map(|v| sizing.volume_spacing(DVec3::from_array(dt.point(v))))
        .collect();
    let mut look_at: Vec<u32> = dt
        .tet_ids()
        .filter(|&t| region_of[t as usize] != OUTSIDE)
        .collect();
    let expected = if progress.cancelled() {
        0
    } else {
        expected_points(dt, sizing, &delta, &look_at)
    };
    progress.progress("interior", 0, expected);
    // A cancelled run stops between rounds; the caller returns `Cancelled`.
    while !look_at.is_empty() && report.rounds < MAX_ROUNDS && !progress.cancelled() {
        let mut candidates: Vec<(DVec3, f64)> = look_at
            .par_iter()
            .filter_map(|&t| candidate(dt, sizing, &delta, t))
            .filter(|(c, d)| keep_out.is_none_or(|k| !k(*c, *d)))
            .collect();
        // Accepted greedily in this order: by position, not by tet id, so the points do not
        // depend on where the kernel's parallel insertion happened to store its tets.
        candidates.par_sort_unstable_by(|a, b| {
            (a.0.x.total_cmp(&b.0.x))
                .then(a.0.y.total_cmp(&b.0.y))
                .then(a.0.z.total_cmp(&b.0.z))
        });
        let mut this_round: RTree<[f64; 3]> = RTree::new();
        let mut accepted: Vec<[f64; 3]> = Vec::new();
        for (c, d) in candidates {
            let p = c.to_array();
            let min = SPACING_FRACTION * d;
            let near = this_round
                .nearest_neighbor(&p)
                .map(|q| DVec3::from_array(*q).distance_squared(c))
                .unwrap_or(f64::INFINITY);
            if near >= min * min {
                this_round.insert(p);
                accepted.push(p);
            }
        }
        if accepted.is_empty() {
            break;
        }
        report.rounds += 1;
        let outcome = match dt.insert_batch(&accepted) {
            Ok(o) => o,
            Err(_) => break,
        };
        report.points += accepted.len() - outcome.on_constrained_face.len();
        report.refused_on_boundary += outcome.on_constrained_face.len();
        progress.progress("interior", report.points as u64, expected);
        let fresh: Vec<f64> = accepted
            .par_iter()
            .map(|p| sizing.volume_spacing(DVec3::from_array(*p)))
            .collect();
        delta.extend(fresh);
        label_created(dt, region_of, &outcome.created, side);
        look_at = outcome
            .created
            .into_iter()
            .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
            .collect();
    }
    report
}

/// About how many points the rounds will insert, for progress only: each region tet's volume
/// over the volume per point of a regular mesh of spacing δ (δ³/√2 for an FCC-like packing),
/// with δ the geometric mean over its centroid and corners, since the first tets span the
/// graded field from the surface outwards and δ grows geometrically there. Measured: cube
/// sample (uniform) 2177 expected for 2073 inserted, turbine 56800 for 73349, wing 45259 for
/// 119050 (the arithmetic mean of δ gave 19133, that of 1/δ³ 15 million). An estimate:
/// `done` may pass it. `delta` holds δ at every point already, so only the centroids are
/// asked of the sizing field.
fn expected_points(dt: &Delaunay, sizing: &SizingField, delta: &[f64], tets: &[u32]) -> u64 {
    let sum: f64 = tets
        .par_iter()
        .map(|&t| {
            let corners = dt.tet(t);
            let p = corners.map(|v| DVec3::from_array(dt.point(v)));
            let volume = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])).abs() / 6.0;
            let centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
            let ln = |d: f64| d.max(f64::MIN_POSITIVE).ln();
            let at_corners: f64 = corners.iter().map(|&v| ln(delta[v as usize])).sum();
            let delta = ((ln(sizing.volume_spacing(centroid)) + at_corners) / 5.0).exp();
            volume * std::f64::consts::SQRT_2 / delta.powi(3)
        })
        .sum();
    if sum.is_finite() {
        sum as u64
    } else {
        0
    }
}

/// Regions of the tets a batch created: each inherits, across an unconstrained face, the
/// region of an older neighbour (a cavity never crosses a recovered face, so the whole cavity
/// lay in one region). When a cavity took a whole piece of the mesh (a small region in the
/// first round), no older neighbour is left: then the recovered faces tell, through `side`
/// (the region on a tet's side of its constrained face).
pub fn label_created(
    dt: &Delaunay,
    region_of: &mut Vec<u32>,
    created: &[u32],
    side: &dyn Fn(&Delaunay, u32, u8) -> Option<u32>,
) {
    const UNKNOWN: u32 = u32::MAX - 1;
    region_of.resize(dt.slot_count().max(region_of.len()), OUTSIDE);
    for &t in created {
        region_of[t as usize] = UNKNOWN;
    }
    let mut pending: Vec<u32> = created.to_vec();
    while !pending.is_empty() {
        let before = pending.len();
        pending.retain(|&t| {
            for f in 0..4u8 {
                if dt.is_constrained(t, f) {
                    continue;
                }
                let (u, _) = dt.neighbor(t, f);
                let r = region_of[u as usize];
                if r != UNKNOWN {
                    region_of[t as usize] = if dt.is_ghost(u) { OUTSIDE } else { r };
                    return false;
                }
            }
            true
        });
        if pending.len() == before {
            let seeded = pending.iter().position(|&t| {
                (0..4u8).any(|f| {
                    if !dt.is_constrained(t, f) {
                        return false;
                    }
                    match side(dt, t, f) {
                        Some(r) => {
                            region_of[t as usize] = r;
                            true
                        }
                        None => false,
                    }
                })
            });
            match seeded {
                Some(k) => {
                    pending.swap_remove(k);
                }
                None => {
                    // No recovered face and no old neighbour: cannot happen for a cavity
                    // grown inside a region; leave it outside rather than guess.
                    for &t in &pending {
                        region_of[t as usize] = OUTSIDE;
                    }
                    break;
                }
            }
        }
    }
}

/// The centroid of tet `t` and δ there, unless an old point or a boundary face of `t` is too
/// close.
fn candidate(dt: &Delaunay, sizing: &SizingField, delta: &[f64], t: u32) -> Option<(DVec3, f64)> {
    let ids = dt.tet(t);
    let v = ids.map(|i| DVec3::from_array(dt.point(i)));
    let c = (v[0] + v[1] + v[2] + v[3]) * 0.25;
    let corners = ids.iter().map(|&i| delta[i as usize]).sum::<f64>() * 0.25;
    // The sources at the centroid itself only where they ask for much less than the corners
    // say: near the surface the corners already carry the sources' spacing.
    let at_centre = sizing.source_spacing(c);
    let d = if at_centre < 0.5 * corners {
        at_centre
    } else {
        corners
    };
    let limit = SPACING_FRACTION * d;
    let too_close = |p: DVec3| p.distance_squared(c) < limit * limit;
    if v.iter().any(|&p| too_close(p)) {
        return None;
    }
    for f in 0..4u8 {
        if dt.is_constrained(t, f) {
            let [a, b, e] = dt
                .face_vertices(t, f)
                .map(|i| DVec3::from_array(dt.point(i)));
            let n = (b - a).cross(e - a);
            let len = n.length();
            if len == 0.0 || (c - a).dot(n).abs() / len < BOUNDARY_FRACTION * d {
                return None;
            }
        } else {
            let (u, g) = dt.neighbor(t, f);
            let far = dt.tet(u)[g as usize];
            if far != super::delaunay::INF && too_close(DVec3::from_array(dt.point(far))) {
                return None;
            }
        }
    }
    Some((c, d))
}
