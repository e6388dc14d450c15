//! Shared test helpers: where the public CAD corpus is, and skipping when it is absent.
#![allow(dead_code)]
use std::path::PathBuf;

use tetrafoil_occt::CadModel;

/// `../shared/cad` relative to the workspace root. None (test skips) when absent, except under
/// CI, where the corpus must be present.
pub fn cad_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/cad"));
    if dir.is_dir() {
        return Some(dir);
    }
    if std::env::var_os("CI").is_some() {
        panic!(
            "CAD corpus {} missing (required when CI is set)",
            dir.display()
        );
    }
    eprintln!("skipping: CAD corpus {} not found", dir.display());
    None
}

pub fn load(dir: &std::path::Path, name: &str) -> CadModel {
    CadModel::read(dir.join(name)).unwrap_or_else(|e| panic!("{e}"))
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm(sub(a, b))
}

/// Diagonal of the model's bounding box: the length scale for relative tolerances.
pub fn model_size(m: &CadModel) -> f64 {
    m.bounding_box().unwrap().unwrap().diagonal()
}
