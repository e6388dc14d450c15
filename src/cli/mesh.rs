//! `tetrafoil mesh`: the pipeline's stages (`pipeline::curves_and_surfaces`, then
//! `pipeline::volume_stage`) watched through the CLI's [`Progress`], with timings and a quality
//! summary on stderr and in `--report`.

use super::progress::Progress;
use crate::io::{self, MeshFormat};
use crate::mesh::quality::{below_1deg, tet_quality, Below1Deg, TetQuality};
use crate::pipeline::crossings::refine_crossings;
use crate::pipeline::{curves_and_surfaces, finish, volume_stage, PipelineError, RefineOutcome};
use crate::prisms::PrismReport;
use crate::progress::Reporter;
use crate::refine::refine_surface;
use crate::sizing::estimate::{check_limit, default_max_elements, estimate_with_limits, human};
use crate::surface::surface_quality;
use crate::volume::{VolumeOptions, VolumeReport};
use anyhow::Context;
use clap::Args;
use serde_json::json;
use std::path::{Path, PathBuf};

#[derive(Args, Debug)]
pub struct MeshArgs {
    /// Case file (.toml) or CAD file (.step/.stp, .iges/.igs, .brep).
    pub input: PathBuf,
    /// Output mesh; the extension picks the format (.su2, .msh, .mesh, .vtu, .vtk, .ugrid,
    /// .lb8.ugrid, .b8.ugrid — with a .mapbc beside —, .cgns, .stl)
    /// unless --format is given. Repeat `-o` to write several files from one run.
    #[arg(short, long, default_value = "mesh.vtu")]
    pub output: Vec<PathBuf>,
    /// Output format (default: by the output's extension; `msh` is Gmsh 4.1, `msh22` 2.2).
    #[arg(long, value_enum)]
    pub format: Option<MeshFormat>,
    /// Write `.vtu` output binary: appended data, zlib-compressed (several times smaller and
    /// faster to write than ASCII; ParaView, VTK and meshio read it).
    #[arg(long)]
    pub binary: bool,
    /// Merge the stretched layers' tets into prisms (and pyramids where a prism meets tets):
    /// a conforming hybrid mesh with fewer cells. Needs directional refinement.
    #[arg(long)]
    pub prisms: bool,
    /// With --prisms: a side quad warped more than this many degrees (between its two
    /// triangles) stays two triangles, and its prism three tets [default: 20].
    #[arg(long, value_name = "DEGREES")]
    pub prism_warp: Option<f64>,
    /// Build the flow domain around the body: shape box, sphere, half-box or half-sphere
    /// (cut by the body's symmetry plane; a native body: box or half-box), and the distance
    /// in body lengths, e.g. `--farfield half-sphere:50`. Faces come out named farfield,
    /// symmetry and the body's.
    #[arg(long, value_name = "SHAPE:SIZE")]
    pub farfield: Option<crate::case::farfield::FarfieldSpec>,
    /// `auto`: a wake sheet from every trailing edge found on the body (two faces meeting in
    /// a thin wedge facing downstream), along the free stream to the far field, embedded and
    /// named wake_1, wake_2, … (usable in --refine-faces).
    #[arg(long, value_enum, value_name = "MODE")]
    pub wakes: Option<WakesMode>,
    /// With --wakes auto: angle of attack in degrees (the free stream tilts from +x to +z).
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    pub alpha: Option<f64>,
    /// With --wakes auto: sideslip in degrees (the free stream turns from +x to +y).
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    pub beta: Option<f64>,
    /// With --wakes auto: the wakes' length in the model's unit (default: to the far field
    /// tetrafoil built, less one far-field cell).
    #[arg(long, value_name = "LENGTH")]
    pub wake_length: Option<f64>,
    /// Override the case's background spacing (with --farfield: the body's spacing).
    #[arg(long)]
    pub size: Option<f64>,
    /// Override the curvature limit δ ≤ 2πR/N (segments per circle; 0 turns it off).
    #[arg(long, value_name = "N")]
    pub curvature_segments: Option<f64>,
    /// Override the proximity limit δ ≤ w/N across faces only w wide (0 turns it off).
    #[arg(long, value_name = "N")]
    pub proximity_cells: Option<f64>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Mesh the other faces when one fails; write a mesh that fails the validity check under
    /// a name marked `.invalid` (the exit status is still an error).
    #[arg(long)]
    pub keep_going: bool,
    /// Stop after the surfaces and write the surface mesh.
    #[arg(long)]
    pub surface_only: bool,
    /// Write a JSON report of timings, counts and quality.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Directional refinement from these faces (names or 0-based CAD ids, comma-separated):
    /// one more stage after the case's own `[[refine]]` stages, with --first and --growth.
    #[arg(long, value_delimiter = ',', value_name = "FACES")]
    pub refine_faces: Vec<String>,
    /// Directional refinement from these edges (names or ids), in the same stage.
    #[arg(long, value_delimiter = ',', value_name = "EDGES")]
    pub refine_curves: Vec<String>,
    /// First spacing next to the refinement source.
    #[arg(long)]
    pub first: Option<f64>,
    /// Instead of --first: the first layer for this y+ by the flat-plate estimate
    /// (Cf = 0.026 Re^-1/7), with --reynolds and --chord.
    #[arg(long)]
    pub yplus: Option<f64>,
    /// With --yplus: the Reynolds number.
    #[arg(long)]
    pub reynolds: Option<f64>,
    /// With --yplus: the length the Reynolds number is based on, in the model's unit.
    #[arg(long)]
    pub chord: Option<f64>,
    /// Growth ratio of the layer spacing.
    #[arg(long, default_value_t = 1.2)]
    pub growth: f64,
    /// Layers of spacing --first next to the source.
    #[arg(long, default_value_t = 3)]
    pub constant: usize,
    /// Refine no farther than this from the source.
    #[arg(long)]
    pub thickness: Option<f64>,
    /// Refuse to mesh when the sizing asks for more elements than this (tets; triangles with
    /// --surface-only), estimated before meshing. Default: what fits in 3/4 of this
    /// machine's memory.
    #[arg(long, value_name = "N")]
    pub max_elements: Option<f64>,
}

