//! CAD input: a STEP, IGES or BREP file as a whole case (`tetrafoil mesh part.step`) or as the
//! model of a case file (`[mesh] cad = "part.step"`).
//!
//! A file whose faces form no solid (a surface set) is sewn, first at 1e-6 of the model's
//! bounding-box diagonal, then at 1e-4; what was done is said on stderr. If sewing makes no
//! solid, the error names the free edges and their faces. Several solids (an assembly) go
//! through OCCT's general fuse, so touching solids share their contact faces.

use super::controls::{Case, ControlOverrides, MeshControls};
use super::error::CaseError;
use crate::model::Model;
use crate::sizing::SizingField;
use std::path::Path;

/// Default curvature limit for CAD input: δ ≤ 2πR/12, floored at size/100.
pub const CURVATURE_SEGMENTS: f64 = 12.0;

/// A CAD file as a case: the oriented model, spacing 1/20 of the bounding-box diagonal (the
/// command line's `--size` overrides it), tolerance 1e-6 of the diagonal, curvature limit on.
pub fn case_from_cad(path: &Path) -> Result<Case, CaseError> {
    case_from_cad_with(path, &ControlOverrides::default())
}

/// [`case_from_cad`] with some mesh controls replaced (the size floor stays 1/100 of the
/// default size).
pub fn case_from_cad_with(path: &Path, overrides: &ControlOverrides) -> Result<Case, CaseError> {
    let (model, extent) = load_cad_model(path).map_err(CaseError::Cad)?;
    let size = extent / 20.0;
    let mut controls = MeshControls {
        size,
        curvature_segments: CURVATURE_SEGMENTS,
        proximity_cells: super::controls::PROXIMITY_CELLS,
        min_size: size / 100.0,
        tolerance: 1e-6 * extent,
    };
    overrides.apply(&mut controls);
    let mut sizing = SizingField::uniform(controls.size);
    sizing.set_local_limits(&model, &controls);
    Ok(Case {
        model,
        controls,
        sizing,
        refinement: Default::default(),
    })
}

/// The oriented, validated model of a CAD file and the diagonal of its bounding box.
/// Errors are messages naming the file and, for topology problems, the faces and edges.
#[cfg(feature = "occt")]
pub(crate) fn load_cad_model(path: &Path) -> Result<(Model, f64), String> {
    use crate::model::cad::{model_from_cad, open_boundary_diagnosis};
    use tetrafoil_occt::CadModel;

    let cad = CadModel::read(path).map_err(|e| e.to_string())?;
    let extent = cad
        .bounding_box()
        .map_err(|e| e.to_string())?
        .map(|b| b.diagonal())
        .filter(|d| d.is_finite() && *d > 0.0)
        .ok_or_else(|| format!("{}: the model is empty (no bounding box)", cad.file()))?;
    let cad = if cad.topology().solids.is_empty() {
        let mut tried = Vec::new();
        let mut solid = None;
        let mut last = None;
        for rel in [1e-6, 1e-4] {
            let tol = rel * extent;
            let (sewn, report) = cad.sew(tol).map_err(|e| e.to_string())?;
            tried.push(format!("{tol:.3e}"));
            if !sewn.topology().solids.is_empty() {
                log::warn!(
                    "{} has no solid: sewed its {} faces at tolerance {tol:.3e} into {} solid(s) ({} free edges left)",
                    cad.file(),
                    report.before.faces,
                    sewn.topology().solids.len(),
                    report.free_edges
                );
                solid = Some(sewn);
                break;
            }
            last = Some(sewn);
        }
        match solid {
            Some(s) => s,
            None => {
                let diagnosed = last.as_ref().unwrap_or(&cad);
                return Err(format!(
                    "{}: contains no solid, and sewing at tolerance {} closes none: {}",
                    cad.file(),
                    tried.join(" then "),
                    open_boundary_diagnosis(diagnosed, 12)
                ));
            }
        }
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
    let model = model_from_cad(&cad).map_err(|e| e.to_string())?;
    Ok((model, extent))
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
pub(crate) fn load_cad_model(path: &Path) -> Result<(Model, f64), String> {
    Err(format!(
        "{}: CAD input (STEP/IGES/BREP) needs the OpenCASCADE bridge: build with the `occt` feature",
        path.display()
    ))
}
