//! Exact geometric predicates and the symbolic tie-break.
//!
//! Every sign decision goes through `robust` (Shewchuk's adaptive exact arithmetic): a fast
//! floating-point evaluation with an error bound, refined exactly only when the bound cannot
//! decide. Nothing here uses an epsilon.
//!
//! Convention (Shewchuk's): `orient(a, b, c, d) > 0` for a positively oriented tet, and then
//! `insphere(a, b, c, d, e) > 0` iff `e` is strictly inside the circumsphere. "Positively
//! oriented" means this order inside the kernel only: its signed volume
//! (b − a) × (c − a) · (d − a) is negative. The finished mesh uses positive volume
//! (`mesh::quality::volume_sign`), and extraction swaps two vertices of every tet.
//!
//! ## Tie-break for cospherical points (symbolic perturbation)
//!
//! When `insphere` is exactly zero we decide as if every point had been lifted onto the
//! paraboloid with an extra infinitesimal height, each point's height infinitely larger than
//! that of every point with a smaller *internal* vertex id. Internal ids are fixed once a
//! point is stored (insertion order: the deterministic BRIO order of the initial set, then
//! later points in the order they are added), so every test sees the same perturbation and
//! the result is the unique Delaunay triangulation of the perturbed set — one particular
//! Delaunay triangulation of the real points (other tools may pick a different one on
//! degenerate input, e.g. another 5- or 6-tet split of a lattice cube). This is the lifted-point
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

