//! Integrals over a trimmed face computed from its boundary alone (Green's theorem), so they
//! work for any face before it is meshed: the signed parametric area of each loop (which orients
//! the loops) and the 3-D area and volume flux of the face (which orient the shells).
//!
//! For an integrand f(u,v) over the trimmed domain D, ∬_D f du dv = ∮_∂D F dv with
//! F(u,v) = ∫_{u₀}^{u} f(s,v) ds, evaluated by Gauss–Legendre quadrature along u.

use super::{FaceId, Model};
use crate::geometry::Surface;
use glam::DVec2;

/// Samples per edge use on a loop polygon.
const SAMPLES_PER_EDGE: usize = 48;

/// 6-point Gauss–Legendre nodes and weights on [-1, 1].
const GL6: [(f64, f64); 6] = [
    (-0.932_469_514_203_152, 0.171_324_492_379_170),
    (-0.661_209_386_466_265, 0.360_761_573_048_139),
    (-0.238_619_186_083_197, 0.467_913_934_572_691),
    (0.238_619_186_083_197, 0.467_913_934_572_691),
    (0.661_209_386_466_265, 0.360_761_573_048_139),
    (0.932_469_514_203_152, 0.171_324_492_379_170),
];

/// 3-point Gauss–Legendre nodes and weights on [-1, 1].
const GL3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// What the boundary integrals of one face give.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FaceIntegrals {
    /// Signed (u,v) area of each loop, in the loop's own direction (counter-clockwise > 0).
    pub loop_areas: Vec<f64>,
    /// 3-D area of the face with its loops as they are oriented now.
    pub area: f64,
    /// ⅓ ∬ S·(Su × Sv) du dv: the face's contribution to an enclosed volume when its normal
    /// `Su × Sv` points outwards.
    pub flux: f64,
}

impl Model {
    /// The loops of a face as (u,v) polygons (closed implicitly), in loop direction.
    /// A face without edge loops gets its parameter rectangle.
    pub fn loop_polygons(&self, face: FaceId) -> Option<Vec<Vec<DVec2>>> {
        self.loop_polygons_by(face, |u, t| self.use_uv(face, u, t))
    }

    /// As [`Model::loop_polygons`], but straight from the pcurves where there are any, without
    /// refining each point by projection: close enough for inside tests on a coarse grid, and
    /// far cheaper on large B-spline faces.
    pub fn loop_polygons_rough(&self, face: FaceId) -> Option<Vec<Vec<DVec2>>> {
        self.loop_polygons_by(face, |u, t| match &u.pcurve {
            Some(pc) => Some(pc.point(t)),
            None => self.use_uv(face, u, t),
        })
    }

    fn loop_polygons_by(
        &self,
        face: FaceId,
        uv_of: impl Fn(&super::EdgeUse, f64) -> Option<DVec2>,
    ) -> Option<Vec<Vec<DVec2>>> {
        let f = &self.faces[face];
        let mut polys = Vec::new();
        for lp in f.loops.iter().filter(|l| !l.uses.is_empty()) {
            let mut poly = Vec::new();
            for u in &lp.uses {
                let e = &self.edges[u.edge];
                for i in 0..SAMPLES_PER_EDGE {
                    let s = i as f64 / SAMPLES_PER_EDGE as f64;
                    let s = if u.reversed { 1.0 - s } else { s };
                    let t = e.range.0 + s * (e.range.1 - e.range.0);
                    let uv = uv_of(u, t)?;
                    poly.push(match poly.last() {
                        Some(&prev) => super::pcurve::unwrap_near(uv, prev, &f.surface.bounds()),
                        None => uv,
                    });
                }
            }
            polys.push(poly);
        }
        if polys.is_empty() {
            let b = f.surface.bounds();
            polys.push(vec![
                DVec2::new(b.u.0, b.v.0),
                DVec2::new(b.u.1, b.v.0),
                DVec2::new(b.u.1, b.v.1),
                DVec2::new(b.u.0, b.v.1),
            ]);
        }
        Some(polys)
    }

    /// Boundary integrals of a face; `None` when a boundary point cannot be put in (u,v).
    pub fn face_integrals(&self, face: FaceId) -> Option<FaceIntegrals> {
        let surface = self.faces[face].surface.as_ref();
        let polys = self.loop_polygons(face)?;
        // Any constant u₀ gives the same ∮ F dv; the loops' smallest u keeps the inner
        // integrals short on a face cut from a much larger surface.
        let u0 = polys
            .iter()
            .flatten()
            .map(|p| p.x)
            .fold(f64::INFINITY, f64::min);
        let u0 = if u0.is_finite() {
            u0
        } else {
            surface.bounds().u.0
        };
        // Edge samples come in runs of SAMPLES_PER_EDGE (even): fit parabolas through pairs of
        // segments; the parameter rectangle of a face without loops is straight-sided.
        let curved = self.faces[face].loops.iter().any(|l| !l.uses.is_empty());
        let mut out = FaceIntegrals::default();
        for poly in &polys {
            out.loop_areas.push(signed_area(poly));
            let (area, flux) = if curved {
                green_integrals_curved(surface, poly, u0)
            } else {
                green_integrals(surface, poly, u0)
            };
            out.area += area;
            out.flux += flux;
        }
        Some(out)
    }
}

