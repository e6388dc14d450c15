//! The spacing function: FELISA sources, background mesh, curvature limit.

mod common;

use glam::DVec3;
use tetrafoil::case::parse_case;
use tetrafoil::sizing::{felisa, BackgroundMesh, SizingField, Source, SourceShape};

#[test]
fn felisa_law_constant_then_doubling() {
    let (d1, r1, r2) = (0.1, 1.0, 3.0);
    assert_eq!(felisa(0.0, d1, r1, r2), d1);
    assert_eq!(felisa(1.0, d1, r1, r2), d1);
    assert!((felisa(3.0, d1, r1, r2) - 0.2).abs() < 1e-15);
    assert!((felisa(5.0, d1, r1, r2) - 0.4).abs() < 1e-15);
    assert!((felisa(2.0, d1, r1, r2) - 0.1 * 2f64.sqrt()).abs() < 1e-15);
}

#[test]
fn sources_measure_distance_to_their_shape() {
    let line = Source {
        shape: SourceShape::Line(DVec3::ZERO, DVec3::X),
        delta1: 0.01,
        r1: 0.1,
        r2: 0.2,
    };
    // 0.3 from the segment's middle: two doublings past r1 = 0.1 → 0.04.
    assert!((line.spacing(DVec3::new(0.5, 0.3, 0.0)) - 0.04).abs() < 1e-12);
    // Beyond the end, the distance is to the end point.
    assert!((line.spacing(DVec3::new(1.3, 0.0, 0.0)) - 0.04).abs() < 1e-12);
    let tri = Source {
        shape: SourceShape::Triangle([DVec3::ZERO, DVec3::X, DVec3::Y]),
        delta1: 0.01,
        r1: 0.1,
        r2: 0.2,
    };
    assert!((tri.spacing(DVec3::new(0.2, 0.2, 0.2)) - 0.02).abs() < 1e-12);
    assert!((tri.spacing(DVec3::new(-0.2, 0.5, 0.0)) - 0.02).abs() < 1e-12);
    let mut field = SizingField::uniform(0.5);
    field.sources.push(line);
    assert_eq!(field.spacing(DVec3::new(0.5, 0.0, 0.0)), 0.01);
    assert_eq!(field.spacing(DVec3::new(0.5, 100.0, 0.0)), 0.5);
}

#[test]
fn background_mesh_interpolates_linearly_and_is_absent_outside() {
    // Two tets filling the prism between z=0 and z=1 under the triangle (0,0),(1,0),(0,1) would
    // need three; use a single tet and a linear spacing δ = 0.1 + 0.2x + 0.3y + 0.4z.
    let nodes = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let f = |p: DVec3| 0.1 + 0.2 * p.x + 0.3 * p.y + 0.4 * p.z;
    let spacing = nodes.iter().map(|&p| f(p)).collect();
    let bg = BackgroundMesh::new(nodes, spacing, vec![[0, 1, 2, 3]]).unwrap();
    for p in [
        DVec3::new(0.1, 0.2, 0.3),
        DVec3::new(0.25, 0.25, 0.25),
        DVec3::new(0.0, 0.5, 0.0),
    ] {
        assert!((bg.spacing(p).unwrap() - f(p)).abs() < 1e-14);
    }
    assert_eq!(bg.spacing(DVec3::new(0.6, 0.6, 0.1)), None);
    assert!(BackgroundMesh::new(vec![DVec3::ZERO; 4], vec![1.0; 4], vec![[0, 1, 2, 3]]).is_err());
    assert!(BackgroundMesh::new(vec![DVec3::ZERO], vec![1.0], vec![[0, 1, 2, 3]]).is_err());
}

