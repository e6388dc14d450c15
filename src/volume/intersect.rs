//! Do two surface triangles cross? Asked when boundary recovery fails, to tell the user why —
//! nearly always the surface itself intersects (faces of one shell crossing, or the solids of an
//! assembly touching or overlapping without shared faces) — and by directional refinement
//! before it keeps a face's new triangles, and by the pipeline to find every crossing of a
//! surface to re-mesh finer there ([`all_crossings`]). Exact predicates throughout: a pair
//! crosses when an edge of one meets the other (non-coplanar), or, for coplanar pairs, when
//! their interiors overlap in the plane. Pairs that share a corner (by index or position) are
//! left alone: they meet legitimately.

use rayon::prelude::*;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

type P = [f64; 3];

fn o3(a: &P, b: &P, c: &P, d: &P) -> f64 {
    let k = |p: &P| robust::Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    };
    robust::orient3d(k(a), k(b), k(c), k(d))
}

fn o2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let k = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
    robust::orient2d(k(a), k(b), k(c))
}

/// Does segment pq meet triangle t (not coplanar with it)?
fn segment_meets(p: &P, q: &P, t: [&P; 3]) -> bool {
    let sp = o3(t[0], t[1], t[2], p);
    let sq = o3(t[0], t[1], t[2], q);
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) || (sp == 0.0 && sq == 0.0) {
        return false;
    }
    let s = [
        o3(p, q, t[0], t[1]),
        o3(p, q, t[1], t[2]),
        o3(p, q, t[2], t[0]),
    ];
    s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)
}

/// Do two coplanar triangles overlap with positive area (projected on the plane's dominant axis)?
fn coplanar_overlap(a: [&P; 3], b: [&P; 3]) -> bool {
    let n = {
        let u = [a[1][0] - a[0][0], a[1][1] - a[0][1], a[1][2] - a[0][2]];
        let v = [a[2][0] - a[0][0], a[2][1] - a[0][1], a[2][2] - a[0][2]];
        [
            (u[1] * v[2] - u[2] * v[1]).abs(),
            (u[2] * v[0] - u[0] * v[2]).abs(),
            (u[0] * v[1] - u[1] * v[0]).abs(),
        ]
    };
    let drop = (0..3).max_by(|&i, &j| n[i].total_cmp(&n[j])).unwrap_or(2);
    let (i, j) = ((drop + 1) % 3, (drop + 2) % 3);
    let pa = a.map(|p| [p[i], p[j]]);
    let pb = b.map(|p| [p[i], p[j]]);
    let ccw = |t: [[f64; 2]; 3]| {
        if o2(t[0], t[1], t[2]) < 0.0 {
            [t[0], t[2], t[1]]
        } else {
            t
        }
    };
    let (pa, pb) = (ccw(pa), ccw(pb));
    // Proper crossing of two edges.
    for k in 0..3 {
        for l in 0..3 {
            let (p, q) = (pa[k], pa[(k + 1) % 3]);
            let (r, s) = (pb[l], pb[(l + 1) % 3]);
            let d1 = o2(p, q, r);
            let d2 = o2(p, q, s);
            let d3 = o2(r, s, p);
            let d4 = o2(r, s, q);
            if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
                return true;
            }
        }
    }
    // A corner strictly inside the other triangle.
    let inside = |t: [[f64; 2]; 3], p: [f64; 2]| (0..3).all(|k| o2(t[k], t[(k + 1) % 3], p) > 0.0);
    pa.iter().any(|&p| inside(pb, p)) || pb.iter().any(|&p| inside(pa, p))
}

/// Do triangles `a` and `b` (corner coordinates) cross?
pub fn triangles_cross(a: [&P; 3], b: [&P; 3]) -> bool {
    if a.iter().any(|p| b.iter().any(|q| p == q)) {
        return false;
    }
    let sb = b.map(|q| o3(a[0], a[1], a[2], q));
    if sb.iter().all(|&s| s == 0.0) {
        return coplanar_overlap(a, b);
    }
    if sb.iter().all(|&s| s > 0.0) || sb.iter().all(|&s| s < 0.0) {
        return false;
    }
    (0..3).any(|k| segment_meets(a[k], a[(k + 1) % 3], b))
        || (0..3).any(|k| segment_meets(b[k], b[(k + 1) % 3], a))
}

/// Bounding box of a triangle.
fn bbox(points: &[P], t: &[u32; 3]) -> (P, P) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &v in t {
        for k in 0..3 {
            lo[k] = lo[k].min(points[v as usize][k]);
            hi[k] = hi[k].max(points[v as usize][k]);
        }
    }
    (lo, hi)
}

fn box_tree(points: &[P], triangles: &[[u32; 3]]) -> RTree<GeomWithData<Rectangle<P>, usize>> {
    RTree::bulk_load(
        triangles
            .iter()
            .enumerate()
            .map(|(k, t)| {
                let (lo, hi) = bbox(points, t);
                GeomWithData::new(Rectangle::from_corners(lo, hi), k)
            })
            .collect(),
    )
}

