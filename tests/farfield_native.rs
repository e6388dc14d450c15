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

/// A frustum along y: a 0.2 × 0.2 end at y = 0 and a 1 × 1 end at y = 4 (x, z in 0..1).
fn frustum() -> String {
    let small = |i: usize, k: usize| [0.4 + 0.2 * i as f64, 0.0, 0.4 + 0.2 * k as f64];
    let big = |i: usize, k: usize| [i as f64, 4.0, k as f64];
    let p = |q: [f64; 3]| format!("[{:?}, {:?}, {:?}]", q[0], q[1], q[2]);
    let mut t = String::from("[mesh]\nsize = 0.25\n");
    for i in 0..2 {
        for k in 0..2 {
            t += &format!(
                "[[vertex]]\nname = \"a{i}{k}\"\npoint = {}\n",
                p(small(i, k))
            );
            t += &format!("[[vertex]]\nname = \"b{i}{k}\"\npoint = {}\n", p(big(i, k)));
            t += &format!("[[edge]]\nname = \"y{i}{k}\"\nstart = \"a{i}{k}\"\nend = \"b{i}{k}\"\n");
        }
    }
    // The end squares' edges, going round (0,0) (1,0) (1,1) (0,1).
    let round = [(0, 0), (1, 0), (1, 1), (0, 1)];
    for end in ["a", "b"] {
        for n in 0..4 {
            let ((i, k), (j, l)) = (round[n], round[(n + 1) % 4]);
            t += &format!(
                "[[edge]]\nname = \"{end}{n}\"\nstart = \"{end}{i}{k}\"\nend = \"{end}{j}{l}\"\n"
            );
        }
    }
    let mut faces = Vec::new();
    let mut face = |t: &mut String, name: &str, c: [[[f64; 3]; 2]; 2], lp: [String; 4]| {
        *t += &format!(
            "[[surface]]\nname = \"{name}_s\"\ncorners = [[{}, {}], [{}, {}]]\n",
            p(c[0][0]),
            p(c[0][1]),
            p(c[1][0]),
            p(c[1][1])
        );
        let lp: Vec<String> = lp.iter().map(|e| format!("\"{e}\"")).collect();
        *t += &format!(
            "[[face]]\nname = \"{name}\"\nsurface = \"{name}_s\"\nloops = [[{}]]\n",
            lp.join(", ")
        );
        faces.push(format!("\"{name}\""));
    };
    let ring = |e: &str| [0, 1, 2, 3].map(|n| format!("{e}{n}"));
    face(
        &mut t,
        "small",
        [[small(0, 0), small(0, 1)], [small(1, 0), small(1, 1)]],
        ring("a"),
    );
    face(
        &mut t,
        "big",
        [[big(0, 0), big(0, 1)], [big(1, 0), big(1, 1)]],
        ring("b"),
    );
    for n in 0..4 {
        let ((i, k), (j, l)) = (round[n], round[(n + 1) % 4]);
        let c = [[small(i, k), small(j, l)], [big(i, k), big(j, l)]];
        let lp = [
            format!("a{n}"),
            format!("y{j}{l}"),
            format!("b{n}"),
            format!("y{i}{k}"),
        ];
        face(&mut t, &format!("side{n}"), c, lp);
    }
    t += &format!(
        "[[region]]\nname = \"solid\"\nfaces = [{}]\n",
        faces.join(", ")
    );
    t
}

/// The frustum's small end lies at y = 0, nearer the origin than its big end at y = 4, but
/// spans a twenty-fifth of the body across y: the half box takes the big end as its plane.
#[test]
fn a_small_flat_end_is_not_a_symmetry_plane() {
    let overrides = ControlOverrides {
        farfield: Some("half-box:1".parse().expect("a spec")),
        ..Default::default()
    };
    let mut case = parse_case_with(&frustum(), "frustum.toml", &overrides).expect("loads");
    let names: Vec<&str> = case
        .model
        .faces
        .iter()
        .filter_map(|f| f.name.as_deref())
        .collect();
    assert!(
        names.contains(&"small") && !names.contains(&"big"),
        "{names:?}"
    );
    let (mesh, report) = mesh_case(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let (lo, hi) = extent_of(&mesh, "symmetry");
    assert!(
        (lo[1] - 4.0).abs() < 1e-12 && (hi[1] - 4.0).abs() < 1e-12,
        "{lo:?} {hi:?}"
    );
    // The box: y from 4 down to the body's centre less 2 + 4 (half the length plus one
    // length); x and z 0.5 ± 4.5; the frustum's volume is (1 + 0.04 + 0.2) · 4 / 3.
    let frustum = (1.0 + 0.04 + 0.2) * 4.0 / 3.0;
    let v = report.validity.volume;
    let want = 9.0 * 9.0 * 8.0 - frustum;
    assert!((v - want).abs() < 1e-9 * want, "volume {v}, want {want}");
}
