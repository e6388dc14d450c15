//! The shape of a prism or a pyramid: every tet of every split positive (exact `orient3d`), so
//! a solver may cut it either way; every face's corners clear of the cell's centre, so a
//! reader that judges orientation from the centre reads it the right way round; the warp of a
//! quad face; the prism measures of the report.

use crate::mesh::quality::volume_sign;
use glam::DVec3;

/// The six splits of a prism `[b0, b1, b2, t0, t1, t2]` into three tets, one per order in
/// which its columns are lifted: column `i` first gives `[bi, bj, bk, ti]`, and so on.
const PRISM_SPLITS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// The corners of the reference prism: the bottom counter-clockwise seen from the top.
const PRISM_REFERENCE: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
];

/// The two splits of a pyramid `[a, b, c, d, e]` (by diagonal a–c, then b–d).
const PYRAMID_TETS: [[usize; 4]; 4] = [[0, 1, 2, 4], [0, 2, 3, 4], [0, 1, 3, 4], [1, 2, 3, 4]];

/// The corners of the reference pyramid: the base counter-clockwise seen from the apex.
const PYRAMID_REFERENCE: [[f64; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 0.5, 1.0],
];

/// The faces of a prism, each a cycle whose right-hand normal points out of the reference.
const PRISM_FACES: [&[usize]; 5] = [
    &[0, 2, 1],
    &[3, 4, 5],
    &[0, 1, 4, 3],
    &[1, 2, 5, 4],
    &[2, 0, 3, 5],
];

/// The faces of a pyramid, as [`PRISM_FACES`].
const PYRAMID_FACES: [&[usize]; 5] = [
    &[0, 3, 2, 1],
    &[0, 1, 4],
    &[1, 2, 4],
    &[2, 3, 4],
    &[3, 0, 4],
];

/// The least centre clearance a prism or pyramid must keep (see [`centre_clearance`]).
///
/// OpenFOAM's `gmshToFoam` calls a prism inside out when the first corner of any face lies
/// below the vertex mean along that face's normal, and "repairs" it by swapping two bottom
/// corners, which leaves a broken cell (open, negative volume). Tall prisms over packed roots
/// can have side quads warped that far though every split is positive. A fifth keeps every
/// corner of every face well clear, whichever corner a reader takes first; it refuses a few
/// hundred of the demo wing's 135 thousand prisms.
pub const MIN_CENTRE_CLEARANCE: f64 = 0.2;

/// Centre clearance of a cell with corners `p` and outward face cycles `faces`: the least,
/// over every face and every corner of it, of the corner's height above the vertex mean of
/// the cell along the face's area normal, over the face's mean corner's height. 1 where every
/// face is planar; 0 or below where a warped face folds back over the centre.
pub fn centre_clearance(p: &[DVec3], faces: &[&[usize]]) -> f64 {
    let centre = p.iter().copied().sum::<DVec3>() / p.len() as f64;
    let mut least = f64::INFINITY;
    for f in faces {
        let c = |k: usize| p[f[k]];
        // A quad's area normal is half the cross product of its diagonals, whatever point
        // its triangles fan from.
        let normal = match f.len() {
            3 => (c(1) - c(0)).cross(c(2) - c(0)),
            _ => (c(2) - c(0)).cross(c(3) - c(1)),
        };
        // Every prism and pyramid candidate passes here: no allocation per face.
        let mut heights = [0.0; 4];
        for (k, h) in heights.iter_mut().enumerate().take(f.len()) {
            *h = (c(k) - centre).dot(normal);
        }
        let heights = &heights[..f.len()];
        let mean = heights.iter().sum::<f64>() / f.len() as f64;
        if mean <= 0.0 {
            return -1.0; // the face looks inward: inside out there
        }
        least = heights.iter().fold(least, |l, &h| l.min(h / mean));
    }
    least
}

/// Whether tet `t` (indices into the cell's corners) has the sign it has in the reference.
fn positive_like_reference(p: &[DVec3], reference: &[[f64; 3]], t: [usize; 4]) -> bool {
    let r = t.map(|i| DVec3::from_array(reference[i]));
    let want = (r[1] - r[0]).cross(r[2] - r[0]).dot(r[3] - r[0]);
    let got = volume_sign(t.map(|i| p[i]));
    got != 0.0 && (got > 0.0) == (want > 0.0)
}

