use super::progress::Progress;
use crate::curve::mesh_curves;
use crate::io::vtk::{self, CellMesh};
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
    progress.say("this build meshes as far as the curves: surface and volume meshing come next");
    let out = CellMesh {
        points: curves.points.clone(),
        cells: segments.iter().map(|(_, s)| s.to_vec()).collect(),
        cell_data: vec![(
            "edge".into(),
            segments.iter().map(|(e, _)| *e as i64).collect(),
        )],
    };
    progress
        .stage("write", || vtk::write(&a.output, &out))
        .with_context(|| format!("writing {}", a.output.display()))?;
    if let Some(path) = &a.report {
        let report = json!({
            "input": a.input.display().to_string(),
            "output": a.output.display().to_string(),
            "pipeline_reached": "curves",
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
