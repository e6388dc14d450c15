//! Surface meshing on native models: closed and manifold shells, triangles oriented with their
//! surface, area equal to the boundary-integral area of every face, sizes following δ.

mod common;

use std::collections::HashMap;
use tetrafoil::case::parse_case;
use tetrafoil::curve::mesh_curves;
use tetrafoil::surface::{mesh_surfaces, SurfaceMesh, SurfaceOptions};

fn mesh(text: &str, name: &str) -> (tetrafoil::case::Case, SurfaceMesh) {
    let case = parse_case(text, name).unwrap();
    let curves = mesh_curves(&case.model, &case.sizing).unwrap();
    let (surface, failures) = mesh_surfaces(
        &case.model,
        &curves,
        &case.sizing,
        SurfaceOptions::default(),
    )
    .unwrap();
    assert!(failures.is_empty());
    (case, surface)
}

/// Every edge of the region's shells is used by exactly two triangles, in opposite directions
/// once the faces are turned to point out of the region.
fn assert_closed_and_consistent(case: &tetrafoil::case::Case, m: &SurfaceMesh) {
    let model = &case.model;
    let mut reversed = vec![false; model.faces.len()];
    let mut in_shell = vec![false; model.faces.len()];
    for fu in model.region_faces(0) {
        reversed[fu.face] = fu.reversed;
        in_shell[fu.face] = true;
    }
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for (t, &f) in m.triangles.iter().zip(&m.face_of) {
        if !in_shell[f] {
            continue;
        }
        let t = if reversed[f] { [t[0], t[2], t[1]] } else { *t };
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "edge {a}-{b} used {n} times in one direction");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "edge {a}-{b} has no opposite use: the shell is open"
        );
    }
}

/// Mesh area per face against the face's boundary-integral area; orientation against Su × Sv.
fn assert_areas_and_orientation(case: &tetrafoil::case::Case, m: &SurfaceMesh, tol: f64) {
    let model = &case.model;
    let mut area = vec![0.0; model.faces.len()];
    for (t, &f) in m.triangles.iter().zip(&m.face_of) {
        let (a, b, c) = (m.points[t[0]], m.points[t[1]], m.points[t[2]]);
        let n = (b - a).cross(c - a);
        area[f] += 0.5 * n.length();
        // The triangle's normal agrees with the surface normal at its centroid.
        let s = &model.faces[f].surface;
        let centroid = (a + b + c) / 3.0;
        let uv = s.closest_uv(centroid, None).unwrap();
        assert!(
            n.dot(s.normal(uv)) > 0.0,
            "inverted triangle on {}",
            model.face_ref(f)
        );
    }
    for (f, &got) in area.iter().enumerate() {
        let exact = model.face_integrals(f).unwrap().area;
        assert!(
            (got - exact).abs() <= tol * exact,
            "{}: mesh area {got} vs {exact}",
            model.face_ref(f)
        );
    }
}

#[test]
fn cube_surface_is_closed_with_exact_area_and_even_edges() {
    let (case, m) = mesh(&common::unit_cube(0.1), "cube");
    assert_closed_and_consistent(&case, &m);
    assert_areas_and_orientation(&case, &m, 1e-9);
    // Euler characteristic of a sphere-like closed surface.
    let nodes: std::collections::HashSet<usize> = m.triangles.iter().flatten().copied().collect();
    let edges = 3 * m.triangles.len() / 2;
    assert_eq!(
        nodes.len() as i64 - edges as i64 + m.triangles.len() as i64,
        2
    );
    // Edge lengths near δ = 0.1.
    let mut lengths = Vec::new();
    for t in &m.triangles {
        for k in 0..3 {
            lengths.push(m.points[t[k]].distance(m.points[t[(k + 1) % 3]]));
        }
    }
    let within = lengths
        .iter()
        .filter(|&&l| (0.06..=0.15).contains(&l))
        .count();
    assert!(
        within as f64 >= 0.95 * lengths.len() as f64,
        "{within} of {} edges in [0.6, 1.5]δ",
        lengths.len()
    );
}

#[test]
fn cavity_box_has_two_closed_shells() {
    let (case, m) = mesh(&common::box_with_cavity(0.4), "cavity");
    assert_closed_and_consistent(&case, &m);
    assert_areas_and_orientation(&case, &m, 1e-9);
}