/// The command line's refinement stage, appended to the case's.
fn cli_stage(a: &MeshArgs, case: &mut crate::case::Case) -> anyhow::Result<()> {
    let stage = crate::case::refine::ExtraStage {
        faces: a.refine_faces.clone(),
        edges: a.refine_curves.clone(),
        first: a.first,
        yplus: a.yplus,
        reynolds: a.reynolds,
        chord: a.chord,
        growth: a.growth,
        constant: a.constant,
        thickness: a.thickness,
    };
    stage
        .add_to(case, |option| format!("--{option}"))
        .map_err(|m| anyhow::anyhow!(m))
}

pub fn run(a: MeshArgs, progress: &Progress) -> anyhow::Result<()> {
    if let Some(n) = a.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build_global()
            .context("setting up the thread pool")?;
    }
    anyhow::ensure!(
        a.format.is_none() || a.output.len() == 1,
        "--format applies to a single output; with several -o, each extension picks its format"
    );
    let outputs: Vec<(PathBuf, MeshFormat)> = a
        .output
        .iter()
        .map(|path| {
            let format = match a.format {
                Some(f) => Some(f),
                None => MeshFormat::from_path(path),
            };
            format.map(|f| (path.clone(), f)).with_context(|| {
                format!(
                    "cannot tell the format of {} from its extension; use .su2, .msh, .mesh, \
                     .vtu, .vtk, .ugrid, .lb8.ugrid, .b8.ugrid, .cgns or .stl, or give --format",
                    path.display()
                )
            })
        })
        .collect::<anyhow::Result<_>>()?;
    let outputs: Vec<(PathBuf, MeshFormat)> = if a.binary {
        anyhow::ensure!(
            outputs
                .iter()
                .any(|(_, f)| matches!(f, MeshFormat::Vtu | MeshFormat::VtuBinary)),
            "--binary applies to .vtu output, and no output is .vtu"
        );
        outputs
            .into_iter()
            .map(|(p, f)| match f {
                MeshFormat::Vtu => (p, MeshFormat::VtuBinary),
                f => (p, f),
            })
            .collect()
    } else {
        outputs
    };
    if let Some(h) = a.size {
        anyhow::ensure!(
            h.is_finite() && h > 0.0,
            "--size must be a positive number, got {h}"
        );
    }
    if let Some(n) = a.curvature_segments {
        anyhow::ensure!(
            crate::case::curvature_segments_ok(n),
            "--curvature-segments must be 0 (off) or at least 3, got {n}"
        );
    }
    if let Some(n) = a.proximity_cells {
        anyhow::ensure!(
            n.is_finite() && n >= 0.0,
            "--proximity-cells must be 0 (off) or a positive number, got {n}"
        );
    }
    let overrides = crate::case::ControlOverrides {
        size: a.size,
        curvature_segments: a.curvature_segments,
        proximity_cells: a.proximity_cells,
        prisms: a.prisms,
        prism_warp: a.prism_warp,
        farfield: a.farfield,
        wakes: auto_wakes(&a)?,
    };
    if let Some(w) = a.prism_warp {
        anyhow::ensure!(
            crate::case::prism_warp_ok(w),
            "--prism-warp must be between 0 and 90 degrees, got {w}"
        );
    }
    if let Some(n) = a.max_elements {
        anyhow::ensure!(
            n.is_finite() && n >= 1.0,
            "--max-elements must be a positive number, got {n}"
        );
    }
    let mut case = progress.stage("load", || super::load_with(&a.input, &overrides))?;
    cli_stage(&a, &mut case)?;
    crate::pipeline::check_prisms(&case)?;
    progress.record(
        "sizing",
        case.sizing.limits_seconds,
        "(curvature and proximity limits, built while loading)",
    );
    let estimate = progress.stage("estimate", || {
        estimate_with_limits(&case.model, &case.sizing, a.surface_only)
    });
    let unit = if a.surface_only { "triangles" } else { "tets" };
    progress.say(&format!(
        "estimate: about {} surface triangles and {} tets before refinement ({} {unit} from \
         the curvature limit, {} from the proximity limit)",
        human(estimate.total.triangles),
        human(estimate.total.tets),
        human(estimate.added_by_curvature),
        human(estimate.added_by_proximity),
    ));
    check_limit(
        &estimate.total,
        a.max_elements.unwrap_or_else(default_max_elements),
        a.surface_only,
        case.controls.size,
    )
    .with_context(|| format!("{}", a.input.display()))?;
    let mut remeshes = Vec::new();
    let (mut mesh, mut volume, refined, mut report) = loop {
        let (mut curves, mut surface, failures) =
            curves_and_surfaces(&case, Reporter::new(progress), a.keep_going)?;
        let segments = curves.segments().count();
        progress.say(&format!(
            "curve mesh: {} nodes, {segments} segments on {} edges",
            curves.points.len(),
            curves.edges.len()
        ));
        for f in &failures {
            progress.say(&format!("warning: {f} (skipped: --keep-going)"));
        }
        progress.say(&format!(
            "surface mesh: {} nodes, {} triangles on {} faces",
            surface.points.len(),
            surface.triangles.len(),
            case.model.faces.len() - failures.len()
        ));
        let sq = surface_quality(&case.model, &surface, &case.sizing);
        progress.say(&format!(
            "surface quality: min angle {:.1}°, {} triangles below 25° ({} at CAD corners sharper \
         than 25°, {} in gaps narrower than the size floor), {:.1}% of edges within [0.6, 1.5]·δ",
            sq.min_angle,
            sq.below_25deg,
            sq.forced_by_corner,
            sq.forced_by_size_floor,
            100.0 * sq.length_share()
        ));
        let mut report = json!({
            "input": a.input.display().to_string(),
            "estimate": estimate,
            "failed_faces": failures.iter().map(|f| f.to_string()).collect::<Vec<_>>(),
            "topology": case.model.summary(),
            "curve_mesh": {
                "nodes": curves.points.len(),
                "segments": segments,
                "edges": curves.edges.len(),
            },
            "surface_mesh": {
                "nodes": surface.points.len(),
                "triangles": surface.triangles.len(),
                "split_faces": surface.split_faces(),
                "quality": sq,
            },
        });
        if a.surface_only {
            // The surface as the volume stage would take it: with the layers' edge and face points.
            if !case.refinement.is_empty() {
                let stages = progress.stage("refine surface", || {
                    refine_surface(
                        &case.model,
                        &mut surface,
                        &mut curves,
                        &case.sizing,
                        &case.refinement,
                    )
                });
                report["refinement"] = serde_json::to_value(&stages)?;
                progress.say(&format!(
                    "refined surface mesh: {} nodes, {} triangles",
                    surface.points.len(),
                    surface.triangles.len()
                ));
            }
            let names: Vec<String> = (0..case.model.faces.len())
                .map(|f| case.model.face_marker(f))
                .collect();
            for (path, format) in &outputs {
                progress
                    .stage("write", || {
                        io::write_surface(path, &surface, &names, *format)
                    })
                    .with_context(|| format!("writing {}", path.display()))?;
            }
            report["output"] = json!(a.output);
            report["pipeline_reached"] = json!("surfaces");
            report["stages"] = json!(progress.stages());
            return write_report(a.report.as_deref(), &report);
        }
        anyhow::ensure!(
            failures.is_empty(),
            "{} face(s) could not be meshed, so no volume mesh can be made; \
         use --surface-only to write the surface mesh of the others",
            failures.len()
        );
        let options = VolumeOptions {
            progress: Reporter::new(progress),
            ..Default::default()
        };
        match volume_stage(&case, &mut curves, &mut surface, options) {
            Ok((mesh, mut volume, refined)) => {
                volume.surface_remeshes = std::mem::take(&mut remeshes);
                break (mesh, volume, refined, report);
            }
            Err(PipelineError::Volume(e)) => {
                let remesh = refine_crossings(&mut case, &surface, &e, remeshes.len())
                    .ok_or(PipelineError::Volume(e))?;
                progress.say(&format!("warning: {remesh}"));
                remeshes.push(remesh);
            }
            Err(e) => return Err(e.into()),
        }
    };
    say_refinement(progress, &refined);
    let quality = tet_quality(&mesh.points, &mesh.tets);
    let below = below_1deg(&mesh);
    say_volume(progress, &volume, mesh.points.len(), &quality, &below);
    report["volume"] = serde_json::to_value(&volume)?;
    if !refined.stages.is_empty() {
        report["refinement"] = serde_json::to_value(&refined)?;
    }
    report["quality"] = serde_json::to_value(&quality)?;
    report["quality"]["below_1deg_split"] = serde_json::to_value(below)?;
    report["pipeline_reached"] = json!("volume");
    if let Some(p) = finish(&case, &mut mesh, &mut volume, Reporter::new(progress)) {
        say_prisms(progress, &p);
        report["prisms"] = serde_json::to_value(&p)?;
        report["volume"]["validity"] = serde_json::to_value(&volume.validity)?;
    }
    let valid = volume.validity.is_valid();
    let written: Vec<PathBuf> = outputs
        .iter()
        .map(|(p, _)| if valid { p.clone() } else { invalid_name(p) })
        .collect();
    if valid || a.keep_going {
        for ((_, format), path) in outputs.iter().zip(&written) {
            progress
                .stage("write", || io::write_volume(path, &mesh, *format))
                .with_context(|| format!("writing {}", path.display()))?;
        }
        report["output"] = json!(written);
    }
    report["stages"] = json!(progress.stages());
    write_report(a.report.as_deref(), &report)?;
    if !valid {
        anyhow::bail!(
            "the volume mesh failed its validity check ({} defects; first: {}){}",
            volume.validity.defect_count,
            volume.validity.defects.first().map_or("", |s| s.as_str()),
            if a.keep_going {
                format!("; written anyway as {written:?}")
            } else {
                "; nothing written (--keep-going writes it under an .invalid name)".into()
            }
        );
    }
    Ok(())
}

