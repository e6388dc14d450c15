//! Column growth: the first part of the volume stage. Every node of a face source starts a
//! column, and the columns grow one level at a time, every column's next site in one Delaunay
//! batch, until each column reaches the distance where its spacing meets the isotropic δ.
//!
//! These are the points the paper's candidate lists lead to (the candidate on a source node's
//! line at the next site), but taken column by column instead of element by element: a tet
//! proposes only its first candidate, so a column whose top is no tet's lowest vertex would
//! stall, and the layers would come out with holes that Delaunay fills with tets spanning
//! several levels. Level by level, each layer's points all exist before the next goes in,
//! so the reconnection of a new level reaches the finished level below.
//!
//! A column stops where its next point would leave its region, come closer to the boundary
//! than half a layer, crowd a point already there (converging columns in a concave corner:
//! within half a layer along the column and half the lesser of δ and the distance between
//! neighbouring roots across it), or lie nearer another part of the source than its own site (past the source's medial
//! axis). The element-driven insertion ([`super::volume::refine_volume`]) follows and fills
//! what the columns left (edge sources, the ends of stopped columns).

use super::field::crowds;
use super::field::{Candidate, StageField};
use super::volume::{clear_of_boundary, PointData, ON_SOURCE};
use crate::progress::Reporter;
use crate::sizing::SizingField;
use crate::volume::delaunay::{Delaunay, INF};
use crate::volume::improve::label;
use crate::volume::OUTSIDE;
use glam::DVec3;

/// A column point farther than this fraction of its layer's spacing from its site (measured
/// by the distance function) has passed the source's medial axis: the column stops.
const SITE_TOLERANCE: f64 = 0.3;

/// What column growth did.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct ColumnReport {
    /// Source nodes that started a column.
    pub roots: usize,
    /// Points inserted on the columns.
    pub points: usize,
    /// Boundary points the columns took as theirs: the face refinement's points on a face
    /// beside the source (a symmetry plane at a wing root) at a column's next site.
    pub adopted: usize,
    /// Levels grown (Delaunay batches).
    pub levels: usize,
    /// Columns stopped short of their reach, by why: the next point left the region or came
    /// near the boundary; it crowded another point; it lay past the source's medial axis.
    pub stopped_boundary: usize,
    pub stopped_crowded: usize,
    pub stopped_medial: usize,
    /// The kernel refused the cone from the new point over the cavity (it does not see
    /// every face around it).
    pub stopped_refused: usize,
}

/// A column's next point: a new point and the cavity it is coned over, or a point already
/// there at its site (on the boundary beside the source) that the column takes.
enum Next {
    Insert(Candidate, Vec<u32>),
    Adopt(Candidate, u32),
}

/// A point within this fraction of the layer spacing of a column's next site is that site's
/// point: the face refinement put it there, on the same line from the same edge node.
const ADOPT_TOLERANCE: f64 = 0.2;

/// Why a column's next point was not proposed.
enum Stop {
    Reached,
    Boundary,
    Crowded,
    Medial,
}

