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
}

pub fn run(a: CheckArgs) -> anyhow::Result<()> {
    let case = super::load(&a.input)?;
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
        for w in &warnings {
            println!("  {w}");
        }
    }
    Ok(())
}
