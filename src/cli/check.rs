use crate::model::validate::Severity;
use clap::Args;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct CheckArgs {
    /// Case file (.toml) or CAD file.
    pub input: PathBuf,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
    /// List every face: id (as a case file's `faces = [...]` takes it), marker, extent.
    #[arg(long)]
    pub faces: bool,
    /// Check the flow domain built around the body, as `tetrafoil mesh --farfield` would.
    #[arg(long, value_name = "SHAPE:SIZE")]
    pub farfield: Option<crate::case::farfield::FarfieldSpec>,
}

pub fn run(a: CheckArgs) -> anyhow::Result<()> {
    let overrides = crate::case::ControlOverrides {
        farfield: a.farfield,
        ..Default::default()
    };
    let case = super::load_with(&a.input, &overrides)?;
    let faces = a.faces.then(|| case.model.face_summaries());
    let summary = case.model.summary();
    let warnings: Vec<String> = case
        .model
        .validate()
        .into_iter()
        .filter(|d| d.severity == Severity::Warning)
        .map(|d| d.to_string())
        .collect();
    if a.json {
        let mut v = serde_json::to_value(&summary)?;
        v["warnings"] = serde_json::json!(warnings);
        // The spacing `tetrafoil mesh` uses by default (1/20 of the diagonal for CAD files).
        v["size"] = serde_json::json!(case.controls.size);
        if let Some(faces) = &faces {
            v["face_details"] = serde_json::to_value(faces)?;
        }
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!("{}", a.input.display());
        println!(
            "  regions {}  shells {}  faces {}  edges {}  vertices {}",
            summary.regions, summary.shells, summary.faces, summary.edges, summary.vertices
        );
        println!(
            "  degenerate edges {}  embedded faces {}  embedded edges {}",
            summary.degenerate_edges, summary.embedded_faces, summary.embedded_edges
        );
        for r in &summary.region_details {
            println!(
                "  region '{}': shells (faces, volume) {:?}",
                r.name,
                r.shell_faces
                    .iter()
                    .zip(&r.shell_volumes)
                    .collect::<Vec<_>>()
            );
        }
        for f in faces.iter().flatten() {
            let [x0, y0, z0] = f.min;
            let [x1, y1, z1] = f.max;
            println!(
                "  face {:>4} {:<20} x {x0:.6e}..{x1:.6e}  y {y0:.6e}..{y1:.6e}  z {z0:.6e}..{z1:.6e}",
                f.id, f.name
            );
        }
        for w in &warnings {
            println!("  {w}");
        }
    }
    Ok(())
}
