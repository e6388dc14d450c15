//! Where the public CAD corpus is: `../shared/cad` beside the checkout. Tests read it from
//! there (nothing of it is copied into the project); outside CI a test without it says so and
//! skips, under CI (the `CI` variable set) its absence is a failure.

use std::path::{Path, PathBuf};

/// The corpus folder, or `None` (said on stdout) when it is absent outside CI.
pub fn cad_dir() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/cad");
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "CAD corpus {} missing (required when CI is set)",
        dir.display()
    );
    println!("skipping: CAD corpus {} not found", dir.display());
    None
}

/// One file of the corpus, or `None` (said on stdout) when it is absent outside CI.
pub fn corpus_file(name: &str) -> Option<PathBuf> {
    let path = cad_dir()?.join(name);
    if path.is_file() {
        return Some(path);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "{} missing (required when CI is set)",
        path.display()
    );
    println!("skipping: {} not found", path.display());
    None
}