/// Grow the columns of every face source of the stage from its nodes, level by level.
pub fn grow_columns(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    field: &StageField,
    sizing: &SizingField,
    data: &mut PointData,
    progress: Reporter<'_>,
) -> ColumnReport {
    let mut report = ColumnReport::default();
    // A top and whether it grows against the source's normal (only a root of a two-sided
    // source does: its second column).
    let mut tops: Vec<(u32, bool)> = Vec::new();
    let roots = roots(dt, region_of, field, data);
    let spacing = root_spacing(dt, &roots);
    for v in roots {
        tops.push((v, false));
        if field.two_sided.contains(&v) {
            tops.push((v, true));
        }
    }
    report.roots = tops.len();
    // A cancelled run stops between two levels; the caller then stops too.
    while !tops.is_empty() && !progress.cancelled() {
        // In root order: each quad between two columns gets its diagonal from the bottom of
        // the column grown first, the order [`super::layers`] keeps.
        tops.sort_unstable_by_key(|&(v, flip)| {
            (data.column[v as usize].map_or(v, |c| c.root), flip)
        });
        let mut grown: Vec<(u32, bool)> = Vec::with_capacity(tops.len());
        for &(top, flip) in &tops {
            let (c, cavity) =
                match next_point(dt, region_of, field, sizing, data, &spacing, (top, flip)) {
                    Ok(Next::Insert(c, cavity)) => (c, cavity),
                    Ok(Next::Adopt(c, v)) => {
                        data.column[v as usize] = data.column_above(field, top, &c);
                        report.adopted += 1;
                        grown.push((v, false));
                        continue;
                    }
                    Err(stop) => {
                        report.count(stop);
                        continue;
                    }
                };
            let region = region_of[cavity[0] as usize];
            let floor = floor_of(field, data, top, c.source);
            let may_grow = |u: u32, v: [u32; 4]| {
                region_of.get(u as usize) == Some(&region) && !lower(data, c.source, floor, v)
            };
            let (v, created) = match dt.insert_in_cavity(c.point.to_array(), &cavity, &may_grow) {
                Ok(x) => x,
                Err(_) => {
                    report.stopped_refused += 1;
                    continue;
                }
            };
            label(region_of, dt.slot_count(), &created, region);
            data.extend(dt, field, sizing);
            data.column[v as usize] = data.column_above(field, top, &c);
            grown.push((v, false));
        }
        if grown.is_empty() {
            break;
        }
        report.levels += 1;
        report.points += grown.len();
        tops = grown;
    }
    report
}

impl ColumnReport {
    fn count(&mut self, stop: Stop) {
        match stop {
            Stop::Reached => {}
            Stop::Boundary => self.stopped_boundary += 1,
            Stop::Crowded => self.stopped_crowded += 1,
            Stop::Medial => self.stopped_medial += 1,
        }
    }
}

/// The part of `top`'s star the next point goes into: its domain tets above the finished
/// layers (a tet with a vertex lower than `top`, by the distance to source `s`, is in the
/// layer below); for a root of a two-sided source, only those on the side `side` points to
/// ([`one_side`]). All in one region, else `None`.
fn star_above(
    dt: &mut Delaunay,
    region_of: &[u32],
    field: &StageField,
    data: &PointData,
    top: u32,
    s: usize,
    side: Option<DVec3>,
) -> Option<Vec<u32>> {
    let floor = floor_of(field, data, top, s);
    let mut star: Vec<u32> = dt
        .tets_around_vertex(top)
        .into_iter()
        .filter(|&t| !dt.is_ghost(t) && region_of.get(t as usize).is_some_and(|&r| r != OUTSIDE))
        .collect();
    if let Some(n) = side {
        star = one_side(dt, &star, top, n);
    }
    let out: Vec<u32> = star
        .into_iter()
        .filter(|&t| !lower(data, s, floor, dt.tet(t)))
        .collect();
    let region = region_of[*out.first()? as usize];
    out.iter()
        .all(|&t| region_of[t as usize] == region)
        .then_some(out)
}

/// The tets of `star` (around a node of an embedded source face) on the side `n` points to:
/// the part connected, across unconstrained faces, to the tet that lies most in direction `n`
/// from the node. The source's own constrained triangles part the star in two, so the side
/// is found by the topology, whatever the sheet's curvature.
fn one_side(dt: &Delaunay, star: &[u32], node: u32, n: DVec3) -> Vec<u32> {
    let origin = DVec3::from_array(dt.point(node));
    let towards = |t: u32| {
        let centre = dt
            .tet(t)
            .iter()
            .map(|&v| DVec3::from_array(dt.point(v)))
            .sum::<DVec3>()
            / 4.0;
        (centre - origin).normalize_or_zero().dot(n)
    };
    let Some(seed) = star
        .iter()
        .copied()
        .max_by(|&a, &b| towards(a).total_cmp(&towards(b)))
    else {
        return Vec::new();
    };
    let mut side = vec![seed];
    let mut next = 0;
    while next < side.len() {
        let t = side[next];
        next += 1;
        for f in 0..4u8 {
            let (u, _) = dt.neighbor(t, f);
            if !dt.is_constrained(t, f) && star.contains(&u) && !side.contains(&u) {
                side.push(u);
            }
        }
    }
    side
}

