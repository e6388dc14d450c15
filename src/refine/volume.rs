//! The volume stage of directional refinement (seed paper, "Delaunay point insertion" and
//! "Minmax point insertion"): every tet larger in the distance metric than its stage's
//! distribution asks for proposes the first of its candidates that is clear of other points
//! and of the boundary; the proposals go in as one Delaunay batch (cavities never cross the
//! recovered boundary, so wakes stay conforming from both sides), and the tets that batch made
//! are looked at next, until nothing is accepted. A tet still too large then gets a point at
//! the middle of its longest edge in the distance metric, by splitting the edge's ring, and
//! the generalised edge swaps ([`super::swap`]) bring the largest angles down.

use super::field::{crowds, Candidate, StageField};
use super::source::Near;
use crate::sizing::SizingField;
use crate::volume::delaunay::{Delaunay, Location, INF};
use crate::volume::{interior::label_created, OUTSIDE};
use glam::DVec3;
use rayon::prelude::*;
use rstar::RTree;

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
    /// Points at the middle of a tet's longest metric edge.
    pub minmax_points: usize,
    /// Tets still larger than their distribution asks for at the end.
    pub still_too_large: usize,
}

/// Distances of every point of the kernel to every source of the stage, and δ there; grown as
/// points are inserted.
pub struct PointData {
    pub near: Vec<Vec<Near>>,
    pub delta: Vec<f64>,
}

