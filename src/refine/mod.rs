//! Directional refinement (seed paper, "Directional refinement"): stretched elements near chosen
//! curves and surfaces, driven by the distance φ to each source and its 1-D spacing
//! distribution. Applied to the isotropic mesh in stages, each stage's sources combined by the
//! minimum of their distributions:
//!
//! 1. edges and faces ([`surface`]): points on model edges, then on faces, at the distribution's
//!    sites, each splitting the triangle(s) holding it, followed by max-angle diagonal swaps —
//!    before the volume is tetrahedralised, so the boundary carries the layers;
//! 2. volume: the columns of the face sources' nodes grown level by level, each point coned
//!    over the part of its column top's star above the finished layers ([`columns`]), so the
//!    layers are prisms; then candidates on the lines from the tets' vertices to their nearest
//!    source points, inserted by Delaunay reconnection ([`volume`]: curve sources, and what
//!    the columns left);
//! 3. generalised edge swaps by the min-max angle ([`swap`]), alternating with 2 while points
//!    go in.
//!
//! Entry points: [`refine_surface`] (between the surface and volume stages) and
//! [`refine_volume_stages`] (inside the volume stage, after the isotropic interior points and
//! improvement); [`quality::stretched_quality`] measures the result.

pub mod clear;
pub mod columns;
mod cone;
pub mod distribution;
mod face_tris;
mod feet;
pub mod field;
pub mod flat;
mod flat_point;
pub mod layers;
pub mod quality;
pub mod smooth;
pub mod source;
pub mod spanning;
pub mod surface;
pub mod swap;
pub mod viscous;
pub mod volume;
mod wedge;

pub use distribution::{Distribution, DistributionError};

use crate::curve::CurveMesh;
use crate::mesh::LayerTag;
use crate::model::{EdgeId, FaceId, Model};
use crate::progress::Reporter;
use crate::sizing::SizingField;
use crate::surface::SurfaceMesh;
use crate::volume::delaunay::Delaunay;
use field::{StageField, StageSource};
use source::SourceDistance;
use std::collections::HashSet;

/// Cycles of Delaunay insertion and swaps per stage.
const INSERT_SWAP_CYCLES: usize = 6;

/// Whether tet `t` has a vertex within the refined distance of a source of some stage (plus
/// half the isotropic spacing: the tets capping the layers take part in the swaps), from the
/// distances `data` keeps per vertex and stage (one lookup per vertex instead of a distance
/// query per tet: the swaps ask this of every tet, pass after pass).
fn within(fields: &[StageField], data: &[volume::PointData], dt: &Delaunay, t: u32) -> bool {
    dt.tet(t).iter().any(|&v| {
        fields.iter().zip(data).any(|(f, d)| {
            let (Some(near), Some(&delta)) = (d.near.get(v as usize), d.delta.get(v as usize))
            else {
                return false;
            };
            let reach = f.reach(delta) + 0.5 * delta;
            near.iter().any(|n| n.phi < reach)
        })
    })
}

/// Largest dihedral angle (degrees) above which a tet takes part in the swaps and the
/// smoothing wherever it lies: clearing the zone and the Delaunay insertions reach beyond the
/// layers and leave a few flat tets there, which the isotropic mesh had not.
const FLAT_ANYWHERE: f64 = 150.0;

/// Whether the swaps and the smoothing look at tet `t`: [`within`] the layers, or flat.
fn to_improve(fields: &[StageField], data: &[volume::PointData], dt: &Delaunay, t: u32) -> bool {
    within(fields, data, dt, t) || swap::score(dt, t) > FLAT_ANYWHERE
}

/// Whether `p`, where the isotropic spacing is `delta`, lies within the reach of some stage's
/// layers: the zone the layers fill, which isotropic interior points keep out of.
pub fn in_refined_zone(fields: &[StageField], p: glam::DVec3, delta: f64) -> bool {
    fields.iter().any(|f| {
        let reach = f.reach(delta);
        f.sources.iter().any(|s| s.distance.near(p).phi < reach)
    })
}

/// One source of a stage: some model faces and/or edges, and the distribution away from them.
#[derive(Clone, Debug)]
pub struct SourceSpec {
    /// How the user named it (for reports).
    pub label: String,
    pub faces: Vec<FaceId>,
    pub edges: Vec<EdgeId>,
    pub distribution: Distribution,
}

