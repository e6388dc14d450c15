//! CAD input: a STEP, IGES or BREP file (or one a geometry plugin claims) as a whole case
//! (`tetrafoil mesh part.step`) or as the model of a case file (`[mesh] cad = "part.step"`).
//!
//! A geometry plugin reads it (OpenCASCADE's `libtetrafoil_occt.so` for STEP, IGES and BREP),
//! or OpenCASCADE built in with the `occt` feature; `kernel_file.rs` makes it ready the
//! same way for both (sewing a surface set, fusing an assembly: what was done is said on
//! stderr). A far field (`farfield.rs`, through the kernel's booleans) makes the body the hole
//! in a flow domain.

use super::controls::{Case, ControlOverrides, MeshControls};
use super::error::CaseError;
use super::farfield::{FarfieldSpec, FlowDomain};
use crate::model::Model;
use crate::sizing::SizingField;
use std::path::Path;

/// Default curvature limit for CAD input: δ ≤ 2πR/12, floored at size/100.
pub const CURVATURE_SEGMENTS: f64 = 12.0;

/// Extensions the built-in OpenCASCADE bridge reads (when built with it).
pub const OCCT_EXTENSIONS: [&str; 6] = ["step", "stp", "iges", "igs", "brep", "brp"];

/// The OpenCASCADE plugin's file name (built from `geometry-bridge/`).
#[cfg(not(feature = "occt"))]
const OCCT_PLUGIN_FILE: &str = if cfg!(target_os = "macos") {
    "libtetrafoil_occt.dylib"
} else {
    "libtetrafoil_occt.so"
};

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
    let (mut model, extent, domain) =
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
    if let Some(request) = &overrides.wakes {
        super::mix::auto_wakes(&mut model, domain.as_ref(), request, controls.tolerance)
            .map_err(|m| CaseError::Cad(format!("{}: {m}", path.display())))?;
    }
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
/// ([`super::plugin_model`]); STEP, IGES and BREP otherwise by OpenCASCADE built in (the `occt`
/// feature), or refused with how to get the plugin.
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
    use crate::model::cad::OcctSource;
    use crate::model::foreign::model_from_foreign;
    use tetrafoil_occt::CadModel;

    let cad = CadModel::read(path).map_err(|e| e.to_string())?;
    let (source, extent) = super::kernel_file::prepare(OcctSource::new(cad))?;
    let (source, domain) = match farfield {
        Some(spec) => {
            let (domain, flow) = super::farfield::build_domain(source, spec, extent)?;
            (domain, Some(flow))
        }
        None => (source, None),
    };
    let model = model_from_foreign(&source).map_err(|e| e.to_string())?;
    Ok((model, extent, domain))
}

/// OpenCASCADE's file operations, for [`super::kernel_file::prepare`].
#[cfg(feature = "occt")]
impl super::kernel_file::KernelFile for crate::model::cad::OcctSource<tetrafoil_occt::CadModel> {
    fn kernel(&self) -> String {
        "OpenCASCADE".into()
    }
    fn bounding_box(&self) -> Option<Result<[glam::DVec3; 2], String>> {
        let b = self.cad().bounding_box().map_err(|e| e.to_string());
        Some(b.and_then(|b| {
            b.map(|b| [b.min, b.max].map(glam::DVec3::from_array))
                .ok_or_else(|| {
                    format!(
                        "{}: the model is empty (no bounding box)",
                        self.cad().file()
                    )
                })
        }))
    }
    fn sew(&self, tolerance: f64) -> Option<Result<Self, String>> {
        Some(
            self.cad()
                .sew(tolerance)
                .map(|r| Self::new(r.0))
                .map_err(|e| e.to_string()),
        )
    }
    fn heal(&self, tolerance: f64) -> Option<Result<Self, String>> {
        Some(
            self.cad()
                .heal(tolerance)
                .map(|r| Self::new(r.0))
                .map_err(|e| e.to_string()),
        )
    }
    fn fuse(&self, tolerance: f64) -> Option<Result<Self, String>> {
        Some(
            (self.cad().fuse_solids(tolerance))
                .map(|r| Self::new(r.0))
                .map_err(|e| e.to_string()),
        )
    }
    fn solids_only(&self) -> Option<Result<Self, String>> {
        Some(
            self.cad()
                .solids_only()
                .map(Self::new)
                .map_err(|e| e.to_string()),
        )
    }
    fn farfield(&self, r: &super::kernel_file::FarfieldRequest) -> Option<Result<Self, String>> {
        use tetrafoil_occt::{Farfield, OuterShape, SymmetryPlane};
        let f = Farfield {
            shape: if r.sphere {
                OuterShape::Sphere
            } else {
                OuterShape::Box
            },
            centre: r.centre,
            half: r.half,
            symmetry: r
                .symmetry
                .map(|(axis, at, positive)| SymmetryPlane { axis, at, positive }),
            fuzzy: r.fuzzy,
        };
        Some(
            self.cad()
                .farfield_domain(&f)
                .map(Self::new)
                .map_err(|e| e.to_string()),
        )
    }
}

#[cfg(not(feature = "occt"))]
fn load_occt_model(
    path: &Path,
    _farfield: Option<FarfieldSpec>,
) -> Result<(Model, f64, Option<FlowDomain>), String> {
    Err(format!(
        "{}: no geometry plugin claims this extension. STEP, IGES and BREP are read by the \
         OpenCASCADE plugin, {}: `make plugins` builds it beside the tetrafoil binary, or name \
         it with --plugin PATH or {}; `tetrafoil plugins` lists the plugins found",
        path.display(),
        OCCT_PLUGIN_FILE,
        crate::geometry::plugin::PATH_VARIABLE
    ))
}
