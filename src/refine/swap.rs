//! Generalised edge swaps by the min-max criterion (seed paper, "Face/edge swapping"): the n
//! tets around an edge (n = 3..7) are re-tessellated in the best of all the ways their ring
//! can be triangulated (the Catalan-many ways; the kernel's `remove_edge` finds the best by
//! dynamic programming instead of listing them), and two tets sharing a face become three
//! around an edge (2-3), whenever that lowers the largest dihedral angle present. Stretched
//! tets cut from points stacked along the normals then have their largest angle near 90°.

use crate::mesh::quality::tet_dihedrals;
use crate::volume::delaunay::Delaunay;
use crate::volume::improve::{flip_a_face_by, label, max_dihedral, max_dihedral_cos};
use crate::volume::OUTSIDE;
use glam::DVec3;
use rayon::prelude::*;

/// Tets whose largest dihedral angle is above this are worked on.
pub const TARGET_MAX_DIHEDRAL: f64 = 95.0;
/// The paper's limit: rings of more tets are rarely worth the work.
pub const MAX_SWAP_RING: usize = 7;
/// A change must raise the cosine of the largest angle by at least this much (no cycling on
/// rounding; about 6e-6 degrees at 90 degrees). The swaps compare cosines: the `acos` per
/// candidate tet was an eighth of their time.
const COS_GAIN: f64 = 1e-7;
const PASSES: usize = 30;

/// What the swaps did.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct SwapReport {
    pub passes: usize,
    pub edge_swaps: usize,
    pub face_swaps: usize,
}

/// The largest dihedral angle of tet `t` (degrees): what the swaps and the smoothing lower.
pub(super) fn score(dt: &Delaunay, t: u32) -> f64 {
    let v = dt.tet(t).map(|i| dt.point(i));
    max_dihedral(&v[0], &v[1], &v[2], &v[3])
}

/// The tets the swaps tried and could not improve, each with the triangulation's change count
/// at the time ([`Delaunay::changes`]). Whether a swap helps a tet depends only on the tets
/// around its edges and across its faces, so such a tet is not tried again until one of
/// them changes ([`Delaunay::unchanged_since`]). Most poor tets of a stretched region stay
/// poor through every insertion/swap cycle; trying them all again each time was most of the
/// swaps' time. Region labels are assumed to change only with the tets they label.
#[derive(Debug, Default)]
pub struct SwapMemo {
    /// Per tet slot: the change count when it last failed, or `NEVER`.
    failed_at: Vec<u64>,
}

const NEVER: u64 = u64::MAX;

impl SwapMemo {
    /// Tet `t` failed before and nothing around it has changed since.
    fn hopeless(&self, dt: &Delaunay, t: u32) -> bool {
        match self.failed_at.get(t as usize) {
            Some(&at) if at != NEVER => dt.unchanged_since(t, at),
            _ => false,
        }
    }

    fn failed(&mut self, dt: &Delaunay, t: u32) {
        if self.failed_at.len() <= t as usize {
            self.failed_at
                .resize(dt.slot_count().max(t as usize + 1), NEVER);
        }
        self.failed_at[t as usize] = dt.changes();
    }
}

/// Swap among the domain tets for which `include` says yes, worst largest angle first;
/// `memo` carries what could not be improved from one call to the next.
pub fn minmax_swaps(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    include: &(dyn Fn(&Delaunay, u32) -> bool + Sync),
    memo: &mut SwapMemo,
) -> SwapReport {
    let all: Vec<u32> = dt.tet_ids().collect();
    minmax_swaps_among(dt, region_of, include, all, &mut Vec::new(), memo)
}