/// A refinement stage: its sources combine by the minimum of their distributions.
#[derive(Clone, Debug, Default)]
pub struct Stage {
    pub sources: Vec<SourceSpec>,
}

/// All stages, run in order.
#[derive(Clone, Debug, Default)]
pub struct Refinement {
    pub stages: Vec<Stage>,
}

impl Refinement {
    pub fn is_empty(&self) -> bool {
        self.stages.iter().all(|s| s.sources.is_empty())
    }

    /// The largest distance any layer of any stage reaches where the spacing is `delta`.
    pub fn reach(&self, delta: f64) -> f64 {
        self.stages
            .iter()
            .flat_map(|s| &s.sources)
            .map(|s| s.distribution.reach(delta))
            .fold(0.0, f64::max)
    }
}

/// What refinement did, stage by stage.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct StageReport {
    pub sources: Vec<String>,
    pub surface: surface::SurfaceRefineReport,
    /// The columns grown level by level from the face sources' nodes.
    pub columns: columns::ColumnReport,
    pub volume: volume::VolumeRefineReport,
    /// The min-max swaps of the stage's insertion cycles (the smoothing's and the last
    /// resort's are in their own reports).
    pub swaps: swap::SwapReport,
    /// Isotropic interior points taken out of the refined zone before the layers go in
    /// (first stage only: the zone of every stage).
    pub cleared: clear::ClearReport,
    /// The prisms of the stage's columns re-split by one column order (last cycle).
    pub layers: layers::LayerReport,
    /// Tets reaching across layers whose neighbourhood was re-tiled as prisms.
    pub spanning: spanning::SpanReport,
    /// Moves of the poor tets' vertices, with swaps, once every stage's points are in (the
    /// last stage's report carries them).
    pub smoothing: smooth::SmoothReport,
    /// The last resort against tets left nearly flat (the last stage's report carries it).
    pub flat: flat::FlatReport,
    /// Seconds spent on edges and faces, in the volume, and on the stage's swaps and re-tiling
    /// (the last stage's also holds the smoothing and the last resort, run after all stages).
    pub seconds: [f64; 3],
}

/// The stage's sources over a surface mesh.
pub fn stage_field<'m>(
    model: &'m Model,
    surface: &SurfaceMesh,
    curves: &CurveMesh,
    stage: &Stage,
) -> StageField<'m> {
    StageField {
        sources: stage
            .sources
            .iter()
            .map(|s| StageSource {
                distance: SourceDistance::new(
                    model,
                    &surface.points,
                    &surface.triangles,
                    &surface.face_of,
                    curves,
                    &s.faces,
                    &s.edges,
                ),
                distribution: s.distribution.clone(),
            })
            .collect(),
        two_sided: two_sided_nodes(model, surface, stage),
    }
}

/// The nodes on an embedded face that is a source of `stage` and on no other face, numbered as
/// the volume mesher numbers its input points ([`crate::volume::gather`]).
fn two_sided_nodes(model: &Model, surface: &SurfaceMesh, stage: &Stage) -> HashSet<u32> {
    let embedded: HashSet<FaceId> = model
        .regions
        .iter()
        .flat_map(|r| r.embedded_faces.iter().copied())
        .filter(|f| stage.sources.iter().any(|s| s.faces.contains(f)))
        .collect();
    let input = crate::volume::gather(surface);
    let mut on_embedded = HashSet::new();
    let mut elsewhere = HashSet::new();
    for (t, f) in input.triangles.iter().zip(&input.face_of) {
        let set = if embedded.contains(f) {
            &mut on_embedded
        } else {
            &mut elsewhere
        };
        set.extend(t.iter().copied());
    }
    on_embedded.retain(|v| !elsewhere.contains(v));
    on_embedded
}

/// Edge and face refinement of every stage, in order, on the surface mesh (and its curve
/// mesh, whose edges gain the new nodes).
pub fn refine_surface(
    model: &Model,
    surface: &mut SurfaceMesh,
    curves: &mut CurveMesh,
    sizing: &SizingField,
    refinement: &Refinement,
) -> Vec<StageReport> {
    refine_surface_except(model, surface, curves, sizing, refinement, &HashSet::new())
}

