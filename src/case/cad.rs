//! CAD input: a STEP, IGES or BREP file as a whole case (`tetrafoil mesh part.step`) or as the
//! model of a case file (`[mesh] cad = "part.step"`).
//!
//! A file whose faces form no solid (a surface set) is sewn at growing tolerances ([`SEW_STEPS`]
//! of the model's bounding-box diagonal, and the file's own largest edge tolerance when it lies
//! between them), then once more after ShapeFix healing; what was done is said on stderr. If
//! sewing makes no solid, the error names the tolerances tried, the free edges and their faces. Several solids (an assembly) go
//! through OCCT's general fuse, so touching solids share their contact faces. A far field
//! (`farfield.rs`) makes the body the hole in a flow domain.

use super::controls::{Case, ControlOverrides, MeshControls, SEW_STEPS};
use super::error::CaseError;
use super::farfield::{FarfieldSpec, FlowDomain};
use crate::model::Model;
use crate::sizing::SizingField;
use std::path::Path;

/// Default curvature limit for CAD input: δ ≤ 2πR/12, floored at size/100.
pub const CURVATURE_SEGMENTS: f64 = 12.0;

/// Extensions the built-in OpenCASCADE bridge reads (when built with it).
pub const OCCT_EXTENSIONS: [&str; 6] = ["step", "stp", "iges", "igs", "brep", "brp"];

/// Whether `path` is a CAD file by its extension: one OpenCASCADE reads, or one a geometry
/// plugin claims.
pub fn is_cad_file(path: &Path) -> bool {
    let Some(ext) = path.extension().and_then(|e| e.to_str()) else {
        return false;
    };
    OCCT_EXTENSIONS.iter().any(|x| x.eq_ignore_ascii_case(ext))
        || crate::geometry::plugin::registry().for_path(path).is_some()
}

/// A CAD file as a case: the oriented model, spacing 1/20 of the bounding-box diagonal (the
/// command line's `--size` overrides it), tolerance 1e-6 of the diagonal, curvature limit on.
pub fn case_from_cad(path: &Path) -> Result<Case, CaseError> {
    case_from_cad_with(path, &ControlOverrides::default())
}

/// [`case_from_cad`] with some mesh controls replaced (the size floor stays 1/100 of the
/// default size).
pub fn case_from_cad_with(path: &Path, overrides: &ControlOverrides) -> Result<Case, CaseError> {
    let (model, extent, domain) =
        load_cad_model(path, overrides.farfield).map_err(CaseError::Cad)?;
    let size = extent / 20.0;
    let mut controls = MeshControls {
        size,
        curvature_segments: CURVATURE_SEGMENTS,
        proximity_cells: super::controls::PROXIMITY_CELLS,
        min_size: size / 100.0,
        tolerance: 1e-6 * extent,
        prisms: false,
        prism_warp: crate::prisms::DEFAULT_MAX_WARP_DEGREES,
    };
    overrides.apply(&mut controls);
    let mut sizing = SizingField::uniform(controls.size);
    if let Some(domain) = &domain {
        super::farfield::size_domain(&mut sizing, &model, domain, controls.size);
    }
    sizing.set_local_limits(&model, &controls);
    if let Some(fault) = model.faults.first() {
        return Err(CaseError::Cad(fault));
    }
    Ok(Case {
        model,
        controls,
        sizing,
        refinement: Default::default(),
    })
}

/// The oriented, validated model of a CAD file and the diagonal of its bounding box; with a
/// far field, the flow domain around it (the diagonal still the body's).
/// Errors are messages naming the file and, for topology problems, the faces and edges.
/// A file whose extension a geometry plugin claims is read by that plugin
/// ([`super::plugin_model`]); STEP, IGES and BREP otherwise by the built-in OpenCASCADE bridge.
pub(crate) fn load_cad_model(
    path: &Path,
    farfield: Option<FarfieldSpec>,
) -> Result<(Model, f64, Option<FlowDomain>), String> {
    match crate::geometry::plugin::registry().for_path(path) {
        Some(plugin) => super::plugin_model::load_plugin_model(plugin, path, farfield),
        None => load_occt_model(path, farfield),
    }
}

#[cfg(feature = "occt")]
fn load_occt_model(
    path: &Path,
    farfield: Option<FarfieldSpec>,
) -> Result<(Model, f64, Option<FlowDomain>), String> {
    use crate::model::cad::model_from_cad;
    use tetrafoil_occt::CadModel;

    let cad = CadModel::read(path).map_err(|e| e.to_string())?;
    let extent = cad
        .bounding_box()
        .map_err(|e| e.to_string())?
        .map(|b| b.diagonal())
        .filter(|d| d.is_finite() && *d > 0.0)
        .ok_or_else(|| format!("{}: the model is empty (no bounding box)", cad.file()))?;
    let cad = if cad.topology().solids.is_empty() {
        sew_into_solid(cad, extent)?
    } else {
        skip_construction_faces(cad)?
    };
    // An assembly's solids touch without sharing faces (a bolt head on a bracket): imprint
    // the contacts so the regions meet on one conforming interface.
    let cad = if cad.topology().solids.len() >= 2 {
        // Fuzzy at the model tolerance: a bolt head tangent to a plate's edge otherwise
        // leaves two vertices microns apart (l_bracket_assembly.step), a pinch no mesh closes.
        let (fused, report) = cad.fuse_solids(1e-6 * extent).map_err(|e| e.to_string())?;
        if report.after != report.before {
            log::warn!(
                "{} has {} solids: imprinted their contacts (general fuse): {} solids, {} faces (were {})",
                cad.file(),
                report.before.solids,
                report.after.solids,
                report.after.faces,
                report.before.faces
            );
        }
        fused
    } else {
        cad
    };
    let (cad, domain) = match farfield {
        Some(spec) => {
            let (cad, domain) = super::farfield::build_domain(cad, spec, extent)?;
            (cad, Some(domain))
        }
        None => (cad, None),
    };
    let model = model_from_cad(&cad).map_err(|e| e.to_string())?;
    Ok((model, extent, domain))
}

