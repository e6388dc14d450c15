//! The whole pipeline in one call, for library users and tests: curves → surfaces →
//! (directional refinement of edges and faces) → volume (with the refinement's volume stage).
//! The stage order lives here only: the command line and the service call
//! [`curves_and_surfaces`] and [`volume_stage`] (or [`mesh_case_refined`]) and watch them
//! through the [`Reporter`] (stages `"curves"`, `"surfaces"`, `"volume"`, and the volume's
//! steps), which also carries cancellation. A volume stage that fails on a surface crossing
//! itself is followed by curves and surfaces again, finer there ([`crossings`]). With
//! `[mesh] prisms`, [`prisms_stage`] (stage `"prisms"`) then merges the layers into prisms;
//! [`finish`] runs it and puts the cells in the writers' order.

pub mod crossings;

use crate::case::Case;
use crate::curve::{mesh_curves, CurveError, CurveMesh};
use crate::mesh::VolumeMesh;
use crate::prisms::{PrismError, PrismReport};
use crate::progress::{Cancelled, Reporter};
use crate::refine::quality::{stretched_quality, StretchedQuality};
use crate::refine::{
    in_refined_zone, refine_surface_except, refine_volume_stages, stage_field, StageReport, Stages,
};
use crate::surface::{mesh_surfaces, SurfaceError, SurfaceMesh, SurfaceOptions};
use crate::volume::{mesh_volume_with, VolumeError, VolumeOptions, VolumeReport};
use std::collections::HashSet;