/// [`refine_surface`] with the faces `unrefined` left without face points (their edges
/// still get the edge points, so they stay conforming): the pipeline's second try when
/// boundary recovery failed on a face's refinement points.
pub fn refine_surface_except(
    model: &Model,
    surface: &mut SurfaceMesh,
    curves: &mut CurveMesh,
    sizing: &SizingField,
    refinement: &Refinement,
    unrefined: &HashSet<usize>,
) -> Vec<StageReport> {
    let mut one = |stage: &Stage, with_feet: bool| {
        let start = std::time::Instant::now();
        let field = stage_field(model, surface, curves, stage);
        let report = surface::refine(
            model, surface, curves, sizing, &field, stage, unrefined, with_feet,
        );
        (report, start.elapsed().as_secs_f64())
    };
    let mut reports: Vec<StageReport> = (refinement.stages.iter())
        .map(|stage| {
            let (report, seconds) = one(stage, true);
            StageReport {
                sources: stage.sources.iter().map(|s| s.label.clone()).collect(),
                surface: report,
                seconds: [seconds, 0.0, 0.0],
                ..Default::default()
            }
        })
        .collect();
    // A later stage's edge nodes and feet split the triangles an earlier stage built its
    // columns from (a fin stage's feet on the fin/fuselage junction, inside the fuselage
    // stage's layer triangles on the fin): each earlier stage runs once more, without feet
    // of its own, so those new nodes get their columns instead of leaving flat triangles (172° at the jet's fin root)
    // that boundary recovery cannot match.
    let last = refinement.stages.len().saturating_sub(1);
    for (stage, total) in refinement.stages[..last].iter().zip(&mut reports) {
        let (report, seconds) = one(stage, false);
        total.surface.add(&report);
        total.seconds[0] += seconds;
    }
    reports
}

/// What [`refine_volume_stages`] refines to, and who hears of its progress.
#[derive(Clone, Copy)]
pub struct Stages<'a, 'm> {
    pub sizing: &'a SizingField,
    /// One per stage, from [`stage_field`].
    pub fields: &'a [StageField<'m>],
    pub progress: Reporter<'a>,
}

