//! Interior points by the centroid method (seed paper, "Volume mesh generation"): the centroid
//! of every tet is a candidate; it is kept when no point — old, or accepted earlier in the same
//! round — lies closer than a fraction of the spacing δ there, and it keeps the same distance
//! from the plane of any boundary face of its tet. Accepted points go in as one batch through
//! the kernel (whose cavities never cross the recovered boundary); the next round looks only
//! at the tets that batch created. Rounds stop when nothing is accepted.

use super::boundary::OUTSIDE;
use super::delaunay::Delaunay;
use crate::sizing::SizingField;
use glam::DVec3;
use rayon::prelude::*;
use rstar::RTree;

/// A candidate closer than `SPACING_FRACTION · δ` to an existing point is refused. With 0.7,
/// the points settle at edge lengths close to δ (measured on uniform boxes: mean edge ≈ δ).
pub const SPACING_FRACTION: f64 = 0.7;
/// A candidate closer than `BOUNDARY_FRACTION · δ` to the plane of a boundary face of its tet
/// is refused: it would make a flat tet against the surface.
pub const BOUNDARY_FRACTION: f64 = 0.4;
/// Safety bound; uniform fields need about a dozen rounds.
const MAX_ROUNDS: usize = 200;

/// What the interior-point stage did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct InteriorReport {
    pub rounds: usize,
    pub points: usize,
    /// Candidates the kernel refused (exactly on a recovered boundary face).
    pub refused_on_boundary: usize,
}

/// Insert interior points until every tet meets the spacing. `region_of` (per tet slot) is
/// refreshed by `reclassify` after every round.
pub fn insert_interior_points<E>(
    dt: &mut Delaunay,
    sizing: &SizingField,
    region_of: &mut Vec<u32>,
    mut reclassify: impl FnMut(&Delaunay) -> Result<Vec<u32>, E>,
) -> Result<InteriorReport, E> {
    let mut report = InteriorReport::default();
    let mut tree: RTree<[f64; 3]> =
        RTree::bulk_load((0..dt.num_points() as u32).map(|v| dt.point(v)).collect());
    let mut look_at: Vec<u32> = dt
        .tet_ids()
        .filter(|&t| region_of[t as usize] != OUTSIDE)
        .collect();
    while !look_at.is_empty() && report.rounds < MAX_ROUNDS {
        let candidates: Vec<(DVec3, f64)> = look_at
            .par_iter()
            .filter_map(|&t| candidate(dt, sizing, t))
            .collect();
        let mut accepted: Vec<[f64; 3]> = Vec::new();
        for (c, delta) in candidates {
            let p = c.to_array();
            let min = SPACING_FRACTION * delta;
            let near = tree
                .nearest_neighbor(&p)
                .map(|q| DVec3::from_array(*q).distance_squared(c))
                .unwrap_or(f64::INFINITY);
            if near >= min * min {
                tree.insert(p);
                accepted.push(p);
            }
        }
        if accepted.is_empty() {
            break;
        }
        report.rounds += 1;
        let outcome = match dt.insert_batch(&accepted) {
            Ok(o) => o,
            Err(_) => break,
        };
        report.points += accepted.len() - outcome.on_constrained_face.len();
        report.refused_on_boundary += outcome.on_constrained_face.len();
        *region_of = reclassify(dt)?;
        look_at = outcome
            .created
            .into_iter()
            .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
            .collect();
    }
    Ok(report)
}

/// The centroid of tet `t` and δ there, unless it sits too close to a boundary face of `t`.
fn candidate(dt: &Delaunay, sizing: &SizingField, t: u32) -> Option<(DVec3, f64)> {
    let v = dt.tet(t).map(|i| DVec3::from_array(dt.point(i)));
    let c = (v[0] + v[1] + v[2] + v[3]) * 0.25;
    let delta = sizing.spacing(c);
    // Cheap rejection: a tet whose vertices are all within the spacing radius cannot take a
    // point at its centroid.
    let limit = SPACING_FRACTION * delta;
    if v.iter().any(|p| p.distance_squared(c) < limit * limit) {
        return None;
    }
    for f in 0..4u8 {
        if dt.is_constrained(t, f) {
            let [a, b, d] = dt
                .face_vertices(t, f)
                .map(|i| DVec3::from_array(dt.point(i)));
            let n = (b - a).cross(d - a);
            let len = n.length();
            if len == 0.0 || (c - a).dot(n).abs() / len < BOUNDARY_FRACTION * delta {
                return None;
            }
        }
    }
    Some((c, delta))
}
