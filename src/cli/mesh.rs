use super::progress::Progress;
use crate::curve::mesh_curves;
use crate::io::vtk::{self, CellMesh};
use crate::surface::{mesh_surfaces, SurfaceOptions};
use anyhow::Context;
use clap::Args;
use serde_json::json;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct MeshArgs {
    /// Case file (.toml) or CAD file.
    pub input: PathBuf,
    /// Output mesh (.vtu or .vtk).
    #[arg(short, long, default_value = "mesh.vtu")]
    pub output: PathBuf,
    /// Override the case's background spacing.
    #[arg(long)]
    pub size: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Mesh the other faces when one fails (the failures are reported).
    #[arg(long)]
    pub keep_going: bool,
    /// Write a JSON report of timings and counts.
    #[arg(long)]
    pub report: Option<PathBuf>,
}

pub fn run(a: MeshArgs, progress: &Progress) -> anyhow::Result<()> {
    if let Some(n) = a.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build_global()
            .context("setting up the thread pool")?;
    }
    let mut case = progress.stage("load", || super::load(&a.input))?;
    if let Some(h) = a.size {
        anyhow::ensure!(
            h.is_finite() && h > 0.0,
            "--size must be a positive number, got {h}"
        );
        case.controls.size = h;
        case.sizing.uniform = h;
    }
    let curves = progress.stage("curves", || mesh_curves(&case.model, &case.sizing))?;
    let segments: Vec<(usize, [usize; 2])> = curves.segments().collect();
    progress.say(&format!(
        "curve mesh: {} nodes, {} segments on {} edges",
        curves.points.len(),
        segments.len(),
        curves.edges.len()
    ));
    let options = SurfaceOptions {
        keep_going: a.keep_going,
    };
    let (surface, failures) = progress.stage("surfaces", || {
        mesh_surfaces(&case.model, &curves, &case.sizing, options)
    })?;
    for f in &failures {
        progress.say(&format!("warning: {f} (skipped: --keep-going)"));
    }
    progress.say(&format!(
        "surface mesh: {} nodes, {} triangles on {} faces",
        surface.points.len(),
        surface.triangles.len(),
        case.model.faces.len() - failures.len()
    ));
    progress.say("this build meshes as far as the surfaces: volume meshing comes next");
    let out = CellMesh {
        points: surface.points.clone(),
        cells: surface.triangles.iter().map(|t| t.to_vec()).collect(),
        cell_data: vec![(
            "face".into(),
            surface.face_of.iter().map(|&f| f as i64).collect(),
        )],
    };
    progress
        .stage("write", || vtk::write(&a.output, &out))
        .with_context(|| format!("writing {}", a.output.display()))?;
    if let Some(path) = &a.report {
        let report = json!({
            "input": a.input.display().to_string(),
            "output": a.output.display().to_string(),
            "pipeline_reached": "surfaces",
            "failed_faces": failures.iter().map(|f| f.to_string()).collect::<Vec<_>>(),
            "surface_mesh": {
                "nodes": surface.points.len(),
                "triangles": surface.triangles.len(),
            },
            "stages": progress.stages(),
            "curve_mesh": {
                "nodes": curves.points.len(),
                "segments": segments.len(),
                "edges": curves.edges.len(),
            },
            "topology": case.model.summary(),
        });
        let text = serde_json::to_string_pretty(&report)?;
        crate::io::write_atomic(path, |w| w.write_all(text.as_bytes()))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}