impl PointData {
    pub fn new(dt: &Delaunay, field: &StageField, sizing: &SizingField) -> Self {
        let (near, delta) = (0..dt.num_points() as u32)
            .into_par_iter()
            .map(|v| {
                let p = DVec3::from_array(dt.point(v));
                (field.near(p), sizing.spacing(p))
            })
            .unzip();
        PointData { near, delta }
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
) -> VolumeRefineReport {
    let mut report = VolumeRefineReport::default();
    let mut look_at: Vec<u32> = dt
        .tet_ids()
        .filter(|&t| region_of[t as usize] != OUTSIDE)
        .collect();
    while !look_at.is_empty() && report.rounds < MAX_ROUNDS {
        let mut proposals: Vec<(Candidate, f64, u32)> = look_at
            .par_iter()
            .filter_map(|&t| propose(dt, field, data, t).map(|(c, d)| (c, d, t)))
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
        for (c, delta, t) in proposals {
            if !clear_of_taken(&c, delta, &taken) {
                continue;
            }
            if !lands_in_region(dt, region_of, &c, delta, t) {
                continue;
            }
            taken.insert(c.point.to_array());
            accepted.push(c.point.to_array());
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
        look_at = outcome
            .created
            .into_iter()
            .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
            .collect();
    }
    report
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

/// The first candidate of tet `t` clear of the points around it and of its boundary faces,
/// with δ there; `None` when `t` meets its distribution or every candidate is refused.
fn propose(
    dt: &Delaunay,
    field: &StageField,
    data: &PointData,
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
    // Only the lowest vertex's candidate: the layers grow column by column from the source's
    // nodes. A tet whose lowest candidate exists already is badly connected, not too large:
    // the swaps reconnect it, and min-max insertion takes what is left.
    field
        .candidates(s, &sites, &pos, &near, centre)
        .into_iter()
        .take(1)
        .find(|c| {
            c.point.is_finite()
                && !around.iter().any(|&q| crowds(c, q, delta))
                && clear_of_boundary(dt, t, c)
        })
        .map(|c| (c, delta))
}

/// A candidate must keep half a layer from the planes of the boundary faces of its tet.
fn clear_of_boundary(dt: &Delaunay, t: u32, c: &Candidate) -> bool {
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

/// Clear of the points this round has accepted so far.
fn clear_of_taken(c: &Candidate, delta: f64, taken: &RTree<[f64; 3]>) -> bool {
    let r = 0.5 * delta;
    taken
        .locate_within_distance(c.point.to_array(), r * r)
        .all(|q| !crowds(c, DVec3::from_array(*q), delta))
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
    let u = match dt.locate(c.point.to_array(), Some(t)) {
        Location::Tet(u) => u,
        _ => return false,
    };
    if region_of.get(u as usize).copied() != region_of.get(t as usize).copied() {
        return false;
    }
    if u == t {
        return true;
    }
    let ids = dt.tet(u);
    !ids.iter()
        .any(|&v| v != INF && crowds(c, DVec3::from_array(dt.point(v)), delta))
        && clear_of_boundary(dt, u, c)
}

/// Tets still too large whose candidates were all refused get a point at the middle of their
/// longest edge in the distance metric (largest |φa − φb| for the demanding source), inserted
/// by splitting the edge's ring; an edge on a boundary face is left alone. Returns the number
/// of points.
pub fn minmax_insertion(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    field: &StageField,
    sizing: &SizingField,
    data: &mut PointData,
) -> usize {
    let mut added = 0;
    {
        let large: Vec<(u32, usize)> = dt
            .tet_ids()
            .filter(|&t| region_of[t as usize] != OUTSIDE)
            .collect::<Vec<_>>()
            .into_par_iter()
            .filter_map(|t| data.demand(dt, field, t).map(|(s, _)| (t, s)))
            .collect();
        let mut this_pass = 0;
        for (t, s) in large {
            if !dt.is_live(t) || dt.is_ghost(t) || region_of[t as usize] == OUTSIDE {
                continue;
            }
            let Some((s2, _)) = data.demand(dt, field, t) else {
                continue;
            };
            let s = if s2 == s { s } else { s2 };
            let ids = dt.tet(t);
            let phi = ids.map(|v| data.near[v as usize][s].phi);
            let mut edges = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
            edges.sort_by(|a, b| {
                let da = (phi[a.0] - phi[a.1]).abs();
                let db = (phi[b.0] - phi[b.1]).abs();
                db.total_cmp(&da)
            });
            let region = region_of[t as usize];
            for (i, j) in edges.into_iter().take(2) {
                let (a, b) = (ids[i], ids[j]);
                let m = (DVec3::from_array(dt.point(a)) + DVec3::from_array(dt.point(b))) * 0.5;
                if crowded_middle(dt, field, data, t, s, m) {
                    continue;
                }
                let Some((ring, _)) = dt.tets_around_edge(a, b) else {
                    continue;
                };
                if ring
                    .iter()
                    .any(|&u| dt.is_ghost(u) || region_of[u as usize] != region)
                    || on_constrained_face(dt, &ring, a, b)
                {
                    continue;
                }
                if let Ok(out) = dt.insert_split(m.to_array(), Some(t), &|_| false) {
                    if region_of.len() < dt.slot_count() {
                        region_of.resize(dt.slot_count(), OUTSIDE);
                    }
                    for &u in &out.created {
                        region_of[u as usize] = if dt.is_ghost(u) { OUTSIDE } else { region };
                    }
                    data.extend(dt, field, sizing);
                    this_pass += 1;
                    break;
                }
            }
        }
        added += this_pass;
    }
    added
}

/// True when a face around edge `ab` (of the tets `ring`) is a recovered boundary face: its
/// middle would split a face the boundary triangles list.
pub(super) fn on_constrained_face(dt: &Delaunay, ring: &[u32], a: u32, b: u32) -> bool {
    ring.iter().any(|&u| {
        let ids = dt.tet(u);
        (0..4u8).any(|f| {
            let opposite = ids[f as usize];
            opposite != a && opposite != b && dt.is_constrained(u, f)
        })
    })
}

/// The middle `m` of an edge of tet `t` is crowded when a point of `t` or of its face
/// neighbours lies within its metric ball (the edge is short across the layers already).
fn crowded_middle(
    dt: &Delaunay,
    field: &StageField,
    data: &PointData,
    t: u32,
    s: usize,
    m: DVec3,
) -> bool {
    let n = field.sources[s].distance.near(m);
    let d = &field.sources[s].distribution;
    let ids = dt.tet(t);
    let c = Candidate {
        point: m,
        site: n.phi,
        dir: n.dir,
        spacing: d.spacing_at(n.phi),
        source: s,
    };
    let delta = data.tet_delta(ids);
    let mut around: Vec<u32> = ids.to_vec();
    for f in 0..4u8 {
        let (u, g) = dt.neighbor(t, f);
        around.push(dt.tet(u)[g as usize]);
    }
    around
        .into_iter()
        .filter(|&v| v != INF)
        .any(|v| crowds(&c, DVec3::from_array(dt.point(v)), delta))
}