/// The tets of the split of a prism lifting its columns in `order`.
fn prism_split(order: [usize; 3]) -> [[usize; 4]; 3] {
    let [i, j, k] = order;
    let (b, t) = (|c: usize| c, |c: usize| c + 3);
    [
        [b(i), b(j), b(k), t(i)],
        [b(j), b(k), t(i), t(j)],
        [b(k), t(i), t(j), t(k)],
    ]
}

/// Whether every tet of every split of prism `p` (corners in [`VolumeMesh`] order) is
/// positive and its faces keep [`MIN_CENTRE_CLEARANCE`].
///
/// [`VolumeMesh`]: crate::mesh::VolumeMesh
pub fn prism_is_valid(p: &[DVec3; 6]) -> bool {
    PRISM_SPLITS
        .iter()
        .flat_map(|&o| prism_split(o))
        .all(|t| positive_like_reference(p, &PRISM_REFERENCE, t))
        && centre_clearance(p, &PRISM_FACES) >= MIN_CENTRE_CLEARANCE
}

/// Whether both splits of pyramid `p` (base, then apex) are positive and its faces keep
/// [`MIN_CENTRE_CLEARANCE`].
pub fn pyramid_is_valid(p: &[DVec3; 5]) -> bool {
    PYRAMID_TETS
        .iter()
        .all(|&t| positive_like_reference(p, &PYRAMID_REFERENCE, t))
        && centre_clearance(p, &PYRAMID_FACES) >= MIN_CENTRE_CLEARANCE
}

/// Volume of a prism (its first split; the same for every split of a valid prism up to the
/// warp of its sides).
pub fn prism_volume(p: &[DVec3; 6]) -> f64 {
    prism_split([0, 1, 2])
        .iter()
        .map(|&t| tet_volume(t.map(|i| p[i])))
        .sum()
}

/// Volume of a pyramid (split by its diagonal a–c).
pub fn pyramid_volume(p: &[DVec3; 5]) -> f64 {
    PYRAMID_TETS[..2]
        .iter()
        .map(|&t| tet_volume(t.map(|i| p[i])))
        .sum()
}

