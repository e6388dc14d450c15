//! Flow domains built around a CAD body (`--farfield`, `[mesh] farfield`): the ONERA M6 wing
//! (the body alone, on its symmetry plane) in a half box and a half sphere. The domain is
//! valid, its volume is the far field's less the wing's, the faces come out named `farfield`
//! and `symmetry` on the right surfaces, and the wing keeps the spacing it has meshed alone.
//! Bad requests are refused with messages naming what is wrong.

mod common;

use common::corpus::corpus_file;
use glam::DVec3;
use std::collections::HashMap;
use tetrafoil::case::farfield::FarfieldSpec;
use tetrafoil::case::{case_from_cad, case_from_cad_with, parse_case, ControlOverrides};
use tetrafoil::mesh::VolumeMesh;
use tetrafoil::pipeline::mesh_case;
use tetrafoil::volume::VolumeOptions;
use tetrafoil_occt::CadModel;

const M6: &str = "onera_m6_wing_sharp_te.stp";

/// The domain's mesh and its volume (the validity check's).
fn domain(path: &std::path::Path, spec: &str) -> (VolumeMesh, f64) {
    let overrides = ControlOverrides {
        farfield: Some(spec.parse().unwrap()),
        ..Default::default()
    };
    let mut case = case_from_cad_with(path, &overrides).unwrap();
    let (mesh, report) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    (mesh, report.validity.volume)
}

/// Boundary triangles per marker name.
fn faces_by_name(m: &VolumeMesh) -> HashMap<String, usize> {
    let mut n = HashMap::new();
    for &k in &m.boundary_marker {
        *n.entry(m.markers[k as usize].name.clone()).or_default() += 1;
    }
    n
}

/// The nodes of the faces named `name`.
fn nodes_of(m: &VolumeMesh, name: &str) -> Vec<DVec3> {
    let mut v: Vec<u32> = (m.boundary.iter().zip(&m.boundary_marker))
        .filter(|(_, &k)| m.markers[k as usize].name == name)
        .flat_map(|(t, _)| *t)
        .collect();
    v.sort_unstable();
    v.dedup();
    v.into_iter().map(|i| m.points[i as usize]).collect()
}

#[test]
fn the_m6_wing_in_a_half_box_and_a_half_sphere() {
    let _occt = common::occt::one_at_a_time();
    let Some(path) = corpus_file(M6) else { return };
    let wing = CadModel::read(&path).unwrap();
    let wing_volume = wing.solid_volume(0).unwrap();
    let b = wing.bounding_box().unwrap().unwrap();
    let side: [f64; 3] = std::array::from_fn(|a| b.max[a] - b.min[a]);
    let length = side.iter().copied().fold(0.0, f64::max);

    // The half box: every face planar, so the mesh holds the exact volume.
    let (m, volume) = domain(&path, "half-box:2");
    let names = faces_by_name(&m);
    assert!(names["farfield"] > 0 && names["symmetry"] > 0, "{names:?}");
    // The wing's root lies on y = 0 with the wing at y > 0: the box keeps that side.
    for p in nodes_of(&m, "symmetry") {
        assert!(
            p.y.abs() < 1e-9 * length,
            "symmetry node off the plane: {p}"
        );
    }
    let far = nodes_of(&m, "farfield");
    assert!(far.iter().all(|p| p.y > -1e-9 * length));
    let top = far.iter().map(|p| p.y).fold(f64::MIN, f64::max);
    assert!(
        (top - (b.max[1] + 2.0 * length)).abs() < 1e-6 * length,
        "{top}"
    );
    let half: [f64; 3] = std::array::from_fn(|a| 0.5 * side[a] + 2.0 * length);
    let box_volume = 2.0 * half[0] * 2.0 * half[2] * (half[1] + 0.5 * (b.max[1] + b.min[1]));
    assert!(
        ((volume - (box_volume - wing_volume)) / (box_volume - wing_volume)).abs() < 1e-6,
        "{volume} against {}",
        box_volume - wing_volume
    );

    // The half sphere: the far field on the sphere of radius 50 lengths + half the diagonal.
    let (m, volume) = domain(&path, "half-sphere:50");
    let radius = 50.0 * length + 0.5 * side.iter().map(|s| s * s).sum::<f64>().sqrt();
    let centre = DVec3::new(
        0.5 * (b.min[0] + b.max[0]),
        0.0,
        0.5 * (b.min[2] + b.max[2]),
    );
    for p in nodes_of(&m, "farfield") {
        assert!(((p - centre).length() / radius - 1.0).abs() < 1e-6, "{p}");
        assert!(p.y > -1e-9 * radius);
    }
    for p in nodes_of(&m, "symmetry") {
        assert!(p.y.abs() < 1e-9 * radius, "{p}");
    }
    // A faceted sphere holds a little less than the sphere.
    let exact = 2.0 / 3.0 * std::f64::consts::PI * radius.powi(3) - wing_volume;
    let ratio = volume / exact;
    assert!(ratio < 1.0 && ratio > 0.97, "{ratio}");
    // The wing keeps the spacing it has alone: its triangles within 20% of the wing meshed
    // by itself, with a far field 50 lengths away spaced far coarser.
    let names = faces_by_name(&m);
    let on_wing: usize = (names.iter())
        .filter(|(n, _)| !matches!(n.as_str(), "farfield" | "symmetry"))
        .map(|(_, c)| c)
        .sum();
    let mut alone = case_from_cad(&path).unwrap();
    let (alone, _) = mesh_case(&mut alone, VolumeOptions::default()).unwrap();
    let ratio = on_wing as f64 / alone.boundary.len() as f64;
    assert!(
        (0.8..1.25).contains(&ratio),
        "{on_wing} against {}",
        alone.boundary.len()
    );
    assert!(names["farfield"] < on_wing / 4, "{names:?}");
}

