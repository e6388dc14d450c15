//! Clearing the refined zone before the layers go in. Isotropic interior points are kept out
//! of the zone when they are placed, but smoothing moves some in and sliver removal adds
//! some; any left there sits between the columns, breaks the prisms of the layers and makes
//! slivers no swap removes. Each is taken out by collapsing it onto the neighbour that leaves
//! the best tets (its star re-tessellated by the kernel, which refuses an invalid collapse).

use crate::volume::delaunay::{Delaunay, INF};
use crate::volume::improve::{label, max_dihedral};
use crate::volume::OUTSIDE;
use glam::DVec3;

/// Sweeps over the points: a collapse refused may go once a neighbour has gone.
const PASSES: usize = 2;

/// What clearing did.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct ClearReport {
    /// Interior points found in the zone.
    pub in_zone: usize,
    /// Of those, taken out.
    pub removed: usize,
}

/// Take the interior points (from `first_movable` on) for which `in_zone` says yes out of the
/// triangulation, where a collapse onto a neighbour is valid.
pub fn clear_zone(
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    first_movable: u32,
    in_zone: &(dyn Fn(DVec3) -> bool + Sync),
) -> ClearReport {
    let mut todo: Vec<u32> = (first_movable..dt.num_points() as u32)
        .filter(|&v| dt.vertex_tet(v).is_some() && in_zone(DVec3::from_array(dt.point(v))))
        .collect();
    let mut report = ClearReport {
        in_zone: todo.len(),
        ..Default::default()
    };
    for _ in 0..PASSES {
        let before = todo.len();
        todo.retain(|&v| !collapse(dt, region_of, v, f64::INFINITY));
        report.removed += before - todo.len();
        if todo.len() == before {
            break;
        }
    }
    report
}

/// Collapse `v` onto the neighbour whose collapse leaves the smallest largest dihedral angle
/// among the valid ones, when that angle is below `below` (degrees); false (nothing changed)
/// when none is valid, the star is not all of one region, or it touches the hull or a
/// constrained face.
pub(super) fn collapse(dt: &mut Delaunay, region_of: &mut Vec<u32>, v: u32, below: f64) -> bool {
    let star = dt.tets_around_vertex(v);
    let Some(&first) = star.first() else {
        return false;
    };
    let region = region_of[first as usize];
    if region == OUTSIDE
        || star.iter().any(|&t| {
            dt.is_ghost(t)
                || region_of[t as usize] != region
                || (0..4u8).any(|f| dt.tet(t)[f as usize] != v && dt.is_constrained(t, f))
        })
    {
        return false;
    }
    let tets: Vec<[u32; 4]> = star.iter().map(|&t| dt.tet(t)).collect();
    let mut around: Vec<u32> = tets.iter().flatten().copied().filter(|&x| x != v).collect();
    around.sort_unstable();
    around.dedup();
    let mut options: Vec<(f64, Vec<[u32; 4]>)> = around
        .iter()
        .filter(|&&w| w != INF)
        .map(|&w| {
            let new: Vec<[u32; 4]> = tets
                .iter()
                .filter(|t| !t.contains(&w))
                .map(|t| t.map(|x| if x == v { w } else { x }))
                .collect();
            let worst = new
                .iter()
                .map(|t| {
                    let p = t.map(|x| dt.point(x));
                    max_dihedral(&p[0], &p[1], &p[2], &p[3])
                })
                .fold(0.0, f64::max);
            (worst, new)
        })
        .collect();
    options.retain(|o| o.0 < below);
    options.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, new) in options {
        if let Ok(ids) = dt.replace_star(v, &new, None, &[]) {
            label(region_of, dt.slot_count(), &ids, region);
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interior_points_in_the_zone_are_collapsed_away_and_the_volume_kept() {
        // A jittered 6³ lattice: the 8 corners' hull, interior points everywhere.
        let mut seed = 3u64;
        let mut noise = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.3
        };
        let mut pts = Vec::new();
        for i in 0..6 {
            for j in 0..6 {
                for k in 0..6 {
                    let inner = |c: i32| (1..5).contains(&c);
                    let j3 = if inner(i) && inner(j) && inner(k) {
                        [noise(), noise(), noise()]
                    } else {
                        [0.0; 3]
                    };
                    pts.push([i as f64 + j3[0], j as f64 + j3[1], k as f64 + j3[2]]);
                }
            }
        }
        let mut dt = Delaunay::new(&pts).unwrap();
        let volume = |dt: &Delaunay| -> f64 {
            dt.tet_ids()
                .filter(|&t| !dt.is_ghost(t))
                .map(|t| {
                    let [a, b, c, d] = dt.tet(t).map(|v| DVec3::from_array(dt.point(v)));
                    (b - a).cross(c - a).dot(d - a).abs() / 6.0
                })
                .sum()
        };
        let v0 = volume(&dt);
        let mut region_of: Vec<u32> = (0..dt.slot_count() as u32)
            .map(|t| if dt.is_ghost(t) { OUTSIDE } else { 0 })
            .collect();
        // The zone: the inner points of levels 1 and 2 (no hull point is in it).
        let zone =
            |p: DVec3| p.z > 0.5 && p.z < 2.5 && p.x > 0.5 && p.x < 4.5 && p.y > 0.5 && p.y < 4.5;
        let report = clear_zone(&mut dt, &mut region_of, 0, &|p| zone(p));
        // 4 × 4 inner columns, levels 1 and 2; most go (26 here: where every neighbour's
        // collapse would fold a tet, the point stays).
        assert_eq!(report.in_zone, 32, "{report:?}");
        assert!(report.removed >= 24, "{report:?}");
        dt.check_valid().unwrap();
        assert!((volume(&dt) - v0).abs() < 1e-9 * v0);
        let left = (0..dt.num_points() as u32)
            .filter(|&v| dt.vertex_tet(v).is_some() && zone(DVec3::from_array(dt.point(v))))
            .count();
        assert_eq!(left, report.in_zone - report.removed);
    }
}
