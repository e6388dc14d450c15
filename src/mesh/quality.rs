//! Quality measures for segments, triangles and tets, and a summary over a cell mesh.

use glam::DVec3;
use serde::Serialize;

/// Smallest interior angle of a triangle, in degrees.
pub fn triangle_min_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let angle = |p: DVec3, q: DVec3, r: DVec3| (q - p).angle_between(r - p).to_degrees();
    angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b))
}

/// Shape quality of a triangle, 4√3·area / Σ side²: 1 for equilateral, 0 for flat.
pub fn triangle_quality(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let area2 = (b - a).cross(c - a).length();
    let sum = a.distance_squared(b) + b.distance_squared(c) + c.distance_squared(a);
    if sum == 0.0 {
        0.0
    } else {
        2.0 * 3f64.sqrt() * area2 / sum
    }
}

/// The six dihedral angles of a tet, in degrees.
pub fn tet_dihedrals(v: [DVec3; 4]) -> [f64; 6] {
    // Edge (i,j) is opposite edge (k,l); the dihedral at (i,j) is between faces ijk and ijl.
    const EDGES: [(usize, usize, usize, usize); 6] = [
        (0, 1, 2, 3),
        (0, 2, 1, 3),
        (0, 3, 1, 2),
        (1, 2, 0, 3),
        (1, 3, 0, 2),
        (2, 3, 0, 1),
    ];
    EDGES.map(|(i, j, k, l)| {
        let e = v[j] - v[i];
        let n1 = e.cross(v[k] - v[i]);
        let n2 = e.cross(v[l] - v[i]);
        n1.angle_between(n2).to_degrees()
    })
}

/// A tet's four face normals, face k opposite vertex k, each scaled to twice its face's area
/// and all pointing the same way (all out of the tet, or all in), so the cosine of the
/// dihedral angle at the edge faces k and l share is `-n_k·n_l / (|n_k| |n_l|)`.
pub fn face_normals(v: [DVec3; 4]) -> [DVec3; 4] {
    const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
    FACES.map(|f| {
        let [p, q, r] = f.map(|i| v[i]);
        (q - p).cross(r - p)
    })
}

/// The largest and the smallest cosine of a tet's six dihedral angles (those of its smallest
/// and its largest angle) from its [`face_normals`] and their lengths; (1, −1) for a tet with
/// a zero-area face.
pub fn dihedral_cosines(n: &[DVec3; 4], lengths: &[f64; 4]) -> (f64, f64) {
    if lengths.contains(&0.0) {
        return (1.0, -1.0);
    }
    let unit = [0, 1, 2, 3].map(|k| n[k] / lengths[k]);
    let mut max_cos = f64::NEG_INFINITY;
    let mut min_cos = f64::INFINITY;
    for k in 0..4 {
        for l in k + 1..4 {
            let c = -unit[k].dot(unit[l]);
            max_cos = max_cos.max(c);
            min_cos = min_cos.min(c);
        }
    }
    (max_cos, min_cos)
}

/// Radius ratio and smallest dihedral angle (degrees) together: the per-cell fields of a VTU
/// file, for millions of cells: [`dihedral_cosines`]'s largest cosine with one reciprocal per
/// face instead of a division per angle.
pub fn tet_shape(v: [DVec3; 4]) -> (f64, f64) {
    let n = face_normals(v);
    let lengths = n.map(DVec3::length);
    if lengths.contains(&0.0) {
        return (0.0, 0.0);
    }
    let inv = lengths.map(f64::recip);
    let mut max_cos = f64::NEG_INFINITY;
    for k in 0..4 {
        for l in k + 1..4 {
            max_cos = max_cos.max(-n[k].dot(n[l]) * inv[k] * inv[l]);
        }
    }
    let min_dihedral = max_cos.clamp(-1.0, 1.0).acos().to_degrees();
    let vol6 = (v[1] - v[0]).dot(n[1]).abs(); // face 1 is (0, 3, 2)
    if vol6 == 0.0 {
        return (0.0, min_dihedral);
    }
    let r_in = vol6 / lengths.iter().sum::<f64>(); // 3V/S, V = vol6/6, S = Σ|n|/2
    (3.0 * r_in / circumradius(v, vol6), min_dihedral)
}

/// Circumradius from |a|²(b×c) + |b|²(c×a) + |c|²(a×b) over 2·(a·(b×c)), with the edges
/// a, b, c from vertex 0 and `vol6` = |a·(b×c)|.
fn circumradius(v: [DVec3; 4], vol6: f64) -> f64 {
    let (a, b, c) = (v[1] - v[0], v[2] - v[0], v[3] - v[0]);
    let num = a.length_squared() * b.cross(c)
        + b.length_squared() * c.cross(a)
        + c.length_squared() * a.cross(b);
    num.length() / (2.0 * vol6)
}

