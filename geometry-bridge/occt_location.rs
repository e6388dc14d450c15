//! Where OpenCASCADE's headers and libraries are. One copy for two build scripts: the bridge's
//! (which compiles and links against them) and the root crate's (which puts the library folder
//! in the RPATH of its tests and examples: they link the bridge as a dev-dependency, and a
//! dev-dependency's `links` metadata does not reach the root crate's build script).
//!
//! In order: `OCCT_INCLUDE_DIR` + `OCCT_LIB_DIR`; the bridge's `builtin` feature's build tree
//! (where occt-sys installs it); `DEP_OCCT_ROOT` (set by the workspace's .cargo/config.toml to
//! `.occt/`, see scripts/install-occt.sh).

use std::env;
use std::path::{Path, PathBuf};

fn first_dir(candidates: &[PathBuf]) -> Option<PathBuf> {
    candidates.iter().find(|p| p.is_dir()).cloned()
}

/// The OCCT include and library folders; `builtin` when OCCT is built from source by
/// occt-sys.
pub fn occt_dirs(builtin: bool) -> Result<(PathBuf, PathBuf), String> {
    for var in ["OCCT_INCLUDE_DIR", "OCCT_LIB_DIR", "DEP_OCCT_ROOT"] {
        println!("cargo:rerun-if-env-changed={var}");
    }
    if let (Ok(inc), Ok(lib)) = (env::var("OCCT_INCLUDE_DIR"), env::var("OCCT_LIB_DIR")) {
        return Ok((inc.into(), lib.into()));
    }
    let root: PathBuf = if builtin {
        // occt-sys installs into <target>/<profile>/build/../OCCT; OUT_DIR is 4 levels below.
        let out = env::var("OUT_DIR").map_err(|_| "OUT_DIR is not set".to_string())?;
        Path::new(&out).join("../../../../OCCT")
    } else {
        env::var("DEP_OCCT_ROOT")
            .map_err(|_| {
                "DEP_OCCT_ROOT is not set: run scripts/install-occt.sh and build inside the \
                 workspace, or set OCCT_INCLUDE_DIR and OCCT_LIB_DIR"
                    .to_string()
            })?
            .into()
    };
    let inc = first_dir(&[root.join("include/opencascade"), root.join("include")])
        .ok_or_else(|| format!("no OCCT headers under {}", root.display()))?;
    let lib = first_dir(&[root.join("lib"), root.join("lib64")])
        .ok_or_else(|| format!("no OCCT libraries under {}", root.display()))?;
    Ok((inc, lib))
}
