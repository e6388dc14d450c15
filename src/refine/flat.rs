//! The last resort against flat tets, once smoothing and swaps are done. A few tets end
//! nearly flat (largest dihedral angle near 180°) where no swap helps: every re-tessellation
//! of their edges' rings folds a tet, and the smoothing keeps column points in their layers,
//! where four points of one layer stay coplanar. Here, where a face of such a tet has a point
//! on the edge between its other two, that edge is split at the point; else each vertex may
//! move where that lowers its star's largest angle (a column point near its layer and its
//! root), and where no move helps, a vertex beyond the first layers is collapsed onto the
//! neighbour that leaves the best star, if that star is better than the one it had. Boundary
//! nodes stay.

use super::clear::collapse;
use super::field::StageField;
use super::flat_point;
use super::smooth::{column_normals, in_layer, move_point};
use super::swap::{self, score, SwapReport};
use super::volume::PointData;
use crate::volume::delaunay::{Delaunay, INF};
use crate::volume::improve::{
    better_position, label, max_dihedral, Combine, VertexMove, CLIMB_STEPS,
};
use crate::volume::OUTSIDE;
use std::collections::HashMap;

/// Tets whose largest dihedral angle (degrees) is above this are worked on.
pub const FLAT_ABOVE: f64 = 165.0;
/// After the moves and collapses, tets above this take part in the swaps.
const SWAP_ABOVE: f64 = 150.0;
/// Rounds of moves, collapses and swaps.
const ROUNDS: usize = 4;
/// How far a column point may leave its layer here, in the layer's spacing (the smoothing
/// keeps it in the layer's plane).
const LAYER_SLACK: f64 = 0.2;
/// How far a column point may move here in all, in its star's shortest edge.
const COLUMN_REACH: f64 = 0.5;
/// Points this many layers from a source stay (they may move a little, not go).
const FIRST_LAYERS: usize = 4;
/// A collapse must lower the star's largest angle by at least this much (degrees).
const GAIN: f64 = 1e-3;

/// What the last resort did.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct FlatReport {
    /// Tets above [`FLAT_ABOVE`] before.
    pub found: usize,
    /// Vertex moves that lowered their star's largest angle.
    pub moved: usize,
    /// Vertices collapsed onto a neighbour.
    pub collapsed: usize,
    /// Edges split at a vertex lying on them.
    pub split: usize,
    /// Points inserted into a cavity around a flat tet ([`flat_point`]).
    pub inserted: usize,
    pub swaps: SwapReport,
    /// Tets above [`FLAT_ABOVE`] after.
    pub left: usize,
}

/// Whether vertex `v` may move: a point of the refinement or the interior, or an older one on
/// no boundary face — a boundary Steiner point that recovery moved into the volume, which can
/// sit a rounding error off a plane whose vertices are not exactly coplanar (a cylinder's
/// edge on a symmetry plane), in tets of no volume.
fn movable(dt: &mut Delaunay, first_movable: u32, v: u32) -> bool {
    if v >= first_movable {
        return true;
    }
    if v == INF {
        return false;
    }
    dt.tets_around_vertex(v).into_iter().all(|t| {
        let corner = dt.tet(t).iter().position(|&x| x == v);
        !dt.is_ghost(t) && (0..4u8).all(|f| Some(f as usize) == corner || !dt.is_constrained(t, f))
    })
}