/// Radius ratio 3·r_in/r_circ: 1 for a regular tet, 0 for a flat one.
pub fn tet_radius_ratio(v: [DVec3; 4]) -> f64 {
    let vol6 = (v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])).abs();
    if vol6 == 0.0 {
        return 0.0;
    }
    let area = |a: DVec3, b: DVec3, c: DVec3| 0.5 * (b - a).cross(c - a).length();
    let surface = area(v[0], v[1], v[2])
        + area(v[0], v[1], v[3])
        + area(v[0], v[2], v[3])
        + area(v[1], v[2], v[3]);
    let r_in = 0.5 * vol6 / surface; // 3V/S with V = vol6/6
    3.0 * r_in / circumradius(v, vol6)
}

/// Summary statistics of one measure.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct Stats {
    pub count: usize,
    pub min: f64,
    pub max: f64,
    pub mean: f64,
}

impl Stats {
    pub fn of(values: impl IntoIterator<Item = f64>) -> Stats {
        let mut s = Stats {
            count: 0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            mean: 0.0,
        };
        for x in values {
            s.count += 1;
            s.min = s.min.min(x);
            s.max = s.max.max(x);
            s.mean += x;
        }
        if s.count > 0 {
            s.mean /= s.count as f64;
        } else {
            s.min = 0.0;
            s.max = 0.0;
        }
        s
    }
}

/// Quality of a mixed cell mesh, by cell kind.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct QualityReport {
    pub points: usize,
    pub segment_length: Stats,
    pub triangle_min_angle: Stats,
    pub tet_dihedral: Stats,
    pub tet_radius_ratio: Stats,
    /// Tets with non-positive volume (exact orientation test).
    pub inverted_tets: usize,
    /// Cells with 6 and 5 nodes (prisms, pyramids): counted, not measured.
    pub prisms: usize,
    pub pyramids: usize,
}

pub fn report(points: &[DVec3], cells: &[Vec<usize>]) -> QualityReport {
    let p = |i: usize| points[i];
    let of_len = |n| cells.iter().filter(move |c| c.len() == n);
    let tets: Vec<[DVec3; 4]> = of_len(4)
        .map(|c| [p(c[0]), p(c[1]), p(c[2]), p(c[3])])
        .collect();
    QualityReport {
        points: points.len(),
        segment_length: Stats::of(of_len(2).map(|c| p(c[0]).distance(p(c[1])))),
        triangle_min_angle: Stats::of(
            of_len(3).map(|c| triangle_min_angle(p(c[0]), p(c[1]), p(c[2]))),
        ),
        tet_dihedral: Stats::of(tets.iter().flat_map(|t| tet_dihedrals(*t))),
        tet_radius_ratio: Stats::of(tets.iter().map(|t| tet_radius_ratio(*t))),
        inverted_tets: tets.iter().filter(|t| volume_sign(**t) <= 0.0).count(),
        prisms: of_len(6).count(),
        pyramids: of_len(5).count(),
    }
}

/// The sign of the tet's volume, exactly: positive when (b − a) × (c − a) · (d − a) > 0, the
/// order every finished mesh and writer uses. (The Delaunay kernel stores its tets in
/// Shewchuk's order instead, `volume::delaunay::predicates::orient > 0`, which is this sign
/// negated; extraction swaps two vertices between the two.)
pub fn volume_sign(v: [DVec3; 4]) -> f64 {
    let c = |p: DVec3| robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    };
    // robust's orient3d is positive when d lies below the plane of a, b, c seen
    // counter-clockwise, i.e. for a negatively oriented tet in the usual convention.
    -robust::orient3d(c(v[0]), c(v[1]), c(v[2]), c(v[3]))
}

/// The quality summary `tetrafoil mesh` prints for a tet mesh.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct TetQuality {
    pub tets: usize,
    pub min_dihedral: f64,
    pub max_dihedral: f64,
    pub radius_ratio: Stats,
    /// Mean edge length of each tet (min, mean, max over the tets).
    pub edge_length: Stats,
    /// Tets per radius-ratio decile: `[0, 0.1)`, …, `[0.9, 1]`.
    pub radius_ratio_histogram: [usize; 10],
    /// Tets whose smallest dihedral is below 1°, 5°, 10°.
    pub below_1deg: usize,
    pub below_5deg: usize,
    pub below_10deg: usize,
}

/// Quality of the tets `tets` of `points` (computed in parallel).
pub fn tet_quality(points: &[DVec3], tets: &[[u32; 4]]) -> TetQuality {
    use rayon::prelude::*;
    let per: Vec<(f64, f64, f64, f64)> = tets
        .par_iter()
        .map(|t| {
            let v = t.map(|i| points[i as usize]);
            let d = tet_dihedrals(v);
            let lo = d.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let mut edges = 0.0;
            for i in 0..4 {
                for j in i + 1..4 {
                    edges += v[i].distance(v[j]);
                }
            }
            (lo, hi, tet_radius_ratio(v), edges / 6.0)
        })
        .collect();
    let mut q = TetQuality {
        tets: tets.len(),
        min_dihedral: per.iter().map(|p| p.0).fold(f64::INFINITY, f64::min),
        max_dihedral: per.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max),
        radius_ratio: Stats::of(per.iter().map(|p| p.2)),
        edge_length: Stats::of(per.iter().map(|p| p.3)),
        ..Default::default()
    };
    if tets.is_empty() {
        q.min_dihedral = 0.0;
        q.max_dihedral = 0.0;
    }
    for &(lo, _, rr, _) in &per {
        q.radius_ratio_histogram[((rr * 10.0) as usize).min(9)] += 1;
        q.below_1deg += (lo < 1.0) as usize;
        q.below_5deg += (lo < 5.0) as usize;
        q.below_10deg += (lo < 10.0) as usize;
    }
    q
}

