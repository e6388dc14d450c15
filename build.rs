//! With the `occt` feature, puts the OCCT library directory in the RPATH of the tetrafoil
//! binary, tests and examples, so they run without LD_LIBRARY_PATH. The directory comes from
//! the bridge crate (`links = "tetrafoil_occt"`, which exports `cargo:libdir=...` as
//! `DEP_TETRAFOIL_OCCT_LIBDIR`). `--disable-new-dtags` writes DT_RPATH rather than DT_RUNPATH:
//! RUNPATH is not used for the OCCT libraries' own dependencies on each other.
fn main() {
    println!("cargo:rerun-if-env-changed=DEP_TETRAFOIL_OCCT_LIBDIR");
    if std::env::var_os("CARGO_FEATURE_OCCT").is_none() {
        return;
    }
    match std::env::var("DEP_TETRAFOIL_OCCT_LIBDIR") {
        Ok(dir) => println!("cargo:rustc-link-arg=-Wl,--disable-new-dtags,-rpath,{dir}"),
        Err(_) => println!(
            "cargo:warning=tetrafoil-occt exported no library directory: set LD_LIBRARY_PATH to run"
        ),
    }
}
