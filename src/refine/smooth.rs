//! Smoothing in the layers: the vertices of the stretched region's poor tets (largest dihedral
//! angle above [`SMOOTH_ABOVE`]) are moved to lower their star's largest angle, alternating with
//! the min-max swaps, once every stage's points are in.
//!
//! The poor tets are where the regular pattern breaks: where the columns fan out or converge
//! (leading edge, trailing edge, tip), where a column stopped and its neighbours went on, and at
//! the top of the layers, where the cells are nearly isotropic and meet the isotropic mesh. No
//! swap fixes a tet whose four points are badly placed for every connection; a move does.
//!
//! A column point moves within its layer — in the plane through it normal to its column's
//! direction (of every stage whose column it is in) — so the layer spacing stays what the
//! distribution asks; only where the layers are nearly isotropic (spacing at least half the
//! isotropic δ) may it also move along its column, by at most [`NORMAL_SLACK`] of the spacing,
//! so that four points of one layer left as a flat tet can part. The moves are a fraction of
//! the star's shortest edge, so the plane's departure from the curved layer is second order. A point off the columns (an
//! element-driven candidate, an isotropic point capping the layers) moves freely. Boundary
//! nodes never move.

use super::field::StageField;
use super::swap::{self, score, SwapReport};
use super::volume::PointData;
use crate::volume::delaunay::Delaunay;
use crate::volume::improve::{better_position, max_dihedral_cos, Combine, VertexMove};
use crate::volume::OUTSIDE;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};

/// Tets whose largest dihedral angle (degrees) is above this have their vertices moved.
pub const SMOOTH_ABOVE: f64 = 110.0;
/// How far a column point where the layers are nearly isotropic may leave its layer, along its
/// column, in its layer's spacing.
pub const NORMAL_SLACK: f64 = 0.1;
/// Rounds of moves and swaps.
const ROUNDS: usize = 8;
/// Gradient steps per move: a point moves again next round, as its neighbours do.
const CLIMB_STEPS: usize = 3;
/// A move may not bring a vertex nearer to a neighbour than this fraction of its shortest
/// edge before smoothing: angles do not see size, so two neighbours in a flat star can
/// otherwise walk onto each other over the rounds (1.1e-6 apart at the wing/fuselage root).
const EDGE_KEPT: f64 = 0.25;

/// What the smoothing did.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct SmoothReport {
    pub rounds: usize,
    /// Vertex moves that lowered their star's largest angle.
    pub moved: usize,
    /// Swaps after the moves.
    pub swaps: SwapReport,
}