/// The volume stage's summary; `points` is the finished mesh's count (the boundary and
/// isotropic interior points, then the recovery's Steiner points and refinement's layers).
fn say_prisms(progress: &Progress, p: &PrismReport) {
    progress.say(&format!(
        "prisms: {} tets → {} prisms + {} pyramids + {} tets ({} cells, {:.1}% fewer; in the \
         layers {} → {} cells, {:.1}% fewer); {} layers; {} boundary quads; worst side-quad warp \
         {:.2}° (allowed {}°); prism skew p50/max {:.1}°/{:.1}°, aspect p50/max {:.0}/{:.0}",
        p.tets_before,
        p.prisms,
        p.pyramids,
        p.tets,
        p.cells,
        100.0 * (1.0 - p.cells as f64 / p.cells_before.max(1) as f64),
        p.layer_cells_before,
        p.layer_cells,
        100.0 * p.layer_reduction,
        p.layers,
        p.boundary_quads,
        p.max_warp,
        p.max_warp_allowed,
        p.skew_p50,
        p.skew_max,
        p.aspect_p50,
        p.aspect_max,
    ));
    progress.say(&format!(
        "  candidates {} (left as tets: {} by shape, {} by warp, {} unmatched beside tets; {} \
         triples not filling a prism)",
        p.candidates, p.refused_shape, p.refused_warp, p.refused_unmatched, p.refused_not_filling
    ));
    if p.stages.len() > 1 {
        let per: Vec<String> = (p.stages.iter())
            .map(|s| {
                format!(
                    "stage {}: {} → {} ({:.1}% fewer)",
                    s.stage + 1,
                    s.layer_cells_before,
                    s.layer_cells,
                    100.0 * s.layer_reduction
                )
            })
            .collect();
        progress.say(&format!("  layer cells by stage: {}", per.join("; ")));
    }
    if let Some(d) = &p.reverted {
        progress.say(&format!(
            "warning: the hybrid mesh failed its validity check ({d}); the tets are kept"
        ));
    }
}