/// Sew a file's faces into a solid: at each tolerance of [`sewing_tolerances`] in turn, then,
/// if every one leaves the shells open, once more at the widest after ShapeFix healing (gaps
/// inside a face's own wires, tiny edges). The error says what was tried and where it is open.
#[cfg(feature = "occt")]
fn sew_into_solid(
    cad: tetrafoil_occt::CadModel,
    extent: f64,
) -> Result<tetrafoil_occt::CadModel, String> {
    use crate::model::cad::open_boundary_diagnosis;
    let tolerances = sewing_tolerances(&cad, extent);
    let mut tried = Vec::new();
    let mut last = None;
    let widest = tolerances.last().copied().unwrap_or(extent * SEW_STEPS[0]);
    // Each tolerance as the file is, then the widest once more after healing.
    let attempts = tolerances
        .iter()
        .map(|&t| (t, false))
        .chain(std::iter::once((widest, true)));
    for (tol, heal) in attempts {
        let healed;
        let source = if heal {
            healed = cad.heal(tol).map_err(|e| e.to_string())?.0;
            &healed
        } else {
            &cad
        };
        let (sewn, report) = source.sew(tol).map_err(|e| e.to_string())?;
        tried.push(format!(
            "{tol:.3e}{}",
            if heal { " after healing" } else { "" }
        ));
        if !sewn.topology().solids.is_empty() {
            log::warn!(
                "{} has no solid: {} its {} faces at tolerance {tol:.3e} into {} solid(s) ({} free edges left)",
                cad.file(),
                if heal { "healed (ShapeFix) and sewed" } else { "sewed" },
                report.before.faces,
                sewn.topology().solids.len(),
                report.free_edges
            );
            return Ok(sewn);
        }
        if !heal {
            last = Some(sewn);
        }
    }
    let diagnosed = last.as_ref().unwrap_or(&cad);
    Err(format!(
        "{}: contains no solid, and sewing at tolerance {} closes none: {}",
        cad.file(),
        tried.join(" then "),
        open_boundary_diagnosis(diagnosed, 12)
    ))
}

/// The tolerances [`sew_into_solid`] tries, ascending: [`SEW_STEPS`] of the diagonal, and the
/// file's own largest edge tolerance (a little over it) where it lies between the first and the
/// last step — the gap the exporting system said its edges may have.
#[cfg(feature = "occt")]
fn sewing_tolerances(cad: &tetrafoil_occt::CadModel, extent: f64) -> Vec<f64> {
    let mut tolerances: Vec<f64> = SEW_STEPS.iter().map(|r| r * extent).collect();
    let own = cad
        .topology()
        .edges
        .iter()
        .map(|e| e.tolerance)
        .fold(0.0, f64::max)
        * 1.5;
    let (lo, hi) = (tolerances[0], tolerances[tolerances.len() - 1]);
    if own > lo && own < hi && tolerances.iter().all(|t| (own / t - 1.0).abs() > 0.1) {
        tolerances.push(own);
        tolerances.sort_by(f64::total_cmp);
    }
    tolerances
}

/// A file with solids may also carry surfaces and open shells beside them (construction
/// geometry, `SHELL_BASED_SURFACE_MODEL` items): they bound no volume, and meshed with the
/// solid they made its surface cross itself or enclose no consistent volume. They are left
/// out, with a note naming them.
#[cfg(feature = "occt")]
fn skip_construction_faces(
    cad: tetrafoil_occt::CadModel,
) -> Result<tetrafoil_occt::CadModel, String> {
    let outside = cad.faces_outside_solids();
    if outside.is_empty() {
        return Ok(cad);
    }
    let t = cad.topology();
    let named: Vec<String> = outside
        .iter()
        .take(8)
        .map(|&f| match &t.faces[f].name {
            Some(n) => format!("face {f} '{n}'"),
            None => format!("face {f}"),
        })
        .collect();
    let more = outside.len().saturating_sub(named.len());
    let kept = cad.solids_only().map_err(|e| e.to_string())?;
    log::warn!(
        "{}: {} face(s) belong to no solid and are not meshed (construction geometry beside the \
         {} solid(s)): {}{}; face ids below are those of the solids alone",
        cad.file(),
        outside.len(),
        t.solids.len(),
        named.join(", "),
        if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        }
    );
    Ok(kept)
}

#[cfg(not(feature = "occt"))]
fn load_occt_model(
    path: &Path,
    _farfield: Option<FarfieldSpec>,
) -> Result<(Model, f64, Option<FlowDomain>), String> {
    Err(format!(
        "{}: no geometry plugin claims this extension, and this tetrafoil was built without the \
         OpenCASCADE bridge (the `occt` feature) that reads STEP, IGES and BREP: see \
         `tetrafoil plugins`",
        path.display()
    ))
}
