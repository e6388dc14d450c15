//! One run of one job, on a worker thread: load the uploaded input, run the pipeline with
//! the job's observer, check the mesh, write each asked format (atomically: a result file is
//! whole or absent) and the report. Messages name the input by its name in the job's folder,
//! never by the server's paths.

use super::files::Layout;
use super::job::Options;
use crate::case::ControlOverrides;
use crate::mesh::quality::tet_quality;
use crate::pipeline::{mesh_case_refined, PipelineError};
use crate::progress::{Cancelled, Reporter};
use crate::volume::{VolumeError, VolumeOptions};
use serde_json::json;
use std::path::Path;

/// How a run ended.
pub enum Outcome {
    Done {
        report: serde_json::Value,
        results: Vec<String>,
    },
    Failed(String),
    Cancelled,
}

/// Whether `name` is a CAD file by its extension.
pub fn is_cad_name(name: &str) -> bool {
    cad_extension(name).is_some()
}

/// The lower-case CAD extension of `name` (`step`, `stp`, `iges`, `igs`, `brep`, `brp`, or
/// one a geometry plugin claims).
pub fn cad_extension(name: &str) -> Option<String> {
    let ext = Path::new(name).extension()?.to_str()?.to_ascii_lowercase();
    crate::case::is_cad_file(Path::new(name)).then_some(ext)
}

/// Mesh job `id` as `options` say, reporting through `progress`.
pub fn run(layout: &Layout, id: &str, options: &Options, progress: Reporter<'_>) -> Outcome {
    let input_dir = layout.input(id);
    // Server paths in messages become the input's own file names.
    let local = |message: String| {
        let prefix = format!("{}/", input_dir.display());
        message.replace(&prefix, "")
    };
    match mesh(layout, id, options, progress) {
        Ok((report, results)) => Outcome::Done { report, results },
        Err(RunError::Cancelled) => Outcome::Cancelled,
        Err(RunError::Failed(message)) => Outcome::Failed(local(message)),
    }
}

enum RunError {
    Cancelled,
    Failed(String),
}

impl From<Cancelled> for RunError {
    fn from(_: Cancelled) -> Self {
        RunError::Cancelled
    }
}

impl From<PipelineError> for RunError {
    fn from(e: PipelineError) -> Self {
        use crate::surface::SurfaceError;
        match e {
            PipelineError::Cancelled(_)
            | PipelineError::Surfaces(SurfaceError::Cancelled(_))
            | PipelineError::Volume(VolumeError::Cancelled(_)) => RunError::Cancelled,
            e => RunError::Failed(e.to_string()),
        }
    }
}

fn failed(e: impl std::fmt::Display) -> RunError {
    RunError::Failed(e.to_string())
}

