//! A new point for a flat tet that moves, splits, collapses and swaps all left (the last step
//! of `flat.rs`). Such a tet sits where the layers' points cannot go anywhere useful: its
//! corners are on the boundary, or in the first layers, or any move folds a neighbour.
//!
//! A point inside a small cavity around the tet — the tet itself, the tet and its neighbours,
//! the ring of tets around one of its two sharpest edges, or that ring and its neighbours —
//! replaces the cavity by the cone from the point over the cavity's outer faces
//! (`cone.rs`; starts: the cavity's and the tet's centroids, the tet's edge midpoints).
//! The best cavity is kept when its cone's largest angle is below the cavity's before. The cavities never cross a constrained face, so the
//! surface and the embedded faces stay as they are.

use super::cone;
use super::swap::score;
use crate::volume::delaunay::Delaunay;
use crate::volume::improve::label;
use glam::DVec3;

/// The cone must lower the cavity's largest angle by at least this much (degrees).
const GAIN: f64 = 1e-3;
/// Edges of the tet whose rings are tried as cavities: its sharpest ones.
const EDGE_RINGS: usize = 2;

/// Insert a point that removes flat tet `t` (a domain tet of region `region_of[t]`), if some
/// cavity around it has a point whose cone is better than the cavity. True when inserted; the
/// new tets are labelled with `t`'s region.
pub fn insert_point(dt: &mut Delaunay, region_of: &mut Vec<u32>, t: u32) -> bool {
    let region = region_of[t as usize];
    let mut best: Option<(f64, Vec<u32>, DVec3)> = None;
    for cavity in cavities(dt, region_of, t) {
        let Some((worst, p)) = best_point(dt, &cavity, t) else {
            continue;
        };
        let before = largest_angle(dt, &cavity);
        let better_than_best = best.as_ref().is_none_or(|b| worst < b.0);
        if worst < before - GAIN && better_than_best {
            best = Some((worst, cavity, p));
        }
    }
    let Some((_, cavity, p)) = best else {
        return false;
    };
    match dt.insert_in_cavity(p.to_array(), &cavity, &|_, _| false) {
        Ok((_, created)) => {
            label(region_of, dt.slot_count(), &created, region);
            true
        }
        Err(_) => false,
    }
}

/// The cavities tried for flat tet `t`, smallest first: each a set of finite tets of `t`'s
/// region with no constrained face between two of them.
fn cavities(dt: &mut Delaunay, region_of: &[u32], t: u32) -> Vec<Vec<u32>> {
    let mut out = vec![vec![t]];
    out.push(with_neighbours(dt, region_of, &[t]));
    let v = dt.tet(t);
    let q = v.map(|i| dt.point(i));
    // The tet's edges by their dihedral angle, largest first: a flat tet's are near 180°.
    let mut edges: Vec<(f64, [usize; 2])> = EDGES
        .iter()
        .map(|&[a, b]| (dihedral_at(&q, a, b), [a, b]))
        .collect();
    edges.sort_by(|x, y| y.0.total_cmp(&x.0));
    for &(_, [a, b]) in edges.iter().take(EDGE_RINGS) {
        let (ring, _) = dt.tets_around_edge_of_tet(t, v[a], v[b]);
        if ring.len() < 2 || !usable(dt, region_of, region_of[t as usize], &ring) {
            continue;
        }
        let grown = with_neighbours(dt, region_of, &ring);
        out.push(ring);
        out.push(grown);
    }
    out
}

/// The six edges of a tet, by corner.
const EDGES: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// The dihedral angle (degrees) of tet `q` at its edge between corners `a` and `b`.
fn dihedral_at(q: &[[f64; 3]; 4], a: usize, b: usize) -> f64 {
    let [c, d] = {
        let mut o = (0..4).filter(|&k| k != a && k != b);
        [o.next().unwrap_or(0), o.next().unwrap_or(0)]
    };
    let p = q.map(DVec3::from_array);
    let axis = p[b] - p[a];
    let off = |k: usize| {
        let w = p[k] - p[a];
        w - axis * (w.dot(axis) / axis.length_squared())
    };
    off(c).angle_between(off(d)).to_degrees()
}

/// Whether the tets `set` are all finite, live, of `region`, with no constrained face between
/// two of them.
fn usable(dt: &Delaunay, region_of: &[u32], region: u32, set: &[u32]) -> bool {
    set.iter().all(|&u| {
        dt.is_live(u)
            && !dt.is_ghost(u)
            && region_of.get(u as usize) == Some(&region)
            && (0..4u8).all(|f| !(set.contains(&dt.neighbor(u, f).0) && dt.is_constrained(u, f)))
    })
}