/// Work on the domain's tets above [`FLAT_ABOVE`], worst first; vertices from `first_movable`
/// on may move or go. `data` per stage keeps the moved points' distances.
pub fn remove_flat_tets(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    fields: &[StageField],
    data: &mut [PointData],
    first_movable: u32,
    memo: &mut swap::SwapMemo,
) -> FlatReport {
    let mut report = FlatReport::default();
    // Where each moved point was before its first move here: the reach counts from there.
    let mut origin: HashMap<u32, glam::DVec3> = HashMap::new();
    for round in 0..ROUNDS {
        let flat = flat_tets(dt, region_of);
        if round == 0 {
            report.found = flat.len();
        }
        if flat.is_empty() {
            break;
        }
        for t in flat {
            if !still_flat(dt, region_of, t) {
                continue;
            }
            if split_through(dt, region_of, t) {
                report.split += 1;
                continue;
            }
            for v in dt.tet(t) {
                if movable(dt, first_movable, v)
                    && move_corner(dt, region_of, fields, data, &mut origin, v)
                {
                    report.moved += 1;
                    if !still_flat(dt, region_of, t) {
                        break;
                    }
                }
            }
            if !still_flat(dt, region_of, t) {
                continue;
            }
            // A point of the first layers stays: without it the wall's layers have a gap.
            for v in dt.tet(t) {
                if v < first_movable || in_the_layers(fields, data, v) {
                    continue;
                }
                let worst = dt
                    .tets_around_vertex(v)
                    .into_iter()
                    .filter(|&u| !dt.is_ghost(u))
                    .map(|u| score(dt, u))
                    .fold(0.0, f64::max);
                if collapse(dt, region_of, v, worst - GAIN) {
                    report.collapsed += 1;
                    break;
                }
            }
            if still_flat(dt, region_of, t) && flat_point::insert_point(dt, region_of, t) {
                report.inserted += 1;
            }
        }
        let s = swap::minmax_swaps(
            dt,
            region_of,
            &|dt: &Delaunay, t| score(dt, t) > SWAP_ABOVE,
            memo,
        );
        report.swaps.passes += s.passes;
        report.swaps.edge_swaps += s.edge_swaps;
        report.swaps.face_swaps += s.face_swaps;
    }
    let left = flat_tets(dt, region_of);
    for &t in &left {
        let v = dt.tet(t);
        let at = v.map(|i| glam::DVec3::from_array(dt.point(i)));
        let centre = (at[0] + at[1] + at[2] + at[3]) / 4.0;
        log::debug!(
            "flat tet left at {centre:.4}: largest angle {:.1}°, movable corners {:?}",
            score(dt, t),
            v.map(|i| movable(dt, first_movable, i))
        );
    }
    report.left = left.len();
    report
}

/// The domain's tets above [`FLAT_ABOVE`], worst first.
fn flat_tets(dt: &Delaunay, region_of: &[u32]) -> Vec<u32> {
    let mut flat: Vec<(f64, u32)> = dt
        .tet_ids()
        .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
        .map(|t| (score(dt, t), t))
        .filter(|&(q, _)| q > FLAT_ABOVE)
        .collect();
    flat.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
    flat.into_iter().map(|(_, t)| t).collect()
}

fn still_flat(dt: &Delaunay, region_of: &[u32], t: u32) -> bool {
    dt.is_live(t)
        && !dt.is_ghost(t)
        && region_of[t as usize] != OUTSIDE
        && score(dt, t) > FLAT_ABOVE
}

/// A face's angle (degrees) above which its vertex counts as lying on the opposite edge.
const ON_EDGE_ANGLE: f64 = 170.0;

/// Where a face of flat tet `t` has three points nearly in a row (a, m, b with m between),
/// no move of any of them helps: m sits on the edge ab, and every step off the line folds a
/// tet of the ring around ab. The edge is split at m instead: each tet of its ring without m
/// becomes two, one on each side of m, and the two tets on the face amb go. Kept when the
/// ring's largest angle goes down; true then.
fn split_through(dt: &mut Delaunay, region_of: &mut Vec<u32>, t: u32) -> bool {
    let v = dt.tet(t);
    let p = v.map(|i| glam::DVec3::from_array(dt.point(i)));
    for skip in 0..4 {
        let face: Vec<usize> = (0..4).filter(|&k| k != skip).collect();
        for k in 0..3 {
            let (m, a, b) = (face[k], face[(k + 1) % 3], face[(k + 2) % 3]);
            let angle = (p[a] - p[m]).angle_between(p[b] - p[m]).to_degrees();
            if angle.is_finite() && angle > ON_EDGE_ANGLE {
                if let Some(done) = split_edge_at(dt, region_of, t, [v[a], v[b]], v[m]) {
                    return done;
                }
            }
        }
    }
    false
}

