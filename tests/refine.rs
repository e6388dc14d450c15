//! Directional refinement, end to end on a generated sample: the cube cavity of
//! `samples/cube_cavity` refined from its six faces through a `[[refine]]` stage of the case
//! file. Measured on the finished mesh: validity, volume, the first-layer height and the layer
//! spacings along the wall normals against the distribution, and the largest angles of the
//! stretched tets. Bad refinement input is refused with the key and line named.

mod common;

use tetrafoil::case::{parse_case, CaseError};
use tetrafoil::mesh::quality::volume_sign;
use tetrafoil::pipeline::mesh_case_refined;
use tetrafoil::samples;
use tetrafoil::volume::VolumeOptions;

fn cavity_text() -> String {
    sample("cube_cavity")
}

const STAGE: &str = r#"
[[refine]]
[[refine.source]]
faces = ["cavity_xmin", "cavity_xmax", "cavity_ymin", "cavity_ymax", "cavity_zmin", "cavity_zmax"]
first = 0.01
growth = 1.2
constant = 3
"#;

fn volume(points: &[glam::DVec3], tets: &[[u32; 4]]) -> f64 {
    tets.iter()
        .map(|t| {
            let v = t.map(|i| points[i as usize]);
            (v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0])) / 6.0
        })
        .sum()
}

#[test]
fn a_cavity_refined_from_its_faces_has_layers_at_the_asked_spacing() {
    let text = cavity_text() + STAGE;
    let mut case = parse_case(&text, "cavity_refined.toml").expect("loads");
    assert_eq!(case.refinement.stages.len(), 1);
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    assert!(mesh
        .tets
        .iter()
        .all(|t| volume_sign(t.map(|i| mesh.points[i as usize])) > 0.0));
    // Flat faces: the refined mesh fills exactly the box less the cavity.
    let v = volume(&mesh.points, &mesh.tets);
    assert!((v - 63.0).abs() < 1e-9 * 63.0, "volume {v}");

    let stage = &refined.stages[0];
    let q = &refined.stretched[0];
    // About one column of 20 layers per wall node (56 nodes), grown level by level; a face
    // source needs no element-driven points.
    assert!(stage.columns.roots >= 50, "{:?}", stage.columns);
    assert!(
        stage.columns.points > 900 && stage.columns.points < 2000,
        "{:?}",
        stage.columns
    );
    assert!(
        stage.volume.points < stage.columns.points,
        "{:?}",
        stage.volume
    );
    assert!(q.wall_nodes >= 50, "{q:?}");
    // First-layer height: within 10% of `first` at the median, 25% at p90.
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!((q.first_layer_ratio.p90 - 1.0).abs() < 0.25, "{q:?}");
    // The first layers along the wall normals follow the distribution (median within 10%).
    assert!(q.layer_ratio_median.len() >= 15, "{q:?}");
    for (k, r) in q.layer_ratio_median.iter().take(15).enumerate() {
        assert!((r - 1.0).abs() < 0.1, "layer {k}: {r} ({q:?})");
    }
    // Aspect ratio δ/first ≈ 35 is reached.
    assert!(q.aspect_ratio.p90 > 20.0, "{q:?}");
    // Largest angles of the stretched tets. Most of this coarse cube's wall nodes sit on its
    // 90° edges and corners, where one column per node fans out into prisms wide at the top,
    // so the wing's figures (p50 93°, p99 128°) are not reached here: p50 106.5°, p99 140.8°,
    // max 158° with the smoothing in the layers (p50 111°, p99 149° without).
    assert!(q.max_dihedral.p50 < 110.0, "{:?}", q.max_dihedral);
    assert!(q.max_dihedral.p99 < 145.0, "{:?}", q.max_dihedral);
    assert!(q.max_dihedral.max < 165.0, "{:?}", q.max_dihedral);
}

fn refused(stage: &str) -> (usize, String, String) {
    let text = cavity_text() + stage;
    let line_of_stage = text.lines().count() - stage.lines().count();
    match parse_case(&text, "bad.toml") {
        Err(CaseError::At {
            line, key, message, ..
        }) => (line - line_of_stage, key, message),
        Err(e) => panic!("refused without a line: {e}"),
        Ok(_) => panic!("accepted:\n{stage}"),
    }
}

