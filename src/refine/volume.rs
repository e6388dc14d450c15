//! The element-driven part of the volume stage (seed paper, "Delaunay point insertion"), after
//! the columns (`refine/columns.rs`) have grown: every tet larger in the distance metric than
//! its stage's distribution asks for proposes the
//! first of its candidates that extends a column (a line rooted on the source) and is clear
//! of other points and of the boundary; the proposals go in as one Delaunay batch (cavities
//! never cross the recovered boundary, so wakes stay conforming from both sides), each new
//! point recorded in its column at its site, and the tets that batch made are looked at next,
//! until nothing is accepted. The prism re-split ([`super::layers`]) and the generalised edge
//! swaps ([`super::swap`]) follow. The paper's "minmax point insertion" (points at the middle
//! of the longest edge of tets still too large) is not built.

use super::field::{crowds, Candidate, StageField};
use super::layers::Column;
use super::source::Near;
use crate::progress::Reporter;
use crate::sizing::sources::distance_to_segment;
use crate::sizing::SizingField;
use crate::volume::delaunay::{Delaunay, Location, INF};
use crate::volume::{interior::label_created, OUTSIDE};
use glam::DVec3;
use rayon::prelude::*;
use rstar::RTree;
use std::collections::HashMap;

/// A point closer to the source than this fraction of the first spacing lies on it (the
/// distance to a curved source is only as exact as the projection onto its geometry).
pub(super) const ON_SOURCE: f64 = 0.01;

/// Safety bound on insertion rounds; a layer takes one or two.
const MAX_ROUNDS: usize = 400;

/// What the volume stage did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct VolumeRefineReport {
    pub rounds: usize,
    /// Points inserted from the candidate lists (Delaunay reconnection).
    pub points: usize,
    /// Proposals refused by the kernel (exactly on a boundary face).
    pub refused_on_boundary: usize,
    /// Tets still larger than their distribution asks for at the end.
    pub still_too_large: usize,
}

/// Distances of every point of the kernel to every source of the stage, δ there, and the
/// column a point of the stage's layers belongs to; grown as points are inserted.
pub struct PointData {
    pub near: Vec<Vec<Near>>,
    pub delta: Vec<f64>,
    pub column: Vec<Option<Column>>,
}

impl PointData {
    pub fn new(dt: &Delaunay, field: &StageField, sizing: &SizingField) -> Self {
        let (near, delta): (Vec<Vec<Near>>, Vec<f64>) = (0..dt.num_points() as u32)
            .into_par_iter()
            .map(|v| {
                let p = DVec3::from_array(dt.point(v));
                (field.near(p), sizing.spacing(p))
            })
            .unzip();
        let column = vec![None; near.len()];
        PointData {
            near,
            delta,
            column,
        }
    }

    /// Add the points of the kernel from `from` on.
    pub fn extend(&mut self, dt: &Delaunay, field: &StageField, sizing: &SizingField) {
        let from = self.near.len() as u32;
        let (near, delta): (Vec<_>, Vec<_>) = (from..dt.num_points() as u32)
            .into_par_iter()
            .map(|v| {
                let p = DVec3::from_array(dt.point(v));
                (field.near(p), sizing.spacing(p))
            })
            .unzip();
        self.near.extend(near);
        self.delta.extend(delta);
        self.column.resize(self.near.len(), None);
    }

    /// Whether a point on vertex `v`'s line extends a column of source `s`: `v` is in one or
    /// lies on the source.
    fn grows_column(&self, field: &StageField, v: u32, s: usize) -> bool {
        match self.column[v as usize] {
            Some(c) => c.source as usize == s,
            None => self.near[v as usize][s].phi <= ON_SOURCE * field.sources[s].distribution.first,
        }
    }