fn say_volume(
    progress: &Progress,
    v: &VolumeReport,
    points: usize,
    q: &TetQuality,
    below: &Below1Deg,
) {
    let r = &v.recovery;
    // Whatever is not a boundary or isotropic interior point: Steiner points left in, sliver
    // points, and the refinement's layers.
    let other = points.saturating_sub(v.boundary_points + v.interior.points);
    for (stage, s) in &v.seconds {
        progress.say(&format!("  {stage:<14} {s:>9.3} s"));
    }
    progress.say(&format!(
        "volume mesh: {} tets, {} points ({} boundary + {} isotropic interior + {} more: \
         refinement, sliver and Steiner points); recovery: {} flips, \
         Steiner points {} on edges + {} on faces, {} taken off the surface again ({} of them \
         moved into the volume), {} left on it",
        q.tets,
        points,
        v.boundary_points,
        v.interior.points,
        other,
        r.flips,
        r.steiner_on_edges,
        r.steiner_on_faces,
        r.steiner_removed,
        r.steiner_interior,
        r.steiner_left_on_surface
    ));
    progress.say(&format!(
        "quality: dihedral {:.2}°..{:.2}°, radius ratio min {:.3} mean {:.3}; \
         tets below 1°/5°/10°: {}/{}/{} (below 1°: {} forced by a needle surface triangle or \
         knife edge, {} not)",
        q.min_dihedral,
        q.max_dihedral,
        q.radius_ratio.min,
        q.radius_ratio.mean,
        q.below_1deg,
        q.below_5deg,
        q.below_10deg,
        below.forced_by_surface,
        below.unforced
    ));
    let h: Vec<String> = q
        .radius_ratio_histogram
        .iter()
        .map(|c| c.to_string())
        .collect();
    progress.say(&format!("radius ratio deciles: {}", h.join(" ")));
}