#[test]
fn curvature_limit_resolves_a_small_circle_under_a_coarse_size() {
    // A quarter-circle edge of radius 0.1 in a case whose size is 1: with n = 12 the spacing on
    // it must not exceed 2π·0.1/12.
    let text = r#"
[mesh]
size = 1.0
curvature_segments = 12
[[vertex]]
name = "a"
point = [0.1, 0, 0]
[[vertex]]
name = "b"
point = [0, 0.1, 0]
[[curve]]
name = "arc"
points = [[0.1, 0, 0], [0.0923880, 0.0382683, 0], [0.0707107, 0.0707107, 0], [0.0382683, 0.0923880, 0], [0, 0.1, 0]]
[[edge]]
name = "arc"
start = "a"
end = "b"
curve = "arc"
"#;
    let case = parse_case(text, "arc").unwrap();
    let limit = std::f64::consts::TAU * 0.1 / 12.0;
    let on_arc = DVec3::new(0.0707107, 0.0707107, 0.0);
    let d = case.sizing.spacing(on_arc);
    assert!(
        d <= 1.05 * limit && d >= 0.8 * limit,
        "δ = {d}, limit {limit}"
    );
    // Far away the uniform size comes back.
    assert_eq!(case.sizing.spacing(DVec3::new(50.0, 0.0, 0.0)), 1.0);
    // Turned off, the arc gets the uniform size.
    let off = parse_case(
        &text.replace("curvature_segments = 12", "curvature_segments = 0"),
        "arc",
    )
    .unwrap();
    assert_eq!(off.sizing.spacing(on_arc), 1.0);
}

#[test]
fn flat_model_has_no_curvature_limit() {
    let case = parse_case(&common::unit_cube(0.3), "cube").unwrap();
    assert_eq!(case.sizing.spacing(DVec3::splat(0.5)), 0.3);
}

#[test]
fn proximity_limit_puts_one_element_across_a_thin_slab() {
    // The slab [0,1]² × [0, 0.05] at size 0.3: its side faces are 0.05 wide. By default
    // (0.5 cells) they are spanned by triangles twice as long as they are wide.
    let slab = common::unit_cube(0.3).replace(", 1]", ", 0.05]");
    let case = parse_case(&slab, "slab").unwrap();
    let side = DVec3::new(0.0, 0.5, 0.025);
    let d = case.sizing.spacing(side);
    assert!((0.1..0.11).contains(&d), "δ on a side face = {d}");
    // Grading away from the sides (rate 0.5): 0.1 + 0.5·0.1 one tenth in, the size at the middle.
    let near = DVec3::new(0.1, 0.5, 0.05);
    let d = case.sizing.spacing(near);
    assert!((0.13..0.17).contains(&d), "δ 0.1 from a side = {d}");
    let middle = DVec3::new(0.5, 0.5, 0.05);
    assert_eq!(case.sizing.spacing(middle), 0.3);
    // Inside the slab the spacing grades twice as fast (VOLUME_RATE): the size there.
    assert_eq!(case.sizing.volume_spacing(DVec3::new(0.5, 0.5, 0.025)), 0.3);
    assert!(case
        .sizing
        .proximity
        .as_ref()
        .is_some_and(|p| !p.is_empty()));
    // One cell across: δ = w; two would ask for 0.025, below the proximity floor size/10.
    let one = parse_case(
        &slab.replace("size = 0.3\n", "size = 0.3\nproximity_cells = 1\n"),
        "slab",
    )
    .unwrap();
    let d = one.sizing.spacing(side);
    assert!((0.05..0.06).contains(&d), "δ with 1 cell = {d}");
    let two = parse_case(
        &slab.replace("size = 0.3\n", "size = 0.3\nproximity_cells = 2\n"),
        "slab",
    )
    .unwrap();
    let d = two.sizing.spacing(side);
    assert!((0.03..0.035).contains(&d), "δ with 2 cells = {d}");
    let off = parse_case(
        &slab.replace("size = 0.3\n", "size = 0.3\nproximity_cells = 0\n"),
        "slab",
    )
    .unwrap();
    assert_eq!(off.sizing.spacing(side), 0.3);
    // A cube as wide as the size has no gap.
    let cube = parse_case(&common::unit_cube(0.3), "cube").unwrap();
    assert!(cube.sizing.proximity.as_ref().is_some_and(|p| p.is_empty()));
}

#[test]
fn proximity_cells_must_not_be_negative() {
    let text = common::unit_cube(0.3).replace("size = 0.3\n", "size = 0.3\nproximity_cells = -1\n");
    let err = parse_case(&text, "cube")
        .err()
        .expect("rejected")
        .to_string();
    assert!(err.contains("mesh.proximity_cells"), "{err}");
}
