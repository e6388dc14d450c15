//! The whole pipeline in one call, for library users and tests: curves → surfaces → volume.
//! (The command line runs the stages one by one to time and report each.)

use crate::case::Case;
use crate::curve::{mesh_curves, CurveError};
use crate::mesh::VolumeMesh;
use crate::surface::{mesh_surfaces, SurfaceError, SurfaceMesh, SurfaceOptions};
use crate::volume::{mesh_volume, VolumeError, VolumeOptions, VolumeReport};

/// The first stage that failed.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    #[error(transparent)]
    Curves(#[from] CurveError),
    #[error(transparent)]
    Surfaces(#[from] SurfaceError),
    #[error(transparent)]
    Volume(#[from] VolumeError),
}

/// Curve and surface meshes of a case (every face must mesh).
pub fn mesh_case_surfaces(case: &Case) -> Result<SurfaceMesh, PipelineError> {
    let curves = mesh_curves(&case.model, &case.sizing)?;
    let (surface, _) = mesh_surfaces(
        &case.model,
        &curves,
        &case.sizing,
        SurfaceOptions::default(),
    )?;
    Ok(surface)
}

/// The volume mesh of a case, with its report (including the validity check).
pub fn mesh_case(
    case: &Case,
    options: VolumeOptions,
) -> Result<(VolumeMesh, VolumeReport), PipelineError> {
    let surface = mesh_case_surfaces(case)?;
    Ok(mesh_volume(&case.model, &surface, &case.sizing, options)?)
}
