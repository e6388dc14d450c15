//! Native geometry mixed into CAD models through a case file: `[[replace_face]]` (a CAD face's
//! surface replaced by a native fit to its samples) and `[[wake]]` (a native sheet attached to
//! CAD edges, embedded in the region).

mod common;
use common::corpus::corpus_file as corpus;
use std::path::{Path, PathBuf};
use tetrafoil::case::parse_case;
use tetrafoil::geometry::Surface;
use tetrafoil_native::FergusonSurface;
use tetrafoil_occt::CadModel;

fn step_wing() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/wing_step/wing_in_box.step")
}

/// A case file next to `cad` (so `cad` is found relative to it) with the extra `entries`.
fn case_text(cad: &Path, entries: &str) -> (String, String) {
    let text = format!(
        "[mesh]\ncad = \"{}\"\n\n{entries}",
        cad.file_name().unwrap().to_string_lossy()
    );
    let path = cad.with_file_name("case.toml").display().to_string();
    (text, path)
}

fn is_native(s: &dyn Surface) -> bool {
    s.as_any()
        .is_some_and(|a| a.downcast_ref::<FergusonSurface>().is_some())
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn replaced_box_face_is_native_with_the_cad_area() {
    let _occt = common::occt::one_at_a_time();
    let Some(cad) = corpus("box_colored_faces.stp") else {
        return;
    };
    let (text, path) = case_text(&cad, "[[replace_face]]\nface = 2\n");
    let case = parse_case(&text, &path).unwrap();
    let m = &case.model;
    assert!(m.validation_errors().is_empty());
    assert!(is_native(m.faces[2].surface.as_ref()));
    assert!(
        !is_native(m.faces[1].surface.as_ref()),
        "only face 2 replaced"
    );
    let ours = m.face_integrals(2).unwrap().area;
    let occt = CadModel::read(&cad).unwrap().face_area(2).unwrap();
    assert!(rel(ours, occt) < 1e-3, "area {ours} vs CAD {occt}");
    assert!(rel(m.regions[0].shells[0].volume, 1e6) < 1e-6);
}

#[test]
fn replaced_lofted_wing_face_keeps_its_area() {
    let _occt = common::occt::one_at_a_time();
    // The STEP wing's lofted side (face 6: a periodic B-spline whose seam is the trailing
    // edge): a curved face where the fit is not exact.
    let (text, path) = case_text(&step_wing(), "[[replace_face]]\nface = 6\nsamples = 97\n");
    let case = parse_case(&text, &path).unwrap();
    let m = &case.model;
    assert!(is_native(m.faces[6].surface.as_ref()));
    let ours = m.face_integrals(6).unwrap().area;
    let occt = CadModel::read(step_wing())
        .unwrap()
        .face_area_adaptive(6, 1e-9)
        .unwrap();
    println!("lofted face area: fit {ours}, CAD {occt}");
    assert!(rel(ours, occt) < 1e-3, "area {ours} vs CAD {occt}");
}

#[test]
fn replace_face_errors_name_the_key_line_and_entity() {
    let _occt = common::occt::one_at_a_time();
    let Some(cad) = corpus("box_colored_faces.stp") else {
        return;
    };
    let (text, path) = case_text(&cad, "[[replace_face]]\nface = \"PartBody\"\n");
    let err = parse_case(&text, &path).err().unwrap().to_string();
    assert!(
        err.contains(":5: replace_face.face:") && err.contains("6 faces are named 'PartBody'"),
        "{err}"
    );
    let (text, path) = case_text(&cad, "[[replace_face]]\nface = 6\n");
    let err = parse_case(&text, &path).err().unwrap().to_string();
    assert!(err.contains("has no face 6"), "{err}");
}

#[test]
fn wake_on_the_onera_m6_trailing_edge_is_an_embedded_face() {
    let _occt = common::occt::one_at_a_time();
    let Some(cad) = corpus("onera_m6_halfsphere_domain.stp") else {
        return;
    };
    // Edge 15 is the wing's sharp trailing edge, (1, 0, 0) to (1.415, 1.476, 0).
    let wake = "[[wake]]\nedges = [15]\ndirection = [1, 0, 0]\nlength = 10\n";
    let (text, path) = case_text(&cad, wake);
    let case = parse_case(&text, &path).unwrap();
    let m = &case.model;
    assert!(m.validation_errors().is_empty());
    let face = m.faces.len() - 1;
    assert_eq!(m.faces[face].name.as_deref(), Some("wake"));
    assert_eq!(m.regions[0].embedded_faces, vec![face]);
    assert!(is_native(m.faces[face].surface.as_ref()));
    let uses: Vec<usize> = m.faces[face].loops[0].uses.iter().map(|u| u.edge).collect();
    assert!(uses.contains(&15), "the wake shares the CAD edge: {uses:?}");
    // A straight trailing edge: the sheet is a parallelogram, area |TE x direction| length.
    let te = m.vertices[m.edges[15].end].point - m.vertices[m.edges[15].start].point;
    let expected = te.cross(glam::DVec3::X).length() * 10.0;
    let area = m.face_integrals(face).unwrap().area;
    assert!(rel(area, expected) < 1e-6, "wake area {area} vs {expected}");
}

#[test]
fn wake_on_the_step_wing_seam_trailing_edge() {
    let _occt = common::occt::one_at_a_time();
    // The STEP wing's trailing edge is the seam of its lofted face (edge 13): used twice by
    // that face, once by the wake.
    let wake = "[[wake]]\nname = \"wing_wake\"\nedges = [13]\ndirection = [1, 0, 0]\nlength = 5\n";
    let (text, path) = case_text(&step_wing(), wake);
    let case = parse_case(&text, &path).unwrap();
    let m = &case.model;
    let face = m.faces.len() - 1;
    assert_eq!(m.faces[face].name.as_deref(), Some("wing_wake"));
    assert_eq!(m.regions[0].embedded_faces, vec![face]);
    // Straight trailing edge: the sheet is the parallelogram, area = TE span x length.
    let area = m.face_integrals(face).unwrap().area;
    assert!(rel(area, 5.0 * 2.0) < 1e-6, "wake area {area}");
}

#[test]
fn wake_errors_name_the_key_line_and_entity() {
    let _occt = common::occt::one_at_a_time();
    let Some(cad) = corpus("onera_m6_halfsphere_domain.stp") else {
        return;
    };
    let bad = [
        ("edges = [99]", "has no edge 99"),
        ("edges = [15, 15]", "listed twice"),
        ("edges = [15, 2]", "degenerate or closed"),
        ("edges = [15, 8]", "one connected chain"),
    ];
    for (edges, expect) in bad {
        let (text, path) = case_text(
            &cad,
            &format!("[[wake]]\n{edges}\ndirection = [1, 0, 0]\nlength = 10\n"),
        );
        let err = parse_case(&text, &path).err().unwrap().to_string();
        assert!(
            err.contains(":5: wake.edges:") && err.contains(expect),
            "{edges}: {err}"
        );
    }
    let (text, path) = case_text(
        &cad,
        "[[wake]]\nedges = [15]\ndirection = [0, 0, 0]\nlength = 10\n",
    );
    let err = parse_case(&text, &path).err().unwrap().to_string();
    assert!(err.contains(":6: wake.direction:"), "{err}");
}

#[test]
fn mixing_entries_need_a_cad_model() {
    let _occt = common::occt::one_at_a_time();
    let text = "[mesh]\nsize = 1.0\n\n[[wake]]\nedges = [0]\ndirection = [1, 0, 0]\nlength = 1\n";
    let err = parse_case(text, "case.toml").err().unwrap().to_string();
    assert!(
        err.contains("case.toml:5: wake.edges:") && err.contains("needs `[mesh] cad`"),
        "{err}"
    );
}
