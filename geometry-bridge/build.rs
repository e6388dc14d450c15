//! Builds the crate's own cxx bridge (cpp/*.cxx) against the same OCCT that opencascade-sys
//! uses, and sets the run-time library path.
//!
//! Where OCCT is: `occt_location.rs` (shared with the root crate's build script).
//!
//! Shared OCCT libraries are found at run time through an RPATH, not LD_LIBRARY_PATH. Cargo only
//! applies `rustc-link-arg` to this package's own tests/examples, so dependents (the tetrafoil
//! binary) read `DEP_TETRAFOIL_OCCT_LIBDIR` in their build script and emit the same argument.

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

#[path = "occt_location.rs"]
mod occt_location;

fn main() {
    let (inc, lib) =
        occt_location::occt_dirs(cfg!(feature = "builtin")).unwrap_or_else(|e| panic!("{e}"));
    let cpp = [
        "cpp/read.cxx",
        "cpp/topology.cxx",
        "cpp/repair.cxx",
        "cpp/geometry.cxx",
        "cpp/build.cxx",
        "cpp/body.cxx",
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
