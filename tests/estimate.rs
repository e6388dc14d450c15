//! The element estimate made before meshing: close to what the mesher then makes, and the
//! guard built on it refuses a mistyped size at once, naming the estimate and the limit.

mod common;

use tetrafoil::case::parse_case;
use tetrafoil::pipeline::mesh_case;
use tetrafoil::sizing::estimate::{estimate_elements, estimate_with_limits};
use tetrafoil::volume::VolumeOptions;

/// A far field: the box [0, 40]³ at spacing 4 with a line source 1 long and 0.05 fine in it
/// (a wing in its flow domain, as sizes go). A fixed sampling grid saw the source from a
/// cell or two and estimated a fraction of the tets made.
fn far_field_with_a_small_source() -> String {
    let (ents, f) = common::box_entities("", 0.0, 40.0, false);
    let faces: Vec<String> = f.iter().map(|f| format!("\"{f}\"")).collect();
    format!(
        "[mesh]\nsize = 4\n{ents}[[region]]\nname = \"fluid\"\nfaces = [{}]\n\
         [[source]]\nkind = \"line\"\npoints = [[19.3, 20.1, 20.2], [20.3, 20.1, 20.2]]\n\
         delta = 0.05\nr1 = 0.2\nr2 = 0.5\n",
        faces.join(", ")
    )
}

/// Estimate against the mesh made, on uniform and locally refined native models.
#[test]
fn the_estimate_follows_the_mesh_made() {
    let cases = [
        ("cube.toml", common::unit_cube(0.08)),
        ("cavity.toml", common::box_with_cavity(0.1)),
        ("far_field.toml", far_field_with_a_small_source()),
    ];
    for (name, text) in cases {
        let mut case = parse_case(&text, name).unwrap();
        let estimate = estimate_elements(&case.model, &case.sizing);
        let (mesh, report) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
        assert!(report.validity.is_valid());
        let tets = mesh.tets.len() as f64;
        let triangles = mesh.boundary.len() as f64;
        println!(
            "{name}: estimated {:.0} tets / {:.0} triangles, made {tets} / {triangles}",
            estimate.tets, estimate.triangles
        );
        let (t, s) = (estimate.tets / tets, estimate.triangles / triangles);
        assert!((0.5..2.0).contains(&t), "{name}: tets estimated {t:.2}x");
        assert!(
            (0.5..2.0).contains(&s),
            "{name}: triangles estimated {s:.2}x"
        );
    }
}

/// The report's share of each limit: a model without curvature asks nothing of that limit.
#[test]
fn a_flat_model_owes_nothing_to_the_curvature_limit() {
    let case = parse_case(&common::unit_cube(0.1), "cube.toml").unwrap();
    let e = estimate_with_limits(&case.model, &case.sizing, false);
    assert_eq!(e.added_by_curvature, 0.0);
    assert_eq!(e.added_by_proximity, 0.0);
    assert!(e.total.tets > 1000.0, "{e:?}");
}

fn tetrafoil(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(args)
        .output()
        .unwrap()
}

/// The typo: the wing sample at size 1e-7 (meant 1e-2) would need some 1e19 tets. It
/// is refused before the curves are meshed, with the estimate, the limit and the way out.
#[test]
fn a_mistyped_size_is_refused_before_meshing() {
    let dir = std::env::temp_dir().join(format!("tetrafoil-estimate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("wing.su2");
    let case = concat!(env!("CARGO_MANIFEST_DIR"), "/samples/wing/case.toml");
    let run = tetrafoil(&["mesh", case, "--size", "1e-7", "-o", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("tetrahedra"), "{stderr}");
    assert!(stderr.contains("--max-elements"), "{stderr}");
    assert!(stderr.contains("size 1e-7"), "{stderr}");
    assert!(
        !stderr.contains("curve mesh:"),
        "curves were meshed: {stderr}"
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// `--max-elements` below the estimate refuses the cube sample; above it, the cube meshes.
#[test]
fn max_elements_sets_the_limit() {
    let dir = std::env::temp_dir().join(format!("tetrafoil-limit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("cube.vtu");
    let case = concat!(env!("CARGO_MANIFEST_DIR"), "/samples/cube/case.toml");
    let o = out.to_str().unwrap();
    let refused = tetrafoil(&["-q", "mesh", case, "--max-elements", "100", "-o", o]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("more than the limit of 100"), "{stderr}");
    assert!(!out.exists());
    let meshed = tetrafoil(&["-q", "mesh", case, "--max-elements", "1e7", "-o", o]);
    assert!(
        meshed.status.success(),
        "{}",
        String::from_utf8_lossy(&meshed.stderr)
    );
    assert!(out.exists());
    let bad = tetrafoil(&["-q", "mesh", case, "--max-elements", "0", "-o", o]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--max-elements must be"));
    std::fs::remove_dir_all(&dir).ok();
}

/// The same far field meshed: the interior points reach the source, which no surface node
/// is near (they took δ from their tet's corners only, and no point came within 0.3 of it).
#[test]
fn a_source_far_from_every_surface_refines_the_volume_around_it() {
    let mut case = parse_case(&far_field_with_a_small_source(), "ff.toml").unwrap();
    let (mesh, report) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    assert!(report.validity.is_valid());
    let beside = |p: glam::DVec3| (p.y - 20.1).hypot(p.z - 20.2) < 0.2 && p.x > 19.4 && p.x < 20.2;
    let near = mesh.points.iter().filter(|&&p| beside(p)).count();
    let mut edges: Vec<f64> = Vec::new();
    for t in &mesh.tets {
        let p = t.map(|i| mesh.points[i as usize]);
        if p.iter().all(|&q| beside(q)) {
            for i in 0..4 {
                for j in i + 1..4 {
                    edges.push(p[i].distance(p[j]));
                }
            }
        }
    }
    edges.sort_by(f64::total_cmp);
    let median = edges.get(edges.len() / 2).copied().unwrap_or(f64::INFINITY);
    println!("{near} points beside the source, median edge {median:.4}");
    // The source's δ is 0.05 there: a cylinder 0.2 in radius and 0.8 long holds some 10³.
    assert!(near > 500, "{near} points");
    assert!((0.03..0.08).contains(&median), "median edge {median}");
}
