//! Wakes found and shed automatically (`--wakes auto`, `[mesh] wakes = "auto"`): the ONERA M6
//! wing (the body alone) in a half-sphere far field sheds one wake from its sharp trailing
//! edge, along the free stream, its root edge a slit of the symmetry face; the mesh is valid
//! with the wake's triangles between cells on both sides and the symmetry plane meshed on both
//! sides of the slit. Bad requests name what is wrong.

mod common;

use common::corpus::corpus_file;
use glam::DVec3;
use std::collections::HashMap;
use tetrafoil::case::{case_from_cad_with, parse_case, AutoWakes, ControlOverrides};
use tetrafoil::model::Model;
use tetrafoil::pipeline::mesh_case;
use tetrafoil::volume::VolumeOptions;

const M6: &str = "onera_m6_wing_sharp_te.stp";

fn overrides(farfield: Option<&str>, wakes: AutoWakes) -> ControlOverrides {
    ControlOverrides {
        farfield: farfield.map(|f| f.parse().unwrap()),
        wakes: Some(wakes),
        ..Default::default()
    }
}

fn face_named(model: &Model, name: &str) -> usize {
    (0..model.faces.len())
        .find(|&f| model.faces[f].name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no face named {name}"))
}

#[test]
fn the_m6_half_model_sheds_one_wake_joined_to_its_symmetry_plane() {
    let _occt = common::occt::one_at_a_time();
    let Some(path) = corpus_file(M6) else { return };
    let mut case = case_from_cad_with(
        &path,
        &overrides(Some("half-sphere:50"), AutoWakes::default()),
    )
    .unwrap();
    let model = &case.model;
    let wakes: Vec<usize> = (0..model.faces.len())
        .filter(|&f| (model.faces[f].name.as_deref()).is_some_and(|n| n.starts_with("wake")))
        .collect();
    assert_eq!(wakes.len(), 1, "one trailing edge, one wake");
    let wake = face_named(model, "wake_1");
    assert!(model.regions[0].embedded_faces.contains(&wake));
    // The wake starts at the trailing edge (x = 810.5 at the root, 1146.6 at the tip, mm) and
    // runs along +x to the far field (50 body lengths of 1218 mm) less one far-field cell.
    let corners: Vec<DVec3> = model.faces[wake].loops[0]
        .uses
        .iter()
        .map(|u| model.vertices[model.use_vertices(u).0].point)
        .collect();
    let x_max = corners.iter().map(|p| p.x).fold(f64::MIN, f64::max);
    let x_min = corners.iter().map(|p| p.x).fold(f64::MAX, f64::min);
    assert!((x_min - 810.49).abs() < 0.1, "{corners:?}");
    assert!(
        x_max > 40.0 * 1218.0 && x_max < 51.0 * 1218.0,
        "{corners:?}"
    );
    assert!(corners.iter().all(|p| p.z.abs() < 1e-3), "{corners:?}");
    // Its root edge is a slit of the symmetry face: used there twice, once each way.
    let symmetry = face_named(model, "symmetry");
    let root = (0..model.edges.len())
        .find(|&e| model.edges[e].name.as_deref() == Some("wake_1_side_start"))
        .unwrap();
    let uses: Vec<bool> = (model.faces[symmetry].loops.iter())
        .flat_map(|l| &l.uses)
        .filter(|u| u.edge == root)
        .map(|u| u.reversed)
        .collect();
    assert_eq!(uses, vec![false, true]);

    let (mesh, report) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let name_of = |t: usize| mesh.markers[mesh.boundary_marker[t] as usize].name.as_str();
    let wake_tris: Vec<usize> = (0..mesh.boundary.len())
        .filter(|&t| name_of(t) == "wake_1")
        .collect();
    assert!(wake_tris.len() > 100, "{}", wake_tris.len());
    let two_sided = tetrafoil::mesh::validity::two_sided_boundary_faces(&mesh);
    assert!(
        wake_tris.iter().all(|&t| two_sided[t]),
        "every wake triangle has cells on both sides"
    );
    // Every edge the wake shares with the symmetry plane (its root row) has two symmetry
    // triangles on it, one each side of the slit, and lies in the plane y = 0 (to rounding;
    // the root node is the CAD vertex, a few 1e-9 off it).
    let edges = |name: &str| -> HashMap<(u32, u32), usize> {
        let mut on_edge = HashMap::new();
        for t in (0..mesh.boundary.len()).filter(|&t| name_of(t) == name) {
            let v = mesh.boundary[t];
            for k in 0..3 {
                let (a, b) = (v[k], v[(k + 1) % 3]);
                *on_edge.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        on_edge
    };
    let symmetry_edges = edges("symmetry");
    let slit: Vec<((u32, u32), usize)> = edges("wake_1")
        .into_keys()
        .filter_map(|e| symmetry_edges.get(&e).map(|&n| (e, n)))
        .collect();
    assert!(slit.len() >= 10, "{} slit edges", slit.len());
    for &((a, b), n) in &slit {
        assert_eq!(n, 2, "symmetry triangles on a slit edge");
        for v in [a, b] {
            let p = mesh.points[v as usize];
            assert!(p.y.abs() < 1e-8 && p.z.abs() < 1e-3 && p.x >= 810.4, "{p}");
        }
    }
}

#[test]
fn automatic_wakes_follow_the_free_stream_and_bad_requests_name_what_is_wrong() {
    let _occt = common::occt::one_at_a_time();
    let Some(path) = corpus_file(M6) else { return };
    // 5° angle of attack: the sheet climbs at 5°.
    let up = AutoWakes {
        alpha: 5.0,
        ..Default::default()
    };
    let case = case_from_cad_with(&path, &overrides(Some("half-box:3"), up)).unwrap();
    let model = &case.model;
    let edge = |name: &str| {
        (0..model.edges.len())
            .find(|&e| model.edges[e].name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no edge named {name}"))
    };
    let side = &model.edges[edge("wake_1_side_start")];
    let (p, q) = (
        model.vertices[side.start].point,
        model.vertices[side.end].point,
    );
    let climb = ((q.z - p.z) / (q.x - p.x)).atan().to_degrees();
    assert!((climb - 5.0).abs() < 1e-6, "{climb}° from {p} to {q}");

    // Sideslip on a half model would carry the wake through its symmetry plane.
    let side = AutoWakes {
        beta: 4.0,
        ..Default::default()
    };
    let Err(e) = case_from_cad_with(&path, &overrides(Some("half-sphere:50"), side)) else {
        panic!("a half model with sideslip loaded")
    };
    let e = e.to_string();
    assert!(e.contains("leaves the symmetry plane y = "), "{e}");
    // A flow domain given as a file: tetrafoil does not know where its far field is.
    let domain = corpus_file("onera_m6_halfsphere_domain.stp").unwrap();
    let Err(e) = case_from_cad_with(&domain, &overrides(None, AutoWakes::default())) else {
        panic!("automatic wakes without a length loaded in a given domain")
    };
    assert!(e.to_string().contains("--wake-length"), "{e}");
    // With a length, the domain's own trailing edge sheds one, joined to its symmetry face.
    let long = AutoWakes {
        length: Some(2000.0),
        ..Default::default()
    };
    let case = case_from_cad_with(&domain, &overrides(None, long)).unwrap();
    let wake = face_named(&case.model, "wake_1");
    assert!(case.model.regions[0].embedded_faces.contains(&wake));

    // A case file's request: a bad mode and a bad angle name the key and line.
    let dir = common::corpus::cad_dir().unwrap();
    let text = |extra: &str| {
        format!(
            "[mesh]\ncad = \"{}\"\nfarfield = {{ shape = \"half-sphere\", size = 50 }}\n{extra}",
            dir.join(M6).display()
        )
    };
    let Err(e) = parse_case(&text("wakes = \"sometimes\"\n"), "m6.toml") else {
        panic!("wakes = \"sometimes\" loaded")
    };
    let e = e.to_string();
    assert!(
        e.contains("m6.toml:4") && e.contains("mesh.wakes") && e.contains("\"auto\""),
        "{e}"
    );
    let Err(e) = parse_case(&text("wakes = \"auto\"\nalpha = 95\n"), "m6.toml") else {
        panic!("alpha = 95 loaded")
    };
    let e = e.to_string();
    assert!(e.contains("m6.toml:5") && e.contains("mesh.alpha"), "{e}");
    // The command line: angles go with --wakes auto.
    let run = common::occt::tetrafoil()
        .args([
            "mesh",
            path.to_str().unwrap(),
            "--alpha",
            "3",
            "-o",
            "x.su2",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success());
    assert!(
        stderr.contains("--alpha goes with --wakes auto"),
        "{stderr}"
    );
}

/// The STEP wing sample (`samples/wing_step`, a flow domain with the wing on its symmetry
/// plane): its skin is one face lofted round the closed section, so its trailing edge is the
/// skin's seam, which sheds the wake as two faces' edge would.
#[test]
fn a_skin_whose_seam_is_the_trailing_edge_sheds_its_wake_from_it() {
    let _occt = common::occt::one_at_a_time();
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/wing_step/wing_in_box.step");
    let long = AutoWakes {
        length: Some(1.5),
        ..Default::default()
    };
    let mut case = case_from_cad_with(&path, &overrides(None, long)).unwrap();
    let model = &case.model;
    let wake = face_named(model, "wake_1");
    let corners: Vec<DVec3> = (model.faces[wake].loops[0].uses.iter())
        .map(|u| model.vertices[model.use_vertices(u).0].point)
        .collect();
    // The trailing edge runs from (1, 0, 0) at the root to (1.6547, 2, 0) at the tip.
    assert!(
        corners
            .iter()
            .any(|p| p.distance(DVec3::new(1.0, 0.0, 0.0)) < 1e-6),
        "{corners:?}"
    );
    assert!(
        corners
            .iter()
            .any(|p| p.distance(DVec3::new(2.5, 0.0, 0.0)) < 1e-6),
        "{corners:?}"
    );
    let (mesh, report) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let two_sided = tetrafoil::mesh::validity::two_sided_boundary_faces(&mesh);
    let wake: Vec<usize> = (0..mesh.boundary.len())
        .filter(|&t| mesh.markers[mesh.boundary_marker[t] as usize].name == "wake_1")
        .collect();
    assert!(
        wake.len() > 20 && wake.iter().all(|&t| two_sided[t]),
        "{}",
        wake.len()
    );
}