#[test]
fn bad_refinement_input_names_the_key_and_line() {
    let (line, key, message) = refused(
        "\n[[refine]]\n[[refine.source]]\nfaces = [\"cavity_xmin\", \"wing\"]\nfirst = 0.01\ngrowth = 1.2\n",
    );
    assert_eq!((line, key.as_str()), (4, "refine.source.faces"));
    assert!(message.contains("no face 'wing'"), "{message}");

    let (line, key, message) =
        refused("\n[[refine]]\n[[refine.source]]\nfaces = [6]\nfirst = 0.01\ngrowth = 1.0\n");
    assert_eq!((line, key.as_str()), (6, "refine.source.growth"));
    assert!(message.contains("thickness"), "{message}");

    let (line, key, message) =
        refused("\n[[refine]]\n[[refine.source]]\nfaces = [6]\nfirst = 0.5\ngrowth = 1.2\n");
    assert_eq!((line, key.as_str()), (5, "refine.source.first"));
    assert!(
        message.contains("not smaller than the isotropic spacing"),
        "{message}"
    );

    let (_, key, message) = refused(
        "\n[[refine]]\n[[refine.source]]\ncurves = [\"nowhere\"]\nfirst = 0.01\ngrowth = 1.2\n",
    );
    assert_eq!(key, "refine.source.curves");
    assert!(message.contains("no edge 'nowhere'"), "{message}");

    let (_, key, _) = refused("\n[[refine]]\n[[refine.source]]\nfirst = 0.01\ngrowth = 1.2\n");
    assert_eq!(key, "refine.source");

    // growth = 1 with a thickness is a valid distribution.
    let text = cavity_text() + "\n[[refine]]\n[[refine.source]]\nfaces = [6]\nfirst = 0.05\ngrowth = 1.0\nthickness = 0.2\n";
    let case = parse_case(&text, "ok.toml").expect("growth 1 with a thickness loads");
    assert_eq!(
        case.refinement.stages[0].sources[0]
            .distribution
            .sites()
            .len(),
        5
    );
}

fn sample(name: &str) -> String {
    samples::all()
        .into_iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| t)
        .expect("the sample")
}

/// The seed paper's first example: the turbine blade refined from its curved faces (native
/// bicubic networks), and from its leading-edge curve.
#[test]
fn a_turbine_blade_refined_from_its_faces_keeps_its_volume_and_layers() {
    let mut iso = parse_case(&sample("turbine"), "turbine.toml").expect("loads");
    let (iso_mesh, _, _) = mesh_case_refined(&mut iso, VolumeOptions::default()).expect("meshes");
    let stage = r#"
[[refine]]
[[refine.source]]
faces = ["blade_suction", "blade_pressure"]
first = 0.004
growth = 1.2
constant = 3
"#;
    let mut case = parse_case(&(sample("turbine") + stage), "turbine_refined.toml").expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    // New points on the curved faces lie on the surface: the facets move a little.
    let (v0, v1) = (
        volume(&iso_mesh.points, &iso_mesh.tets),
        volume(&mesh.points, &mesh.tets),
    );
    assert!((v1 - v0).abs() < 1e-3 * v0, "volume {v1} against {v0}");
    let q = &refined.stretched[0];
    assert!(q.wall_nodes > 1000, "{q:?}");
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!((q.first_layer_ratio.p90 - 1.0).abs() < 0.25, "{q:?}");
    assert!(q.layer_ratio_median.len() >= 8, "{q:?}");
    for (k, r) in q.layer_ratio_median.iter().take(8).enumerate() {
        assert!((r - 1.0).abs() < 0.1, "layer {k}: {r} ({q:?})");
    }
    // The issue's goal, p50 ≤ 100° and p99 ≤ 130° (measured: 94°, 122°).
    assert!(q.max_dihedral.p50 <= 100.0, "{:?}", q.max_dihedral);
    assert!(q.max_dihedral.p99 <= 130.0, "{:?}", q.max_dihedral);
    // Faces crossing the layers (hub, casing) took points at the distribution's distances.
    assert!(
        refined.stages[0].surface.face_points > 500,
        "{:?}",
        refined.stages[0].surface
    );

    let curve = "\n[[refine]]\n[[refine.source]]\ncurves = [\"le\"]\nfirst = 0.004\ngrowth = 1.2\n";
    let mut case = parse_case(&(sample("turbine") + curve), "turbine_le.toml").expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let v2 = volume(&mesh.points, &mesh.tets);
    assert!((v2 - v0).abs() < 1e-3 * v0, "volume {v2} against {v0}");
    let s = &refined.stages[0];
    // 495 volume points at the surface/volume grading 0.5/0.75 (over 500 at 0.25/0.5); 687
    // volume and 8 edge points since the curvature limit samples at its own spacing (the
    // curve's first mesh is closer to the distribution there).
    assert!(s.surface.edge_points > 5 && s.volume.points > 400, "{s:?}");
}