/// The band of distances to source `s` of `top`'s layer: below it a point is lower than
/// `top` (half the layer under it), above it higher (half the layer over it).
fn floor_of(field: &StageField, data: &PointData, top: u32, s: usize) -> (f64, f64) {
    let d = &field.sources[s].distribution;
    let phi = data.near[top as usize][s].phi;
    match data.column[top as usize] {
        Some(c) if c.level > 0 => {
            let k = c.level as usize;
            (
                phi - 0.5 * d.layer_spacing(k - 1),
                phi + 0.5 * d.layer_spacing(k),
            )
        }
        _ => (f64::NEG_INFINITY, f64::INFINITY),
    }
}

/// Whether a tet on vertices `v` lies in the layers below `top`: a vertex lower than the
/// band and none above it (a tet reaching from below to far above spans the layers where
/// they have a gap, and may join the cavity).
fn lower(data: &PointData, s: usize, band: (f64, f64), v: [u32; 4]) -> bool {
    let phi = |x: u32| data.near.get(x as usize).map(|n| n[s].phi);
    v.iter().any(|&x| phi(x).is_some_and(|p| p < band.0))
        && v.iter().all(|&x| phi(x).is_none_or(|p| p < band.1))
}

/// The nodes of the stage's face sources inside the domain: a vertex on a face source (its
/// direction there is the source's normal) with a domain tet around it.
fn roots(dt: &mut Delaunay, region_of: &[u32], field: &StageField, data: &PointData) -> Vec<u32> {
    let mut out = Vec::new();
    for v in 0..dt.num_points() as u32 {
        let Some(s) = source_of_root(field, data, v) else {
            continue;
        };
        if data.column[v as usize].is_some_and(|c| c.source as usize != s) {
            continue;
        }
        let inside = dt
            .tets_around_vertex(v)
            .iter()
            .any(|&t| region_of.get(t as usize).is_some_and(|&r| r != OUTSIDE));
        if inside {
            out.push(v);
        }
    }
    out
}

/// Per root, the distance to the nearest other root it shares a tet with: how far apart
/// its columns start. Where the source's mesh is finer than the isotropic δ (a leading edge
/// refined by an earlier curve stage), neighbouring columns stand closer than δ.
fn root_spacing(dt: &mut Delaunay, roots: &[u32]) -> std::collections::HashMap<u32, f64> {
    let is_root: std::collections::HashSet<u32> = roots.iter().copied().collect();
    let mut out = std::collections::HashMap::with_capacity(roots.len());
    for &r in roots {
        let p = DVec3::from_array(dt.point(r));
        let nearest = (dt.tets_around_vertex(r).iter())
            .flat_map(|&t| dt.tet(t))
            .filter(|&v| v != INF && v != r && is_root.contains(&v))
            .map(|v| p.distance(DVec3::from_array(dt.point(v))))
            .fold(f64::INFINITY, f64::min);
        out.insert(r, nearest);
    }
    out
}

/// The finest-spaced face source vertex `v` lies on, if any.
fn source_of_root(field: &StageField, data: &PointData, v: u32) -> Option<usize> {
    let near = data.near.get(v as usize)?;
    (0..field.sources.len())
        .filter(|&s| {
            let first = field.sources[s].distribution.first;
            near[s].phi <= ON_SOURCE * first && near[s].dir != DVec3::ZERO
        })
        .min_by(|&a, &b| {
            let fa = field.sources[a].distribution.first;
            let fb = field.sources[b].distribution.first;
            fa.total_cmp(&fb)
        })
}

