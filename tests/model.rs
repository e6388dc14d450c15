//! Topology: automatic orientation of loops and shells, validation, case-file errors.

mod common;

use glam::{DVec2, DVec3};
use tetrafoil::case::parse_case;
use tetrafoil::model::Model;

/// A point inside face `f` (centre of its parameter rectangle: fine for the box faces).
fn face_point(m: &Model, f: usize) -> (DVec2, DVec3, DVec3) {
    let s = &m.faces[f].surface;
    let b = s.bounds();
    let uv = DVec2::new(0.5 * (b.u.0 + b.u.1), 0.5 * (b.v.0 + b.v.1));
    (uv, s.point(uv), s.normal(uv))
}

#[test]
fn cube_faces_point_out_of_the_region() {
    let case = parse_case(&common::unit_cube(0.2), "cube").unwrap();
    let m = &case.model;
    assert_eq!(m.regions.len(), 1);
    assert_eq!(m.regions[0].shells.len(), 1);
    let shell = &m.regions[0].shells[0];
    assert!((shell.volume - 1.0).abs() < 1e-9, "volume {}", shell.volume);
    let centre = DVec3::splat(0.5);
    for fu in &shell.faces {
        let (_, p, n) = face_point(m, fu.face);
        let n = if fu.reversed { -n } else { n };
        assert!(
            n.dot(p - centre) > 0.0,
            "{} points inwards",
            m.face_ref(fu.face)
        );
    }
}

#[test]
fn cavity_shell_is_found_and_points_into_the_cavity() {
    let case = parse_case(&common::box_with_cavity(0.5), "cavity").unwrap();
    let m = &case.model;
    let shells = &m.regions[0].shells;
    assert_eq!(shells.len(), 2);
    assert!(
        (shells[0].volume - 64.0).abs() < 1e-8,
        "outer {}",
        shells[0].volume
    );
    assert!(
        (shells[1].volume - 1.0).abs() < 1e-9,
        "cavity {}",
        shells[1].volume
    );
    let centre = DVec3::splat(2.0);
    for (k, shell) in shells.iter().enumerate() {
        for fu in &shell.faces {
            let (_, p, n) = face_point(m, fu.face);
            let n = if fu.reversed { -n } else { n };
            // Away from the region: out of the box for the outer shell, into the cavity
            // (towards the centre) for the cavity shell.
            let out = n.dot(p - centre);
            if k == 0 {
                assert!(out > 0.0);
            } else {
                assert!(out < 0.0);
            }
        }
    }
}

#[test]
fn outer_loop_and_holes_are_found_and_oriented() {
    // A square plate z = 0 with a square hole, hole listed first and in clockwise order.
    let text = r#"
[mesh]
size = 0.1
[[vertex]]
name = "a"
point = [0, 0, 0]
[[vertex]]
name = "b"
point = [3, 0, 0]
[[vertex]]
name = "c"
point = [3, 3, 0]
[[vertex]]
name = "d"
point = [0, 3, 0]
[[vertex]]
name = "h1"
point = [1, 1, 0]
[[vertex]]
name = "h2"
point = [2, 1, 0]
[[vertex]]
name = "h3"
point = [2, 2, 0]
[[vertex]]
name = "h4"
point = [1, 2, 0]
[[edge]]
name = "ab"
start = "a"
end = "b"
[[edge]]
name = "bc"
start = "b"
end = "c"
[[edge]]
name = "cd"
start = "c"
end = "d"
[[edge]]
name = "da"
start = "d"
end = "a"
[[edge]]
name = "g1"
start = "h1"
end = "h2"
[[edge]]
name = "g2"
start = "h2"
end = "h3"
[[edge]]
name = "g3"
start = "h3"
end = "h4"
[[edge]]
name = "g4"
start = "h4"
end = "h1"
[[surface]]
name = "plane"
corners = [[[-1, -1, 0], [-1, 4, 0]], [[4, -1, 0], [4, 4, 0]]]
[[face]]
name = "plate"
surface = "plane"
loops = [["g1", "g2", "g3", "g4"], ["da", "cd", "bc", "ab"]]
"#;
    let case = parse_case(text, "plate").unwrap();
    let m = &case.model;
    let integrals = m.face_integrals(0).unwrap();
    // Outer loop first and counter-clockwise in (u,v); the hole clockwise.
    assert_eq!(m.faces[0].loops[0].uses.len(), 4);
    assert_eq!(
        m.edges[m.faces[0].loops[0].uses[0].edge]
            .name
            .as_deref()
            .map(|n| n.len()),
        Some(2)
    );
    let outer_edges: Vec<&str> = m.faces[0].loops[0]
        .uses
        .iter()
        .map(|u| m.edges[u.edge].name.as_deref().unwrap())
        .collect();
    assert!(outer_edges
        .iter()
        .all(|n| ["ab", "bc", "cd", "da"].contains(n)));
    // The plane's (u,v) is scaled: the patch spans 5 units over [0,1].
    let scale = 1.0 / 25.0;
    assert!(
        (integrals.loop_areas[0] - 9.0 * scale).abs() < 1e-9,
        "{:?}",
        integrals.loop_areas
    );
    assert!(
        (integrals.loop_areas[1] + 1.0 * scale).abs() < 1e-9,
        "{:?}",
        integrals.loop_areas
    );
    // 3-D area: 9 − 1.
    assert!(
        (integrals.area - 8.0).abs() < 1e-9,
        "area {}",
        integrals.area
    );
}

