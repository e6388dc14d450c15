//! Flow domains around a native body (`[mesh] farfield`, `--farfield` on a native case): the
//! cube sample as the body in a box and in a half box on its ymin plane. The domain is valid,
//! its volume is the box's less the cube's, the far field's faces come out as one marker
//! `farfield` (and `symmetry` on the plane), the body keeps its faces' names and its spacing,
//! and a refinement stage on the body still runs. Bad requests name what is wrong.

use std::collections::HashMap;
use tetrafoil::case::{parse_case, parse_case_with, CaseError, ControlOverrides};
use tetrafoil::mesh::VolumeMesh;
use tetrafoil::pipeline::{mesh_case, mesh_case_refined};
use tetrafoil::samples;
use tetrafoil::volume::VolumeOptions;

fn cube() -> String {
    samples::all()
        .into_iter()
        .find(|(n, _)| *n == "cube")
        .map(|(_, t)| t)
        .expect("the cube sample")
}

/// Boundary triangles per marker name.
fn faces_by_name(m: &VolumeMesh) -> HashMap<String, usize> {
    let mut n = HashMap::new();
    for &k in &m.boundary_marker {
        *n.entry(m.markers[k as usize].name.clone()).or_default() += 1;
    }
    n
}

/// The extent of the nodes of the faces named `name`, per axis.
fn extent_of(m: &VolumeMesh, name: &str) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for (t, &k) in m.boundary.iter().zip(&m.boundary_marker) {
        if m.markers[k as usize].name != name {
            continue;
        }
        for &v in t {
            let p = m.points[v as usize].to_array();
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
    }
    (lo, hi)
}

fn with_farfield(text: &str, table: &str) -> String {
    text.replacen("[mesh]\n", &format!("[mesh]\nfarfield = {table}\n"), 1)
}

/// The unit cube, 2 body lengths out: a box of side 5 about its centre, less the cube.
#[test]
fn a_native_body_in_a_box() {
    let text = with_farfield(&cube(), r#"{ shape = "box", size = 2 }"#);
    let mut case = parse_case(&text, "cube_in_box.toml").expect("loads");
    let (mesh, report) = mesh_case(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let v = report.validity.volume;
    assert!((v - (125.0 - 1.0)).abs() < 1e-9 * 125.0, "volume {v}");
    let names = faces_by_name(&mesh);
    for n in ["farfield", "xmin", "xmax", "ymin", "ymax", "zmin", "zmax"] {
        assert!(names.get(n).copied().unwrap_or(0) > 0, "{n}: {names:?}");
    }
    assert_eq!(names.len(), 7, "{names:?}");
    let (lo, hi) = extent_of(&mesh, "farfield");
    for a in 0..3 {
        assert!(
            (lo[a] + 2.0).abs() < 1e-12 && (hi[a] - 3.0).abs() < 1e-12,
            "{lo:?} {hi:?}"
        );
    }
    // The body keeps the case's spacing (0.0866): its faces are as fine as the cube alone;
    // the far field is coarser.
    let alone = {
        let mut case = parse_case(&cube(), "cube.toml").expect("loads");
        let (mesh, _) = mesh_case(&mut case, VolumeOptions::default()).expect("meshes");
        faces_by_name(&mesh)["zmin"]
    };
    let here = names["zmin"];
    assert!(
        (here as f64) > 0.7 * alone as f64 && (here as f64) < 1.3 * alone as f64,
        "zmin triangles {here} here, {alone} alone"
    );
}

/// On a half box the cube's ymin face is the symmetry plane: it goes, and the box's face on
/// y = 0 (named `symmetry`) has its loop as a hole. The box reaches 2.5 above the cube's
/// centre: 5 × 3 × 5, less the cube. Refinement from zmax still runs.
#[test]
fn a_native_half_body_in_a_half_box_with_layers() {
    let stage = r#"
[[refine]]
[[refine.source]]
faces = ["zmax"]
first = 0.01
growth = 1.2
"#;
    let text = with_farfield(&cube(), r#"{ shape = "half-box", size = 2 }"#) + stage;
    let mut case = parse_case(&text, "half_cube.toml").expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let v = report.validity.volume;
    assert!((v - (75.0 - 1.0)).abs() < 1e-9 * 75.0, "volume {v}");
    let names = faces_by_name(&mesh);
    assert!(!names.contains_key("ymin"), "{names:?}");
    assert!(names["symmetry"] > 0 && names["farfield"] > 0, "{names:?}");
    let (lo, hi) = extent_of(&mesh, "symmetry");
    assert!(lo[1].abs() < 1e-12 && hi[1].abs() < 1e-12, "{lo:?} {hi:?}");
    let (lo, hi) = extent_of(&mesh, "farfield");
    assert!(
        lo[1].abs() < 1e-12 && (hi[1] - 3.0).abs() < 1e-12,
        "{lo:?} {hi:?}"
    );
    assert!(refined.stages[0].volume.points + refined.stages[0].columns.points > 0);
}

/// The same through the command line's override, and the refusals.
#[test]
fn native_far_fields_refuse_what_they_cannot_build() {
    let overrides = |spec: &str| ControlOverrides {
        farfield: Some(spec.parse().expect("a spec")),
        ..Default::default()
    };
    let case = parse_case_with(&cube(), "cube.toml", &overrides("box:3")).expect("loads");
    let far = case
        .model
        .faces
        .iter()
        .filter(|f| f.name.as_deref() == Some("farfield"))
        .count();
    assert_eq!(far, 6);
    let message = |r: Result<_, CaseError>| match r {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted"),
    };
    let m = message(parse_case_with(
        &cube(),
        "cube.toml",
        &overrides("sphere:3"),
    ));
    assert!(
        m.contains("--farfield sphere") && m.contains("box or half-box"),
        "{m}"
    );
    let text = with_farfield(&cube(), r#"{ shape = "half-sphere", size = 3 }"#);
    let m = message(parse_case(&text, "c.toml"));
    assert!(m.contains("c.toml:") && m.contains("mesh.farfield"), "{m}");
    let clash = cube().replace("name = \"zmax\"\n", "name = \"symmetry\"\n");
    let clash = clash.replace("\"zmax\"]", "\"symmetry\"]");
    let m = message(parse_case_with(&clash, "clash.toml", &overrides("box:3")));
    assert!(m.contains("'symmetry'"), "{m}");
}
