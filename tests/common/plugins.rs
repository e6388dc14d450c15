//! Geometry plugins built for tests with the system C compiler, as the Makefile builds them:
//! the analytic kernel (`plugins/analytic-c/`) and the deliberately broken fixture
//! (`tests/plugins/faulty.c`) in its variants. Each library is built once per test binary,
//! into a temporary file renamed into place.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

static BUILD: Mutex<()> = Mutex::new(());

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Compile `sources` (relative to the project) into `libtetrafoil_<name>.so` with `defines`.
pub fn build(name: &str, sources: &[PathBuf], defines: &[&str]) -> PathBuf {
    let _one = BUILD.lock().unwrap_or_else(|e| e.into_inner());
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plugins");
    std::fs::create_dir_all(&dir).expect("plugin folder");
    let out = dir.join(format!(
        "libtetrafoil_{name}{}",
        std::env::consts::DLL_SUFFIX
    ));
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let status = Command::new(std::env::var("CC").unwrap_or_else(|_| "cc".into()))
        .args([
            "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "-fPIC", "-shared",
        ])
        .arg("-I")
        .arg(root().join("include"))
        .args(defines.iter().map(|d| format!("-D{d}")))
        .args(sources)
        .arg("-o")
        .arg(&tmp)
        .arg("-lm")
        .status()
        .expect("the C compiler (cc) runs");
    assert!(status.success(), "building the {name} plugin failed");
    std::fs::rename(&tmp, &out).expect("plugin renamed into place");
    out
}

/// The analytic kernel of `plugins/analytic-c/`.
pub fn analytic() -> PathBuf {
    let dir = root().join("plugins/analytic-c");
    let mut sources: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("plugins/analytic-c")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "c"))
        .collect();
    sources.sort();
    build("analytic", &sources, &[])
}

/// The broken fixture built with `-DFAULT=<fault>` (`FAULT_ABI`, `FAULT_ERROR`, ...).
pub fn faulty(fault: &str) -> PathBuf {
    let name = format!(
        "faulty_{}",
        fault.trim_start_matches("FAULT_").to_lowercase()
    );
    build(
        &name,
        &[root().join("tests/plugins/faulty.c")],
        &[&format!("FAULT={fault}")],
    )
}
