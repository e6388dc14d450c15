//! OpenCASCADE for the CAD tests, the way users get it: the plugin `libtetrafoil_occt.so`,
//! which building the `tetrafoil-occt` dev-dependency puts beside the test binaries (in
//! `target/<profile>/deps`). Library calls find it there by themselves (plugins beside the
//! executable); the `tetrafoil` binary, one folder up, is pointed at it through
//! `TETRAFOIL_PLUGIN_PATH`. The tests' reference values (volumes, areas, orientations) come
//! from OpenCASCADE directly (`tetrafoil_occt::CadModel`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use tetrafoil::geometry::plugin::{registry, Plugin, PluginSource};
use tetrafoil::model::foreign::{import_foreign, model_from_foreign};
use tetrafoil::model::Model;

/// The plugin file, beside this test binary.
pub fn plugin_file() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let dir = exe.parent().expect("the test binary's folder");
    let name = format!("libtetrafoil_occt{}", std::env::consts::DLL_SUFFIX);
    [dir.join(&name), dir.join("deps").join(&name)]
        .into_iter()
        .find(|p| p.is_file())
        .unwrap_or_else(|| {
            panic!(
                "{name} is built with the tetrafoil-occt dev-dependency, beside {}",
                dir.display()
            )
        })
}

/// The `tetrafoil` binary, reading STEP, IGES and BREP through the plugin.
pub fn tetrafoil() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_tetrafoil"));
    c.env("TETRAFOIL_PLUGIN_PATH", plugin_file());
    c
}

/// The loaded OpenCASCADE plugin (the one claiming `.step`).
pub fn plugin() -> Arc<Plugin> {
    (registry().plugins.iter())
        .map(|(p, _)| p)
        .find(|p| p.claims("step"))
        .cloned()
        .unwrap_or_else(|| {
            panic!(
                "no plugin claims .step (expected {})",
                plugin_file().display()
            )
        })
}

/// `path` as the plugin reads it.
pub fn open(path: &Path) -> PluginSource {
    PluginSource::open(&plugin(), path).unwrap_or_else(|e| panic!("{e}"))
}

/// `source` sewn at `tolerance`.
pub fn sew(source: &PluginSource, tolerance: f64) -> PluginSource {
    source
        .sew(tolerance)
        .expect("the OCCT plugin sews")
        .unwrap_or_else(|e| panic!("{e}"))
}

/// `source`'s solids fused at `tolerance`.
pub fn fuse(source: &PluginSource, tolerance: f64) -> PluginSource {
    source
        .fuse(tolerance)
        .expect("the OCCT plugin fuses")
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The validated, oriented model of `source`.
pub fn model(source: &PluginSource) -> Result<Model, String> {
    model_from_foreign(source).map_err(|e| e.to_string())
}

/// The model of `source` as imported, before validation.
pub fn imported(source: &PluginSource) -> Result<Model, String> {
    import_foreign(source).map_err(|e| e.to_string())
}

static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Held by each test of a binary that reads files through both copies of the bridge: the
/// plugin (loaded at run time) and `CadModel` (linked in). Each copy serialises OpenCASCADE's
/// file readers with its own lock, so two tests at once could read concurrently (a crash).
pub fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}