#[test]
fn bad_far_fields_are_refused_with_what_is_wrong() {
    let _occt = common::occt::one_at_a_time();
    // Too close, and an unknown shape: refused before anything is read.
    let e = "box:0.5".parse::<FarfieldSpec>().unwrap_err();
    assert!(e.contains("at least 1 body length"), "{e}");
    let run = common::occt::tetrafoil()
        .args([
            "mesh",
            "nothing.step",
            "--farfield",
            "cone:5",
            "-o",
            "x.su2",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert!(
        stderr.contains("unknown far-field shape 'cone'") && stderr.contains("half-sphere"),
        "{stderr}"
    );
    // A native case's far field needs a body (`tests/farfield_native.rs` has the rest).
    let text = "[mesh]\nsize = 0.1\nfarfield = { shape = \"box\", size = 10 }\n";
    let Err(e) = parse_case(text, "native.toml") else {
        panic!("a native case with a far field and no body loaded")
    };
    let e = e.to_string();
    assert!(
        e.contains("native.toml:3") && e.contains("mesh.farfield") && e.contains("no body"),
        "{e}"
    );
    let Some(dir) = common::corpus::cad_dir() else {
        return;
    };
    // A case file's far field: an unknown shape names the key and its line.
    let case = format!(
        "[mesh]\ncad = \"{}\"\nfarfield = {{ shape = \"cube\", size = 10 }}\n",
        dir.join(M6).display()
    );
    let Err(e) = parse_case(&case, "wing.toml") else {
        panic!("a far field of unknown shape loaded")
    };
    let e = e.to_string();
    assert!(
        e.contains("wing.toml:3") && e.contains("mesh.farfield.shape") && e.contains("'cube'"),
        "{e}"
    );
    // A half domain needs a symmetry face: a sphere has none.
    let overrides = ControlOverrides {
        farfield: Some("half-sphere:10".parse().unwrap()),
        ..Default::default()
    };
    let Err(e) = case_from_cad_with(&dir.join("sphere_revolved.step"), &overrides) else {
        panic!("a half domain around a sphere loaded")
    };
    let e = e.to_string();
    assert!(
        e.contains("sphere_revolved.step") && e.contains("no flat face of the body"),
        "{e}"
    );
    // A whole wing and fuselage: its flat wing tips are no symmetry face (they span a tenth
    // of the body), nor is the plane through the fuselage's axis, where the profile faces
    // between its two solids have all their vertices.
    let Err(e) = case_from_cad_with(&dir.join("wing_fuselage_2solids.step"), &overrides) else {
        panic!("a half domain around a whole wing and fuselage loaded")
    };
    let e = e.to_string();
    assert!(e.contains("a flat wing tip or end cap is not one"), "{e}");
    // A body that is not closed, even after sewing: its free edges, by id and coordinates.
    let overrides = ControlOverrides {
        farfield: Some("box:5".parse().unwrap()),
        ..Default::default()
    };
    let Err(e) = case_from_cad_with(&dir.join("cube_fillet_open_shell.stp"), &overrides) else {
        panic!("a far field around an open body loaded")
    };
    let e = e.to_string();
    assert!(
        e.contains("40 free edges") && e.contains("edge 0 (from (0, 10, 10) to (0, 50, 10))"),
        "{e}"
    );
}