/// A CAD file often gives one name to all the faces of a part: a source naming it takes them
/// all, and an unknown name is answered with the names there are.
#[test]
fn a_name_shared_by_several_cad_faces_selects_them_all() {
    let text = |faces: &str| {
        format!("\n[[refine]]\n[[refine.source]]\nfaces = [{faces}]\nfirst = 0.001\ngrowth = 1.2\n")
    };
    let c = step_wing_case("names", &text("\"wing\"")).unwrap();
    let named: Vec<usize> = (0..c.model.faces.len())
        .filter(|&f| c.model.faces[f].name.as_deref() == Some("wing"))
        .collect();
    assert_eq!(named.len(), 2);
    assert_eq!(c.refinement.stages[0].sources[0].faces, named);

    let e = step_wing_case("names", &text("\"skin\"")).err().unwrap();
    assert!(
        e.contains("no face 'skin'") && e.contains("named farfield, symmetry, wing"),
        "{e}"
    );
}

/// The case `[mesh] cad = <the STEP wing sample>` followed by `rest`, loaded from a case file
/// in its own temporary folder (`tag` names it); the error as text.
fn step_wing_case(tag: &str, rest: &str) -> Result<tetrafoil::case::Case, String> {
    let step =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/wing_step/wing_in_box.step");
    let tmp = std::env::temp_dir().join(format!("tetrafoil-refine-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let case = tmp.join("case.toml");
    let text = format!("[mesh]\ncad = {:?}\n{rest}", step.display().to_string());
    std::fs::write(&case, text).unwrap();
    let loaded = tetrafoil::case::load_case(&case).map_err(|e| e.to_string());
    std::fs::remove_dir_all(&tmp).ok();
    loaded
}

/// The issue's aspect-ratio bar: the STEP wing (through OpenCASCADE) refined from its skin
/// with `first` a thousandth of the isotropic spacing there, and the mesh stays valid. The
/// skin's spacing is set by a line source along the quarter chord (δ = 0.05 over the wing)
/// with the curvature limit coarsened (3 segments per circle: δ ≈ 0.02 at the leading edge)
/// to keep the test's size down; `first` = 2e-5 is then δ/1000 or finer everywhere.
#[test]
fn the_step_wing_takes_a_first_layer_a_thousandth_of_the_spacing() {
    let rest = "curvature_segments = 3\n\n[[source]]\nkind = \"line\"\n\
                points = [[0.25, 0, 0], [1.405, 2, 0]]\ndelta = 0.05\nr1 = 0.8\nr2 = 1.6\n\n\
                [[refine]]\n[[refine.source]]\n\
                faces = [\"wing\"]\nfirst = 2e-5\ngrowth = 1.3\n";
    let mut c = step_wing_case("aspect", rest).expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut c, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    assert!(mesh
        .tets
        .iter()
        .all(|t| volume_sign(t.map(|i| mesh.points[i as usize])) > 0.0));
    let q = &refined.stretched[0];
    // Aspect ratio 10³ reached (p90 1468 when written), the first layer where it was asked.
    assert!(q.aspect_ratio.p90 > 1000.0, "{q:?}");
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!((q.first_layer_ratio.p90 - 1.0).abs() < 0.25, "{q:?}");
    assert!(q.wall_nodes > 1000, "{q:?}");
    println!("{q:?}");
    // Angles (p50 93.6°, p99 140.8° when written: the coarse skin's facets fan the columns).
    assert!(q.max_dihedral.p50 < 100.0, "{q:?}");
    assert!(q.max_dihedral.p99 < 150.0, "{q:?}");
    // Sliver removal left the zone to the layers: no points there.
    assert_eq!(report.slivers.points, 0, "{:?}", report.slivers);
}

/// A sharp trailing edge on a symmetry plane under a thin first layer: the plane's layer
/// points there form triangles of aspect ratio ~10³ that the volume's boundary recovery has
/// to find in the hull's own triangulation of the plane. A hull edge crossing a segment
/// next to one of its ends used to be chased by halving the segment towards that end (a
/// Steiner point every halving, 3·10⁻⁶ apart at the end, then "no Steiner point could be
/// inserted"). Only the recovery is run (no interior points, no volume refinement).
#[test]
fn a_thin_layer_at_a_trailing_edge_on_the_symmetry_plane_is_recovered() {
    let rest = "curvature_segments = 6\n\n[[source]]\nkind = \"line\"\n\
                points = [[0.25, 0, 0], [1.405, 2, 0]]\ndelta = 0.05\nr1 = 0.8\nr2 = 1.6\n\n\
                [[refine]]\n[[refine.source]]\n\
                faces = [\"wing\"]\nfirst = 2e-5\ngrowth = 1.3\n";
    let c = step_wing_case("trailing-edge", rest).expect("loads");
    let progress = tetrafoil::progress::Reporter::default();
    let (mut curves, mut surface, _) =
        tetrafoil::pipeline::curves_and_surfaces(&c, progress, false).expect("surfaces");
    let refined = tetrafoil::refine::refine_surface(
        &c.model,
        &mut surface,
        &mut curves,
        &c.sizing,
        &c.refinement,
    );
    assert!(
        refined[0].surface.face_points > 1000,
        "{:?}",
        refined[0].surface
    );
    let options = VolumeOptions {
        interior_points: false,
        improve: false,
        ..VolumeOptions::default()
    };
    let (mesh, report) =
        tetrafoil::volume::mesh_volume_with(&c.model, &surface, &c.sizing, options, None, None)
            .expect("the boundary is recovered");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    assert!(mesh
        .tets
        .iter()
        .all(|t| volume_sign(t.map(|i| mesh.points[i as usize])) > 0.0));
    // A few boundary Steiner points, not a cascade of them (31 when written).
    let r = &report.recovery;
    assert!(r.steiner_on_edges + r.steiner_on_faces < 100, "{r:?}");
}

/// The seed paper's wing, refined from its skin and its wake sheet in one stage: the wake is
/// an embedded face, so the fluid lies on both sides of it and each of its nodes starts two
/// columns, one each way. Measured on the written mesh: a point at the first layer's height
/// above and below the wake's nodes, and the stretched region's figures.
#[test]
fn the_wing_refined_from_skin_and_wake_has_layers_on_both_sides_of_the_wake() {
    const FIRST: f64 = 0.004;
    let stage = format!(
        "\n[[refine]]\n[[refine.source]]\nfaces = [\"wing_upper\", \"wing_lower\", \"wing_tip\", \
         \"wake\"]\nfirst = {FIRST}\ngrowth = 1.3\nconstant = 2\n"
    );
    let mut case = parse_case(&(sample("wing") + &stage), "wing_wake.toml").expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    // The wake sheet lies in z = 0 from the trailing edge to x = 10; away from its edges. The
    // layers' smoothing may move a point sideways by a fraction of `first`.
    let inside = |p: &&glam::DVec3| p.x > 2.5 && p.x < 9.5 && p.y > 0.1 && p.y < 1.9;
    let roots: Vec<_> = mesh
        .points
        .iter()
        .filter(|p| inside(p) && p.z == 0.0)
        .collect();
    let has_point = |root: &glam::DVec3, z: f64| {
        mesh.points
            .iter()
            .any(|p| (p.z - z).abs() < 0.25 * FIRST && (p.x - root.x).hypot(p.y - root.y) < FIRST)
    };
    let both = roots
        .iter()
        .filter(|r| has_point(r, FIRST) && has_point(r, -FIRST))
        .count();
    // 18 wake nodes inside at the grading 0.5/0.75 (22 at 0.25/0.5); 16 of the 18 have both
    // points since the interior points honour the sample's line sources and face points on
    // a triangle's edge split it (17 before).
    assert!(roots.len() >= 15, "{} wake nodes", roots.len());
    assert!(
        both * 20 >= roots.len() * 17,
        "{both} of {} wake nodes have a first layer point above and below",
        roots.len()
    );
    let q = &refined.stretched[0];
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!(q.max_dihedral.p50 <= 100.0, "{:?}", q.max_dihedral);
    assert!(q.max_dihedral.p99 <= 130.0, "{:?}", q.max_dihedral);
}

/// The wing from its skin at aspect ratio 100 (δ/`first`, δ = 0.05): the symmetry plane beside
/// the root takes some twenty layer points per line, whose feet on the root edges once split
/// its segments again and again until boundary recovery failed there. A segment now splits
/// once.
#[test]
fn the_wing_takes_a_first_layer_a_hundredth_of_its_spacing() {
    let stage = "\n[[refine]]\n[[refine.source]]\nfaces = [\"wing_upper\", \"wing_lower\", \
                 \"wing_tip\"]\nfirst = 0.0005\ngrowth = 1.2\nconstant = 3\n";
    let mut case = parse_case(&(sample("wing") + stage), "wing_100.toml").expect("loads");
    let (_, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let q = &refined.stretched[0];
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!((q.first_layer_ratio.p90 - 1.0).abs() < 0.25, "{q:?}");
    // Measured: p50 91.3°, p99 123.5°, largest 177.0° (before the last resort against flat
    // tets, some were flat: 180°).
    assert!(q.max_dihedral.p50 <= 100.0, "{:?}", q.max_dihedral);
    assert!(q.max_dihedral.p99 <= 130.0, "{:?}", q.max_dihedral);
    assert!(q.max_dihedral.max < 179.0, "{:?}", q.max_dihedral);
}

/// Where layer tools fail: a gap narrower than two layer stacks. Two cavities face each other
/// across a gap 0.03 wide, all their faces sources of one stage (first 0.002, growth 1.2: a
/// stack alone grows to the spacing 0.1, far thicker than the gap). The distance is to the
/// nearer wall, so the two stacks meet halfway: the mesh is valid, fills the box less the
/// cavities, and has its first layer at `first` from both walls of the gap.
#[test]
fn the_layers_of_two_walls_meet_halfway_across_a_narrow_gap() {
    let gap = 0.03;
    let first = 0.002;
    let faces: Vec<String> = (["a", "b"].iter())
        .flat_map(|p| {
            (0..3).flat_map(move |axis| (0..2).map(move |s| format!("\"{p}f{axis}{s}\"")))
        })
        .collect();
    let text = common::two_cavities_across_a_gap(0.1, gap)
        + &format!(
            "[[refine]]\n[[refine.source]]\nfaces = [{}]\nfirst = {first}\ngrowth = 1.2\n\
             constant = 3\n",
            faces.join(", ")
        );
    let mut case = parse_case(&text, "gap.toml").expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let v = volume(&mesh.points, &mesh.tets);
    let expected = 1.0 - 2.0 * 0.25 * 0.4 * 0.4;
    assert!((v - expected).abs() < 1e-9, "volume {v}");
    let q = &refined.stretched[0];
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    // Across the gap, along its middle: the layers' x from both walls.
    let (x0, x1) = (0.5 - 0.5 * gap, 0.5 + 0.5 * gap);
    let mut xs: Vec<f64> = (mesh.points.iter())
        .filter(|p| (p.y - 0.5).abs() < 0.1 && (p.z - 0.5).abs() < 0.1)
        .filter(|p| p.x > x0 + 1e-9 && p.x < x1 - 1e-9)
        .map(|p| p.x)
        .collect();
    xs.sort_by(f64::total_cmp);
    assert!(!xs.is_empty(), "no layer points in the gap");
    let (lowest, highest) = (xs[0], xs[xs.len() - 1]);
    assert!(
        ((lowest - x0) / first - 1.0).abs() < 0.1,
        "first layer off wall a at {lowest}"
    );
    assert!(
        ((x1 - highest) / first - 1.0).abs() < 0.1,
        "first layer off wall b at {highest}"
    );
    // As many levels on each side of the middle: the stacks meet halfway.
    let mut levels: Vec<f64> = Vec::new();
    for x in xs {
        if levels.last().is_none_or(|&l| x - l > 0.1 * first) {
            levels.push(x);
        }
    }
    let left = levels.iter().filter(|&&x| x < 0.5 - 0.1 * first).count();
    let right = levels.iter().filter(|&&x| x > 0.5 + 0.1 * first).count();
    assert!(left >= 4 && left.abs_diff(right) <= 1, "levels {levels:?}");
}

/// A stage refining the cube from its edge `x_y0z0` (the bottom wall's front edge).
const CUBE_EDGE_STAGE: &str = r#"
[[refine]]
[[refine.source]]
curves = ["x_y0z0"]
first = 0.001
growth = 1.2
constant = 2
"#;

/// The cube refined from its edge `x_y0z0` alone. The edge stage packs points along both
/// walls; at the edge of its reach, a thin triangle of the ymin wall was crossed by a hull
/// edge lying in that wall, and boundary recovery put each Steiner point at the projection of
/// the last one, each piece of the fan crossed again, until two nodes stood 1e-11 apart and
/// the validity check refused the mesh (38 Steiner points). Now a Steiner point goes at a
/// vertex's projection only when the vertex lies clear of the segment.
#[test]
fn a_curve_stage_alone_on_a_concave_corner_is_valid() {
    let text = sample("cube") + CUBE_EDGE_STAGE;
    let mut case = parse_case(&text, "edge.toml").expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    // Measured: 13 Steiner points (38 before, in a geometric cascade).
    assert!(
        report.recovery.steiner_on_edges < 20,
        "{:?}",
        report.recovery
    );
    let v = volume(&mesh.points, &mesh.tets);
    assert!((v - 1.0).abs() < 1e-9, "volume {v}");
    let s = &refined.stages[0];
    // Measured: 232 volume points.
    assert!(s.volume.points > 150, "{s:?}");
}

/// A curve source along a concave corner of the domain (the cube's edge on its bottom and
/// front walls, as a wing/body junction would be), then the bottom wall: the lines from the
/// curve's nodes to the tets' centres run too close to the walls, so the columns start on the
/// wedge's bisector. Before that, the curve stage put no volume point in, and the tets between
/// the walls' packed face points and the isotropic interior stayed slivers (1,680 below 1°).
#[test]
fn a_curve_along_a_concave_corner_gets_volume_layers() {
    // The bottom wall's stage is the plate's (`common::plate::STAGE`).
    let text = sample("cube") + CUBE_EDGE_STAGE + common::plate::STAGE;
    let mut case = parse_case(&text, "corner.toml").expect("loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let s = &refined.stages[0];
    // Measured: 303 volume points.
    assert!(s.volume.points > 150, "{s:?}");
    let v = volume(&mesh.points, &mesh.tets);
    assert!((v - 1.0).abs() < 1e-9, "volume {v}");
    // Measured: 267 tets below 1° (44 of them forced by the surface).
    let q = tetrafoil::mesh::quality::tet_quality(&mesh.points, &mesh.tets);
    assert!(q.below_1deg < 600, "{q:?}");
}
