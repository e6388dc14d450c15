//! A region of tets re-tiled as a cone from one apex: the region's boundary faces, each joined
//! to the apex. The apex is an existing vertex of the boundary (no point added) or a new
//! point placed for the cone: from the best of a few starts, hill-climbed on the cone's
//! largest dihedral angle, every cone tet positive by the exact `orient`. Used for the flat
//! tets nothing else removes (`flat_point.rs`) and for the tops of re-tiled stacks of
//! prisms that the tets above do not meet (`spanning.rs`).

use crate::volume::delaunay::predicates::orient;
use crate::volume::delaunay::Delaunay;
use crate::volume::improve::{climb_worst_angle, max_dihedral};
use glam::DVec3;
use std::collections::BTreeMap;

/// Hill-climb steps for a new apex.
const CLIMB: usize = 40;

/// A boundary face as its three vertices ordered so that a tet on them and a point `x` is
/// positive exactly when `x` is on the region's side; keyed by the sorted vertices.
pub type Faces = BTreeMap<[u32; 3], [u32; 3]>;

/// The face of positive tet `v` opposite corner `f`, ordered towards the tet's side.
fn inward(v: [u32; 4], f: usize) -> [u32; 3] {
    match f {
        0 => [v[2], v[1], v[3]],
        1 => [v[0], v[2], v[3]],
        2 => [v[1], v[0], v[3]],
        _ => [v[0], v[1], v[2]],
    }
}