fn say_refinement(progress: &Progress, r: &RefineOutcome) {
    for (k, (s, q)) in r.stages.iter().zip(&r.stretched).enumerate() {
        progress.say(&format!(
            "refinement stage {} ({}): {} edge + {} face points, {} volume points in {} rounds, \
             {} edge + {} face swaps; {} tets still too large \
             ({:.2} s edges and faces, {:.2} s volume, {:.2} s swaps)",
            k + 1,
            s.sources.join("; "),
            s.surface.edge_points,
            s.surface.face_points,
            s.volume.points,
            s.volume.rounds,
            s.swaps.edge_swaps,
            s.swaps.face_swaps,
            s.volume.still_too_large,
            s.seconds[0],
            s.seconds[1],
            s.seconds[2]
        ));
        progress.say(&format!(
            "  stretched region: {} tets, max dihedral p50 {:.1}° p90 {:.1}° p99 {:.1}° max \
             {:.1}°; aspect ratio p50 {:.0} max {:.0}; first layer / first: p10 {:.2} p50 {:.2} \
             p90 {:.2} over {} wall nodes",
            q.tets,
            q.max_dihedral.p50,
            q.max_dihedral.p90,
            q.max_dihedral.p99,
            q.max_dihedral.max,
            q.aspect_ratio.p50,
            q.aspect_ratio.max,
            q.first_layer_ratio.p10,
            q.first_layer_ratio.p50,
            q.first_layer_ratio.p90,
            q.wall_nodes
        ));
        if q.junction_nodes > 0 {
            let j = &q.junction_first_layer_ratio;
            progress.say(&format!(
                "  at junctions with other stages' walls: first layer / first p10 {:.2} p50 {:.2} \
                 p90 {:.2} over {} wall nodes",
                j.p10, j.p50, j.p90, q.junction_nodes
            ));
        }
        let f = &s.flat;
        if f.found > 0 {
            progress.say(&format!(
                "  tets above {:.0}° after smoothing: {} ({} vertex moves, {} edges split, {} collapses, {} points inserted, \
                 {} swaps); {} left",
                crate::refine::flat::FLAT_ABOVE,
                f.found,
                f.moved,
                f.split,
                f.collapsed,
                f.inserted,
                f.swaps.edge_swaps + f.swaps.face_swaps,
                f.left
            ));
        }
    }
}

