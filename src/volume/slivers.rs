//! Sliver removal by point insertion, after flips and smoothing have done what they can.
//!
//! A sliver whose four corners cannot move (all on the surface) and that no flip removes —
//! a flat tet resting on one or two boundary faces — is broken by a new interior point: the
//! sliver is split at its centroid, Lawson flips around the point (never across a recovered
//! face) connect it to the tets beyond the sliver's interior faces, and the point is then
//! smoothed (hill-climb on its star's worst angle, which lifts it off the surface) and the
//! edges of its worst tets are offered to edge removal.

use super::boundary::OUTSIDE;
use super::delaunay::Delaunay;
use super::improve::{min_dihedral, polish_vertex};
use glam::DVec3;

/// Tets below this many degrees with no movable corner get a point.
pub const SLIVER_BELOW: f64 = 5.0;
/// Tets below this many degrees get a point whatever their corners (what smoothing left).
pub const ALWAYS_BELOW: f64 = 1.0;
/// Insertion rounds; each looks again at what is still below [`SLIVER_BELOW`].
const ROUNDS: usize = 5;
/// Lawson flips allowed around one new point.
const FLIP_LIMIT: usize = 64;

/// Tets sliver removal leaves alone: those in the zone directional refinement rebuilds
/// afterwards (its layers replace them; points there would only be cleared again).
pub type LeaveAlone<'a> = dyn Fn(&Delaunay, u32) -> bool + Sync + 'a;

/// What sliver removal did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct SliverReport {
    /// Slivers found in the first round.
    pub found: usize,
    /// Points inserted.
    pub points: usize,
    /// Slivers left after the last round.
    pub left: usize,
}

/// Insert points to break slivers of the domain (`region_of` kept up to date).
pub fn remove_slivers(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    first_movable: u32,
    leave: &LeaveAlone<'_>,
) -> SliverReport {
    let mut report = SliverReport::default();
    // Points of this stage whose star still held a tet below ALWAYS_BELOW after their polish:
    // a sliver at such a point gets no further point. In a gap between two surfaces far
    // narrower than the spacing, every point only makes new slivers (gmsh_solid_56.step put
    // 55-70 k points in one 0.002-wide slot, and spent minutes doing it).
    let mut failed: std::collections::HashSet<u32> = Default::default();
    for round in 0..ROUNDS {
        let slivers = slivers(dt, region_of, first_movable, leave);
        if round == 0 {
            report.found = slivers.len();
        }
        if slivers.is_empty() {
            break;
        }
        for t in slivers {
            if !dt.is_live(t) || region_of[t as usize] == OUTSIDE || score(dt, t) >= SLIVER_BELOW {
                continue;
            }
            if dt.tet(t).iter().any(|c| failed.contains(c)) {
                continue;
            }
            // Corners that may move get another polish first (earlier points of this pass
            // may have changed their stars); a point is the last resort.
            for c in dt.tet(t) {
                if c >= first_movable {
                    polish_vertex(dt, region_of, c);
                }
            }
            if !dt.is_live(t) || score(dt, t) >= SLIVER_BELOW {
                continue;
            }
            let region = region_of[t as usize];
            let v = dt.tet(t).map(|i| DVec3::from_array(dt.point(i)));
            let centroid = (v[0] + v[1] + v[2] + v[3]) * 0.25;
            // Split the sliver at its centroid, then let Lawson flips around the new point
            // reach past the sliver's interior faces: a plain Bowyer–Watson insertion misses a
            // flat sliver whose circumsphere lies on the far side of the surface.
            let Ok(split) = dt.insert_split(centroid.to_array(), Some(t), &|_| false) else {
                continue;
            };
            dt.flip_around(split.vertex, &|_| false, FLIP_LIMIT);
            let star = dt.tets_around_vertex(split.vertex);
            if region_of.len() < dt.slot_count() {
                region_of.resize(dt.slot_count(), OUTSIDE);
            }
            for &u in &star {
                region_of[u as usize] = region;
            }
            report.points += 1;
            polish_vertex(dt, region_of, split.vertex);
            let worst = dt
                .tets_around_vertex(split.vertex)
                .into_iter()
                .filter(|&u| !dt.is_ghost(u))
                .map(|u| score(dt, u))
                .fold(f64::INFINITY, f64::min);
            if worst < ALWAYS_BELOW {
                failed.insert(split.vertex);
            }
        }
    }
    report.left = slivers(dt, region_of, first_movable, leave).len();
    report
}

fn score(dt: &Delaunay, t: u32) -> f64 {
    let v = dt.tet(t).map(|i| dt.point(i));
    min_dihedral(&v[0], &v[1], &v[2], &v[3])
}

/// Domain tets below [`ALWAYS_BELOW`], and below [`SLIVER_BELOW`] with no corner that
/// smoothing may move, worst first.
/// (Between 1° and 5° with a movable corner, a new point made things worse than smoothing
/// on the ONERA wing.)
fn slivers(
    dt: &Delaunay,
    region_of: &[u32],
    first_movable: u32,
    leave: &LeaveAlone<'_>,
) -> Vec<u32> {
    let mut found: Vec<(f64, u32)> = dt
        .tet_ids()
        .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
        .map(|t| (score(dt, t), t))
        .filter(|&(q, t)| {
            (q < ALWAYS_BELOW || (q < SLIVER_BELOW && dt.tet(t).iter().all(|&v| v < first_movable)))
                && !leave(dt, t)
        })
        .collect();
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    found.into_iter().map(|(_, t)| t).collect()
}
