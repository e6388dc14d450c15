//! Quality improvement after the points are in (seed paper, "Face/edge swapping"; Shewchuk's
//! topological improvement; Freitag & Ollivier-Gooch's smoothing): for every tet whose
//! smallest dihedral angle is below the target, worst first,
//!
//! 1. remove one of its edges — the ring of tets around the edge re-tessellated by the
//!    triangulation of the ring that maximises the minimum dihedral angle (the kernel's
//!    dynamic program), taken only when that minimum beats the ring's present one;
//! 2. else a 2-3 flip through one of its faces, when the three new tets beat the two;
//! 3. then move each of its interior vertices towards the centre of its neighbours (halving
//!    the step until it helps), only when every tet of the star stays positively oriented
//!    (exact `orient3d`) and the star's worst angle improves.
//!
//! Recovered boundary faces are constrained in the kernel, so no flip removes one, and
//! boundary nodes (everything inserted before the interior points) never move.

use super::boundary::OUTSIDE;
use super::delaunay::predicates::orient;
use super::delaunay::Delaunay;
use crate::mesh::quality::face_normals;
use glam::DVec3;
use rayon::prelude::*;

/// What the improvement did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct ImproveReport {
    pub edge_removals: usize,
    pub face_flips: usize,
    pub smoothed_vertices: usize,
    pub passes: usize,
    pub min_dihedral_before: f64,
    pub min_dihedral_after: f64,
}

/// Tets whose smallest dihedral angle is below this are worked on.
pub const TARGET_DIHEDRAL: f64 = 30.0;
const PASSES: usize = 4;
/// Tets below this many degrees that the centroid move does not help get the (costlier)
/// hill-climb on their worst angle.
const CLIMB_BELOW: f64 = 10.0;
/// Gradient steps of the climb in the isotropic improvement.
pub const CLIMB_STEPS: usize = 8;

/// Smallest dihedral angle of a tet, in degrees (any orientation). From the four face
/// normals, all outward or all inward: the dihedral at the edge shared by faces k and l has
/// cos = −n̂_k·n̂_l, so the smallest angle needs one `acos` (this runs on every tet of every
/// pass). The faces' vertex orders make the normals consistent by construction; orienting each
/// against its opposite vertex instead failed on a flat tet (a parallelogram of four interior
/// points), where that test is rounding: it scored the 0° tet as 180°.
pub fn min_dihedral(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    angle(dihedral_cosines(a, b, c, d).0)
}

/// Largest dihedral angle of a tet, in degrees (any orientation; 180° for a flat one): the
/// min-max criterion of directional refinement's swaps.
pub fn max_dihedral(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    angle(dihedral_cosines(a, b, c, d).1)
}

/// Cosine of the largest dihedral angle (−1 for a flat tet): for callers that compare it
/// with a threshold before paying for the `acos` (the smoothing scores millions of stars).
pub fn max_dihedral_cos(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    dihedral_cosines(a, b, c, d).1
}

