//! Sliver removal by point insertion, after flips and smoothing have done what they can.
//!
//! A sliver whose four corners cannot move (all on the surface, or pinned between bad tets)
//! and that no flip removes — typically a flat tet resting on a boundary face — is broken by
//! a new interior point: above the sliver's boundary face at the height of a regular tet on
//! that face, or at the sliver's centroid when it has no boundary face. The kernel's cavity
//! never crosses a recovered face, so the surface stays as it is. The new point is then
//! smoothed (hill-climb on its star's worst angle) and the edges of its worst tets are offered
//! to edge removal.

use super::boundary::OUTSIDE;
use super::delaunay::Delaunay;
use super::improve::{min_dihedral, polish_vertex};
use glam::DVec3;

/// Tets below this many degrees get a point.
pub const SLIVER_BELOW: f64 = 5.0;
/// Insertion rounds; each looks again at what is still below [`SLIVER_BELOW`].
const ROUNDS: usize = 3;

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

/// Gives the tets an insertion created (the slice) their region in `region_of`.
pub type LabelNew<'a> = dyn Fn(&Delaunay, &mut Vec<u32>, &[u32]) + 'a;

/// Insert points to break slivers of the domain; `label` gives the tets an insertion created
/// their region (as interior points do).
pub fn remove_slivers(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    first_movable: u32,
    label: &LabelNew<'_>,
) -> SliverReport {
    let mut report = SliverReport::default();
    for round in 0..ROUNDS {
        let slivers = slivers(dt, region_of, first_movable);
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
            let p = breaking_point(dt, t);
            let Ok(outcome) = dt.insert(p.to_array(), Some(t)) else {
                continue;
            };
            label(dt, region_of, &outcome.created);
            report.points += 1;
            polish_vertex(dt, region_of, outcome.vertex);
        }
    }
    report.left = slivers(dt, region_of, first_movable).len();
    report
}

fn score(dt: &Delaunay, t: u32) -> f64 {
    let v = dt.tet(t).map(|i| dt.point(i));
    min_dihedral(&v[0], &v[1], &v[2], &v[3])
}

/// Domain tets below [`SLIVER_BELOW`] with no corner that smoothing may move, worst first.
/// (With a movable corner, a new point made things worse than smoothing on the ONERA wing:
/// the new point's cavity takes out tets the flips had improved.)
fn slivers(dt: &Delaunay, region_of: &[u32], first_movable: u32) -> Vec<u32> {
    let mut found: Vec<(f64, u32)> = dt
        .tet_ids()
        .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
        .filter(|&t| dt.tet(t).iter().all(|&v| v < first_movable))
        .map(|t| (score(dt, t), t))
        .filter(|&(q, _)| q < SLIVER_BELOW)
        .collect();
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    found.into_iter().map(|(_, t)| t).collect()
}

/// Where to put the point that breaks sliver `t`: above its largest boundary face, on the
/// tet's side, at the height of a regular tet on that face; else its centroid.
fn breaking_point(dt: &Delaunay, t: u32) -> DVec3 {
    let ids = dt.tet(t);
    let p = ids.map(|i| DVec3::from_array(dt.point(i)));
    let centroid = (p[0] + p[1] + p[2] + p[3]) * 0.25;
    let mut best: Option<(f64, DVec3)> = None;
    for f in 0..4u8 {
        if !dt.is_constrained(t, f) {
            continue;
        }
        let [a, b, c] = dt
            .face_vertices(t, f)
            .map(|i| DVec3::from_array(dt.point(i)));
        let n = (b - a).cross(c - a);
        let area2 = n.length();
        if area2 == 0.0 {
            continue;
        }
        let mut n = n / area2;
        // Into the tet: towards the corner opposite the face.
        if n.dot(p[f as usize] - a) < 0.0 {
            n = -n;
        }
        let edge = (a.distance(b) + b.distance(c) + c.distance(a)) / 3.0;
        let above = (a + b + c) / 3.0 + n * (edge * (2.0f64 / 3.0).sqrt());
        if best.is_none_or(|(s, _)| area2 > s) {
            best = Some((area2, above));
        }
    }
    best.map_or(centroid, |(_, q)| q)
}