/// Tets below 1° minimum dihedral that the surface mesh forces, and those it does not. Forced:
/// a tet on a boundary triangle with an angle α below 1° (its dihedral there is about α or
/// less: the three dihedrals at that corner sum to π plus its solid angle, which the thin
/// triangle keeps small), or a tet on a knife edge, a surface edge where the domain's own
/// dihedral angle is below 1° (inside a sharp trailing edge every tet along it is that thin).
/// The rest are the volume mesher's to remove.
#[derive(Clone, Copy, Debug, Default, Serialize, PartialEq, Eq)]
pub struct Below1Deg {
    pub forced_by_surface: usize,
    pub unforced: usize,
}

/// Split the tets of `mesh` below 1° by whether the surface mesh forces them.
pub fn below_1deg(mesh: &crate::mesh::VolumeMesh) -> Below1Deg {
    use std::collections::HashMap;
    let key = |mut f: [u32; 3]| {
        f.sort_unstable();
        f
    };
    let needle: HashMap<[u32; 3], bool> = mesh
        .boundary
        .iter()
        .map(|&t| {
            let [a, b, c] = t.map(|i| mesh.points[i as usize]);
            (key(t), triangle_min_angle(a, b, c) < 1.0)
        })
        .collect();
    // Knife edges: two outward boundary triangles whose normals nearly oppose, on a convex
    // edge (the far corner of one lies behind the other).
    let mut at_edge: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    for (k, t) in mesh.boundary.iter().enumerate() {
        for i in 0..3 {
            let mut e = [t[i], t[(i + 1) % 3]];
            e.sort_unstable();
            at_edge.entry(e).or_default().push(k);
        }
    }
    let normal = |k: usize| {
        let [a, b, c] = mesh.triangle_points(k);
        (b - a).cross(c - a).normalize_or_zero()
    };
    let cos1 = 1f64.to_radians().cos();
    let knife: std::collections::HashSet<[u32; 2]> = at_edge
        .iter()
        .filter(|(e, ts)| {
            if ts.len() != 2 {
                return false;
            }
            let (n1, n2) = (normal(ts[0]), normal(ts[1]));
            let far = mesh.boundary[ts[1]]
                .into_iter()
                .find(|v| !e.contains(v))
                .map(|v| mesh.points[v as usize]);
            let a = mesh.points[e[0] as usize];
            n1.dot(n2) < -cos1 && far.is_some_and(|p| (p - a).dot(n1) < 0.0)
        })
        .map(|(e, _)| *e)
        .collect();
    let mut out = Below1Deg::default();
    for (k, t) in mesh.tets.iter().enumerate() {
        let lo = tet_dihedrals(mesh.tet_points(k))
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        if lo >= 1.0 {
            continue;
        }
        let forced = (0..4).any(|skip| {
            let f = [0, 1, 2, 3]
                .into_iter()
                .filter(|&i| i != skip)
                .map(|i| t[i])
                .collect::<Vec<_>>();
            needle.get(&key([f[0], f[1], f[2]])) == Some(&true)
        }) || (0..4).any(|i| {
            (i + 1..4).any(|j| {
                let mut e = [t[i], t[j]];
                e.sort_unstable();
                knife.contains(&e)
            })
        });
        if forced {
            out.forced_by_surface += 1;
        } else {
            out.unforced += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tet_shape_agrees_with_the_separate_measures() {
        let regular = [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ];
        let (q, d) = tet_shape(regular);
        assert!((q - 1.0).abs() < 1e-12, "{q}");
        assert!((d - (1f64 / 3.0).acos().to_degrees()).abs() < 1e-9, "{d}");
        // A stretched sliver-ish tet, either orientation.
        let thin = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.3, 1.0, 0.0),
            DVec3::new(0.4, 0.3, 0.02),
        ];
        for v in [thin, [thin[1], thin[0], thin[2], thin[3]]] {
            let (q, d) = tet_shape(v);
            assert!((q - tet_radius_ratio(v)).abs() < 1e-12);
            let six = tet_dihedrals(v).into_iter().fold(f64::INFINITY, f64::min);
            assert!((d - six).abs() < 1e-9, "{d} against {six}");
            assert!(d < 5.0);
        }
        // Flat: both zero.
        let flat = [thin[0], thin[1], thin[2], DVec3::new(0.5, 0.5, 0.0)];
        assert_eq!(tet_shape(flat).0, 0.0);
    }
}