/// Smallest and largest dihedral angles, in degrees, from the face normals (see
/// [`min_dihedral`]); a tet with a zero-area face scores (0°, 180°).
pub fn dihedral_extremes(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> (f64, f64) {
    let (largest_cos, smallest_cos) = dihedral_cosines(a, b, c, d);
    (angle(largest_cos), angle(smallest_cos))
}

/// The angle in degrees of a cosine that rounding may have pushed past ±1.
fn angle(cos: f64) -> f64 {
    cos.clamp(-1.0, 1.0).acos().to_degrees()
}

/// The largest and the smallest cosine of a tet's six dihedral angles
/// ([`crate::mesh::quality::dihedral_cosines`]).
fn dihedral_cosines(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> (f64, f64) {
    let n = face_normals([a, b, c, d].map(|p| DVec3::from_array(*p)));
    crate::mesh::quality::dihedral_cosines(&n, &n.map(DVec3::length))
}

fn tet_score(dt: &Delaunay, t: u32) -> f64 {
    let v = dt.tet(t).map(|i| dt.point(i));
    min_dihedral(&v[0], &v[1], &v[2], &v[3])
}

/// Improve the tets of the domain (`region_of[t] != OUTSIDE`). Vertices with input index
/// below `first_movable` stay where they are.
pub fn improve(dt: &mut Delaunay, region_of: &mut Vec<u32>, first_movable: u32) -> ImproveReport {
    improve_except(dt, region_of, first_movable, &|_, _| false)
}

/// [`improve`], leaving alone the tets `leave` names (the zone directional refinement rebuilds,
/// once it has been polished: its poor tets between wall points are past what flips and
/// smoothing do, and cost most of a pass).
pub fn improve_except(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    first_movable: u32,
    leave: &(dyn Fn(&Delaunay, u32) -> bool + Sync),
) -> ImproveReport {
    let mut report = ImproveReport {
        min_dihedral_before: domain_min(dt, region_of),
        ..Default::default()
    };
    for _ in 0..PASSES {
        report.passes += 1;
        let domain: Vec<u32> = dt
            .tet_ids()
            .filter(|&t| region_of[t as usize] != OUTSIDE)
            .collect();
        let mut bad: Vec<(f64, u32)> = domain
            .par_iter()
            .map(|&t| (tet_score(dt, t), t))
            .filter(|&(q, t)| q < TARGET_DIHEDRAL && !leave(dt, t))
            .collect();
        if bad.is_empty() {
            break;
        }
        bad.sort_by(|x, y| x.0.total_cmp(&y.0));
        let before = (
            report.edge_removals,
            report.face_flips,
            report.smoothed_vertices,
        );
        for &(_, t) in &bad {
            if !dt.is_live(t) || dt.is_ghost(t) || region_of[t as usize] == OUTSIDE {
                continue;
            }
            let q = tet_score(dt, t);
            if q >= TARGET_DIHEDRAL {
                continue;
            }
            if remove_an_edge(dt, region_of, t) {
                report.edge_removals += 1;
                continue;
            }
            if flip_a_face(dt, region_of, t) {
                report.face_flips += 1;
                continue;
            }
            let climb = q < CLIMB_BELOW;
            for v in dt.tet(t) {
                if v >= first_movable && smooth_vertex(dt, region_of, v, climb) {
                    report.smoothed_vertices += 1;
                }
            }
        }
        if before
            == (
                report.edge_removals,
                report.face_flips,
                report.smoothed_vertices,
            )
        {
            break;
        }
    }
    report.min_dihedral_after = domain_min(dt, region_of);
    report
}

fn domain_min(dt: &Delaunay, region_of: &[u32]) -> f64 {
    let domain: Vec<u32> = dt
        .tet_ids()
        .filter(|&t| region_of[t as usize] != OUTSIDE)
        .collect();
    domain
        .par_iter()
        .map(|&t| tet_score(dt, t))
        .reduce(|| f64::INFINITY, f64::min)
}

/// Give freshly created tets the region of the tets they replaced.
pub fn label(region_of: &mut Vec<u32>, slots: usize, created: &[u32], region: u32) {
    if region_of.len() < slots {
        region_of.resize(slots, OUTSIDE);
    }
    for &t in created {
        region_of[t as usize] = region;
    }
}

/// Try removing each edge of `t`; true when one went.
fn remove_an_edge(dt: &mut Delaunay, region_of: &mut Vec<u32>, t: u32) -> bool {
    let v = dt.tet(t);
    let region = region_of[t as usize];
    for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
        let (a, b) = (v[i], v[j]);
        let Some((ring_tets, _)) = dt.tets_around_edge(a, b) else {
            continue;
        };
        if ring_tets
            .iter()
            .any(|&u| dt.is_ghost(u) || region_of[u as usize] != region)
        {
            continue;
        }
        let current = ring_tets
            .iter()
            .map(|&u| tet_score(dt, u))
            .fold(f64::INFINITY, f64::min);
        if let Ok(created) = dt.remove_edge_if_better(None, a, b, current, min_dihedral) {
            label(region_of, dt.slot_count(), &created, region);
            return true;
        }
    }
    false
}

/// A quality of a tet from its four corners (higher is better).
pub type TetQuality = dyn Fn(&[f64; 3], &[f64; 3], &[f64; 3], &[f64; 3]) -> f64;

/// Try a 2-3 flip through each face of `t`; true when one was made.
fn flip_a_face(dt: &mut Delaunay, region_of: &mut Vec<u32>, t: u32) -> bool {
    flip_a_face_by(dt, region_of, t, &min_dihedral, 0.0).is_some()
}

/// A 2-3 flip through a face of `t` (neither constrained nor to another region) when the
/// three new tets' smallest `quality` beats the pair's by more than `gain`; the created tets.
/// Isotropic improvement passes the smallest dihedral, directional refinement's swaps the
/// negated largest one.
pub fn flip_a_face_by(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    t: u32,
    quality: &TetQuality,
    gain: f64,
) -> Option<[u32; 3]> {
    let region = region_of[t as usize];
    let of = |dt: &Delaunay, t: u32| {
        let v = dt.tet(t).map(|i| dt.point(i));
        quality(&v[0], &v[1], &v[2], &v[3])
    };
    for f in 0..4u8 {
        if dt.is_constrained(t, f) {
            continue;
        }
        let (u, g) = dt.neighbor(t, f);
        if dt.is_ghost(u) || region_of[u as usize] != region {
            continue;
        }
        let current = of(dt, t).min(of(dt, u));
        let p = dt.point(dt.tet(t)[f as usize]);
        let q = dt.point(dt.tet(u)[g as usize]);
        let [x, y, z] = dt.face_vertices(t, f).map(|i| dt.point(i));
        let new = quality(&p, &q, &x, &y)
            .min(quality(&p, &q, &y, &z))
            .min(quality(&p, &q, &z, &x));
        if new > current + gain {
            if let Ok(created) = dt.flip23(t, f) {
                label(region_of, dt.slot_count(), &created, region);
                return Some(created);
            }
        }
    }
    None
}

/// Settle a freshly inserted vertex `v`: smooth it (with the climb), then offer the edges of
/// its star's tets below the target to edge removal.
pub fn polish_vertex(dt: &mut Delaunay, region_of: &mut Vec<u32>, v: u32) {
    smooth_vertex(dt, region_of, v, true);
    for t in dt.tets_around_vertex(v) {
        if dt.is_live(t)
            && !dt.is_ghost(t)
            && region_of[t as usize] != OUTSIDE
            && tet_score(dt, t) < TARGET_DIHEDRAL
        {
            remove_an_edge(dt, region_of, t);
        }
    }
}

/// Move interior vertex `v` towards the centroid of its neighbours when that improves its
/// star's worst tet (by the smallest dihedral angle) and keeps every tet positive, else (with
/// `climb`) up the gradient of the star's worst angle; true when it moved.
fn smooth_vertex(dt: &mut Delaunay, region_of: &[u32], v: u32, climb: bool) -> bool {
    let how = VertexMove {
        score: min_dihedral,
        combine: Combine::Worst,
        project: &|p| p,
        climb: if climb { CLIMB_STEPS } else { 0 },
    };
    move_vertex(dt, region_of, v, &how)
}

/// A tet's score from its four corners (larger is better).
pub type TetScore = fn(&[f64; 3], &[f64; 3], &[f64; 3], &[f64; 3]) -> f64;

/// How [`move_vertex`] may move a vertex and what it judges the star by.
pub struct VertexMove<'a> {
    /// A tet's score (larger is better).
    pub score: TetScore,
    /// How the star's score follows from its tets'.
    pub combine: Combine,
    /// Where a trial position lands: the identity for a free vertex; onto a surface for one
    /// that must keep a property (a layer point keeps its distance to the wall).
    pub project: &'a dyn Fn(DVec3) -> DVec3,
    /// How many steps up the worst score's gradient to take when the centroid does not help
    /// (0: none).
    pub climb: usize,
}