/// Volume refinement and min-max swaps of every stage (`fields`, from [`stage_field`] over the
/// refined surface), in order, on the kernel's tets
/// (`region_of` per tet slot, `side` the region on a tet's side of a recovered face).
pub fn refine_volume_stages(
    stages: Stages<'_, '_>,
    dt: &mut Delaunay,
    region_of: &mut Vec<u32>,
    side: &dyn Fn(&Delaunay, u32, u8) -> Option<u32>,
    first_movable: u32,
    reports: &mut [StageReport],
) -> Vec<Option<LayerTag>> {
    let Stages {
        sizing,
        fields,
        progress,
    } = stages;
    // Interior points that smoothing or sliver removal left in the zone would break the
    // columns: they go first.
    let cleared = clear::clear_zone(dt, region_of, first_movable, &|p| {
        in_refined_zone(fields, p, sizing.spacing(p))
    });
    if let Some(r) = reports.first_mut() {
        r.cleared = cleared;
    }
    // Delaunay insertion until no candidate goes in, then min-max swaps, which reconnect the
    // tets that spanned layers without being too large; then insertion again from the
    // reconnected tets, while it adds points.
    let mut memo = swap::SwapMemo::default();
    let mut data: Vec<volume::PointData> = Vec::new();
    // Progress counts steps: per stage its columns and each insertion/swap cycle (a stage that
    // ends early jumps to its last step). A cancelled run returns at the next step with the
    // tets valid; the volume stage then reports the cancel.
    let steps_per_stage = 1 + INSERT_SWAP_CYCLES as u64;
    let total = fields.len() as u64 * steps_per_stage;
    progress.progress("refinement", 0, total);
    for (k, field) in fields.iter().enumerate() {
        let start = std::time::Instant::now();
        data.push(volume::PointData::new(dt, field, sizing));
        let d = data.last_mut().expect("pushed");
        let grown = columns::grow_columns(dt, region_of, field, sizing, d, progress);
        if let Some(r) = reports.get_mut(k) {
            r.columns = grown;
        }
        let first_step = k as u64 * steps_per_stage;
        progress.progress("refinement", first_step + 1, total);
        let mut stage_swap_seconds = 0.0;
        let mut stage_swaps = swap::SwapReport::default();
        for cycle in 0..INSERT_SWAP_CYCLES {
            if progress.cancelled() {
                return layer_tags(&data);
            }
            let d = data.last_mut().expect("pushed");
            d.extend(dt, field, sizing);
            let v = volume::refine_volume(dt, region_of, side, field, sizing, d, progress);
            let added = v.points;
            if let Some(r) = reports.get_mut(k) {
                r.volume.rounds += v.rounds;
                r.volume.points += v.points;
                r.volume.refused_on_boundary += v.refused_on_boundary;
            }
            let s0 = std::time::Instant::now();
            // Prisms first: the swaps cannot undo a flat tet between two prisms.
            let prisms = layers::reconnect(dt, region_of, &data[k].column);
            if let Some(r) = reports.get_mut(k) {
                r.layers = prisms;
            }
            // Only tets within the refined distance of this or an earlier stage's sources.
            data[k].extend(dt, field, sizing);
            let known = &data[..=k];
            let again = swap::minmax_swaps(
                dt,
                region_of,
                &|dt: &Delaunay, t| to_improve(&fields[..=k], known, dt, t),
                &mut memo,
            );
            stage_swap_seconds += s0.elapsed().as_secs_f64();
            stage_swaps.edge_swaps += again.edge_swaps;
            stage_swaps.face_swaps += again.face_swaps;
            stage_swaps.passes += again.passes;
            progress.progress("refinement", first_step + 2 + cycle as u64, total);
            if added == 0 {
                break;
            }
        }
        // Once the stage's points are all in: the tets still reaching across its layers.
        let s0 = std::time::Instant::now();
        let spans = spanning::retile_spanning(dt, region_of, &data[k].column);
        stage_swap_seconds += s0.elapsed().as_secs_f64();
        progress.progress("refinement", first_step + steps_per_stage, total);
        if let Some(r) = reports.get_mut(k) {
            r.spanning = spans;
            r.swaps = stage_swaps;
            r.seconds[1] = start.elapsed().as_secs_f64() - stage_swap_seconds;
            r.seconds[2] = stage_swap_seconds;
        }
    }
    // What is left too large, per stage, once every stage has its points.
    let start = std::time::Instant::now();
    for (d, f) in data.iter_mut().zip(fields) {
        d.extend(dt, f, sizing);
    }
    let smoothing = smooth::smooth_layers(
        dt,
        region_of,
        fields,
        &mut data,
        first_movable,
        &|dt: &Delaunay, d: &[volume::PointData], t| to_improve(fields, d, dt, t),
        &mut memo,
    );
    let flat = flat::remove_flat_tets(dt, region_of, fields, &mut data, first_movable, &mut memo);
    if let Some(r) = reports.last_mut() {
        r.smoothing = smoothing;
        r.flat = flat;
    }
    for (k, f) in fields.iter().enumerate() {
        data[k].extend(dt, f, sizing);
        if let Some(r) = reports.get_mut(k) {
            r.volume.still_too_large = volume::count_too_large(dt, region_of, f, &data[k]);
        }
    }
    if let Some(r) = reports.last_mut() {
        r.seconds[2] += start.elapsed().as_secs_f64();
    }
    layer_tags(&data)
}

/// Each kernel point's column and level, from the stages' point data (a point in the columns
/// of two stages keeps the first's).
fn layer_tags(data: &[volume::PointData]) -> Vec<Option<LayerTag>> {
    let n = data.iter().map(|d| d.column.len()).max().unwrap_or(0);
    let mut tags = vec![None; n];
    for (stage, d) in data.iter().enumerate() {
        for (tag, c) in tags.iter_mut().zip(&d.column) {
            if let (None, Some(c)) = (&tag, c) {
                *tag = Some(LayerTag {
                    stage: stage as u16,
                    source: c.source as u16,
                    root: c.root,
                    below: c.below,
                    level: c.level,
                });
            }
        }
    }
    tags
}
