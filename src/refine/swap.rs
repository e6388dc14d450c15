//! Generalised edge swaps by the min-max criterion (seed paper, "Face/edge swapping"): the n
//! tets around an edge (n = 3..7) are re-tessellated in the best of all the ways their ring
//! can be triangulated (the Catalan-many ways; the kernel's `remove_edge` finds the best by
//! dynamic programming instead of listing them), and two tets sharing a face become three
//! around an edge (2-3), whenever that lowers the largest dihedral angle present. Stretched
//! tets cut from points stacked along the normals then have their largest angle near 90°.

use crate::mesh::quality::tet_dihedrals;
use crate::volume::delaunay::Delaunay;
use crate::volume::improve::{flip_a_face_by, label, max_dihedral};
use crate::volume::OUTSIDE;
use glam::DVec3;
use rayon::prelude::*;

/// Tets whose largest dihedral angle is above this are worked on.
pub const TARGET_MAX_DIHEDRAL: f64 = 95.0;
/// The paper's limit: rings of more tets are rarely worth the work.
pub const MAX_SWAP_RING: usize = 7;
/// A change must lower the largest angle by at least this much (degrees): no cycling.
const GAIN: f64 = 1e-3;
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

/// Swap among the domain tets for which `include` says yes, worst largest angle first.
pub fn minmax_swaps(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    include: &(dyn Fn(&Delaunay, u32) -> bool + Sync),
) -> SwapReport {
    let all: Vec<u32> = dt.tet_ids().collect();
    minmax_swaps_among(dt, region_of, include, all, &mut Vec::new())
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
) -> SwapReport {
    let mut report = SwapReport::default();
    // The first pass looks at every poor tet of `start`; later passes only at what the swaps
    // made and its neighbours.
    let mut look_at: Vec<u32> = start
        .into_par_iter()
        .filter(|&t| {
            dt.is_live(t) && !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE && include(dt, t)
        })
        .collect();
    for _ in 0..PASSES {
        report.passes += 1;
        let mut bad: Vec<(f64, u32)> = look_at
            .par_iter()
            .filter(|&&t| dt.is_live(t) && !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
            .map(|&t| (score(dt, t), t))
            .filter(|&(q, _)| q > TARGET_MAX_DIHEDRAL)
            .collect();
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
        look_at = next
            .into_par_iter()
            .filter(|&t| dt.is_live(t) && !dt.is_ghost(t) && include(dt, t))
            .collect();
    }
    report
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
        let worst = ring.iter().map(|&u| score(dt, u)).fold(0.0, f64::max);
        // The kernel maximises the minimum score: the negated largest angle.
        let current = -(worst - GAIN);
        let minus =
            |p: &[f64; 3], q: &[f64; 3], r: &[f64; 3], s: &[f64; 3]| -max_dihedral(p, q, r, s);
        if let Ok(created) = dt.remove_edge_if_better(Some(t), a, b, current, minus) {
            label(region_of, dt.slot_count(), &created, region);
            return Some(created);
        }
    }
    None
}

/// A 2-3 flip through one of `t`'s faces when that lowers the pair's largest angle.
fn swap_a_face(dt: &mut Delaunay, region_of: &mut Vec<u32>, t: u32) -> Option<Vec<u32>> {
    let minus = |p: &[f64; 3], q: &[f64; 3], r: &[f64; 3], s: &[f64; 3]| -max_dihedral(p, q, r, s);
    flip_a_face_by(dt, region_of, t, &minus, GAIN).map(|c| c.to_vec())
}
