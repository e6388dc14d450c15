//! Builds the crate's own cxx bridge (cpp/*.cxx) against the same OCCT that opencascade-sys
//! uses, and sets the run-time library path.
//!
//! OCCT location, in order: `OCCT_INCLUDE_DIR` + `OCCT_LIB_DIR`; the `builtin` feature's build
//! tree (where occt-sys installs it); `DEP_OCCT_ROOT` (set by the workspace's .cargo/config.toml
//! to `.occt/`, see scripts/install-occt.sh).
//!
//! Shared OCCT libraries are found at run time through an RPATH, not LD_LIBRARY_PATH. Cargo only
//! applies `rustc-link-arg` to this package's own tests/examples, so dependents (the tetrafoil
//! binary) read `DEP_TETRAFOIL_OCCT_LIBDIR` in their build script and emit the same argument.
use std::env;
use std::path::{Path, PathBuf};

/// OCCT toolkits the shim calls directly (opencascade-sys links them too; naming them here keeps
/// the link correct if that list changes).
const LIBS: &[&str] = &[
    "TKernel",
    "TKMath",
    "TKG2d",
    "TKG3d",
    "TKGeomBase",
    "TKGeomAlgo",
    "TKBRep",
    "TKTopAlgo",
    "TKPrim",
    "TKOffset",
    "TKBO",
    "TKShHealing",
    "TKXSBase",
    "TKDESTEP",
    "TKCAF",
    "TKLCAF",
    "TKXCAF",
];

fn first_dir(candidates: &[PathBuf]) -> Option<PathBuf> {
    candidates.iter().find(|p| p.is_dir()).cloned()
}

fn occt_dirs() -> (PathBuf, PathBuf) {
    for var in ["OCCT_INCLUDE_DIR", "OCCT_LIB_DIR", "DEP_OCCT_ROOT"] {
        println!("cargo:rerun-if-env-changed={var}");
    }
    if let (Ok(inc), Ok(lib)) = (env::var("OCCT_INCLUDE_DIR"), env::var("OCCT_LIB_DIR")) {
        return (inc.into(), lib.into());
    }
    let root: PathBuf = if cfg!(feature = "builtin") {
        // occt-sys installs into <target>/<profile>/build/../OCCT; OUT_DIR is 4 levels below.
        Path::new(&env::var("OUT_DIR").unwrap()).join("../../../../OCCT")
    } else {
        env::var("DEP_OCCT_ROOT")
            .expect("DEP_OCCT_ROOT is not set: run scripts/install-occt.sh and build inside the workspace, or set OCCT_INCLUDE_DIR and OCCT_LIB_DIR")
            .into()
    };
    let inc = first_dir(&[root.join("include/opencascade"), root.join("include")])
        .unwrap_or_else(|| panic!("no OCCT headers under {}", root.display()));
    let lib = first_dir(&[root.join("lib"), root.join("lib64")])
        .unwrap_or_else(|| panic!("no OCCT libraries under {}", root.display()));
    (inc, lib)
}

fn main() {
    let (inc, lib) = occt_dirs();
    let cpp = [
        "cpp/read.cxx",
        "cpp/topology.cxx",
        "cpp/repair.cxx",
        "cpp/geometry.cxx",
        "cpp/build.cxx",
        "cpp/farfield.cxx",
    ];
    cxx_build::bridge("src/ffi.rs")
        .files(cpp)
        .include(&inc)
        .std("c++17")
        .define("_USE_MATH_DEFINES", None)
        .flag_if_supported("-Wno-deprecated-declarations")
        .flag_if_supported("-Wno-unused-parameter")
        .compile("tetrafoil_occt_shim");

    println!("cargo:rustc-link-search=native={}", lib.display());
    for l in LIBS {
        println!("cargo:rustc-link-lib=dylib={l}");
    }
    // DT_RPATH (not RUNPATH) so the OCCT libraries' own dependencies on each other resolve too.
    println!(
        "cargo:rustc-link-arg=-Wl,--disable-new-dtags,-rpath,{}",
        lib.display()
    );
    println!("cargo:libdir={}", lib.display());
    println!("cargo:rerun-if-changed=src/ffi.rs");
    println!("cargo:rerun-if-changed=cpp");
}
