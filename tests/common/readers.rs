//! Programs no one here wrote that the writer tests open our files with: meshio and Gmsh in
//! `.readers/venv` (`scripts/install-readers.sh`), OpenFOAM (`scripts/install-openfoam.sh`).
//! Outside CI a missing one is said on stdout and its test skips; under CI (the `CI` variable
//! set) its absence is a failure.

use std::path::{Path, PathBuf};

/// `path` when it exists, else `None` (said on stdout) outside CI; `install` names the script
/// that puts it there.
pub fn tool(path: &Path, install: &str) -> Option<PathBuf> {
    if path.exists() {
        return Some(path.to_path_buf());
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "{} missing ({install}; required when CI is set)",
        path.display()
    );
    println!("SKIPPED: {} not installed (run {install})", path.display());
    None
}

/// The Python of `.readers/venv`, which has meshio and gmsh.
pub fn readers_python() -> Option<PathBuf> {
    let python = Path::new(env!("CARGO_MANIFEST_DIR")).join(".readers/venv/bin/python");
    tool(&python, "scripts/install-readers.sh")
}