/// A pair of crossing triangles, one of them among `these`, if there is one.
fn crossing_of(
    points: &[P],
    triangles: &[[u32; 3]],
    tree: &RTree<GeomWithData<Rectangle<P>, usize>>,
    these: impl IntoIterator<Item = usize>,
) -> Option<(usize, usize)> {
    let corners = |k: usize| triangles[k].map(|v| &points[v as usize]);
    for i in these {
        let (lo, hi) = bbox(points, &triangles[i]);
        let env = AABB::from_corners(lo, hi);
        for other in tree.locate_in_envelope_intersecting(&env) {
            let j = other.data;
            if j != i && triangles_cross(corners(i), corners(j)) {
                return Some((i.min(j), i.max(j)));
            }
        }
    }
    None
}

/// A pair of crossing triangles among those near triangle `near` (within a few of its sizes),
/// if there is one.
pub fn crossing_near(points: &[P], triangles: &[[u32; 3]], near: usize) -> Option<(usize, usize)> {
    let tree = box_tree(points, triangles);
    let (lo, hi) = bbox(points, triangles.get(near)?);
    let size = (0..3)
        .map(|k| 2.0 * (hi[k] - lo[k]).max(0.0))
        .fold(0.0, f64::max);
    let region = AABB::from_corners(
        [lo[0] - size, lo[1] - size, lo[2] - size],
        [hi[0] + size, hi[1] + size, hi[2] + size],
    );
    let nearby: Vec<usize> = tree
        .locate_in_envelope_intersecting(&region)
        .map(|g| g.data)
        .collect();
    crossing_of(points, triangles, &tree, nearby)
}

/// A pair of crossing triangles, one of them among `these` (the triangles a change made), if
/// there is one.
pub fn crossing_among(
    points: &[P],
    triangles: &[[u32; 3]],
    these: impl IntoIterator<Item = usize>,
) -> Option<(usize, usize)> {
    crossing_of(points, triangles, &box_tree(points, triangles), these)
}

/// Every pair of crossing triangles, each once with the lower index first, in index order
/// (searched across the threads).
pub fn all_crossings(points: &[P], triangles: &[[u32; 3]]) -> Vec<(usize, usize)> {
    let tree = box_tree(points, triangles);
    let corners = |k: usize| triangles[k].map(|v| &points[v as usize]);
    (0..triangles.len())
        .into_par_iter()
        .flat_map_iter(|i| {
            let (lo, hi) = bbox(points, &triangles[i]);
            let env = AABB::from_corners(lo, hi);
            let mut pairs: Vec<(usize, usize)> = tree
                .locate_in_envelope_intersecting(&env)
                .map(|g| g.data)
                .filter(|&j| j > i && triangles_cross(corners(i), corners(j)))
                .map(|j| (i, j))
                .collect();
            pairs.sort_unstable();
            pairs
        })
        .collect()
}

/// One re-mesh of a surface that crossed itself: what was found and what was asked for.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CrossingRemesh {
    /// Pairs of surface triangles that crossed.
    pub crossings: usize,
    /// The faces the crossing triangles lie on (the first few).
    pub faces: Vec<String>,
    /// Centre of the first crossing pair.
    pub at: [f64; 3],
    /// The smallest spacing asked for around the crossings.
    pub spacing: f64,
}

impl std::fmt::Display for CrossingRemesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the surface mesh crossed itself ({} triangle pair(s) on {}, the first near {}): \
             meshing the surfaces again with the spacing there halved (down to {:.3e})",
            self.crossings,
            self.faces.join(", "),
            crate::geometry::Xyz(glam::DVec3::from_array(self.at)),
            self.spacing
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_and_touching_pairs() {
        let a = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let pierce = [[0.2, 0.2, -1.0], [0.3, 0.2, 1.0], [0.2, 0.3, 1.0]];
        let above = [[0.2, 0.2, 0.5], [0.3, 0.2, 1.0], [0.2, 0.3, 1.0]];
        let coplanar_overlap = [[0.2, 0.2, 0.0], [2.0, 0.2, 0.0], [0.2, 2.0, 0.0]];
        let coplanar_apart = [[1.0, 1.0, 0.0], [2.0, 1.0, 0.0], [1.0, 2.0, 0.0]];
        fn r(t: &[[f64; 3]; 3]) -> [&[f64; 3]; 3] {
            [&t[0], &t[1], &t[2]]
        }
        assert!(triangles_cross(r(&a), r(&pierce)));
        assert!(!triangles_cross(r(&a), r(&above)));
        assert!(triangles_cross(r(&a), r(&coplanar_overlap)));
        assert!(!triangles_cross(r(&a), r(&coplanar_apart)));
        let points = [a, pierce].concat();
        let tris = [[0, 1, 2], [3, 4, 5]];
        assert_eq!(crossing_near(&points, &tris, 0), Some((0, 1)));
        assert_eq!(crossing_among(&points, &tris, [1]), Some((0, 1)));
        let apart = [a, above].concat();
        assert_eq!(crossing_among(&apart, &tris, [0, 1]), None);
        assert_eq!(all_crossings(&points, &tris), vec![(0, 1)]);
        assert!(all_crossings(&apart, &tris).is_empty());
    }
}
