//! Reads every file of the public corpus and checks counts against the file text.
mod common;

use tetrafoil_occt::{CadError, CadModel};

/// ADVANCED_FACE entities in a STEP file's text (the reference face count).
fn advanced_faces(text: &str) -> usize {
    text.matches("ADVANCED_FACE").count()
}

#[test]
fn corpus_summary_and_face_counts() {
    let Some(dir) = common::cad_dir() else { return };
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let e = p.extension().and_then(|e| e.to_str()).unwrap_or("");
            matches!(e, "step" | "stp" | "igs" | "iges" | "brep")
        })
        .collect();
    names.sort();
    let mut checked = 0;
    for path in names {
        let file = path.file_name().unwrap().to_string_lossy().to_string();
        let model = match CadModel::read(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("{file}: read error: {e}");
                continue;
            }
        };
        let t = model.topology();
        let c = t.counts();
        let named = t.faces.iter().filter(|f| f.name.is_some()).count();
        let solid_names: Vec<_> = t.solids.iter().filter_map(|s| s.name.clone()).collect();
        let diagnosis = match model.check_solids() {
            Ok(()) => "ok".to_string(),
            Err(e) => e.to_string(),
        };
        println!(
            "{file}: {} solids, {} shells, {} faces ({named} named), {} edges, {} vertices, {} free edges; solids named {solid_names:?}; check: {diagnosis}; warnings {:?}",
            c.solids, c.shells, c.faces, c.edges, c.vertices, t.free_edges.len(), model.warnings()
        );
        let is_step = file.ends_with(".stp") || file.ends_with(".step");
        if is_step && c.solids == 1 && model.check_solids().is_ok() {
            let text = std::fs::read_to_string(&path).unwrap();
            assert_eq!(c.faces, advanced_faces(&text), "{file}: face count");
            checked += 1;
        }
    }
    assert!(
        checked >= 10,
        "only {checked} single-solid STEP files checked"
    );
}

#[test]
fn missing_and_garbage_files_are_typed_errors() {
    let missing = CadModel::read("/nonexistent/model.step");
    assert!(matches!(missing, Err(CadError::NotFound { .. })));
    let dir = std::env::temp_dir().join(format!("tetrafoil-occt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("garbage.step");
    std::fs::write(&bad, "this is not ISO-10303-21\n").unwrap();
    let err = CadModel::read(&bad).err().expect("garbage must not read");
    assert!(err.to_string().contains("garbage.step"), "{err}");
    assert!(
        matches!(err, CadError::Unreadable { .. } | CadError::Empty { .. }),
        "{err:?}"
    );
    let bad_igs = dir.join("garbage.igs");
    std::fs::write(&bad_igs, "nope\n").unwrap();
    let err = CadModel::read(&bad_igs)
        .err()
        .expect("garbage must not read");
    assert!(
        matches!(err, CadError::Unreadable { .. } | CadError::Empty { .. }),
        "{err:?}"
    );
    let txt = dir.join("model.txt");
    std::fs::write(&txt, "x").unwrap();
    assert!(matches!(
        CadModel::read(&txt),
        Err(CadError::UnknownFormat { .. })
    ));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn open_and_unsewn_shells_are_diagnosed() {
    let Some(dir) = common::cad_dir() else { return };
    // The box's MANIFOLD_SOLID_BREP points at an OPEN_SHELL, but its six faces share every
    // edge: OCCT's transfer yields a closed shell and a valid solid, which is the right reading.
    let model = CadModel::read(dir.join("box_open_shell_invalid.stp")).unwrap();
    let t = model.topology();
    assert_eq!((t.faces.len(), t.solids.len()), (6, 1));
    assert!(t.shells[0].closed && t.free_edges.is_empty());
    assert!(model.check_solids().is_ok());
    let vol = model.solid_volume(0).unwrap();
    assert!(vol > 0.0, "box volume {vol}");
    for file in [
        "cube_fillet_open_shell.stp",
        "t106_turbine_cascade_shells.step",
    ] {
        let result = CadModel::read(dir.join(file)).and_then(|m| m.check_solids());
        let err = result
            .err()
            .unwrap_or_else(|| panic!("{file}: accepted as valid solids"));
        println!("{file}: {err}");
        assert!(err.to_string().contains(file));
        assert!(
            matches!(err, CadError::OpenShell { .. } | CadError::NoSolid { .. }),
            "{file}: {err:?}"
        );
    }
}