/// Smooth the vertices of the poor tets for which `include` says yes (the stretched region,
/// judged from `data`),
/// vertices from `first_movable` on; `data` per stage (their columns and distances, updated for
/// the points that move).
pub fn smooth_layers(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    fields: &[StageField],
    data: &mut [PointData],
    first_movable: u32,
    include: &(dyn Fn(&Delaunay, &[PointData], u32) -> bool + Sync),
    memo: &mut swap::SwapMemo,
) -> SmoothReport {
    let mut report = SmoothReport::default();
    // After the first round, only vertices whose star changed (a neighbour moved, a swap
    // remade a tet) are tried again: a move found impossible stays impossible until then.
    let mut changed: Option<HashSet<u32>> = None;
    // Each vertex's shortest edge the first time it is tried, times EDGE_KEPT.
    let mut floor: HashMap<u32, f64> = HashMap::new();
    for _ in 0..ROUNDS {
        report.rounds += 1;
        let clock = std::time::Instant::now();
        let known: &[PointData] = data;
        let mut poor: Vec<(f64, u32)> = dt
            .tet_ids()
            .filter(|&t| region_of[t as usize] != OUTSIDE)
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|t| (score(dt, t), t))
            .filter(|&(q, t)| q > SMOOTH_ABOVE && include(dt, known, t))
            .collect();
        if poor.is_empty() {
            break;
        }
        // Worst first: a vertex shared by several poor tets moves for the worst of them.
        poor.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
        log::debug!(
            "layer smoothing round {}: {} poor tets, {} above 125°, {} above 150°",
            report.rounds,
            poor.len(),
            poor.iter().filter(|p| p.0 > 125.0).count(),
            poor.iter().filter(|p| p.0 > 150.0).count()
        );
        let mut seen = HashSet::new();
        let vertices: Vec<u32> = poor
            .iter()
            .flat_map(|&(_, t)| dt.tet(t))
            .filter(|&v| {
                v >= first_movable
                    && seen.insert(v)
                    && changed.as_ref().is_none_or(|c| c.contains(&v))
            })
            .collect();
        let first_round = changed.is_none();
        let mut moved = 0;
        let mut moved_tets: Vec<u32> = Vec::new();
        let mut left = vertices;
        while !left.is_empty() {
            let (batch, rest) = independent(dt, region_of, left);
            left = rest;
            for (v, star) in &batch {
                floor
                    .entry(*v)
                    .or_insert_with(|| EDGE_KEPT * shortest_edge(dt, *v, star, None));
            }
            let known: &[PointData] = data;
            let dt_ref: &Delaunay = dt;
            let to: Vec<Option<DVec3>> = batch
                .par_iter()
                .map(|(v, star)| {
                    let normals = column_normals(fields, known, *v, 0.0);
                    let at = DVec3::from_array(dt_ref.point(*v));
                    let project = |p: DVec3| in_layer(p, at, &normals);
                    let how = VertexMove {
                        score: excess,
                        combine: Combine::Sum,
                        project: &project,
                        climb: CLIMB_STEPS,
                    };
                    better_position(dt_ref, *v, star, &how)
                })
                .collect();
            for ((v, star), p) in batch.iter().zip(to) {
                let Some(p) = p else { continue };
                if shortest_edge(dt, *v, star, Some(p)) < floor[v] {
                    continue;
                }
                move_point(dt, fields, data, *v, p);
                moved_tets.extend(star);
                moved += 1;
            }
        }
        report.moved += moved;
        let moving = clock.elapsed().as_secs_f64();
        let known: &[PointData] = data;
        // The first round's swaps look at every tet; later ones at the moved stars.
        let start = if first_round {
            dt.tet_ids().collect()
        } else {
            moved_tets.clone()
        };
        let mut made = Vec::new();
        let s = swap::minmax_swaps_among(
            dt,
            region_of,
            &|dt: &Delaunay, t| include(dt, known, t),
            start,
            &mut made,
            memo,
        );
        changed = Some(
            moved_tets
                .iter()
                .chain(&made)
                .filter(|&&t| dt.is_live(t))
                .flat_map(|&t| dt.tet(t))
                .collect(),
        );
        log::debug!(
            "layer smoothing round {}: {moved} moves in {moving:.1} s, {} swaps in {:.1} s",
            report.rounds,
            s.edge_swaps + s.face_swaps,
            clock.elapsed().as_secs_f64() - moving
        );
        report.swaps.passes += s.passes;
        report.swaps.edge_swaps += s.edge_swaps;
        report.swaps.face_swaps += s.face_swaps;
        if moved == 0 {
            break;
        }
    }
    report
}

/// The shortest edge from vertex `v` (or from `at`, were it there) to the other vertices of
/// its `star`.
fn shortest_edge(dt: &Delaunay, v: u32, star: &[u32], at: Option<DVec3>) -> f64 {
    let from = at.unwrap_or_else(|| DVec3::from_array(dt.point(v)));
    (star.iter())
        .flat_map(|&t| dt.tet(t))
        .filter(|&w| w != v)
        .map(|w| from.distance(DVec3::from_array(dt.point(w))))
        .fold(f64::INFINITY, f64::min)
}

/// Move vertex `v` to `p`, and its distances to every stage's sources with it.
pub(super) fn move_point(
    dt: &mut Delaunay,
    fields: &[StageField],
    data: &mut [PointData],
    v: u32,
    p: DVec3,
) {
    dt.set_point(v, p.to_array());
    for (d, f) in data.iter_mut().zip(fields) {
        if let Some(n) = d.near.get_mut(v as usize) {
            *n = f.near(p);
        }
    }
}

/// Of `vertices` (in order), those that share no tet with an earlier one taken, each with its
/// star (finite domain tets only: a vertex on the hull or beside the outside is dropped), and
/// the rest. Moves of the taken vertices do not interact: they are found in parallel, and
/// come out the same on any number of threads.
fn independent(
    dt: &mut Delaunay,
    region_of: &[u32],
    vertices: Vec<u32>,
) -> (Vec<(u32, Vec<u32>)>, Vec<u32>) {
    let mut blocked: HashSet<u32> = HashSet::new();
    let (mut taken, mut rest) = (Vec::new(), Vec::new());
    for v in vertices {
        if blocked.contains(&v) {
            rest.push(v);
            continue;
        }
        let star = dt.tets_around_vertex(v);
        if star
            .iter()
            .any(|&t| dt.is_ghost(t) || region_of[t as usize] == OUTSIDE)
        {
            continue;
        }
        for &t in &star {
            blocked.extend(dt.tet(t));
        }
        taken.push((v, star));
    }
    (taken, rest)
}

