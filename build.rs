//! Puts the OCCT library directory in the RPATH of what links OpenCASCADE, so it runs without
//! LD_LIBRARY_PATH: the tests and examples (they link the bridge, a dev-dependency, for
//! OpenCASCADE's own measures and constructions) and, with the `occt` feature, the binary.
//! With the feature the directory comes from the bridge crate (`links = "tetrafoil_occt"`,
//! exported as `DEP_TETRAFOIL_OCCT_LIBDIR`); without it, from the same search the bridge's
//! build script makes (`geometry-bridge/occt_location.rs`). `--disable-new-dtags` writes
//! DT_RPATH rather than DT_RUNPATH: RUNPATH is not used for the OCCT libraries' own
//! dependencies on each other.

#[path = "geometry-bridge/occt_location.rs"]
mod occt_location;

fn rpath(dir: &str) -> String {
    format!("-Wl,--disable-new-dtags,-rpath,{dir}")
}

fn main() {
    println!("cargo:rerun-if-env-changed=DEP_TETRAFOIL_OCCT_LIBDIR");
    println!("cargo:rerun-if-changed=geometry-bridge/occt_location.rs");
    if std::env::var_os("CARGO_FEATURE_OCCT").is_some() {
        match std::env::var("DEP_TETRAFOIL_OCCT_LIBDIR") {
            Ok(dir) => println!("cargo:rustc-link-arg={}", rpath(&dir)),
            Err(_) => println!(
                "cargo:warning=tetrafoil-occt exported no library directory: set LD_LIBRARY_PATH to run"
            ),
        }
        return;
    }
    let found = occt_location::occt_dirs(false).or_else(|_| occt_location::occt_dirs(true));
    match found {
        Ok((_, lib)) => {
            let arg = rpath(&lib.display().to_string());
            for kind in ["tests", "examples", "benches"] {
                println!("cargo:rustc-link-arg-{kind}={arg}");
            }
        }
        Err(e) => println!("cargo:warning=OCCT not found for the tests' RPATH ({e}): set LD_LIBRARY_PATH to run them"),
    }
}