fn mesh(
    layout: &Layout,
    id: &str,
    options: &Options,
    progress: Reporter<'_>,
) -> Result<(serde_json::Value, Vec<String>), RunError> {
    let input = layout.input(id).join(&options.input);
    let overrides = ControlOverrides {
        size: options.size,
        ..Default::default()
    };
    let mut case = progress
        .stage("load", || {
            if is_cad_name(&options.input) {
                crate::case::case_from_cad_with(&input, &overrides)
            } else {
                crate::case::load_case_with(&input, &overrides)
            }
        })
        .map_err(failed)?;
    if let Some(r) = &options.refine {
        let stage = crate::case::refine::ExtraStage {
            faces: r.faces.clone(),
            edges: r.curves.clone(),
            first: r.first,
            yplus: r.yplus,
            reynolds: r.reynolds,
            chord: r.chord,
            growth: r.growth,
            constant: r.constant,
            thickness: r.thickness,
        };
        stage
            .add_to(&mut case, |option| option.replace('-', "_"))
            .map_err(RunError::Failed)?;
    }
    progress.check()?;
    // A mistyped size would otherwise hold a worker for hours; the job's memory limit would
    // stop it too, but only after it had allocated that much.
    let estimate = crate::sizing::estimate::estimate_elements(&case.model, &case.sizing);
    crate::sizing::estimate::check_limit(
        &estimate,
        crate::sizing::estimate::default_max_elements(),
        false,
        case.controls.size,
    )
    .map_err(|e| RunError::Failed(e.to_string()))?;
    let volume_options = VolumeOptions {
        progress,
        ..Default::default()
    };
    crate::pipeline::check_prisms(&case).map_err(|e| RunError::Failed(e.to_string()))?;
    let (mut mesh, mut volume, refined) = mesh_case_refined(&mut case, volume_options)?;
    progress.check()?;
    // Quality of the tets, before any are merged into prisms.
    let quality = tet_quality(&mesh.points, &mesh.tets);
    let prisms = crate::pipeline::finish(&case, &mut mesh, &mut volume, progress);
    if !volume.validity.is_valid() {
        return Err(RunError::Failed(format!(
            "the volume mesh failed its validity check ({} defects; first: {})",
            volume.validity.defect_count,
            volume.validity.defects.first().map_or("", |s| s.as_str())
        )));
    }
    let mut results = Vec::new();
    for (name, format) in options.mesh_formats() {
        let path = layout.result(id, &name, format.extension());
        progress
            .stage("write", || crate::io::write_volume(&path, &mesh, format))
            .map_err(|e| failed(format!("writing the {name} result: {e}")))?;
        results.push(name);
        progress.check()?;
    }
    super::files::write_file(&layout.surface(id), surface_json(&mesh).as_bytes())
        .map_err(|e| failed(format!("writing the surface for the web view: {e}")))?;
    let mut report = json!({
        "input": options.input,
        "topology": case.model.summary(),
        "mesh": {
            "nodes": mesh.points.len(),
            "tets": mesh.tets.len(),
            "prisms": mesh.prisms.len(),
            "pyramids": mesh.pyramids.len(),
            "boundary_triangles": mesh.boundary.len(),
            "boundary_quads": mesh.boundary_quads.len(),
            "markers": mesh.markers.iter().map(|m| &m.name).collect::<Vec<_>>(),
            "regions": mesh.regions.iter().map(|m| &m.name).collect::<Vec<_>>(),
        },
        "volume": serde_json::to_value(&volume).map_err(failed)?,
        "quality": serde_json::to_value(&quality).map_err(failed)?,
    });
    if !refined.stages.is_empty() {
        report["refinement"] = serde_json::to_value(&refined).map_err(failed)?;
    }
    if let Some(p) = prisms {
        report["prisms"] = serde_json::to_value(&p).map_err(failed)?;
    }
    let text = serde_json::to_string_pretty(&report).map_err(failed)?;
    super::files::write_file(&layout.report(id), text.as_bytes())
        .map_err(|e| failed(format!("writing the report: {e}")))?;
    Ok((report, results))
}

/// The boundary triangles for the web page's viewer (a boundary quad as two): only the nodes
/// they use, renumbered; `points` flat `x, y, z`, `triangles` flat node triples, `marker_of`
/// an index into `markers` per triangle.
fn surface_json(mesh: &crate::mesh::VolumeMesh) -> String {
    let mut new_id = vec![u32::MAX; mesh.points.len()];
    let mut points: Vec<f32> = Vec::new();
    let mut triangles: Vec<u32> = Vec::with_capacity(mesh.boundary.len() * 3);
    let mut marker_of: Vec<u32> = Vec::with_capacity(mesh.boundary.len());
    let halves = mesh.boundary_faces().flat_map(|(f, m)| {
        let second = (f.len() == 4).then(|| [f[0], f[2], f[3]]);
        std::iter::once(([f[0], f[1], f[2]], m)).chain(second.map(|t| (t, m)))
    });
    for (t, m) in halves {
        marker_of.push(m);
        for v in t {
            let slot = &mut new_id[v as usize];
            if *slot == u32::MAX {
                *slot = (points.len() / 3) as u32;
                let p = mesh.points[v as usize];
                points.extend([p.x as f32, p.y as f32, p.z as f32]);
            }
            triangles.push(*slot);
        }
    }
    json!({
        "points": points,
        "triangles": triangles,
        "marker_of": marker_of,
        "markers": mesh.markers.iter().map(|m| &m.name).collect::<Vec<_>>(),
    })
    .to_string()
}