/// `set` and the finite tets of its region beyond its faces that are not constrained.
fn with_neighbours(dt: &Delaunay, region_of: &[u32], set: &[u32]) -> Vec<u32> {
    let region = region_of[set[0] as usize];
    let mut out = set.to_vec();
    for &u in set {
        for f in 0..4u8 {
            let (w, _) = dt.neighbor(u, f);
            if out.contains(&w) || dt.is_constrained(u, f) || dt.is_ghost(w) {
                continue;
            }
            if region_of.get(w as usize) == Some(&region) {
                out.push(w);
            }
        }
    }
    out
}

/// The largest dihedral angle of the tets `set`.
fn largest_angle(dt: &Delaunay, set: &[u32]) -> f64 {
    set.iter().map(|&u| score(dt, u)).fold(0.0, f64::max)
}

/// The best point in `cavity` (which holds flat tet `t`) and its cone's largest angle: `None`
/// where no start sees every outer face.
fn best_point(dt: &Delaunay, cavity: &[u32], t: u32) -> Option<(f64, DVec3)> {
    let faces = cone::boundary(dt, cavity);
    let q = dt.tet(t).map(|i| DVec3::from_array(dt.point(i)));
    let mut starts = vec![
        cone::centroid(dt, &faces),
        (q[0] + q[1] + q[2] + q[3]) / 4.0,
    ];
    starts.extend(EDGES.iter().map(|&[a, b]| (q[a] + q[b]) / 2.0));
    let shortest = EDGES
        .iter()
        .map(|&[a, b]| (q[a] - q[b]).length())
        .fold(f64::INFINITY, f64::min);
    cone::best_point(dt, &faces, &starts, shortest)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat_count(dt: &Delaunay, above: f64) -> usize {
        dt.tet_ids()
            .filter(|&t| !dt.is_ghost(t))
            .filter(|&t| largest_angle(dt, &[t]) > above)
            .count()
    }

    /// An interior point of a lattice pushed towards the opposite face of one tet of its star
    /// until that tet is flat (largest angle above 170°): a new point in a cavity around it
    /// takes its place, the triangulation stays valid and keeps its volume.
    #[test]
    fn a_flat_tet_gives_way_to_a_new_point() {
        let mut pts = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                for k in 0..4 {
                    let wobble = 0.04 * ((i * 5 + j * 3 + k * 7) % 5) as f64;
                    pts.push([
                        i as f64 + wobble,
                        j as f64 + 0.5 * wobble,
                        k as f64 - wobble,
                    ]);
                }
            }
        }
        let v = 21u32; // (1, 1, 1)
        let mut dt = Delaunay::new(&pts).expect("triangulated");
        let volume = |dt: &Delaunay| {
            cone::tests::volume(
                dt,
                dt.tet_ids().filter(|&t| !dt.is_ghost(t)).map(|t| dt.tet(t)),
            )
        };
        let whole = volume(&dt);
        let from = DVec3::from_array(dt.point(v));
        // Push `v` towards the plane of the face opposite it in some star tet, as far as the
        // star stays positive, until that tet is flat.
        let mut flat = None;
        'search: for t in dt.tets_around_vertex(v) {
            let others: Vec<DVec3> = dt
                .tet(t)
                .into_iter()
                .filter(|&i| i != v)
                .map(|i| DVec3::from_array(dt.point(i)))
                .collect();
            let n = (others[1] - others[0])
                .cross(others[2] - others[0])
                .normalize();
            let foot = from - n * (from - others[0]).dot(n);
            for k in 1..40 {
                let p = foot + (from - foot) * 0.5f64.powi(k);
                dt.set_point(v, p.to_array());
                let star = dt.tets_around_vertex(v);
                let positive = star.iter().all(|&u| {
                    let q = dt.tet(u).map(|i| dt.point(i));
                    orient_positive(&q)
                });
                if !positive {
                    break;
                }
                if largest_angle(&dt, &[t]) > 170.0 {
                    flat = Some(t);
                    break 'search;
                }
            }
            dt.set_point(v, from.to_array());
        }
        let t = flat.expect("a tet pushed flat");
        let before = flat_count(&dt, 170.0);
        let mut region_of = vec![0u32; dt.slot_count()];
        assert!(insert_point(&mut dt, &mut region_of, t));
        assert!(dt.check_valid().is_ok());
        assert!(flat_count(&dt, 170.0) < before, "{before}");
        assert!((volume(&dt) - whole).abs() < 1e-9 * whole);
    }

    fn orient_positive(q: &[[f64; 3]; 4]) -> bool {
        crate::volume::delaunay::predicates::orient(&q[0], &q[1], &q[2], &q[3]) > 0.0
    }
}
