//! Case files: native geometry, topology and mesh controls in one TOML file. Loading parses
//! the schema ([`schema`]), builds the geometry and topology, computes pcurves, orients the
//! model and builds the sizing function. Every error names the key or entity and its line.

mod build;
mod cad;
mod controls;
mod error;
pub mod farfield;
mod farfield_native;
mod kernel_file;
mod mix;
mod plugin_model;
pub mod refine;
pub mod schema;

pub use build::{parse_case, parse_case_with};
pub use cad::{
    case_from_cad, case_from_cad_with, is_cad_file, CURVATURE_SEGMENTS, OCCT_EXTENSIONS,
};
pub use controls::{
    curvature_segments_ok, prism_warp_ok, AutoWakes, Case, ControlOverrides, MeshControls,
    PROXIMITY_CELLS, PROXIMITY_FLOOR,
};
pub use error::CaseError;
pub use kernel_file::SEW_STEPS;

use std::path::Path;

/// Read and build a case file.
pub fn load_case(path: &Path) -> Result<Case, CaseError> {
    load_case_with(path, &ControlOverrides::default())
}

/// [`load_case`] with some mesh controls replaced.
pub fn load_case_with(path: &Path, overrides: &ControlOverrides) -> Result<Case, CaseError> {
    let text = std::fs::read_to_string(path).map_err(|e| CaseError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    parse_case_with(&text, &path.display().to_string(), overrides)
}