#[test]
fn wing_sample_faces_mesh_with_their_area() {
    let text = tetrafoil::samples::all()
        .into_iter()
        .find(|(n, _)| *n == "wing")
        .unwrap()
        .1;
    let (case, m) = mesh(&text, "wing");
    assert_closed_and_consistent(&case, &m);
    // Curved faces: chordal error only.
    assert_areas_and_orientation(&case, &m, 5e-3);
    let share = angle_share(&m);
    assert!(
        share >= 0.97,
        "{:.1}% of {} triangles with min angle >= 25°",
        100.0 * share,
        m.triangles.len()
    );
}

/// `tetrafoil mesh` of the unit cube (size 0.25) with `--surface-only` and `extra` arguments,
/// in a folder of its own (`tag`): the report, and `tetrafoil quality --json` of the written
/// surface.
fn cube_surface_only(tag: &str, extra: &[&str]) -> (serde_json::Value, serde_json::Value) {
    let dir = std::env::temp_dir().join(format!("tetrafoil-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let case = dir.join("cube.toml");
    std::fs::write(&case, common::unit_cube(0.25)).unwrap();
    let (out, report) = (dir.join("cube.vtu"), dir.join("report.json"));
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["mesh", case.to_str().unwrap(), "-o", out.to_str().unwrap()])
        .args(["--report", report.to_str().unwrap(), "--surface-only", "-q"])
        .args(extra)
        .status()
        .unwrap();
    assert!(status.success());
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let q = std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["quality", out.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(q.status.success());
    let v: serde_json::Value = serde_json::from_slice(&q.stdout).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (r, v)
}

#[test]
fn cli_writes_the_surface_mesh_and_quality_reads_it() {
    let (r, v) = cube_surface_only("surface-test", &[]);
    let triangles = r["surface_mesh"]["triangles"].as_u64().unwrap();
    assert!(triangles > 100);
    assert_eq!(v["triangle_min_angle"]["count"].as_u64(), Some(triangles));
    assert!(v["triangle_min_angle"]["min"].as_f64().unwrap() > 20.0);
}

/// `--surface-only` with a refinement writes the surface the volume stage would take: the
/// faces beside the source carry the layers' edge and face points.
#[test]
fn cli_surface_only_writes_the_refined_surface() {
    let refine = ["--refine-faces", "0", "--first", "0.02", "--growth", "1.3"];
    let (r, v) = cube_surface_only("refsurf-test", &refine);
    let before = r["surface_mesh"]["triangles"].as_u64().unwrap();
    let stage = &r["refinement"][0]["surface"];
    assert!(stage["edge_points"].as_u64().unwrap() > 0, "{stage}");
    assert!(stage["face_points"].as_u64().unwrap() > 0, "{stage}");
    let written = v["triangle_min_angle"]["count"].as_u64().unwrap();
    assert!(
        written > before,
        "{written} triangles written, {before} before refinement"
    );
}

/// A prism over a 10 × 0.25 triangle at δ = 1: the bottom and top faces are wedges between
/// nearly parallel edges, narrower than δ everywhere and with staggered nodes on the two long
/// sides, so only needles fit. The front used to stop there (clearance against slivers).
fn thin_wedge_prism() -> String {
    let (l, w, h) = (10.0, 0.25, 1.0);
    let vertices = [
        ("a0", [0.0, 0.0, 0.0]),
        ("b0", [l, 0.0, 0.0]),
        ("c0", [l, w, 0.0]),
        ("a1", [0.0, 0.0, h]),
        ("b1", [l, 0.0, h]),
        ("c1", [l, w, h]),
    ];
    let mut s = String::from("[mesh]\nsize = 1.0\n");
    for (n, p) in vertices {
        s += &format!("[[vertex]]\nname = \"{n}\"\npoint = {p:?}\n");
    }
    let edges = [
        "a0 b0", "b0 c0", "c0 a0", "a1 b1", "b1 c1", "c1 a1", "a0 a1", "b0 b1", "c0 c1",
    ];
    for e in edges {
        let (a, b) = e.split_once(' ').unwrap();
        s += &format!("[[edge]]\nname = \"{a}{b}\"\nstart = \"{a}\"\nend = \"{b}\"\n");
    }
    let p = |x: f64, y: f64, z: f64| format!("[{x:?}, {y:?}, {z:?}]");
    let surfaces = [
        (
            "bottom",
            [
                p(0.0, 0.0, 0.0),
                p(0.0, 1.0, 0.0),
                p(l, 0.0, 0.0),
                p(l, 1.0, 0.0),
            ],
        ),
        (
            "top",
            [p(0.0, 0.0, h), p(0.0, 1.0, h), p(l, 0.0, h), p(l, 1.0, h)],
        ),
        (
            "side_ab",
            [
                p(0.0, 0.0, 0.0),
                p(0.0, 0.0, h),
                p(l, 0.0, 0.0),
                p(l, 0.0, h),
            ],
        ),
        (
            "side_ac",
            [p(0.0, 0.0, 0.0), p(0.0, 0.0, h), p(l, w, 0.0), p(l, w, h)],
        ),
        (
            "side_bc",
            [p(l, 0.0, 0.0), p(l, 0.0, h), p(l, w, 0.0), p(l, w, h)],
        ),
    ];
    for (n, c) in &surfaces {
        s += &format!(
            "[[surface]]\nname = \"{n}\"\ncorners = [[{}, {}], [{}, {}]]\n",
            c[0], c[1], c[2], c[3]
        );
    }
    let faces = [
        ("bottom", "a0b0 b0c0 c0a0"),
        ("top", "a1b1 b1c1 c1a1"),
        ("side_ab", "a0b0 b0b1 a1b1 a0a1"),
        ("side_ac", "c0a0 a0a1 c1a1 c0c1"),
        ("side_bc", "b0c0 c0c1 b1c1 b0b1"),
    ];
    let quoted = |x: &str| -> String {
        let v: Vec<String> = x.split(' ').map(|e| format!("\"{e}\"")).collect();
        v.join(", ")
    };
    for (n, l) in faces {
        s += &format!(
            "[[face]]\nname = \"{n}\"\nsurface = \"{n}\"\nloops = [[{}]]\n",
            quoted(l)
        );
    }
    s += "[[region]]\nname = \"solid\"\nfaces = [\"bottom\", \"top\", \"side_ab\", \"side_ac\", \"side_bc\"]\n";
    s
}

#[test]
fn thin_wedge_between_nearly_parallel_edges_closes() {
    let (case, m) = mesh(&thin_wedge_prism(), "wedge");
    assert_closed_and_consistent(&case, &m);
    assert_areas_and_orientation(&case, &m, 1e-9);
}

/// Share of triangles with a minimum angle of at least 25°.
fn angle_share(m: &SurfaceMesh) -> f64 {
    let good = m
        .triangles
        .iter()
        .filter(|t| {
            tetrafoil::mesh::quality::triangle_min_angle(
                m.points[t[0]],
                m.points[t[1]],
                m.points[t[2]],
            ) >= 25.0
        })
        .count();
    good as f64 / m.triangles.len() as f64
}

/// A unit cube at δ = 0.025 has faces of ~3700 triangles: each is cut into parts meshed
/// concurrently. The shells stay closed with the exact area, the angles are as good as with
/// the faces meshed whole, and one thread and two give the same mesh.
#[test]
fn large_native_faces_are_split_and_stay_closed() {
    let case = parse_case(&common::unit_cube(0.025), "fine cube").unwrap();
    let curves = mesh_curves(&case.model, &case.sizing).unwrap();
    let run = |threads: usize, whole_faces: bool| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let options = SurfaceOptions {
            whole_faces,
            ..Default::default()
        };
        pool.install(|| mesh_surfaces(&case.model, &curves, &case.sizing, options))
            .unwrap()
            .0
    };
    let (one, two, whole) = (run(1, false), run(2, false), run(2, true));
    assert_eq!(one.split_faces(), 6);
    assert!(one.face_parts.iter().all(|&p| p >= 2));
    assert_eq!(whole.split_faces(), 0);
    assert_closed_and_consistent(&case, &one);
    assert_areas_and_orientation(&case, &one, 1e-9);
    assert_eq!(one.points, two.points);
    assert_eq!(one.triangles, two.triangles);
    let (split, unsplit) = (angle_share(&one), angle_share(&whole));
    println!(
        "parts {:?}, triangles {} (whole {}), angles >= 25°: {:.2}% (whole {:.2}%)",
        one.face_parts,
        one.triangles.len(),
        whole.triangles.len(),
        100.0 * split,
        100.0 * unsplit
    );
    assert!(split >= 0.99 && split >= unsplit - 0.002);
}
