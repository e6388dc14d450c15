//! How many elements a sizing field asks for, estimated before anything is meshed, so that a
//! mistyped size (1e-7 for 1e-2) is refused in a second with the estimate in the message
//! instead of running for hours towards billions of tets.
//!
//! - Surface triangles: ∬ dA / (√3/4 · δ²) over every face, by the midpoint rule on a grid of
//!   the face's (u,v) box, cells outside the trimming loops dropped.
//! - Tets: ∫ dV / δ³ over each region, by the midpoint rule on a grid of the model's bounding
//!   box, scaled by the regions' volume over the box's (δ in the box is δ near and around the
//!   model, which is what a graded limit or a source asks for in the region too), times the
//!   tets per δ³; plus the layer of tets that a surface meshed finer than the volume
//!   brings with it (a few per triangle).
//!
//! Both are estimates (within a factor of about two on the samples and the corpus); the guard
//! only needs the order of magnitude.

use super::SizingField;
use crate::model::Model;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Grid cells per face direction for the surface estimate.
const FACE_GRID: usize = 12;
/// Grid cells per bounding-box direction for the volume estimate.
const BOX_GRID: usize = 24;
/// Tets per δ³ of volume in a mesh graded to δ (measured: cube, wing and corpus meshes give
/// 6–8; a regular tet would give 6√2 ≈ 8.5).
const TETS_PER_CUBE: f64 = 7.0;
/// Tets per surface triangle beyond the volume's own: next to a surface meshed finer than
/// the volume around it, the tets are as small as its triangles (gmsh_part.step: 5278
/// triangles, 3305 tets from the volume term, 9902 made).
const TETS_PER_TRIANGLE: f64 = 1.3;
/// Triangles per δ² of area (an equilateral triangle of side δ has area √3/4 δ²).
const TRIANGLES_PER_SQUARE: f64 = 2.3;
/// Heap bytes per tet at the peak of a volume run (tets, points, the kernel's adjacency, the
/// surface and the output mesh together; measured on the wing and corpus runs: 250–400).
pub const BYTES_PER_TET: f64 = 450.0;

/// The estimate: surface triangles, tets and the memory the tets need.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ElementEstimate {
    pub triangles: f64,
    pub tets: f64,
    /// Peak heap bytes of the volume stage, from [`BYTES_PER_TET`].
    pub bytes: f64,
}

impl ElementEstimate {
    /// The number that matters: tets for a volume mesh, else triangles.
    pub fn elements(&self, surface_only: bool) -> f64 {
        if surface_only {
            self.triangles
        } else {
            self.tets.max(self.triangles)
        }
    }
}

/// The estimate, and how many of its elements each local limit adds (the estimate with the
/// limit minus the estimate without it).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct SizingEstimate {
    #[serde(flatten)]
    pub total: ElementEstimate,
    /// Tets (triangles for a surface-only run) the curvature limit adds.
    pub added_by_curvature: f64,
    /// Tets (triangles for a surface-only run) the proximity limit adds.
    pub added_by_proximity: f64,
}

/// [`estimate_elements`] with the share of each local limit: the estimates with and without
/// each limit come from one pass over the samples.
pub fn estimate_with_limits(
    model: &Model,
    sizing: &SizingField,
    surface_only: bool,
) -> SizingEstimate {
    let [total, without_curvature, without_proximity] = estimate_variants(model, sizing);
    let n = total.elements(surface_only);
    SizingEstimate {
        total,
        added_by_curvature: (n - without_curvature.elements(surface_only)).max(0.0),
        added_by_proximity: (n - without_proximity.elements(surface_only)).max(0.0),
    }
}

/// Estimate the elements `sizing` asks for on `model`.
pub fn estimate_elements(model: &Model, sizing: &SizingField) -> ElementEstimate {
    estimate_variants(model, sizing)[0]
}

