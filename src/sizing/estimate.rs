//! How many elements a sizing field asks for, estimated before anything is meshed, so that a
//! mistyped size (1e-7 for 1e-2) is refused in a second with the estimate in the message
//! instead of running for hours towards billions of tets.
//!
//! - Surface triangles: ∬ dA / (√3/4 · δ²) over every face, by the midpoint rule on cells of
//!   the face's (u,v) box, cells outside the trimming loops dropped.
//! - Tets: ∫ dV / δ³ over each region, by the midpoint rule on cells of the model's bounding
//!   box, scaled by the regions' volume over the box's (δ in the box is δ near and around the
//!   model, which is what a graded limit or a source asks for in the region too), times the
//!   tets per δ³; plus the layer of tets that a surface meshed finer than the volume
//!   brings with it (a few per triangle).
//!
//! The cells adapt: one is split in 8 (in 4 on a face) while it may hold spacings well below
//! its size. A fixed grid missed whatever is small beside a large domain — a wing in a
//! far field a hundred chords wide, its line source and curvature limit inside one cell —
//! and gave a twentieth of the tets made. The smallest δ a cell may hold is bounded below
//! without sampling it: the graded limits change by at most their rate times the distance,
//! and a source's spacing grows with the distance to its shape.
//!
//! Both are estimates (within a factor of about two on the samples and the corpus); the guard
//! only needs the order of magnitude.

use super::graded::VOLUME_RATE;
use super::SizingField;
use crate::model::Model;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use rstar::primitives::GeomWithData;
use rstar::{RTree, AABB};