fn err(text: &str) -> String {
    match parse_case(text, "case.toml") {
        Err(e) => e.to_string(),
        Ok(_) => panic!("expected an error"),
    }
}

#[test]
fn missing_key_is_named() {
    let text = common::unit_cube(0.2).replace("size = 0.2\n", "");
    let e = err(&text);
    assert!(e.contains("size") && e.contains("missing"), "{e}");
}

#[test]
fn wrong_type_is_named_with_its_line() {
    let text = common::unit_cube(0.2).replace("size = 0.2", "size = \"fine\"");
    let e = err(&text);
    assert!(e.contains("line 2") && e.contains("size"), "{e}");
}

#[test]
fn unknown_key_is_an_error() {
    let text = common::unit_cube(0.2).replace("size = 0.2", "size = 0.2\nsizee = 0.3");
    let e = err(&text);
    assert!(e.contains("sizee") && e.contains("line 3"), "{e}");
}

#[test]
fn bad_value_names_key_and_line() {
    let text = common::unit_cube(0.2).replace("size = 0.2", "size = -1.0");
    let e = err(&text);
    assert!(e.contains("case.toml:2: mesh.size"), "{e}");
}

#[test]
fn unknown_reference_names_the_entry() {
    let text = common::unit_cube(0.2).replacen("surface = \"f00\"", "surface = \"nope\"", 1);
    let e = err(&text);
    assert!(
        e.contains("face 'f00'.surface") && e.contains("no surface named 'nope'"),
        "{e}"
    );
    let line = text.lines().position(|l| l.contains("\"nope\"")).unwrap() + 1;
    assert!(e.contains(&format!("case.toml:{line}:")), "{e}");
}

#[test]
fn open_loop_names_the_face_and_edges() {
    // Drop one edge from face f00's loop.
    let text = common::unit_cube(0.2);
    let start = text.find("name = \"f00\"").unwrap();
    let loops_at = start + text[start..].find("loops = [[").unwrap();
    let line_end = loops_at + text[loops_at..].find('\n').unwrap();
    let line = &text[loops_at..line_end];
    let first_comma = line.find(", ").unwrap();
    let shortened = format!("loops = [[{}", &line[first_comma + 2..]);
    let text = text.replacen(line, &shortened, 1);
    let e = err(&text);
    assert!(e.contains("face 0 'f00'") && e.contains("open"), "{e}");
}

#[test]
fn edge_used_by_one_face_of_a_closed_shell() {
    let text = common::unit_cube(0.2).replace("\"f00\", ", "");
    let e = err(&text);
    assert!(
        e.contains("used by only one face") && e.contains("region 0 'solid'"),
        "{e}"
    );
}

#[test]
fn edge_off_its_face_is_reported() {
    // Move one top vertex up: the straight edges to it leave the flat side faces.
    let text = common::unit_cube(0.2).replacen("point = [1, 1, 1]", "point = [1, 1, 1.2]", 1);
    let e = err(&text);
    assert!(e.contains("does not lie on the face's surface"), "{e}");
}

#[test]
fn cli_check_fails_with_the_message_and_nonzero_exit() {
    let dir = std::env::temp_dir().join(format!("tetrafoil-model-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("broken.toml");
    std::fs::write(&path, common::unit_cube(0.2).replace("\"f00\", ", "")).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("used by only one face"), "{stderr}");
    assert!(!stderr.contains("panicked"));
    let good = dir.join("good.toml");
    std::fs::write(&good, common::unit_cube(0.2)).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["check", good.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["faces"], 6);
    assert_eq!(v["edges"], 12);
    assert_eq!(v["vertices"], 8);
    assert_eq!(v["shells"], 1);
    // `--faces`: each face's id, marker and extent; the cube's are its six sides.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["check", good.to_str().unwrap(), "--json", "--faces"])
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let faces = v["face_details"].as_array().unwrap();
    assert_eq!(faces.len(), 6);
    for (k, f) in faces.iter().enumerate() {
        assert_eq!(f["id"], k);
        let span = |a: usize| f["max"][a].as_f64().unwrap() - f["min"][a].as_f64().unwrap();
        let flat: Vec<usize> = (0..3).filter(|&a| span(a).abs() < 1e-12).collect();
        assert_eq!(flat.len(), 1, "{f}");
        assert!(
            (0..3).all(|a| flat.contains(&a) || (span(a) - 1.0).abs() < 1e-12),
            "{f}"
        );
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["check", good.to_str().unwrap(), "--faces"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        text.lines()
            .filter(|l| l.trim_start().starts_with("face "))
            .count(),
        6
    );
    let _ = std::fs::remove_dir_all(&dir);
}