    /// The column a point inserted on vertex `from`'s line at candidate `c`'s site joins:
    /// `from`'s own, or a new one rooted at `from` when it lies on the source.
    pub(super) fn column_above(
        &mut self,
        field: &StageField,
        from: u32,
        c: &Candidate,
    ) -> Option<Column> {
        let d = &field.sources[c.source].distribution;
        let level = d.sites().partition_point(|&x| x < c.site);
        if d.sites().get(level) != Some(&c.site) {
            return None;
        }
        let base = match self.column[from as usize] {
            Some(col) if col.source as usize == c.source => col,
            Some(_) => return None,
            None if self.near[from as usize][c.source].phi <= ON_SOURCE * d.first => {
                let col = Column {
                    root: from,
                    level: 0,
                    source: c.source as u32,
                    below: false,
                };
                self.column[from as usize] = Some(col);
                col
            }
            None => return None,
        };
        // From a root, the side is the candidate's: against the source's normal is below.
        let below = if base.level == 0 {
            c.dir.dot(self.near[from as usize][c.source].dir) < 0.0
        } else {
            base.below
        };
        Some(Column {
            level: level as u32,
            below,
            ..base
        })
    }

    /// The stage's demand on tet `t`: the source and the sites it spans.
    pub fn demand(&self, dt: &Delaunay, field: &StageField, t: u32) -> Option<(usize, Vec<f64>)> {
        let ids = dt.tet(t);
        let near: Vec<&[Near]> = ids.iter().map(|&v| &self.near[v as usize][..]).collect();
        field.demand(&near, self.tet_delta(ids))
    }

    fn tet_delta(&self, ids: [u32; 4]) -> f64 {
        ids.iter().map(|&v| self.delta[v as usize]).sum::<f64>() * 0.25
    }
}

/// Refine the domain's tets (`region_of[t] != OUTSIDE`) for one stage.
pub fn refine_volume(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    side: &dyn Fn(&Delaunay, u32, u8) -> Option<u32>,
    field: &StageField,
    sizing: &SizingField,
    data: &mut PointData,
    progress: Reporter<'_>,
) -> VolumeRefineReport {
    let mut report = VolumeRefineReport::default();
    let mut look_at: Vec<u32> = dt
        .tet_ids()
        .filter(|&t| region_of[t as usize] != OUTSIDE)
        .collect();
    // The kernel's points when the stage starts (bulk-loaded, never inserted into: rstar
    // 0.12's bulk load can leave leaves at uneven depths, which a later insert panics on),
    // and those this call adds.
    let points = kernel_points(dt);
    let wedges = super::wedge::curve_wedges(dt, region_of, &curve_nodes(field, data));
    let mut added: RTree<[f64; 3]> = RTree::new();
    // A cancelled run stops between two rounds (the tets stay valid).
    while !look_at.is_empty() && report.rounds < MAX_ROUNDS && !progress.cancelled() {
        let mut proposals: Vec<(Candidate, f64, u32)> = look_at
            .par_iter()
            .filter_map(|&t| propose(dt, field, data, &wedges, t).map(|(c, d)| (c, d, t)))
            .collect();
        // Lowest sites first, then by position: the layers grow from the source outwards, and
        // the points do not depend on where the kernel stored its tets.
        proposals.par_sort_unstable_by(|a, b| {
            (a.0.site.total_cmp(&b.0.site))
                .then(a.0.point.x.total_cmp(&b.0.point.x))
                .then(a.0.point.y.total_cmp(&b.0.point.y))
                .then(a.0.point.z.total_cmp(&b.0.point.z))
        });
        let mut taken: RTree<[f64; 3]> = RTree::new();
        let mut accepted: Vec<[f64; 3]> = Vec::new();
        let mut columns: Vec<Option<Column>> = Vec::new();
        for (c, delta, t) in proposals {
            if !clear_of_taken(&c, delta, &taken) || !clear_of_nearest(&c, delta, &points, &added) {
                continue;
            }
            if !lands_in_region(dt, region_of, &c, delta, t) {
                continue;
            }
            taken.insert(c.point.to_array());
            accepted.push(c.point.to_array());
            let from = dt.tet(t)[c.from];
            columns.push(data.column_above(field, from, &c));
        }
        if accepted.is_empty() {
            break;
        }
        report.rounds += 1;
        let Ok(outcome) = dt.insert_batch(&accepted) else {
            break;
        };
        report.points +=
            accepted.len() - outcome.on_constrained_face.len() - outcome.duplicates.len();
        report.refused_on_boundary += outcome.on_constrained_face.len();
        label_created(dt, region_of, &outcome.created, side);
        data.extend(dt, field, sizing);
        let refused: std::collections::HashSet<u32> = (outcome.duplicates.iter())
            .map(|d| d.index)
            .chain(outcome.on_constrained_face.iter().copied())
            .collect();
        for (&v, col) in outcome.vertices.iter().zip(columns) {
            if !refused.contains(&v) {
                data.column[v as usize] = col;
                added.insert(dt.point(v));
            }
        }
        look_at = outcome
            .created
            .into_iter()
            .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
            .collect();
    }
    report
}