/// The estimate with every contribution, without the curvature limit and without the
/// proximity limit (the order of [`SizingField::spacing_with_and_without_limits`]).
fn estimate_variants(model: &Model, sizing: &SizingField) -> [ElementEstimate; 3] {
    let faces: Vec<([f64; 3], [DVec3; 2])> = (0..model.faces.len())
        .into_par_iter()
        .map(|f| face_estimate(model, f, sizing))
        .collect();
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for (_, [a, b]) in &faces {
        lo = lo.min(*a);
        hi = hi.max(*b);
    }
    for v in &model.vertices {
        lo = lo.min(v.point);
        hi = hi.max(v.point);
    }
    let region_volume: f64 = model
        .regions
        .iter()
        .map(|r| {
            let outer = r.shells.first().map_or(0.0, |s| s.volume);
            let cavities: f64 = r.shells.iter().skip(1).map(|s| s.volume).sum();
            (outer - cavities).max(0.0)
        })
        .sum();
    let has_volume = region_volume > 0.0 && lo.cmple(hi).all();
    let inverse_cubes = if has_volume {
        mean_inverse_cube(sizing, lo, hi)
    } else {
        [0.0; 3]
    };
    std::array::from_fn(|k| {
        let triangles = TRIANGLES_PER_SQUARE * faces.iter().map(|(t, _)| t[k]).sum::<f64>();
        let tets = if has_volume {
            TETS_PER_CUBE * region_volume * inverse_cubes[k] + TETS_PER_TRIANGLE * triangles
        } else {
            0.0
        };
        ElementEstimate {
            triangles,
            tets,
            bytes: BYTES_PER_TET * tets,
        }
    })
}

/// Mean of 1/δ³ over the box for each variant (midpoint rule; a flat box gets a one-cell
/// thickness).
fn mean_inverse_cube(sizing: &SizingField, lo: DVec3, hi: DVec3) -> [f64; 3] {
    let n = BOX_GRID;
    let step = (hi - lo) / n as f64;
    let sum = (0..n * n)
        .into_par_iter()
        .map(|ij| {
            let (i, j) = (ij / n, ij % n);
            let mut sum = [0.0; 3];
            for k in 0..n {
                let p = lo + step * DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5);
                let d = sizing.spacing_with_and_without_limits(p, super::graded::VOLUME_RATE);
                for (s, d) in sum.iter_mut().zip(d) {
                    *s += d.powi(-3);
                }
            }
            sum
        })
        .reduce(|| [0.0; 3], |a, b| std::array::from_fn(|k| a[k] + b[k]));
    sum.map(|s| s / (n * n * n) as f64)
}

/// (∬ dA / δ² for each variant, bounding box of the samples) of one face.
fn face_estimate(model: &Model, face: usize, sizing: &SizingField) -> ([f64; 3], [DVec3; 2]) {
    let surface = model.faces[face].surface.as_ref();
    let polys = model.loop_polygons_rough(face).unwrap_or_default();
    // The (u,v) box of the trimming loops, not of the surface: a small face cut from a large
    // B-spline would otherwise be sampled mostly outside itself.
    let (u0, u1, v0, v1) = if polys.iter().any(|p| !p.is_empty()) {
        let mut b = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for q in polys.iter().flatten() {
            b = (b.0.min(q.x), b.1.max(q.x), b.2.min(q.y), b.3.max(q.y));
        }
        b
    } else {
        let b = surface.bounds();
        (b.u.0, b.u.1, b.v.0, b.v.1)
    };
    let (du, dv) = ((u1 - u0) / FACE_GRID as f64, (v1 - v0) / FACE_GRID as f64);
    let mut sum = [0.0; 3];
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for i in 0..FACE_GRID {
        for j in 0..FACE_GRID {
            let uv = DVec2::new(u0 + (i as f64 + 0.5) * du, v0 + (j as f64 + 0.5) * dv);
            if !(polys.is_empty() || super::curvature::inside_face(&polys, uv)) {
                continue;
            }
            let d = surface.derivs(uv);
            let area = d.normal_raw().length() * du * dv;
            if !(area.is_finite() && d.p.is_finite()) {
                continue;
            }
            lo = lo.min(d.p);
            hi = hi.max(d.p);
            let spacing = sizing.spacing_with_and_without_limits(d.p, super::graded::RATE);
            for (s, d) in sum.iter_mut().zip(spacing) {
                *s += area / d.powi(2);
            }
        }
    }
    (sum, [lo, hi])
}