/// [`minmax_swaps`] starting from the tets `start` only (a tet no swap could help stays
/// unhelped until its surroundings change, so a caller that knows what changed passes just
/// that); the tets the swaps made are appended to `made`.
pub fn minmax_swaps_among(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    include: &(dyn Fn(&Delaunay, u32) -> bool + Sync),
    start: Vec<u32>,
    made_all: &mut Vec<u32>,
    memo: &mut SwapMemo,
) -> SwapReport {
    let mut report = SwapReport::default();
    // The first pass looks at every poor tet of `start`; later passes only at what the swaps
    // made and its neighbours.
    // Callers pass the stars of moved points, which overlap: each tet once.
    let mut look_at = start;
    look_at.par_sort_unstable();
    look_at.dedup();
    for _ in 0..PASSES {
        report.passes += 1;
        let mut bad = poor_tets(dt, region_of, include, memo, look_at);
        if bad.is_empty() {
            break;
        }
        bad.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
        bad.dedup_by_key(|x| x.1);
        let mut made: Vec<u32> = Vec::new();
        for &(_, t) in &bad {
            if !dt.is_live(t) || dt.is_ghost(t) || region_of[t as usize] == OUTSIDE {
                continue;
            }
            if score(dt, t) <= TARGET_MAX_DIHEDRAL {
                continue;
            }
            if let Some(c) = swap_an_edge(dt, region_of, t) {
                report.edge_swaps += 1;
                made.extend(c);
            } else if let Some(c) = swap_a_face(dt, region_of, t) {
                report.face_swaps += 1;
                made.extend(c);
            } else {
                memo.failed(dt, t);
            }
        }
        if made.is_empty() {
            break;
        }
        made_all.extend(&made);
        let mut next: Vec<u32> = Vec::with_capacity(made.len() * 5);
        for &t in &made {
            if !dt.is_live(t) || dt.is_ghost(t) {
                continue;
            }
            next.push(t);
            for f in 0..4u8 {
                next.push(dt.neighbor(t, f).0);
            }
        }
        next.sort_unstable();
        next.dedup();
        look_at = next;
    }
    report
}

/// The tets of `ts` worth a try, with their largest angle: live domain tets above the target
/// that `include` takes and the memo does not know to be hopeless (the cheap tests first:
/// `include` may ask a distance tree).
fn poor_tets(
    dt: &Delaunay,
    region_of: &[u32],
    include: &(dyn Fn(&Delaunay, u32) -> bool + Sync),
    memo: &SwapMemo,
    ts: Vec<u32>,
) -> Vec<(f64, u32)> {
    ts.into_par_iter()
        .filter(|&t| {
            dt.is_live(t)
                && !dt.is_ghost(t)
                && region_of[t as usize] != OUTSIDE
                && !memo.hopeless(dt, t)
        })
        .map(|t| (score(dt, t), t))
        .filter(|&(q, t)| q > TARGET_MAX_DIHEDRAL && include(dt, t))
        .collect()
}

/// Re-tessellate the ring of one of `t`'s edges when that lowers the ring's largest angle.
/// Only the edges whose own dihedral angle is above the target are tried, largest first:
/// removing an edge with a good angle leaves the poor one in place (and trying all six cost
/// most of the refinement's time).
fn swap_an_edge(dt: &mut Delaunay, region_of: &mut Vec<u32>, t: u32) -> Option<Vec<u32>> {
    const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    let v = dt.tet(t);
    let region = region_of[t as usize];
    // A zero-area face (three points of one layer in a row) has no angle: it is the worst.
    let angles = tet_dihedrals(v.map(|i| DVec3::from_array(dt.point(i)))).map(|a| {
        if a.is_finite() {
            a
        } else {
            180.0
        }
    });
    let mut order: Vec<usize> = (0..6)
        .filter(|&e| angles[e] > TARGET_MAX_DIHEDRAL)
        .collect();
    order.sort_by(|&x, &y| angles[y].total_cmp(&angles[x]));
    for e in order {
        let (i, j) = EDGES[e];
        let (a, b) = (v[i], v[j]);
        let (ring, _) = dt.tets_around_edge_of_tet(t, a, b);
        if ring.len() > MAX_SWAP_RING
            || ring
                .iter()
                .any(|&u| dt.is_ghost(u) || region_of[u as usize] != region)
        {
            continue;
        }
        // The kernel maximises the minimum score: the cosine of the largest angle.
        let worst = ring
            .iter()
            .map(|&u| {
                let q = dt.tet(u).map(|i| dt.point(i));
                max_dihedral_cos(&q[0], &q[1], &q[2], &q[3])
            })
            .fold(1.0, f64::min);
        let current = worst + COS_GAIN;
        if let Ok(created) = dt.remove_edge_if_better(Some(t), a, b, current, max_dihedral_cos) {
            label(region_of, dt.slot_count(), &created, region);
            return Some(created);
        }
    }
    None
}

/// A 2-3 flip through one of `t`'s faces when that lowers the pair's largest angle.
fn swap_a_face(dt: &mut Delaunay, region_of: &mut Vec<u32>, t: u32) -> Option<Vec<u32>> {
    flip_a_face_by(dt, region_of, t, &max_dihedral_cos, COS_GAIN).map(|c| c.to_vec())
}