/// A star's score from its tets' scores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Combine {
    /// The worst tet's: the min-max criterion.
    Worst,
    /// The sum: a score that is zero for good tets and falls steeply for poor ones then
    /// helps the poor ones without trading the others' quality for them.
    Sum,
}

/// Move interior vertex `v` to a better position for its star ([`better_position`]). True
/// when it moved.
pub fn move_vertex(dt: &mut Delaunay, region_of: &[u32], v: u32, how: &VertexMove) -> bool {
    let star = dt.tets_around_vertex(v);
    if star
        .iter()
        .any(|&t| dt.is_ghost(t) || region_of[t as usize] == OUTSIDE)
    {
        return false;
    }
    match better_position(dt, v, &star, how) {
        Some(p) => {
            dt.set_point(v, p.to_array());
            true
        }
        None => false,
    }
}

/// A better position for vertex `v`, whose star (finite domain tets) is `star`: towards the
/// centroid of its neighbours (step halved until it helps), else, with `climb`, up the
/// gradient of the star's worst score. Every position is projected first, every tet must stay
/// positive (exact `orient3d`), and the star's score must improve. Reads the triangulation
/// only, so vertices that share no tet can be looked at in parallel.
pub fn better_position(dt: &Delaunay, v: u32, star: &[u32], how: &VertexMove) -> Option<DVec3> {
    let tets: Vec<[u32; 4]> = star.iter().map(|&t| dt.tet(t)).collect();
    let old = dt.point(v);
    let worst = |p: [f64; 3]| -> Option<f64> {
        let p = (how.project)(DVec3::from_array(p)).to_array();
        let mut w = match how.combine {
            Combine::Worst => f64::INFINITY,
            Combine::Sum => 0.0,
        };
        for t in &tets {
            let c = t.map(|i| if i == v { p } else { dt.point(i) });
            if orient(&c[0], &c[1], &c[2], &c[3]) <= 0.0 {
                return None;
            }
            let s = (how.score)(&c[0], &c[1], &c[2], &c[3]);
            w = match how.combine {
                Combine::Worst => w.min(s),
                Combine::Sum => w + s,
            };
        }
        Some(w)
    };
    // A star holding a zero-volume tet (four coplanar points) has no score: any position
    // where every tet has volume is better, and the way out is off the flat tets' planes.
    let mut off_plane = Vec::new();
    for t in &tets {
        let c = t.map(|i| dt.point(i));
        let o = orient(&c[0], &c[1], &c[2], &c[3]);
        if o < 0.0 {
            return None;
        }
        if o == 0.0 {
            let [p, q, r] = others(t, v).map(|i| DVec3::from_array(dt.point(i)));
            if let Some(n) = (q - p).cross(r - p).try_normalize() {
                off_plane.extend([n, -n]);
            }
        }
    }
    let current = worst(old).unwrap_or(f64::NEG_INFINITY);
    let mut sum = DVec3::ZERO;
    let mut n = 0.0;
    for t in &tets {
        for &i in t {
            if i != v {
                sum += DVec3::from_array(dt.point(i));
                n += 1.0;
            }
        }
    }
    let target = sum / n;
    let from = DVec3::from_array(old);
    let mut step = 1.0;
    for _ in 0..4 {
        let p = (from + (target - from) * step).to_array();
        if let Some(w) = worst(p) {
            if w > current {
                return Some((how.project)(DVec3::from_array(p)));
            }
        }
        step *= 0.5;
    }
    if how.climb == 0 {
        return None;
    }
    // The centroid does not help (a sliver against the boundary, a vertex pulled between
    // bad tets): climb the star's worst angle instead, along its numerical gradient.
    let shortest = tets
        .iter()
        .flat_map(|t| t.iter().filter(|&&i| i != v))
        .map(|&i| (DVec3::from_array(dt.point(i)) - from).length())
        .fold(f64::INFINITY, f64::min);
    let (from, current) = if current.is_finite() {
        (from, current)
    } else {
        pattern_step(from, current, shortest, &off_plane, &worst)?
    };
    climb_worst_angle(from, current, shortest, how.climb, &worst)
        .or(Some(from).filter(|&p| p != DVec3::from_array(old)))
        .map(|p| (how.project)(p))
}