fn tet_volume(p: [DVec3; 4]) -> f64 {
    (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0
}

/// Warp of quad `q` (corners in cycle order), degrees: the larger of the angles between the
/// two triangles' normals over its two diagonals; 0 for a planar quad.
pub fn warp_degrees(q: [DVec3; 4]) -> f64 {
    let angle = |a: DVec3, b: DVec3| a.angle_between(b).to_degrees();
    let n = |i: usize, j: usize, k: usize| (q[j] - q[i]).cross(q[k] - q[i]);
    angle(n(0, 1, 2), n(0, 2, 3)).max(angle(n(1, 2, 3), n(1, 3, 0)))
}

/// Skew of a prism, degrees: the largest angle between a column edge and the normal of the
/// bottom triangle (0 for a right prism).
pub fn prism_skew_degrees(p: &[DVec3; 6]) -> f64 {
    let normal = (p[1] - p[0]).cross(p[2] - p[0]);
    (0..3)
        .map(|i| (p[i + 3] - p[i]).angle_between(normal).to_degrees())
        .fold(0.0, f64::max)
}

/// Aspect ratio of a prism: its longest triangle edge over its mean column height (large for
/// the thin prisms of the first layers).
pub fn prism_aspect(p: &[DVec3; 6]) -> f64 {
    let edge = (0..3)
        .flat_map(|i| [(i, (i + 1) % 3), (i + 3, (i + 1) % 3 + 3)])
        .map(|(a, b)| p[a].distance(p[b]))
        .fold(0.0, f64::max);
    let height = (0..3).map(|i| p[i].distance(p[i + 3])).sum::<f64>() / 3.0;
    edge / height.max(f64::MIN_POSITIVE)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn right_prism(h: f64) -> [DVec3; 6] {
        PRISM_REFERENCE.map(|c| DVec3::new(c[0], c[1], c[2] * h))
    }

    #[test]
    fn a_right_prism_is_valid_and_its_mirror_is_not() {
        let p = right_prism(0.01);
        assert!(prism_is_valid(&p));
        assert!((prism_volume(&p) - 0.005).abs() < 1e-15);
        assert!((prism_aspect(&p) - 2f64.sqrt() / 0.01).abs() < 1e-9);
        assert!(prism_skew_degrees(&p) < 1e-12);
        let mirrored = [p[0], p[2], p[1], p[3], p[5], p[4]];
        assert!(!prism_is_valid(&mirrored));
    }

    /// The right prism of height 0.2 with its top turned by `degrees` about the axis through
    /// the centroid.
    fn twisted(degrees: f64) -> [DVec3; 6] {
        let mut p = right_prism(0.2);
        let c = DVec3::new(1.0 / 3.0, 1.0 / 3.0, 0.0);
        let (s, co) = degrees.to_radians().sin_cos();
        for q in &mut p[3..] {
            let d = *q - c - DVec3::Z * 0.2;
            *q = c + DVec3::new(co * d.x - s * d.y, s * d.x + co * d.y, 0.2);
        }
        p
    }

    #[test]
    fn a_twisted_prism_is_refused_though_some_splits_are_positive() {
        let all_splits_positive = |p: &[DVec3; 6]| {
            PRISM_SPLITS
                .iter()
                .flat_map(|&o| prism_split(o))
                .all(|t| positive_like_reference(p, &PRISM_REFERENCE, t))
        };
        // At 20° the sides are warped but clear of the centre (clearance 0.47).
        assert!(prism_is_valid(&twisted(20.0)));
        // At 40° all six splits are still positive, but the sides fold over the centre
        // (clearance -0.09): a reader judging by the centre would turn it inside out.
        let p = twisted(40.0);
        assert!(all_splits_positive(&p));
        assert!(centre_clearance(&p, &PRISM_FACES) < 0.0);
        assert!(!prism_is_valid(&p));
        // At 80° the split lifting column 0 first is positive, two others are not.
        let p = twisted(80.0);
        assert!(!all_splits_positive(&p));
        let first = prism_split([0, 1, 2]);
        assert!(first
            .iter()
            .all(|&t| positive_like_reference(&p, &PRISM_REFERENCE, t)));
    }

    #[test]
    fn a_needle_prism_with_positive_splits_is_refused_for_its_folded_side() {
        // A prism the demo wing's skin stage made over packed roots (coordinates as written
        // to MSH): 0.04 tall, two bottom corners 0.002 apart. gmshToFoam read it as inside out.
        let p = [
            [0.9633409285095468, 1.737449247263628, -0.08390429722507824],
            [0.941121960562257, 1.7544487194257787, -0.058496235132530446],
            [0.9649092324602576, 1.7398529887997063, -0.08464197096796675],
            [0.9550656989157101, 1.7422747705628925, -0.09894498500426954],
            [0.9277176553880471, 1.764087816205917, -0.06940990223866876],
            [0.9555052743153498, 1.7431539574900616, -0.09895914302086936],
        ]
        .map(DVec3::from_array);
        assert!(PRISM_SPLITS
            .iter()
            .flat_map(|&o| prism_split(o))
            .all(|t| positive_like_reference(&p, &PRISM_REFERENCE, t)));
        let clearance = centre_clearance(&p, &PRISM_FACES);
        assert!(clearance < 0.0, "{clearance}");
        assert!(!prism_is_valid(&p));
        // A right prism's faces are planar: clearance 1, however thin.
        assert!((centre_clearance(&right_prism(1e-4), &PRISM_FACES) - 1.0).abs() < 1e-9);
        let pyramid = PYRAMID_REFERENCE.map(DVec3::from_array);
        assert!((centre_clearance(&pyramid, &PYRAMID_FACES) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn warp_of_a_planar_quad_is_zero_and_of_a_bent_one_its_fold() {
        let flat = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        assert!(warp_degrees(flat) < 1e-12);
        let mut bent = flat;
        bent[2].z = 1.0; // fold along the diagonal b-d by 45°... measured both ways
        let w = warp_degrees(bent);
        assert!(w > 30.0 && w < 90.0, "{w}");
    }

    #[test]
    fn pyramid_orientation_matters() {
        let p = PYRAMID_REFERENCE.map(DVec3::from_array);
        assert!(pyramid_is_valid(&p));
        assert!((pyramid_volume(&p) - 1.0 / 3.0).abs() < 1e-15);
        let reversed = [p[0], p[3], p[2], p[1], p[4]];
        assert!(!pyramid_is_valid(&reversed));
    }
}