/// The first stage that failed.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    #[error(transparent)]
    Curves(#[from] CurveError),
    #[error(transparent)]
    Surfaces(#[from] SurfaceError),
    #[error(transparent)]
    Volume(#[from] VolumeError),
    #[error("meshing {0}")]
    Cancelled(#[from] Cancelled),
    /// A geometry plugin could not answer a query (the first fault of the run).
    #[error("{0}")]
    Geometry(String),
}

/// Stop when the model's plugin kernel failed a query during the last stage: the stage's
/// result was built on placeholder answers.
fn geometry_ok(case: &Case) -> Result<(), PipelineError> {
    match case.model.faults.first() {
        Some(fault) => Err(PipelineError::Geometry(fault)),
        None => Ok(()),
    }
}

/// Refuse prisms before meshing when nothing would make layers to group.
pub fn check_prisms(case: &Case) -> Result<(), PrismError> {
    let layered =
        (case.refinement.stages.iter()).any(|s| s.sources.iter().any(|x| !x.faces.is_empty()));
    if case.controls.prisms && !layered {
        return Err(PrismError::NoLayers);
    }
    Ok(())
}

/// The stage `"prisms"` when the case asks for prisms: the layers' tets merged into prisms and
/// pyramids, and the validity check run again on the hybrid mesh (its result replaces
/// `report.validity`). Should the hybrid mesh fail the check, the tet mesh is kept and the
/// report says why.
pub fn prisms_stage(
    case: &Case,
    mesh: &mut VolumeMesh,
    report: &mut VolumeReport,
    progress: Reporter,
) -> Option<PrismReport> {
    if !case.controls.prisms {
        return None;
    }
    progress.stage("prisms", || {
        let tets = mesh.clone();
        match crate::prisms::group(mesh, case.controls.prism_warp) {
            Ok(mut grouped) => {
                let validity = crate::mesh::validity::check(mesh);
                if validity.is_valid() {
                    report.validity = validity;
                } else {
                    let first = validity.defects.first().cloned().unwrap_or_default();
                    log::warn!(
                        "the hybrid mesh failed its validity check ({first}): the tets are kept"
                    );
                    grouped.reverted = Some(first);
                    *mesh = tets;
                }
                Some(grouped)
            }
            Err(e) => {
                log::warn!("{e}");
                None
            }
        }
    })
}

/// The last step before the writers: [`prisms_stage`], then the cells in the order of their
/// lowest node ([`VolumeMesh::order_cells`]).
pub fn finish(
    case: &Case,
    mesh: &mut VolumeMesh,
    report: &mut VolumeReport,
    progress: Reporter,
) -> Option<PrismReport> {
    let prisms = prisms_stage(case, mesh, report, progress);
    mesh.order_cells();
    prisms
}

/// What directional refinement did and reached, stage by stage.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct RefineOutcome {
    pub stages: Vec<StageReport>,
    pub stretched: Vec<StretchedQuality>,
}

/// Curve and surface meshes of a case (every face must mesh).
pub fn mesh_case_surfaces(case: &Case) -> Result<SurfaceMesh, PipelineError> {
    Ok(curves_and_surfaces(case, Reporter::default(), false)?.1)
}

/// The stages `"curves"` and `"surfaces"`, reported through `progress`. With `keep_going` a
/// face that fails is left out and returned with the meshes (the command line's
/// `--keep-going`); otherwise the first failure is the error.
pub fn curves_and_surfaces(
    case: &Case,
    progress: Reporter<'_>,
    keep_going: bool,
) -> Result<(CurveMesh, SurfaceMesh, Vec<SurfaceError>), PipelineError> {
    let curves = progress.stage("curves", || mesh_curves(&case.model, &case.sizing));
    geometry_ok(case)?;
    let curves = curves?;
    progress.check()?;
    let options = SurfaceOptions {
        progress,
        keep_going,
        ..Default::default()
    };
    let surfaces = progress.stage("surfaces", || {
        mesh_surfaces(&case.model, &curves, &case.sizing, options)
    });
    geometry_ok(case)?;
    let (surface, failures) = surfaces?;
    progress.check()?;
    Ok((curves, surface, failures))
}

/// The stage `"volume"`: [`volume_with_refinement`], reported through `options.progress`.
pub fn volume_stage(
    case: &Case,
    curves: &mut CurveMesh,
    surface: &mut SurfaceMesh,
    options: VolumeOptions,
) -> Result<(VolumeMesh, VolumeReport, RefineOutcome), PipelineError> {
    let volume = options.progress.stage("volume", || {
        volume_with_refinement(case, curves, surface, options)
    });
    geometry_ok(case)?;
    Ok(volume?)
}

/// The volume mesh of a case, with its report (including the validity check). The case's
/// sizing gains the local refinement of any surface re-mesh ([`crossings`]).
pub fn mesh_case(
    case: &mut Case,
    options: VolumeOptions,
) -> Result<(VolumeMesh, VolumeReport), PipelineError> {
    let (mesh, report, _) = mesh_case_refined(case, options)?;
    Ok((mesh, report))
}

/// [`mesh_case`] with the refinement's own report.
pub fn mesh_case_refined(
    case: &mut Case,
    options: VolumeOptions,
) -> Result<(VolumeMesh, VolumeReport, RefineOutcome), PipelineError> {
    let mut remeshes = Vec::new();
    loop {
        let (mut curves, mut surface, _) = curves_and_surfaces(case, options.progress, false)?;
        match volume_stage(case, &mut curves, &mut surface, options) {
            Ok((mesh, mut report, refined)) => {
                report.surface_remeshes = remeshes;
                return Ok((mesh, report, refined));
            }
            Err(PipelineError::Volume(e)) => {
                let remesh = crossings::refine_crossings(case, &surface, &e, remeshes.len())
                    .ok_or(PipelineError::Volume(e))?;
                log::warn!("{remesh}");
                remeshes.push(remesh);
            }
            Err(e) => return Err(e),
        }
    }
}

/// The volume stage, with the case's directional refinement when it has any: edges and faces
/// refined first (`surface` and `curves` gain the new nodes), then the volume, then the
/// stretched region measured on the finished mesh. When boundary recovery fails on a face
/// that got refinement points (thin layer triangles beside a sharp trailing edge on a
/// symmetry plane), the run starts again from the unrefined surface with that face's points
/// left out, a few faces at most: the columns then stop at that face instead of the run.
pub fn volume_with_refinement(
    case: &Case,
    curves: &mut CurveMesh,
    surface: &mut SurfaceMesh,
    options: VolumeOptions,
) -> Result<(VolumeMesh, VolumeReport, RefineOutcome), VolumeError> {
    if case.refinement.is_empty() {
        let (mesh, report) =
            mesh_volume_with(&case.model, surface, &case.sizing, options, None, None)?;
        return Ok((mesh, report, RefineOutcome::default()));
    }
    let (surface0, curves0) = (surface.clone(), curves.clone());
    let sources: HashSet<usize> = (case.refinement.stages.iter())
        .flat_map(|s| s.sources.iter().flat_map(|x| x.faces.clone()))
        .collect();
    let mut unrefined: HashSet<usize> = HashSet::new();
    loop {
        match refined_volume(case, curves, surface, options, &unrefined) {
            Err(VolumeError::Recovery {
                face,
                face_index: Some(f),
                at,
                detail,
            }) if !sources.contains(&f) && !unrefined.contains(&f) && unrefined.len() < RETRIES => {
                log::warn!(
                    "boundary recovery failed on {face} near {} ({detail}): meshing again with \
                     that face's refinement points left out",
                    crate::geometry::Xyz(at)
                );
                unrefined.insert(f);
                *surface = surface0.clone();
                *curves = curves0.clone();
            }
            other => return other,
        }
    }
}

/// Faces whose refinement points may be left out, one try each, before a recovery failure
/// is the run's.
const RETRIES: usize = 3;

/// One try of [`volume_with_refinement`], the faces `unrefined` without face points.
fn refined_volume(
    case: &Case,
    curves: &mut CurveMesh,
    surface: &mut SurfaceMesh,
    options: VolumeOptions,
    unrefined: &HashSet<usize>,
) -> Result<(VolumeMesh, VolumeReport, RefineOutcome), VolumeError> {
    let r = &case.refinement;
    let mut stages =
        refine_surface_except(&case.model, surface, curves, &case.sizing, r, unrefined);
    let (surface, curves) = (&*surface, &*curves);
    let fields: Vec<_> = r
        .stages
        .iter()
        .map(|s| stage_field(&case.model, surface, curves, s))
        .collect();
    let progress = options.progress;
    let mut stage = |dt: &mut _,
                     region_of: &mut _,
                     side: &dyn Fn(&_, u32, u8) -> Option<u32>,
                     first_movable| {
        let plan = Stages {
            sizing: &case.sizing,
            fields: &fields,
            progress,
        };
        refine_volume_stages(plan, dt, region_of, side, first_movable, &mut stages)
    };
    // The layers fill the refined zone: isotropic interior points stay out of it.
    let keep_out = |p: glam::DVec3, delta: f64| in_refined_zone(&fields, p, delta);
    let (mesh, report) = mesh_volume_with(
        &case.model,
        surface,
        &case.sizing,
        options,
        Some(&mut stage),
        Some(&keep_out),
    )?;
    let stretched = r
        .stages
        .iter()
        .zip(&fields)
        .enumerate()
        .map(|(k, (s, field))| {
            let faces = |s: &crate::refine::Stage| -> HashSet<usize> {
                s.sources.iter().flat_map(|x| x.faces.clone()).collect()
            };
            let others: HashSet<usize> = (r.stages.iter().enumerate())
                .filter(|&(j, _)| j != k)
                .flat_map(|(_, other)| faces(other))
                .filter(|f| !faces(s).contains(f))
                .collect();
            stretched_quality(&mesh, field, &case.sizing, &faces(s), &others)
        })
        .collect();
    Ok((mesh, report, RefineOutcome { stages, stretched }))
}