/// The three vertices of `t` other than `v`, in an order that keeps no orientation.
fn others(t: &[u32; 4], v: u32) -> [u32; 3] {
    let mut o = [0; 3];
    let mut k = 0;
    for &i in t {
        if i != v && k < 3 {
            o[k] = i;
            k += 1;
        }
    }
    o
}

/// Both ways along each axis: the directions a pattern search tries.
const AXES: [DVec3; 6] = [
    DVec3::X,
    DVec3::NEG_X,
    DVec3::Y,
    DVec3::NEG_Y,
    DVec3::Z,
    DVec3::NEG_Z,
];

/// The best position a step along one of `directions` reaches where `worst` is above
/// `value`, with its score: steps from a quarter of the star's shortest edge down, halved
/// until one helps. Used where the slope says nothing: off the planes of a star's
/// zero-volume tets (any valid position is better), or where the slope is zero.
fn pattern_step(
    from: DVec3,
    value: f64,
    shortest: f64,
    directions: &[DVec3],
    worst: &dyn Fn([f64; 3]) -> Option<f64>,
) -> Option<(DVec3, f64)> {
    let mut step = 0.25 * shortest;
    for _ in 0..12 {
        let best = directions
            .iter()
            .filter_map(|&d| {
                let p = from + d * step;
                worst(p.to_array()).map(|w| (p, w))
            })
            .filter(|&(_, w)| w > value)
            .max_by(|x, y| x.1.total_cmp(&y.1));
        if best.is_some() {
            return best;
        }
        step *= 0.5;
    }
    None
}