/// The kernel's vertices lying on a curve source of the stage, with the curve's tangent.
fn curve_nodes(field: &StageField, data: &PointData) -> Vec<(u32, DVec3)> {
    (0..data.near.len() as u32)
        .filter_map(|v| {
            let near = &data.near[v as usize];
            (0..near.len())
                .find(|&s| {
                    near[s].along != DVec3::ZERO
                        && near[s].phi <= ON_SOURCE * field.sources[s].distribution.first
                })
                .map(|s| (v, near[s].along))
        })
        .collect()
}

/// Tets of the domain still larger than the stage's distributions ask for.
pub fn count_too_large(
    dt: &Delaunay,
    region_of: &[u32],
    field: &StageField,
    data: &PointData,
) -> usize {
    let ids: Vec<u32> = dt
        .tet_ids()
        .filter(|&t| region_of[t as usize] != OUTSIDE)
        .collect();
    ids.par_iter()
        .filter(|&&t| data.demand(dt, field, t).is_some())
        .count()
}

/// The first candidate of tet `t` that extends a column, when clear of the points around it
/// and of its boundary faces (or, from a curve's node, the same site on its wedge's
/// bisector), with δ there; `None` when `t` meets its distribution or the candidate is refused.
fn propose(
    dt: &Delaunay,
    field: &StageField,
    data: &PointData,
    wedges: &HashMap<u32, DVec3>,
    t: u32,
) -> Option<(Candidate, f64)> {
    let (s, sites) = data.demand(dt, field, t)?;
    let ids = dt.tet(t);
    let pos = ids.map(|v| DVec3::from_array(dt.point(v)));
    let near: Vec<&[Near]> = ids.iter().map(|&v| &data.near[v as usize][..]).collect();
    let delta = data.tet_delta(ids);
    let centre = (pos[0] + pos[1] + pos[2] + pos[3]) * 0.25;
    let mut around: Vec<DVec3> = pos.to_vec();
    for f in 0..4u8 {
        let (u, g) = dt.neighbor(t, f);
        let far = dt.tet(u)[g as usize];
        if far != INF {
            around.push(DVec3::from_array(dt.point(far)));
        }
    }
    // Only the first candidate on a column's line (in the paper's order: the lowest such
    // vertex's): the layers grow column by column from the source's nodes, and a point on the
    // line of an isotropic point would start a stray column between them. A tet whose first
    // candidate exists already is badly connected, not too large: the swaps reconnect it.
    let first = field
        .candidates(s, &sites, &pos, &near, centre, true)
        .into_iter()
        .find(|c| data.grows_column(field, ids[c.from], c.source))?;
    let clear = |c: &Candidate| {
        c.point.is_finite()
            && !around.iter().any(|&q| crowds(c, q, delta))
            && clear_of_boundary_around(dt, t, c)
    };
    if clear(&first) {
        return Some((first, delta));
    }
    // A curve's node whose line to this tet's centre runs too close to a wall: the line
    // along its wedge's bisector instead (`super::wedge`).
    let bisector = *wedges.get(&ids[first.from])?;
    let on_bisector = Candidate {
        point: near[first.from][first.source].foot + bisector * first.site,
        dir: bisector,
        ..first
    };
    clear(&on_bisector).then_some((on_bisector, delta))
}

/// A candidate must keep half a layer from the planes of the boundary faces of its tet.
pub(super) fn clear_of_boundary(dt: &Delaunay, t: u32, c: &Candidate) -> bool {
    (0..4u8).all(|f| {
        if !dt.is_constrained(t, f) {
            return true;
        }
        let [a, b, e] = dt
            .face_vertices(t, f)
            .map(|i| DVec3::from_array(dt.point(i)));
        let n = (b - a).cross(e - a);
        let len = n.length();
        len > 0.0 && (c.point - a).dot(n).abs() / len >= 0.5 * c.spacing
    })
}

