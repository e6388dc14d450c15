//! The command line: `tetrafoil mesh`, `check`, `quality`, `plugins`, and the service's
//! `serve` and `submit`.

mod check;
mod logger;
mod mesh;
mod plugins;
mod progress;
mod quality;
mod serve;
mod submit;

use clap::{Parser, Subcommand};

#[derive(Parser, Debug)]
#[command(
    name = "tetrafoil",
    version,
    about = "Tetrahedral meshes with directional refinement for aerodynamic CFD"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// No progress, timings or notes on stderr.
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// Debug records too (the parallel kernel's passes, a stuck advancing front).
    #[arg(long, short, global = true)]
    pub verbose: bool,
    /// Load this geometry plugin (a shared library implementing include/tetrafoil_geometry.h)
    /// before those found in TETRAFOIL_PLUGIN_PATH and beside the executable; repeatable.
    #[arg(long = "plugin", global = true, value_name = "PATH")]
    pub plugins: Vec<std::path::PathBuf>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Mesh a case file (or CAD file) as far as the pipeline goes.
    Mesh(Box<mesh::MeshArgs>),
    /// Load and validate a case, print a topology summary.
    Check(check::CheckArgs),
    /// Quality summary of a mesh file (.vtu or .vtk).
    Quality(quality::QualityArgs),
    /// Run the mesh service (HTTP API, job queue, workers): see docs/service.md.
    Serve(serve::ServeArgs),
    /// Send a file to a running service; --wait follows it, -o downloads the result.
    Submit(submit::SubmitArgs),
    /// List the geometry plugins found, their versions and the extensions they read.
    Plugins,
}

/// Run the command line; errors go to the caller, which prints them and exits non-zero.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    logger::init(cli.quiet, cli.verbose);
    for path in &cli.plugins {
        crate::geometry::plugin::add_path(path)?;
    }
    let progress = progress::Progress::new(!cli.quiet);
    match cli.command {
        Command::Mesh(a) => mesh::run(*a, &progress),
        Command::Check(a) => check::run(a),
        Command::Quality(a) => quality::run(a),
        Command::Serve(a) => serve::run(a),
        Command::Submit(a) => submit::run(a, cli.quiet),
        Command::Plugins => plugins::run(),
    }
}

/// What kind of input a path is, by extension: CAD (OpenCASCADE's or a plugin's) or a case.
pub fn is_cad(path: &std::path::Path) -> bool {
    crate::case::is_cad_file(path)
}

/// A case file or a CAD file, with mesh controls from the command line.
pub(crate) fn load_with(
    path: &std::path::Path,
    overrides: &crate::case::ControlOverrides,
) -> anyhow::Result<crate::case::Case> {
    if is_cad(path) {
        return Ok(crate::case::case_from_cad_with(path, overrides)?);
    }
    Ok(crate::case::load_case_with(path, overrides)?)
}