/// Maximum without `f64::max`'s NaN handling (one instruction); inputs are never NaN here
/// (coordinates are checked finite on entry), and a NaN would only make the filter fall
/// through to the exact predicate.
#[inline(always)]
fn fmax(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// Exact orientation sign carrier: > 0 when `d` is on the positive side of `abc`
/// (`abcd` positively oriented), < 0 on the other side, 0 when coplanar.
///
/// A semi-static filter runs first: the determinant is evaluated in floating point on
/// coordinates translated to `d`, and accepted when it exceeds a bound on its rounding error
/// derived from the largest translated coordinate `m`: with every one of the 6 expanded terms
/// at most `m³` and at most 6 rounded operations on any path, the error is below
/// `γ₆ · 6m³ ≈ 4·10⁻¹⁵ m³`; we use `10⁻¹³ m³` (25× margin). The bound is only used for
/// `m` in `[10⁻⁶⁰, 10⁶⁰]`, where neither overflow nor underflow can spoil it. Otherwise, and
/// whenever the filter cannot decide, Shewchuk's adaptive exact `robust::orient3d` decides.
#[inline(always)]
pub fn orient(a: &[f64; 3], b: &[f64; 3], c_: &[f64; 3], d: &[f64; 3]) -> f64 {
    let (adx, ady, adz) = (a[0] - d[0], a[1] - d[1], a[2] - d[2]);
    let (bdx, bdy, bdz) = (b[0] - d[0], b[1] - d[1], b[2] - d[2]);
    let (cdx, cdy, cdz) = (c_[0] - d[0], c_[1] - d[1], c_[2] - d[2]);
    let det = adx * (bdy * cdz - bdz * cdy)
        + bdx * (cdy * adz - cdz * ady)
        + cdx * (ady * bdz - adz * bdy);
    let m = fmax(
        fmax(fmax(adx.abs(), ady.abs()), fmax(adz.abs(), bdx.abs())),
        fmax(
            fmax(bdy.abs(), bdz.abs()),
            fmax(fmax(cdx.abs(), cdy.abs()), cdz.abs()),
        ),
    );
    if m > 1e-60 && m < 1e60 {
        let bound = 1e-13 * m * m * m;
        if det > bound || det < -bound {
            return det;
        }
    }
    if m <= 65536.0 && all_small_integers(&[a, b, c_, d]) {
        // Integer inputs: the translations are exact and every term is below 6·2⁴⁸ < 2⁵³,
        // so the floating-point determinant above is exact (zero included).
        return det;
    }
    robust::orient3d(c(a), c(b), c(c_), c(d))
}

/// Exact in-sphere sign carrier for a positively oriented `abcd`: > 0 strictly inside.
///
/// Same filter idea as [`orient`]: coordinates translated to `e`, every one of the 24
/// expanded terms is at most `3m⁵`, at most ~14 rounded operations on any path, so the error
/// is below `γ₁₄ · 72m⁵ ≈ 1.2·10⁻¹³ m⁵`; we accept `|det| > 10⁻¹¹ m⁵` (80× margin) for
/// `m` in `[10⁻⁴⁰, 10⁴⁰]`, and otherwise call the adaptive exact `robust::insphere`.
#[inline(always)]
pub fn insphere(a: &[f64; 3], b: &[f64; 3], c_: &[f64; 3], d: &[f64; 3], e: &[f64; 3]) -> f64 {
    let (aex, aey, aez) = (a[0] - e[0], a[1] - e[1], a[2] - e[2]);
    let (bex, bey, bez) = (b[0] - e[0], b[1] - e[1], b[2] - e[2]);
    let (cex, cey, cez) = (c_[0] - e[0], c_[1] - e[1], c_[2] - e[2]);
    let (dex, dey, dez) = (d[0] - e[0], d[1] - e[1], d[2] - e[2]);
    let ab = aex * bey - bex * aey;
    let bc = bex * cey - cex * bey;
    let cd = cex * dey - dex * cey;
    let da = dex * aey - aex * dey;
    let ac = aex * cey - cex * aey;
    let bd = bex * dey - dex * bey;
    let abc = aez * bc - bez * ac + cez * ab;
    let bcd = bez * cd - cez * bd + dez * bc;
    let cda = cez * da + dez * ac + aez * cd;
    let dab = dez * ab + aez * bd + bez * da;
    let alift = aex * aex + aey * aey + aez * aez;
    let blift = bex * bex + bey * bey + bez * bez;
    let clift = cex * cex + cey * cey + cez * cez;
    let dlift = dex * dex + dey * dey + dez * dez;
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    let mx = fmax(fmax(aex.abs(), bex.abs()), fmax(cex.abs(), dex.abs()));
    let my = fmax(fmax(aey.abs(), bey.abs()), fmax(cey.abs(), dey.abs()));
    let mz = fmax(fmax(aez.abs(), bez.abs()), fmax(cez.abs(), dez.abs()));
    let m = fmax(fmax(mx, my), mz);
    if m > 1e-40 && m < 1e40 {
        let m2 = m * m;
        let bound = 1e-11 * m2 * m2 * m;
        if det > bound || det < -bound {
            return det;
        }
        if m <= 512.0 && all_small_integers(&[a, b, c_, d, e]) {
            // Integer inputs: exact translations, every partial result below 72·2⁴⁵ < 2⁵³,
            // so `det` is exact (zero included).
            return det;
        }
        let dd = dd::insphere(a, b, c_, d, e);
        let dd_bound = 1e-27 * m2 * m2 * m;
        if dd > dd_bound || dd < -dd_bound {
            return dd;
        }
    }
    robust::insphere(c(a), c(b), c(c_), c(d), c(e))
}

/// All coordinates are integers of magnitude ≤ 2²⁰ (so their differences are exact).
#[cold]
fn all_small_integers(pts: &[&[f64; 3]]) -> bool {
    pts.iter()
        .all(|p| p.iter().all(|&x| x.trunc() == x && x.abs() <= 1048576.0))
}

/// Middle stage of the in-sphere test: the same determinant in double-double arithmetic
/// (about 106 significant bits) on exactly computed translations. Points that are nearly but
/// not exactly cospherical — the normal case for points sampled on a curved surface — fail
/// the double filter but are decided here, far cheaper than the fully exact expansion
/// arithmetic. Its error is below ~10 double-double operations × ~4u² relative, times the
/// term bound `72m⁵`, i.e. under `4·10⁻²⁹ m⁵`; the caller accepts `|det| > 10⁻²⁷ m⁵`.
mod dd {
    #[derive(Clone, Copy)]
    pub struct Dd(f64, f64);

    #[inline(always)]
    fn two_sum(a: f64, b: f64) -> Dd {
        let s = a + b;
        let bb = s - a;
        Dd(s, (a - (s - bb)) + (b - bb))
    }
    #[inline(always)]
    fn quick_two_sum(a: f64, b: f64) -> Dd {
        let s = a + b;
        Dd(s, b - (s - a))
    }
    #[inline(always)]
    fn split(a: f64) -> (f64, f64) {
        let t = 134_217_729.0 * a; // 2^27 + 1 (Dekker)
        let hi = t - (t - a);
        (hi, a - hi)
    }
    #[inline(always)]
    fn two_prod(a: f64, b: f64) -> Dd {
        let p = a * b;
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        Dd(p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
    #[inline(always)]
    fn add(x: Dd, y: Dd) -> Dd {
        let s = two_sum(x.0, y.0);
        let t = two_sum(x.1, y.1);
        let s = quick_two_sum(s.0, s.1 + t.0);
        quick_two_sum(s.0, s.1 + t.1)
    }
    #[inline(always)]
    fn sub(x: Dd, y: Dd) -> Dd {
        add(x, Dd(-y.0, -y.1))
    }
    #[inline(always)]
    fn mul(x: Dd, y: Dd) -> Dd {
        let p = two_prod(x.0, y.0);
        quick_two_sum(p.0, p.1 + (x.0 * y.1 + x.1 * y.0))
    }

    pub fn insphere(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3], e: &[f64; 3]) -> f64 {
        let t = |p: &[f64; 3], k: usize| two_sum(p[k], -e[k]);
        let (aex, aey, aez) = (t(a, 0), t(a, 1), t(a, 2));
        let (bex, bey, bez) = (t(b, 0), t(b, 1), t(b, 2));
        let (cex, cey, cez) = (t(c, 0), t(c, 1), t(c, 2));
        let (dex, dey, dez) = (t(d, 0), t(d, 1), t(d, 2));
        let m2 = |x: Dd, y: Dd, z: Dd, w: Dd| sub(mul(x, y), mul(z, w));
        let ab = m2(aex, bey, bex, aey);
        let bc = m2(bex, cey, cex, bey);
        let cd = m2(cex, dey, dex, cey);
        let da = m2(dex, aey, aex, dey);
        let ac = m2(aex, cey, cex, aey);
        let bd = m2(bex, dey, dex, bey);
        let abc = add(sub(mul(aez, bc), mul(bez, ac)), mul(cez, ab));
        let bcd = add(sub(mul(bez, cd), mul(cez, bd)), mul(dez, bc));
        let cda = add(add(mul(cez, da), mul(dez, ac)), mul(aez, cd));
        let dab = add(add(mul(dez, ab), mul(aez, bd)), mul(bez, da));
        let lift = |x: Dd, y: Dd, z: Dd| add(add(mul(x, x), mul(y, y)), mul(z, z));
        let alift = lift(aex, aey, aez);
        let blift = lift(bex, bey, bez);
        let clift = lift(cex, cey, cez);
        let dlift = lift(dex, dey, dez);
        let det = add(
            sub(mul(dlift, abc), mul(clift, dab)),
            sub(mul(blift, cda), mul(alift, bcd)),
        );
        det.0 + det.1
    }
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
    order.sort_unstable_by_key(|a| std::cmp::Reverse(a.0));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filters_agree_with_robust() {
        let mut x = 0x1234_5678_9abc_def1u64;
        let mut f = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..20000 {
            let scale = [1.0, 1e-3, 1e5, 3.0][k % 4];
            let mut p = || [f() * scale, f() * scale, f() * scale];
            let (a, b, cc, d, mut e) = (p(), p(), p(), p(), p());
            if k % 7 == 0 {
                // Near-degenerate: e close to a.
                e = [a[0] + 1e-17, a[1], a[2]];
            }
            let o1 = orient(&a, &b, &cc, &d).signum();
            let o2 = robust::orient3d(c(&a), c(&b), c(&cc), c(&d)).signum();
            assert_eq!(o1, o2);
            let s1 = insphere(&a, &b, &cc, &d, &e).signum();
            let s2 = robust::insphere(c(&a), c(&b), c(&cc), c(&d), c(&e)).signum();
            assert_eq!(s1, s2);
        }
        // Nearly cospherical: normalised points on the unit sphere.
        for _ in 0..5000 {
            let mut q = || {
                let v = [f() - 0.5, f() - 0.5, f() - 0.5];
                let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                [v[0] / l, v[1] / l, v[2] / l]
            };
            let (a, b, cc, d, e) = (q(), q(), q(), q(), q());
            let s1 = insphere(&a, &b, &cc, &d, &e).signum();
            let s2 = robust::insphere(c(&a), c(&b), c(&cc), c(&d), c(&e)).signum();
            assert_eq!(s1, s2);
            let s1 = dd::insphere(&a, &b, &cc, &d, &e).signum();
            assert!(s1 == s2 || s2 == 0.0);
        }
        // Corners of the cube [0, s]³ by bits (x 1, y 2, z 4): four corners and the opposite
        // one are cospherical, the four of a face coplanar. On the lattice (s = 3) the integer
        // shortcut gives the exact zero; on the unit cube, the exact path.
        let corners = |s: f64, ids: [usize; 5]| {
            ids.map(|k| [k & 1, (k >> 1) & 1, (k >> 2) & 1].map(|b| b as f64 * s))
        };
        for s in [3.0, 1.0] {
            let c = corners(s, [0, 1, 2, 4, 7]);
            assert_eq!(insphere(&c[0], &c[1], &c[2], &c[3], &c[4]), 0.0, "{s}");
            let f = corners(s, [0, 1, 3, 2, 4]);
            assert_eq!(orient(&f[0], &f[1], &f[2], &f[3]), 0.0, "{s}");
        }
    }
}