/// The next point of the column whose top is `top` (against the source's normal when `flip`:
/// the second column of a two-sided root), and the cavity it goes into; `root_spacing` from
/// [`root_spacing`].
fn next_point(
    dt: &mut Delaunay,
    region_of: &[u32],
    field: &StageField,
    sizing: &SizingField,
    data: &PointData,
    root_spacing: &std::collections::HashMap<u32, f64>,
    (top, flip): (u32, bool),
) -> Result<Next, Stop> {
    let (s, level) = match data.column[top as usize] {
        Some(c) => (c.source as usize, c.level as usize),
        None => (source_of_root(field, data, top).ok_or(Stop::Reached)?, 0),
    };
    let d = &field.sources[s].distribution;
    let Some(&site) = d.sites().get(level + 1) else {
        return Err(Stop::Reached);
    };
    let mut near = data.near[top as usize][s];
    if near.dir == DVec3::ZERO {
        return Err(Stop::Reached);
    }
    if flip {
        near.dir = -near.dir;
    }
    let root_side = (level == 0 && field.two_sided.contains(&top)).then_some(near.dir);
    let point = near.foot + near.dir * site;
    let delta = sizing.spacing(point);
    if site > d.reach(delta) * (1.0 + 1e-12) {
        return Err(Stop::Reached);
    }
    let c = Candidate {
        point,
        site,
        dir: near.dir,
        along: near.along,
        spacing: d.layer_spacing(level),
        source: s,
        from: 0,
    };
    let phi = field.sources[s].distance.near(point).phi;
    if (phi - site).abs() > SITE_TOLERANCE * c.spacing {
        return Err(Stop::Medial);
    }
    if let Some(v) = point_at_site(dt, data, top, &c) {
        return Ok(Next::Adopt(c, v));
    }
    let cavity = star_above(dt, region_of, field, data, top, s, root_side).ok_or(Stop::Boundary)?;
    // Across the column, a point crowds within half the isotropic δ, or within half the
    // distance to the next column where the columns stand closer than δ.
    let root = data.column[top as usize].map_or(top, |col| col.root);
    let across = root_spacing.get(&root).map_or(delta, |&h| h.min(delta));
    let crowded = cavity.iter().any(|&t| {
        dt.tet(t)
            .iter()
            .any(|&v| v != INF && v != top && crowds(&c, DVec3::from_array(dt.point(v)), across))
    });
    if crowded {
        return Err(Stop::Crowded);
    }
    if !cavity.iter().all(|&t| clear_of_boundary(dt, t, &c)) {
        return Err(Stop::Boundary);
    }
    Ok(Next::Insert(c, cavity))
}

/// A neighbour of `top` in no column, within [`ADOPT_TOLERANCE`] layers of candidate `c`'s
/// point: the face refinement's point at that site on a face beside the source. A column
/// rooted on the edge between the source and that face (a wing root on a symmetry plane)
/// then has its points on the face, and the prisms between it and the columns beside it
/// exist, instead of a gap that Delaunay fills with flat tets.
fn point_at_site(dt: &mut Delaunay, data: &PointData, top: u32, c: &Candidate) -> Option<u32> {
    let tol2 = (ADOPT_TOLERANCE * c.spacing).powi(2);
    let mut best: Option<(f64, u32)> = None;
    for t in dt.tets_around_vertex(top) {
        for v in dt.tet(t) {
            if v == INF || v == top || data.column.get(v as usize).is_none_or(|c| c.is_some()) {
                continue;
            }
            let d2 = DVec3::from_array(dt.point(v)).distance_squared(c.point);
            if d2 <= tol2 && best.is_none_or(|(b, _)| d2 < b) {
                best = Some((d2, v));
            }
        }
    }
    best.map(|(_, v)| v)
}
