//! Exact geometric predicates and the symbolic tie-break.
//!
//! Every sign decision goes through `robust` (Shewchuk's adaptive exact arithmetic): a fast
//! floating-point evaluation with an error bound, refined exactly only when the bound cannot
//! decide. Nothing here uses an epsilon.
//!
//! Convention (Shewchuk's): `orient(a, b, c, d) > 0` for a positively oriented tet, and then
//! `insphere(a, b, c, d, e) > 0` iff `e` is strictly inside the circumsphere.
//!
//! ## Tie-break for cospherical points (symbolic perturbation)
//!
//! When `insphere` is exactly zero we decide as if every point had been lifted onto the
//! paraboloid with an extra infinitesimal height, each point's height infinitely larger than
//! that of every point with a smaller vertex index (vertex index = input index, a fixed total
//! order that does not depend on insertion order). This is the lifted-point
//! perturbation of Edelsbrunner–Mücke as specialised to Delaunay by Devillers–Teillaud: the
//! perturbed point set has no five cospherical points, so it has a unique Delaunay
//! triangulation, which is also a Delaunay triangulation of the real points. Expanding the
//! perturbed determinant, the sign is decided by the first non-zero term, taking the five
//! points in decreasing index order:
//!
//! * if the query point `e` has the largest index, `e` is outside (raising `e` pushes it out);
//! * if tet vertex `v_i` has the largest index, the answer is the sign of the orientation of
//!   the tet with `v_i` replaced by `e` (raising `v_i` tilts the sphere towards the side of
//!   the face opposite `v_i` that holds `v_i`); if that orientation is zero too, go on to the
//!   next point.
//!
//! So a point exactly on the circumsphere of a tet is *outside* unless a tet vertex with a
//! larger index than the point says "inside" through its orientation — the
//! "cospherical → outside unless the index rule says inside" scheme, made exact.
//! Orientation tests are never perturbed: a zero orientation in the walk just means "not
//! beyond this face".

use robust::Coord3D;

#[inline(always)]
fn c(p: &[f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}

/// Exact orientation sign carrier: > 0 when `d` is on the positive side of `abc`
/// (`abcd` positively oriented), < 0 on the other side, 0 when coplanar.
#[inline(always)]
pub fn orient(a: &[f64; 3], b: &[f64; 3], c_: &[f64; 3], d: &[f64; 3]) -> f64 {
    robust::orient3d(c(a), c(b), c(c_), c(d))
}

/// Exact in-sphere sign carrier for a positively oriented `abcd`: > 0 strictly inside.
#[inline(always)]
pub fn insphere(a: &[f64; 3], b: &[f64; 3], c_: &[f64; 3], d: &[f64; 3], e: &[f64; 3]) -> f64 {
    robust::insphere(c(a), c(b), c(c_), c(d), c(e))
}

/// Orientation of the four points `v` with position `i` replaced by `p`.
#[inline(always)]
pub fn orient_replaced(pts: &[[f64; 3]], v: &[u32; 4], i: usize, p: &[f64; 3]) -> f64 {
    let g = |k: usize| -> &[f64; 3] {
        if k == i {
            p
        } else {
            &pts[v[k] as usize]
        }
    };
    orient(g(0), g(1), g(2), g(3))
}

/// Is point `p` (vertex index `pi`) in conflict with the finite, positively oriented tet `v`
/// under the symbolic perturbation described in the module docs? Never ambiguous.
#[inline]
pub fn in_sphere_perturbed(pts: &[[f64; 3]], v: &[u32; 4], pi: u32, p: &[f64; 3]) -> bool {
    let s = insphere(
        &pts[v[0] as usize],
        &pts[v[1] as usize],
        &pts[v[2] as usize],
        &pts[v[3] as usize],
        p,
    );
    if s > 0.0 {
        true
    } else if s < 0.0 {
        false
    } else {
        perturbed_tie(pts, v, pi, p)
    }
}

/// The exact tie-break for `insphere == 0` (see module docs).
#[cold]
pub fn perturbed_tie(pts: &[[f64; 3]], v: &[u32; 4], pi: u32, p: &[f64; 3]) -> bool {
    // Slots 0..3 are the tet's vertices, slot 4 the query point; order by decreasing index.
    let mut order = [(v[0], 0usize), (v[1], 1), (v[2], 2), (v[3], 3), (pi, 4)];
    order.sort_unstable_by(|a, b| b.0.cmp(&a.0));
    for &(_, slot) in &order {
        if slot == 4 {
            return false;
        }
        let o = orient_replaced(pts, v, slot, p);
        if o != 0.0 {
            return o > 0.0;
        }
    }
    // Unreachable for a non-degenerate tet: replacing its vertices one by one by `p` cannot
    // give four zero volumes. Treat as outside, which is always safe for the cavity.
    false
}