/// Refusal of a run whose estimate is above the limit.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "the sizing asks for about {} {what} (estimated from the size field before meshing; about {} \
     of memory), more than the limit of {}: check the size (uniform size {}), or raise \
     the limit with --max-elements",
    human(*.estimated),
    human_bytes(*.bytes),
    human(*.limit),
    crate::geometry::Coord(*.size)
)]
pub struct TooManyElements {
    pub estimated: f64,
    pub limit: f64,
    pub bytes: f64,
    pub size: f64,
    pub what: &'static str,
}

/// Refuse an estimate above `limit` elements.
pub fn check_limit(
    estimate: &ElementEstimate,
    limit: f64,
    surface_only: bool,
    size: f64,
) -> Result<(), TooManyElements> {
    let n = estimate.elements(surface_only);
    if n > limit || !n.is_finite() {
        return Err(TooManyElements {
            estimated: n,
            limit,
            bytes: if surface_only { 0.0 } else { estimate.bytes },
            size,
            what: if surface_only {
                "surface triangles"
            } else {
                "tetrahedra"
            },
        });
    }
    Ok(())
}

/// The default limit: the tets whose peak memory fits in three quarters of this machine's
/// memory (`/proc/meminfo`), or 50 million where that cannot be read.
pub fn default_max_elements() -> f64 {
    let total = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("MemTotal:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map(|kib| kib * 1024.0);
    match total {
        Some(bytes) if bytes > 0.0 => (0.75 * bytes / BYTES_PER_TET).floor(),
        _ => 5e7,
    }
}

/// 1.2 million, 3.4e12 — a count as a person reads it.
pub fn human(n: f64) -> String {
    if !n.is_finite() {
        "infinitely many".into()
    } else if n >= 1e15 {
        format!("{n:.1e}")
    } else if n >= 1e9 {
        format!("{:.1} billion", n / 1e9)
    } else if n >= 1e6 {
        format!("{:.1} million", n / 1e6)
    } else if n >= 1e4 {
        format!("{:.0} thousand", n / 1e3)
    } else {
        format!("{n:.0}")
    }
}

fn human_bytes(b: f64) -> String {
    if b >= 1024f64.powi(4) * 1024.0 {
        format!("{:.1e} bytes", b)
    } else if b >= 1024f64.powi(4) {
        format!("{:.1} TiB", b / 1024f64.powi(4))
    } else if b >= 1024f64.powi(3) {
        format!("{:.1} GiB", b / 1024f64.powi(3))
    } else {
        format!("{:.0} MiB", b / 1024f64.powi(2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_read_as_people_write_them() {
        assert_eq!(human(1.23e6), "1.2 million");
        assert_eq!(human(3.4e18), "3.4e18");
        assert_eq!(human(950.0), "950");
        assert_eq!(human_bytes(3.0 * 1024f64.powi(3)), "3.0 GiB");
    }

    #[test]
    fn an_estimate_over_the_limit_is_refused_with_the_numbers() {
        let e = ElementEstimate {
            triangles: 1e6,
            tets: 4e18,
            bytes: 4e18 * BYTES_PER_TET,
        };
        let err = check_limit(&e, 1e8, false, 1e-7).unwrap_err();
        let text = err.to_string();
        assert!(text.contains("4.0e18 tetrahedra"), "{text}");
        assert!(text.contains("100.0 million"), "{text}");
        assert!(text.contains("--max-elements"), "{text}");
        assert!(check_limit(&e, 1e8, true, 1e-7).is_ok());
    }
}