/// Hill-climb `worst` (the star's smallest dihedral, `None` where a tet inverts) from `from`,
/// whose value is `current`, with steps bounded by a fraction of the star's shortest edge.
/// Returns a better position, or `None` when no step helps.
pub fn climb_worst_angle(
    from: DVec3,
    current: f64,
    shortest: f64,
    steps: usize,
    worst: &dyn Fn([f64; 3]) -> Option<f64>,
) -> Option<DVec3> {
    let h = shortest * 1e-4;
    let (mut at, mut value) = (from, current);
    for _ in 0..steps {
        let mut grad = DVec3::ZERO;
        for axis in 0..3 {
            let mut e = DVec3::ZERO;
            e[axis] = h;
            // One-sided where a probe inverts a tet: a vertex of a flat tet can leave its
            // plane only to the side that gives the tet volume, and that is the way to go.
            grad[axis] = match (worst((at + e).to_array()), worst((at - e).to_array())) {
                (Some(up), Some(down)) => (up - down) / (2.0 * h),
                (Some(up), None) => (up - value) / h,
                (None, Some(down)) => (value - down) / h,
                (None, None) => 0.0,
            };
        }
        let Some(dir) = grad.try_normalize() else {
            // No slope: a point in a row with two others scores the same a step to either
            // side, so the central differences cancel. Try the axes one by one instead.
            match pattern_step(at, value, shortest, &AXES, worst) {
                Some(better) => {
                    (at, value) = better;
                    continue;
                }
                None => break,
            }
        };
        let mut step = 0.25 * shortest;
        let mut moved = false;
        for _ in 0..8 {
            let p = at + dir * step;
            if let Some(w) = worst(p.to_array()) {
                if w > value {
                    (at, value) = (p, w);
                    moved = true;
                    break;
                }
            }
            step *= 0.5;
        }
        if !moved {
            break;
        }
    }
    (value > current).then_some(at)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn min_dihedral_matches_the_six_angle_formula() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 0.1, 0.0],
            [0.3, 0.9, 0.2],
            [0.2, 0.3, 0.8],
        ];
        let v = pts.map(DVec3::from_array);
        let six = crate::mesh::quality::tet_dihedrals(v)
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let fast = min_dihedral(&pts[0], &pts[1], &pts[2], &pts[3]);
        assert!((six - fast).abs() < 1e-9, "{six} vs {fast}");
        // Regular tet: arccos(1/3) everywhere; orientation does not matter.
        let r = [
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ];
        let want = (1.0f64 / 3.0).acos().to_degrees();
        assert!((min_dihedral(&r[0], &r[1], &r[2], &r[3]) - want).abs() < 1e-9);
        assert!((min_dihedral(&r[1], &r[0], &r[2], &r[3]) - want).abs() < 1e-9);
    }

    /// Four interior points of a sphere mesh that made a parallelogram (d = b + c − a): the
    /// per-face orientation test used to score this flat tet 180°.
    #[test]
    fn min_dihedral_of_a_flat_tet_is_zero() {
        let a = [-1.7634504804930602, 1.7841353657571701, 2.7334031013114863];
        let b = [-2.1756307282494736, 1.1178828513087722, 2.172561676939364];
        let c = [-2.1420136332459276, 1.8631821985983588, 3.1960659099905264];
        let d = [-2.5541938810023406, 1.1969296841499608, 2.6352244856184037];
        assert!(min_dihedral(&a, &b, &c, &d) < 0.01);
        assert!(min_dihedral(&b, &a, &c, &d) < 0.01);
    }
}