/// Split edge `ab` (of tet `t`) at its ring vertex `m`, if that lowers the ring's largest
/// angle; `None` when `m` is not on the ring or the ring is not all of one domain region.
fn split_edge_at(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    t: u32,
    [a, b]: [u32; 2],
    m: u32,
) -> Option<bool> {
    let (ring, _) = dt.tets_around_edge_of_tet(t, a, b);
    let region = region_of[t as usize];
    if ring
        .iter()
        .any(|&u| dt.is_ghost(u) || region_of[u as usize] != region)
    {
        return None;
    }
    let tets: Vec<[u32; 4]> = ring.iter().map(|&u| dt.tet(u)).collect();
    if !tets.iter().any(|u| u.contains(&m)) {
        return None;
    }
    let mut new = Vec::with_capacity(2 * tets.len());
    for u in tets.iter().filter(|u| !u.contains(&m)) {
        let rest: Vec<u32> = u.iter().copied().filter(|&x| x != a && x != b).collect();
        new.push([a, m, rest[0], rest[1]]);
        new.push([m, b, rest[0], rest[1]]);
    }
    let (old_worst, old_flat) = judge(dt, &tets);
    let (new_worst, new_flat) = judge(dt, &new);
    // Four points in a row leave the largest angle at 180° after one split, with one flat
    // tet fewer: that counts as better too.
    let better = new_worst < old_worst - GAIN || (new_worst <= old_worst && new_flat < old_flat);
    if !better {
        return Some(false);
    }
    match dt.replace_tets(&ring, &new) {
        Ok(ids) => {
            label(region_of, dt.slot_count(), &ids, region);
            Some(true)
        }
        Err(_) => Some(false),
    }
}

/// The largest dihedral angle of the tets `set` and how many are above [`FLAT_ABOVE`].
fn judge(dt: &Delaunay, set: &[[u32; 4]]) -> (f64, usize) {
    set.iter()
        .map(|u| {
            let q = u.map(|x| dt.point(x));
            max_dihedral(&q[0], &q[1], &q[2], &q[3])
        })
        .fold((0.0, 0), |(w, n), a| {
            (w.max(a), n + usize::from(a > FLAT_ABOVE))
        })
}

/// Minus the largest dihedral angle: the min-max criterion as a score to maximise.
fn minus_max_dihedral(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    -max_dihedral(a, b, c, d)
}

/// Whether `v` lies within the first [`FIRST_LAYERS`] layers of some source (the points there
/// make the spacing the solver's wall needs).
fn in_the_layers(fields: &[StageField], data: &[PointData], v: u32) -> bool {
    data.iter().zip(fields).any(|(d, f)| {
        d.near.get(v as usize).is_some_and(|near| {
            near.iter()
                .zip(&f.sources)
                .any(|(n, s)| s.distribution.layer_of(n.phi) < FIRST_LAYERS)
        })
    })
}

/// The shortest edge from `v` in its star `star`.
fn shortest_edge(dt: &Delaunay, star: &[u32], v: u32) -> f64 {
    let at = glam::DVec3::from_array(dt.point(v));
    star.iter()
        .flat_map(|&t| dt.tet(t))
        .filter(|&i| i != v)
        .map(|i| (glam::DVec3::from_array(dt.point(i)) - at).length())
        .fold(f64::INFINITY, f64::min)
}

/// Move interior vertex `v` where that lowers its star's largest angle; a column point (or one
/// in the first layers) only near its layer and within [`COLUMN_REACH`] of where it was first
/// (`origin`). True when it moved.
fn move_corner(
    dt: &mut Delaunay,
    region_of: &[u32],
    fields: &[StageField],
    data: &mut [PointData],
    origin: &mut HashMap<u32, glam::DVec3>,
    v: u32,
) -> bool {
    let star = dt.tets_around_vertex(v);
    if star
        .iter()
        .any(|&t| dt.is_ghost(t) || region_of[t as usize] == OUTSIDE)
    {
        return false;
    }
    let normals = column_normals(fields, data, v, LAYER_SLACK);
    let at = glam::DVec3::from_array(dt.point(v));
    let from = *origin.entry(v).or_insert(at);
    let reach = if normals.is_empty() && !in_the_layers(fields, data, v) {
        f64::INFINITY
    } else {
        COLUMN_REACH * shortest_edge(dt, &star, v)
    };
    let project = |p: glam::DVec3| {
        let q = in_layer(p, at, &normals);
        from + (q - from).clamp_length_max(reach)
    };
    let how = VertexMove {
        score: minus_max_dihedral,
        combine: Combine::Worst,
        project: &project,
        climb: CLIMB_STEPS,
    };
    match better_position(dt, v, &star, &how) {
        Some(p) => {
            move_point(dt, fields, data, v, p);
            true
        }
        None => false,
    }
}