fn key(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

/// The outer faces of the kernel's tets `set`.
pub fn boundary(dt: &Delaunay, set: &[u32]) -> Faces {
    let tets: Vec<[u32; 4]> = set.iter().map(|&u| dt.tet(u)).collect();
    boundary_of(dt, &tets)
}

/// The outer faces of the tets `tets` (vertex sets in any order; a flat one gives none).
pub fn boundary_of(dt: &Delaunay, tets: &[[u32; 4]]) -> Faces {
    let mut count: BTreeMap<[u32; 3], ([u32; 3], usize)> = BTreeMap::new();
    for &t in tets {
        let q = t.map(|i| dt.point(i));
        let s = orient(&q[0], &q[1], &q[2], &q[3]);
        if s == 0.0 {
            continue;
        }
        let v = if s > 0.0 { t } else { [t[0], t[1], t[3], t[2]] };
        for f in 0..4 {
            let face = inward(v, f);
            count.entry(key(face)).or_insert((face, 0)).1 += 1;
        }
    }
    count
        .into_iter()
        .filter(|(_, (_, n))| *n == 1)
        .map(|(k, (face, _))| (k, face))
        .collect()
}

/// The boundary of region `outer` less the region `inner` inside it: faces of one not on the
/// other, those of `inner` turned to face away from it.
pub fn difference(outer: &Faces, inner: &Faces) -> Faces {
    let mut out: Faces = outer
        .iter()
        .filter(|(k, _)| !inner.contains_key(*k))
        .map(|(k, f)| (*k, *f))
        .collect();
    for (k, f) in inner {
        if !outer.contains_key(k) {
            out.insert(*k, [f[1], f[0], f[2]]);
        }
    }
    out
}

/// Minus the largest dihedral angle of the cone from `p` over `faces` (positions), `None`
/// where a cone tet is not positive.
fn cone_score(faces: &[[[f64; 3]; 3]], p: &[f64; 3]) -> Option<f64> {
    let mut w = f64::INFINITY;
    for [a, b, c] in faces {
        if orient(a, b, c, p) <= 0.0 {
            return None;
        }
        w = w.min(-max_dihedral(a, b, c, p));
    }
    Some(w)
}

/// The best new apex for `faces`: its cone's largest angle and position, from the best of
/// `starts`, climbed with steps up to a quarter of `scale`. `None` where no start sees every
/// face.
pub fn best_point(
    dt: &Delaunay,
    faces: &Faces,
    starts: &[DVec3],
    scale: f64,
) -> Option<(f64, DVec3)> {
    let at: Vec<[[f64; 3]; 3]> = faces.values().map(|f| f.map(|i| dt.point(i))).collect();
    let score = |p: [f64; 3]| cone_score(&at, &p);
    let (from, value) = starts
        .iter()
        .filter_map(|&p| score(p.to_array()).map(|s| (p, s)))
        .max_by(|x, y| x.1.total_cmp(&y.1))?;
    let p = climb_worst_angle(from, value, scale, CLIMB, &score).unwrap_or(from);
    score(p.to_array()).map(|s| (-s, p))
}

/// The best existing vertex of `faces` as apex: its cone's largest angle and the vertex.
/// The faces on the vertex are the cone's own sides and get no tet.
pub fn best_vertex(dt: &Delaunay, faces: &Faces) -> Option<(f64, u32)> {
    let mut vertices: Vec<u32> = faces.values().flatten().copied().collect();
    vertices.sort_unstable();
    vertices.dedup();
    vertices
        .into_iter()
        .filter_map(|v| {
            let at: Vec<[[f64; 3]; 3]> = faces
                .values()
                .filter(|f| !f.contains(&v))
                .map(|f| f.map(|i| dt.point(i)))
                .collect();
            cone_score(&at, &dt.point(v)).map(|s| (-s, v))
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))
}

/// The cone's tets from apex `v` (a vertex index, new or existing) over `faces`.
pub fn tets(faces: &Faces, v: u32) -> Vec<[u32; 4]> {
    faces
        .values()
        .filter(|f| !f.contains(&v))
        .map(|f| [f[0], f[1], f[2], v])
        .collect()
}

/// Centroid of the vertices of `faces`.
pub fn centroid(dt: &Delaunay, faces: &Faces) -> DVec3 {
    let mut vertices: Vec<u32> = faces.values().flatten().copied().collect();
    vertices.sort_unstable();
    vertices.dedup();
    let sum: DVec3 = vertices
        .iter()
        .map(|&i| DVec3::from_array(dt.point(i)))
        .sum();
    sum / vertices.len().max(1) as f64
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The volume of the tets `tets`.
    pub(in crate::refine) fn volume(dt: &Delaunay, tets: impl Iterator<Item = [u32; 4]>) -> f64 {
        tets.map(|t| {
            let q = t.map(|i| DVec3::from_array(dt.point(i)));
            (q[1] - q[0]).cross(q[2] - q[0]).dot(q[3] - q[0]).abs() / 6.0
        })
        .sum()
    }

    /// The star of the middle point of a 3×3×3 lattice: its boundary, a cone over it from a
    /// new point, a tet split at a new point, and the difference of two regions.
    #[test]
    fn a_region_is_seen_as_a_cone_from_a_vertex_or_a_new_point() {
        let mut pts = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    let wobble = 0.05 * ((i * 7 + j * 3 + k * 5) % 4) as f64;
                    pts.push([
                        i as f64 + wobble,
                        j as f64 - wobble,
                        k as f64 + 0.5 * wobble,
                    ]);
                }
            }
        }
        let centre = 13u32; // (1, 1, 1)
        let mut dt = Delaunay::new(&pts).expect("triangulated");
        let finite =
            |dt: &Delaunay| -> Vec<u32> { dt.tet_ids().filter(|&t| !dt.is_ghost(t)).collect() };
        let whole = volume(&dt, finite(&dt).into_iter().map(|t| dt.tet(t)));
        let star: Vec<u32> = dt.tets_around_vertex(centre);
        assert!(
            star.iter().all(|&t| !dt.is_ghost(t)),
            "the centre is interior"
        );
        let faces = boundary(&dt, &star);
        // The star's boundary: every face of a star tet opposite the centre.
        assert_eq!(faces.len(), star.len());
        assert!(faces.values().all(|f| !f.contains(&centre)));
        // From a corner of the star, the cone drops the centre: the kernel refuses it.
        let (_, corner) = best_vertex(&dt, &faces).expect("a corner sees the star");
        assert!(dt.replace_tets(&star, &tets(&faces, corner)).is_err());
        assert!(dt.check_valid().is_ok());
        // A new apex, started from the centroid and from the centre: near the centre, and no
        // worse than the centre's own star.
        let own = star
            .iter()
            .map(|&t| {
                let q = dt.tet(t).map(|i| dt.point(i));
                max_dihedral(&q[0], &q[1], &q[2], &q[3])
            })
            .fold(0.0, f64::max);
        let at_centre = DVec3::from_array(dt.point(centre));
        let (worst, p) =
            best_point(&dt, &faces, &[centroid(&dt, &faces), at_centre], 1.0).expect("an apex");
        assert!(worst <= own + 1e-9 && worst > 60.0, "{worst} against {own}");
        assert!(p.distance(at_centre) < 0.5, "{p}");
        // A new point: one tet of the star split in four at its centroid.
        let t = star[0];
        let c = dt.tet(t).map(|i| DVec3::from_array(dt.point(i)));
        let one = boundary(&dt, &[t]);
        let index = dt.num_points() as u32;
        let (v, ids) = dt
            .replace_tets_with_point(
                &[t],
                &tets(&one, index),
                ((c[0] + c[1] + c[2] + c[3]) / 4.0).to_array(),
            )
            .expect("a tet split at its centroid");
        assert_eq!((v, ids.len()), (index, 4));
        assert!(dt.check_valid().is_ok());
        let after = volume(&dt, finite(&dt).into_iter().map(|t| dt.tet(t)));
        assert!((after - whole).abs() < 1e-12 * whole, "{whole} vs {after}");
        // The difference of a region and itself is empty; of the new star and its first
        // half, the other half's boundary, oriented the same way.
        let star: Vec<u32> = dt.tets_around_vertex(centre);
        let all = boundary(&dt, &star);
        assert!(difference(&all, &all).is_empty());
        let (half, other) = star.split_at(star.len() / 2);
        let half: Vec<[u32; 4]> = half.iter().map(|&t| dt.tet(t)).collect();
        let rest = difference(&all, &boundary_of(&dt, &half));
        // Faces compared up to rotation (the same orientation).
        let canon = |f: &Faces| -> Faces {
            f.iter()
                .map(|(k, v)| {
                    let m = (0..3).min_by_key(|&i| v[i]).unwrap_or(0);
                    (*k, [v[m], v[(m + 1) % 3], v[(m + 2) % 3]])
                })
                .collect()
        };
        assert_eq!(canon(&rest), canon(&boundary(&dt, other)));
    }
}