/// Largest dihedral angles above this (degrees) count against a star.
const EXCESS_ABOVE: f64 = 100.0;
/// cos [`EXCESS_ABOVE`].
const EXCESS_ABOVE_COS: f64 = -0.173_648_177_666_930_4;

/// Minus the squared excess of a tet's largest dihedral angle over [`EXCESS_ABOVE`]: summed
/// over a star, it weighs the poorest tets most and leaves the good ones alone.
fn excess(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let cos = max_dihedral_cos(a, b, c, d);
    // Most of a star is below the threshold: no `acos` for those.
    if cos >= EXCESS_ABOVE_COS {
        return 0.0;
    }
    let e = (cos.clamp(-1.0, 1.0).acos().to_degrees() - EXCESS_ABOVE).max(0.0);
    -e * e
}

/// The unit directions of the columns vertex `v` belongs to, one per stage, made orthonormal
/// (a point in the layers of two stages, at a corner, moves along the line they leave), each
/// with how far the point may move along it, down and up, to stay within the slack of its
/// site.
/// Where the layers are not nearly isotropic, a point may leave its layer by `slack` of the
/// spacing (none for the smoothing; a little for the last resort against flat tets).
pub(super) fn column_normals(
    fields: &[StageField],
    data: &[PointData],
    v: u32,
    slack: f64,
) -> Vec<(DVec3, f64, f64)> {
    let mut out: Vec<(DVec3, f64, f64)> = Vec::new();
    for (d, f) in data.iter().zip(fields) {
        let Some(c) = d.column.get(v as usize).copied().flatten() else {
            continue;
        };
        let near = d.near[v as usize][c.source as usize];
        let mut n = near.dir;
        for (m, _, _) in &out {
            n -= *m * n.dot(*m);
        }
        let dist = &f.sources[c.source as usize].distribution;
        let Some(&site) = dist.sites().get(c.level as usize) else {
            continue;
        };
        let spacing = dist.layer_spacing(c.level.saturating_sub(1) as usize);
        let isotropic = d
            .delta
            .get(v as usize)
            .is_some_and(|&delta| spacing >= 0.5 * delta);
        let slack = if isotropic {
            NORMAL_SLACK.max(slack) * spacing
        } else {
            slack * spacing
        };
        let off = near.phi - site;
        if let Some(n) = n.try_normalize() {
            out.push((n, (-slack - off).min(0.0), (slack - off).max(0.0)));
        }
    }
    out
}

/// `p` moved into the layer through `at`: its components along the orthonormal `normals`
/// kept within their bounds (down, up) of those of `at`.
pub(super) fn in_layer(p: DVec3, at: DVec3, normals: &[(DVec3, f64, f64)]) -> DVec3 {
    normals.iter().fold(p, |q, &(n, lo, hi)| {
        let a = (q - at).dot(n);
        q - n * (a - a.clamp(lo, hi))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_threshold_cosine_is_that_of_the_threshold() {
        assert!((EXCESS_ABOVE.to_radians().cos() - EXCESS_ABOVE_COS).abs() < 1e-15);
    }

    #[test]
    fn a_layer_point_keeps_its_height() {
        let n = [(DVec3::Z, 0.0, 0.0)];
        let at = DVec3::new(1.0, 2.0, 0.5);
        let q = in_layer(DVec3::new(1.3, 1.9, 0.9), at, &n);
        assert_eq!(q, DVec3::new(1.3, 1.9, 0.5));
        // Two stages: only along the line both layers leave.
        let n2 = [(DVec3::Z, 0.0, 0.0), (DVec3::X, 0.0, 0.0)];
        let q = in_layer(DVec3::new(1.3, 1.9, 0.9), at, &n2);
        assert_eq!(q, DVec3::new(1.0, 1.9, 0.5));
        // With slack: up to it along the column, not beyond.
        let q = in_layer(DVec3::new(1.3, 1.9, 0.9), at, &[(DVec3::Z, -0.25, 0.25)]);
        assert_eq!(q, DVec3::new(1.3, 1.9, 0.75));
        let q = in_layer(DVec3::new(1.3, 1.9, 0.6), at, &[(DVec3::Z, -0.25, 0.25)]);
        assert_eq!(q, DVec3::new(1.3, 1.9, 0.6));
    }
}
