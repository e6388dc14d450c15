//! OpenCASCADE as a geometry plugin (`libtetrafoil_occt.so`, built from `geometry-bridge/`).
//! The default `tetrafoil` links no OpenCASCADE library and reads STEP only through the
//! plugin; without one it says how to get it. Built with OpenCASCADE inside (`--features
//! occt`, as `make test` runs this file too), the plugin gives the same meshes as the built-in
//! bridge: a few small files of the shared corpus meshed by the same binary both ways (a plain
//! solid, a sphere, a surface set that must be sewn, a file that cannot be sewn), compared by
//! surface triangles, tets, volume and dihedral range (or the error).
//! `benches/plugin-occt.sh` runs the whole corpus and times both.

mod common;

#[cfg(feature = "occt")]
use common::corpus::cad_dir;
use common::occt::plugin_file as occt_plugin;
use std::path::Path;
use std::process::Command;

#[cfg(feature = "occt")]
/// What a run made: the report's counts and quality, or its error line.
fn mesh(file: &Path, plugin: Option<&Path>, tag: &str) -> String {
    mesh_with(file, plugin, tag, &[])
}

#[cfg(feature = "occt")]
fn mesh_with(file: &Path, plugin: Option<&Path>, tag: &str, extra: &[&str]) -> String {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("plugin-occt");
    std::fs::create_dir_all(&dir).unwrap();
    let stem = file.file_stem().unwrap().to_string_lossy();
    let report = dir.join(format!("{stem}-{tag}.json"));
    let _ = std::fs::remove_file(&report);
    let mut c = Command::new(env!("CARGO_BIN_EXE_tetrafoil"));
    if let Some(p) = plugin {
        c.arg("--plugin").arg(p);
    }
    let out = c
        .args(["-q", "mesh"])
        .arg(file)
        .arg("-o")
        .arg(dir.join(format!("{stem}-{tag}.vtu")))
        .arg("--report")
        .arg(&report)
        .args(extra)
        .env_remove("TETRAFOIL_PLUGIN_PATH")
        .output()
        .expect("tetrafoil runs");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{err}");
    if !out.status.success() {
        return err
            .lines()
            .find(|l| l.contains("error"))
            .unwrap_or("")
            .to_string();
    }
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let q = &r["quality"];
    format!(
        "triangles {} tets {} volume {:.12e} dihedral {}..{}",
        r["surface_mesh"]["triangles"],
        q["tets"],
        r["volume"]["validity"]["volume"].as_f64().unwrap_or(0.0),
        q["min_dihedral"],
        q["max_dihedral"]
    )
}

#[cfg(feature = "occt")]
#[test]
fn the_occt_plugin_meshes_as_the_built_in_bridge() {
    let Some(cad) = cad_dir() else { return };
    let plugin = occt_plugin();
    for name in [
        "box_colored_faces.stp",
        "sphere_revolved.step",
        "cylinder_catia_trimmed.igs",
        "cube_fillet_open_shell.stp",
    ] {
        let file = cad.join(name);
        let built_in = mesh(&file, None, "built-in");
        let through_plugin = mesh(&file, Some(&plugin), "plugin");
        assert!(!built_in.is_empty(), "{name}: no result");
        assert_eq!(built_in, through_plugin, "{name}");
    }
}

/// The far field is built by the plugin's booleans, and the symmetry plane found on the
/// plugin's geometry: the ONERA M6 wing in a half sphere, surfaces only.
#[cfg(feature = "occt")]
#[test]
fn the_occt_plugin_builds_the_same_far_field() {
    let Some(cad) = cad_dir() else { return };
    let file = cad.join("onera_m6_wing_sharp_te.stp");
    let args = ["--farfield", "half-sphere:10", "--surface-only"];
    let built_in = mesh_with(&file, None, "ff-built-in", &args);
    let through_plugin = mesh_with(&file, Some(&occt_plugin()), "ff-plugin", &args);
    assert!(built_in.starts_with("triangles"), "{built_in}");
    assert_eq!(built_in, through_plugin);
}

#[test]
fn the_occt_plugin_lists_its_extensions() {
    let out = Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .arg("--plugin")
        .arg(occt_plugin())
        .arg("plugins")
        .output()
        .expect("tetrafoil runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(
        text.contains("occt") && text.contains(".step .stp .iges .igs .brep .brp"),
        "{text}"
    );
    assert!(text.contains("--plugin"), "{text}");
}

/// The default binary, copied away from any plugin: no OpenCASCADE library linked, and a STEP
/// file refused with what to do; given the plugin, the same file meshes.
#[cfg(not(feature = "occt"))]
#[test]
fn the_default_binary_reads_step_only_through_the_plugin() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("binary-alone");
    std::fs::create_dir_all(&dir).unwrap();
    let alone = dir.join("tetrafoil");
    let tmp = dir.join(format!(".tetrafoil.{}", std::process::id()));
    std::fs::copy(env!("CARGO_BIN_EXE_tetrafoil"), &tmp).unwrap();
    std::fs::rename(&tmp, &alone).unwrap();
    if let Ok(ldd) = Command::new("ldd").arg(&alone).output() {
        let libs = String::from_utf8_lossy(&ldd.stdout);
        assert!(!libs.contains("libTK"), "OpenCASCADE linked:\n{libs}");
    }
    let step = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/wing_step/wing_in_box.step");
    let run = |plugin: bool| {
        let mut c = Command::new(&alone);
        c.env_remove("TETRAFOIL_PLUGIN_PATH");
        if plugin {
            c.arg("--plugin").arg(occt_plugin());
        }
        c.args(["-q", "check"]).arg(&step).output().unwrap()
    };
    let refused = run(false);
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success());
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.contains("wing_in_box.step") && err.contains("libtetrafoil_occt"),
        "{err}"
    );
    let read = run(true);
    let out = String::from_utf8_lossy(&read.stdout);
    assert!(
        read.status.success(),
        "{}",
        String::from_utf8_lossy(&read.stderr)
    );
    assert!(out.contains("faces 8"), "{out}");
}