/// [`clear_of_boundary`] for tet `t` and, where the candidate comes within half a layer of
/// one of `t`'s edges, for every tet around that edge. A tet may touch the boundary with an
/// edge only (a symmetry plane's edge between two column points): a point beside that edge,
/// clear of `t`'s own faces, would lie on the plane, and the Delaunay cavity would cone it
/// over the plane's faces into tets of no volume.
pub(super) fn clear_of_boundary_around(dt: &Delaunay, t: u32, c: &Candidate) -> bool {
    if !clear_of_boundary(dt, t, c) {
        return false;
    }
    let v = dt.tet(t);
    for i in 0..4 {
        for j in i + 1..4 {
            let (a, b) = (v[i], v[j]);
            if a == INF || b == INF {
                continue;
            }
            let (pa, pb) = (
                DVec3::from_array(dt.point(a)),
                DVec3::from_array(dt.point(b)),
            );
            if distance_to_segment(c.point, pa, pb) >= 0.5 * c.spacing {
                continue;
            }
            let (ring, _) = dt.tets_around_edge_of_tet(t, a, b);
            if ring
                .iter()
                .any(|&u| !dt.is_ghost(u) && !clear_of_boundary(dt, u, c))
            {
                return false;
            }
        }
    }
    true
}

/// Every point of the kernel's tets, for [`clear_of_nearest`].
fn kernel_points(dt: &Delaunay) -> RTree<[f64; 3]> {
    let mut used = vec![false; dt.num_points()];
    for t in dt.tet_ids() {
        for v in dt.tet(t) {
            if v != INF {
                used[v as usize] = true;
            }
        }
    }
    let points = (0..dt.num_points() as u32)
        .filter(|&v| used[v as usize])
        .map(|v| dt.point(v))
        .collect();
    RTree::bulk_load(points)
}

/// Clear of the nearest point of the whole kernel, not only of the tet's neighbours: among
/// tets of no volume (a stretched tip before the swaps) a point a rounding away from a
/// vertex may lie in a tet that vertex is not on, and the pair then bounds tets of no volume.
fn clear_of_nearest(
    c: &Candidate,
    delta: f64,
    points: &RTree<[f64; 3]>,
    added: &RTree<[f64; 3]>,
) -> bool {
    [points, added].iter().all(|tree| {
        tree.nearest_neighbor(&c.point.to_array())
            .is_none_or(|q| !crowds(c, DVec3::from_array(*q), delta))
    })
}

/// Clear of the points this round has accepted so far.
fn clear_of_taken(c: &Candidate, delta: f64, taken: &RTree<[f64; 3]>) -> bool {
    let r = 0.5 * delta;
    taken
        .locate_within_distance(c.point.to_array(), r * r)
        .all(|q| !crowds(c, DVec3::from_array(*q), delta))
}

/// The domain tet of `t`'s region holding `p`, if `p` lies in one.
fn locate_in_region(dt: &mut Delaunay, region_of: &[u32], p: DVec3, t: u32) -> Option<u32> {
    let u = match dt.locate(p.to_array(), Some(t)) {
        Location::Tet(u) => u,
        _ => return None,
    };
    let r = region_of.get(u as usize).copied();
    (r.is_some() && r != Some(OUTSIDE) && r == region_of.get(t as usize).copied()).then_some(u)
}

/// The candidate lies in a domain tet of `t`'s region, clear of that tet's points and
/// boundary faces too.
fn lands_in_region(
    dt: &mut Delaunay,
    region_of: &[u32],
    c: &Candidate,
    delta: f64,
    t: u32,
) -> bool {
    let Some(u) = locate_in_region(dt, region_of, c.point, t) else {
        return false;
    };
    if u == t {
        return true;
    }
    let ids = dt.tet(u);
    !ids.iter()
        .any(|&v| v != INF && crowds(c, DVec3::from_array(dt.point(v)), delta))
        && clear_of_boundary_around(dt, u, c)
}