/// `wing.su2` → `wing.invalid.su2`.
fn invalid_name(path: &Path) -> PathBuf {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
    let name = match path.extension().and_then(|e| e.to_str()) {
        Some(ext) => format!("{stem}.invalid.{ext}"),
        None => format!("{stem}.invalid"),
    };
    path.with_file_name(name)
}

fn write_report(path: Option<&Path>, report: &serde_json::Value) -> anyhow::Result<()> {
    if let Some(path) = path {
        let text = serde_json::to_string_pretty(report)?;
        crate::io::write_atomic(path, |w| w.write_all(text.as_bytes()))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}

/// `--wakes`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum WakesMode {
    /// Wakes from every trailing edge found.
    Auto,
}

/// `--wakes auto` with its angles and length, checked.
fn auto_wakes(a: &MeshArgs) -> anyhow::Result<Option<crate::case::AutoWakes>> {
    for (v, flag) in [(a.alpha, "--alpha"), (a.beta, "--beta")] {
        if let Some(x) = v {
            anyhow::ensure!(
                x.is_finite() && x.abs() < 90.0,
                "{flag} must be an angle in degrees between -90 and 90, got {x}"
            );
        }
    }
    if let Some(l) = a.wake_length {
        anyhow::ensure!(
            l.is_finite() && l > 0.0,
            "--wake-length must be a positive length, got {l}"
        );
    }
    if a.wakes.is_none() {
        let given = [
            (a.alpha.is_some(), "--alpha"),
            (a.beta.is_some(), "--beta"),
            (a.wake_length.is_some(), "--wake-length"),
        ];
        if let Some((_, flag)) = given.iter().find(|(g, _)| *g) {
            anyhow::bail!("{flag} goes with --wakes auto (it sets the automatic wakes)");
        }
        return Ok(None);
    }
    Ok(Some(crate::case::AutoWakes {
        alpha: a.alpha.unwrap_or(0.0),
        beta: a.beta.unwrap_or(0.0),
        length: a.wake_length,
    }))
}