/// Signed area of a closed polygon (shoelace).
pub fn signed_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| poly[i].perp_dot(poly[(i + 1) % n]))
        .sum::<f64>()
        * 0.5
}

/// (∬ |Su×Sv|, ⅓ ∬ S·(Su×Sv)) over the polygon's interior by ∮ F dv.
fn green_integrals(surface: &dyn Surface, poly: &[DVec2], u0: f64) -> (f64, f64) {
    let n = poly.len();
    let mut area = 0.0;
    let mut flux = 0.0;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let dv = b.y - a.y;
        if dv == 0.0 {
            continue;
        }
        // 3-point Gauss on the segment, parameter s in [0,1].
        for &(x, w) in &GL3 {
            let p = a.lerp(b, 0.5 * (x + 1.0));
            let (fa, ff) = inner(surface, p, u0);
            area += 0.5 * w * fa * dv;
            flux += 0.5 * w * ff * dv;
        }
    }
    (area, flux)
}

/// As [`green_integrals`], but along the parabola through each run of three samples (the
/// samples of one edge are equally spaced in its parameter), so a curved trim loop is followed
/// to O(h⁴) instead of cut by chords (straight segments lose (2π/n)²/6 of a circle's area).
fn green_integrals_curved(surface: &dyn Surface, poly: &[DVec2], u0: f64) -> (f64, f64) {
    let n = poly.len();
    debug_assert!(n.is_multiple_of(2));
    let mut area = 0.0;
    let mut flux = 0.0;
    for i in (0..n).step_by(2) {
        let (p0, p1, p2) = (poly[i], poly[(i + 1) % n], poly[(i + 2) % n]);
        // c(s) = p0 + b s + a s², s in [0, 2], through p0, p1, p2 at s = 0, 1, 2.
        let b = 0.5 * (-3.0 * p0 + 4.0 * p1 - p2);
        let a = 0.5 * (p0 - 2.0 * p1 + p2);
        for half in [0.0, 1.0] {
            for &(x, w) in &GL3 {
                let s = half + 0.5 * (x + 1.0);
                let c = p0 + b * s + a * s * s;
                let dv = (b + 2.0 * a * s).y;
                if dv == 0.0 {
                    continue;
                }
                let (fa, ff) = inner(surface, c, u0);
                area += 0.5 * w * fa * dv;
                flux += 0.5 * w * ff * dv;
            }
        }
    }
    (area, flux)
}

/// F(u,v) = ∫_{u0}^{u} f(s,v) ds for f = |Su×Sv| and f = ⅓ S·(Su×Sv), by adaptive
/// Gauss–Legendre quadrature: a piece is halved only while the two halves disagree with the
/// whole by more than [`INNER_TOLERANCE`], so planes and cylinders (polynomial or nearly so
/// along u) cost one or two pieces, not a fixed many.
fn inner(surface: &dyn Surface, p: DVec2, u0: f64) -> (f64, f64) {
    if p.x == u0 {
        return (0.0, 0.0);
    }
    let whole = piece(surface, u0, p.x, p.y);
    let (fa, ff, _) = refine_piece(surface, u0, p.x, p.y, whole, INNER_DEPTH);
    (fa, ff)
}

/// Relative agreement at which a piece of the inner integral is accepted.
const INNER_TOLERANCE: f64 = 1e-8;
/// At most 2^INNER_DEPTH pieces.
const INNER_DEPTH: u32 = 7;

/// (∫|Su×Sv|, ∫⅓ S·(Su×Sv), ∫⅓ |S||Su×Sv|) over u in [a, b] at v by 6-point Gauss; the last
/// is the scale the flux's error is measured against (the flux itself may cancel to zero).
fn piece(surface: &dyn Surface, a: f64, b: f64, v: f64) -> (f64, f64, f64) {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let (mut fa, mut ff, mut scale) = (0.0, 0.0, 0.0);
    for &(x, w) in &GL6 {
        let d = surface.derivs(DVec2::new(mid + half * x, v));
        let n = d.normal_raw();
        let len = n.length();
        fa += half * w * len;
        ff += half * w * d.p.dot(n) / 3.0;
        scale += half * w * d.p.length() * len / 3.0;
    }
    (fa, ff, scale)
}

fn refine_piece(
    surface: &dyn Surface,
    a: f64,
    b: f64,
    v: f64,
    whole: (f64, f64, f64),
    depth: u32,
) -> (f64, f64, f64) {
    let m = 0.5 * (a + b);
    let (l, r) = (piece(surface, a, m, v), piece(surface, m, b, v));
    let halves = (l.0 + r.0, l.1 + r.1, l.2 + r.2);
    let agree = (halves.0 - whole.0).abs() <= INNER_TOLERANCE * halves.0.abs()
        && (halves.1 - whole.1).abs() <= INNER_TOLERANCE * halves.2.abs();
    if agree || depth == 0 {
        return halves;
    }
    let l = refine_piece(surface, a, m, v, l, depth - 1);
    let r = refine_piece(surface, m, b, v, r, depth - 1);
    (l.0 + r.0, l.1 + r.1, l.2 + r.2)
}