/// Grid cells per face direction for the surface estimate, before any split.
const FACE_GRID: usize = 12;
/// Grid cells per bounding-box direction for the volume estimate, before any split.
const BOX_GRID: usize = 24;
/// A cell is split while it is larger than this many of the smallest spacings it may hold.
const SPLIT_ABOVE: f64 = 3.0;
/// Splits deep: cells down to 1/2⁸ of the first grid's.
const MAX_DEPTH: u32 = 8;
/// Spacing evaluations at most, per face and for the volume: past them the estimate is
/// already large, and the cells left whole are counted at their centre.
const FACE_BUDGET: usize = 40_000;
const BOX_BUDGET: usize = 400_000;
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
    let coarse = Features::bulk_load(coarse_features(model, sizing));
    let faces: Vec<FaceEstimate> = (0..model.faces.len())
        .into_par_iter()
        .map(|f| face_estimate(model, f, sizing, &coarse))
        .collect();
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for f in &faces {
        lo = lo.min(f.bounds[0]);
        hi = hi.max(f.bounds[1]);
    }
    for v in &model.vertices {
        lo = lo.min(v.point);
        hi = hi.max(v.point);
    }
    let sums: [f64; 3] = std::array::from_fn(|k| faces.iter().map(|f| f.sums[k]).sum());
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
        let samples = faces.into_iter().flat_map(|f| f.samples).collect();
        mean_inverse_cube(sizing, &Features::bulk_load(samples), lo, hi)
    } else {
        [0.0; 3]
    };
    std::array::from_fn(|k| {
        let triangles = TRIANGLES_PER_SQUARE * sums[k];
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

/// Places where the spacing is known to be small: surface samples with their spacing, in an
/// R*-tree, so a cell of the volume (or of another face) can ask for the smallest inside it.
type Features = RTree<GeomWithData<[f64; 3], f64>>;

/// The smallest spacing a cell of centre `c` and half-diagonal `half` may hold, as far as the
/// features inside its box and the sources say (a source asks for no less than its spacing
/// at the cell's nearest possible distance from its shape).
fn smallest_in_cell(sizing: &SizingField, features: &Features, c: DVec3, half: f64) -> f64 {
    let mut least = f64::INFINITY;
    for s in &sizing.sources {
        let d = (s.shape.distance(c) - half).max(0.0);
        least = least.min(super::sources::felisa(d, s.delta1, s.r1, s.r2));
    }
    let envelope = AABB::from_corners((c - half).to_array(), (c + half).to_array());
    for f in features.locate_in_envelope(&envelope) {
        least = least.min(f.data);
    }
    least
}

/// Whether a cell of size `extent` whose centre asks for `delta` must be split: it may hold
/// spacings below half its centre's, and it is larger than them.
fn needs_split(extent: f64, delta: f64, least: f64) -> bool {
    least < 0.5 * delta && extent > SPLIT_ABOVE * least
}

/// Mean of 1/δ³ over the box for each variant: the midpoint rule on adaptive cells.
fn mean_inverse_cube(sizing: &SizingField, features: &Features, lo: DVec3, hi: DVec3) -> [f64; 3] {
    let n = BOX_GRID;
    let step = (hi - lo) / n as f64;
    let mut cells: Vec<(DVec3, DVec3)> = (0..n * n * n)
        .map(|ijk| {
            let (i, j, k) = (ijk / (n * n), (ijk / n) % n, ijk % n);
            let c = lo + step * DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5);
            (c, step)
        })
        .collect();
    let mut sum = [0.0; 3];
    let mut evaluations = 0;
    for depth in 0..=MAX_DEPTH {
        // (centre, size, spacings there, whether to split)
        let sampled: Vec<(DVec3, DVec3, [f64; 3], bool)> = cells
            .par_iter()
            .map(|&(c, size)| {
                let d = sizing.spacing_with_and_without_limits(c, VOLUME_RATE);
                let half = 0.5 * size.length();
                let least = smallest_in_cell(sizing, features, c, half);
                (
                    c,
                    size,
                    d,
                    depth < MAX_DEPTH && needs_split(2.0 * half, d[0], least),
                )
            })
            .collect();
        evaluations += sampled.len();
        let room = BOX_BUDGET.saturating_sub(evaluations) / 8;
        let mut next = Vec::new();
        for &(c, size, d, split) in &sampled {
            if split && next.len() < 8 * room {
                let q = size * 0.25;
                for o in 0..8 {
                    let sign = |bit: usize| if o & bit == 0 { -1.0 } else { 1.0 };
                    next.push((c + q * DVec3::new(sign(1), sign(2), sign(4)), size * 0.5));
                }
                continue;
            }
            let volume = size.x * size.y * size.z;
            for (s, d) in sum.iter_mut().zip(d) {
                *s += volume * d.powi(-3);
            }
        }
        cells = next;
        if cells.is_empty() {
            break;
        }
    }
    let size = hi - lo;
    let volume = size.x * size.y * size.z;
    if volume > 0.0 {
        sum.map(|s| s / volume)
    } else {
        [0.0; 3]
    }
}

/// The spacing at the centres of a [`FACE_GRID`]² grid on every face: the features that tell
/// each face's cells (and the volume's) where another face asks for less.
fn coarse_features(model: &Model, sizing: &SizingField) -> Vec<GeomWithData<[f64; 3], f64>> {
    (0..model.faces.len())
        .into_par_iter()
        .flat_map_iter(|f| {
            let surface = model.faces[f].surface.as_ref();
            let (u0, u1, v0, v1) = face_box(model, f);
            let n = FACE_GRID;
            (0..n * n).filter_map(move |ij| {
                let uv = DVec2::new(
                    u0 + ((ij / n) as f64 + 0.5) * (u1 - u0) / n as f64,
                    v0 + ((ij % n) as f64 + 0.5) * (v1 - v0) / n as f64,
                );
                let p = surface.point(uv);
                p.is_finite()
                    .then(|| GeomWithData::new(p.to_array(), sizing.spacing(p)))
            })
        })
        .collect()
}

/// The (u,v) box of face `f`'s trimming loops (of its surface when it has none): a small face
/// cut from a large B-spline would otherwise be sampled mostly outside itself.
fn face_box(model: &Model, f: usize) -> (f64, f64, f64, f64) {
    let polys = model.loop_polygons_rough(f).unwrap_or_default();
    if polys.iter().any(|p| !p.is_empty()) {
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
        let b = model.faces[f].surface.bounds();
        (b.u.0, b.u.1, b.v.0, b.v.1)
    }
}

/// One face's estimate: ∬ dA / δ² for each variant, the bounding box of its samples, and the
/// samples (features for the volume's cells). The midpoint rule on adaptive (u,v) cells,
/// sized in 3-D by the surface's derivatives at their centre.
fn face_estimate(
    model: &Model,
    face: usize,
    sizing: &SizingField,
    features: &Features,
) -> FaceEstimate {
    let surface = model.faces[face].surface.as_ref();
    let polys = model.loop_polygons_rough(face).unwrap_or_default();
    let (u0, u1, v0, v1) = face_box(model, face);
    let step = DVec2::new((u1 - u0) / FACE_GRID as f64, (v1 - v0) / FACE_GRID as f64);
    let mut cells: Vec<(DVec2, DVec2)> = (0..FACE_GRID * FACE_GRID)
        .map(|ij| {
            let (i, j) = (ij / FACE_GRID, ij % FACE_GRID);
            let c = DVec2::new(
                u0 + (i as f64 + 0.5) * step.x,
                v0 + (j as f64 + 0.5) * step.y,
            );
            (c, step)
        })
        .collect();
    let mut out = FaceEstimate {
        sums: [0.0; 3],
        bounds: [DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)],
        samples: Vec::new(),
    };
    let mut evaluations = 0;
    for depth in 0..=MAX_DEPTH {
        let mut next: Vec<(DVec2, DVec2)> = Vec::new();
        for &(uv, size) in &cells {
            evaluations += 1;
            let d = surface.derivs(uv);
            if !(d.p.is_finite() && d.du.is_finite() && d.dv.is_finite()) {
                continue;
            }
            let spacing = sizing.spacing_with_and_without_limits(d.p, super::graded::RATE);
            let extent = DVec2::new(d.du.length() * size.x, d.dv.length() * size.y).length();
            let least = smallest_in_cell(sizing, features, d.p, 0.5 * extent);
            let room = evaluations + next.len() + 4 <= FACE_BUDGET;
            if depth < MAX_DEPTH && room && needs_split(extent, spacing[0], least) {
                let q = size * 0.25;
                for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
                    next.push((uv + DVec2::new(a * q.x, b * q.y), size * 0.5));
                }
                continue;
            }
            if !(polys.is_empty() || super::curvature::inside_face(&polys, uv)) {
                continue;
            }
            let area = d.normal_raw().length() * size.x * size.y;
            if !area.is_finite() {
                continue;
            }
            out.bounds = [out.bounds[0].min(d.p), out.bounds[1].max(d.p)];
            out.samples
                .push(GeomWithData::new(d.p.to_array(), spacing[0]));
            for (s, d) in out.sums.iter_mut().zip(spacing) {
                *s += area / d.powi(2);
            }
        }
        cells = next;
        if cells.is_empty() {
            break;
        }
    }
    out
}

/// What [`face_estimate`] gives.
struct FaceEstimate {
    sums: [f64; 3],
    bounds: [DVec3; 2],
    samples: Vec<GeomWithData<[f64; 3], f64>>,
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
