//! Directional refinement on flow domains of the public CAD corpus (`../shared/cad`): the
//! failure classes found there, each on the file that showed it. Slow (release profile, with
//! `TETRAFOIL_SLOW_TESTS` set, as CI does); skipped, and said so, otherwise.

mod common;
use common::corpus::corpus_file;
use tetrafoil::case::parse_case;
use tetrafoil::mesh::quality::volume_sign;
use tetrafoil::pipeline::mesh_case_refined;
use tetrafoil::volume::VolumeOptions;

/// The corpus file `name`, when the slow tests run and the corpus is there.
fn slow_file(name: &str) -> Option<std::path::PathBuf> {
    if std::env::var_os("TETRAFOIL_SLOW_TESTS").is_none() {
        println!("skipped (slow; set TETRAFOIL_SLOW_TESTS=1)");
        return None;
    }
    corpus_file(name)
}

/// The validity check passed and every tet is positive (exact orientation).
fn assert_valid(mesh: &tetrafoil::mesh::VolumeMesh, report: &tetrafoil::volume::VolumeReport) {
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    assert!(mesh
        .tets
        .iter()
        .all(|t| volume_sign(t.map(|i| mesh.points[i as usize])) > 0.0));
}

/// A `[[refine]]` stage of one source, the faces `faces` (TOML list items) with first layer
/// `first`, growth 1.25 and 3 constant layers.
fn wall_stage(faces: &str, first: f64) -> String {
    format!(
        "[[refine]]\n[[refine.source]]\nfaces = [{faces}]\nfirst = {first}\ngrowth = 1.25\n\
         constant = 3\n\n"
    )
}

/// The case `[mesh] cad = path` followed by `rest`.
fn cad_case(path: &std::path::Path, rest: &str) -> tetrafoil::case::Case {
    let text = format!("[mesh]\ncad = {:?}\n{rest}", path.display().to_string());
    parse_case(&text, "refine_cad.toml").expect("the case loads")
}

/// The ONERA M6 half-sphere domain, the wing's skin (faces 2–11) refined. Its layer points
/// on the symmetry plane at the sharp trailing edge make near-needle triangles that boundary
/// recovery chases with Steiner points until it fails ("surface vertex lies on this edge",
/// first seen here). The pipeline then meshes again with the symmetry plane's layer points
/// left out: the run ends with a valid mesh and the layers as asked on the wing. (Without
/// interior points, to keep the test short.)
#[test]
fn the_m6_wing_domain_refined_from_its_skin_gives_a_valid_mesh() {
    let Some(path) = slow_file("onera_m6_halfsphere_domain.stp") else {
        return;
    };
    let mut c = cad_case(
        &path,
        "min_size = 0.004\n\n[[source]]\nkind = \"line\"\n\
         points = [[0.5, 0, 0], [1.2, 1.48, 0]]\ndelta = 0.04\nr1 = 0.3\nr2 = 0.6\n\n\
         [[refine]]\n[[refine.source]]\nfaces = [2, 3, 4, 5, 6, 7, 8, 9, 10, 11]\n\
         first = 0.0006\ngrowth = 1.2\nconstant = 3\n",
    );
    let options = VolumeOptions {
        interior_points: false,
        ..VolumeOptions::default()
    };
    let (mesh, report, refined) = mesh_case_refined(&mut c, options).expect("meshes");
    assert_valid(&mesh, &report);
    let s = &refined.stages[0].surface;
    // The symmetry plane's points left out (1 face) or kept; never more faces than that.
    assert!(s.faces_kept_unrefined <= 1, "{s:?}");
    let q = &refined.stretched[0];
    assert!(q.wall_nodes > 4000, "{q:?}");
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!(q.max_dihedral.p50 < 100.0, "{q:?}");
}

/// The hemisphere-cylinder domain, its body (faces 3 and 4) refined. The cylinder's edge on
/// the symmetry plane has its nodes a rounding off the plane (y ≈ 1e-16), the plane's
/// refinement points lie on it exactly, and boundary recovery's Steiner points there were
/// "moved into the volume" by a step of zero: two tets of no volume (180°, aspect ratio
/// 2.6·10¹⁵) passed the exact validity check. No tet may be a needle.
#[test]
fn the_hemisphere_cylinder_refined_from_its_body_has_no_tet_of_no_volume() {
    let Some(path) = slow_file("hemisphere_cylinder_domain.stp") else {
        return;
    };
    let mut c = cad_case(
        &path,
        "\n[[refine]]\n[[refine.source]]\nfaces = [3, 4]\nfirst = 0.005\ngrowth = 1.2\n",
    );
    let (mesh, report, refined) =
        mesh_case_refined(&mut c, VolumeOptions::default()).expect("meshes");
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let mut needles = 0;
    for t in &mesh.tets {
        let p = t.map(|i| mesh.points[i as usize]);
        assert!(volume_sign(p) > 0.0);
        let v = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0;
        let mut longest: f64 = 0.0;
        for i in 0..4 {
            for j in i + 1..4 {
                longest = longest.max(p[i].distance(p[j]));
            }
        }
        if v < 1e-9 * longest.powi(3) {
            needles += 1;
        }
    }
    assert_eq!(needles, 0);
    let q = &refined.stretched[0];
    // 175.3° and aspect ratio 266 when written (2.6e15 before).
    assert!(q.max_dihedral.max < 178.0, "{q:?}");
    assert!(q.aspect_ratio.max < 1e4, "{q:?}");
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
}

/// Parts refined from their face 0 at a first spacing of a six-hundredth of the diagonal
/// (the sweep that found this). The edge stage bisects each model edge for the point where
/// the distance crosses a site; where the computed distance jumps (its foot changes facet),
/// the bisection ended on the jump, the lower piece was bisected onto the same point again,
/// and two edge nodes a rounding apart went into the volume: the validity check refused 12 of
/// the corpus's 33 files this way. Every one of these now gives a valid mesh with its
/// layers.
#[test]
fn edge_points_never_land_on_each_other_where_the_distance_jumps() {
    for (name, first) in [
        ("gmsh_part.step", 0.354),
        ("u_joint.stp", 0.228),
        ("occt_linkrods.step", 0.00935),
    ] {
        let Some(path) = slow_file(name) else {
            return;
        };
        let mut c = cad_case(
            &path,
            &format!(
                "\n[[refine]]\n[[refine.source]]\nfaces = [0]\nfirst = {first}\ngrowth = 1.2\n"
            ),
        );
        let options = VolumeOptions {
            interior_points: false,
            ..VolumeOptions::default()
        };
        // The validity check refuses two nodes of a tet a rounding apart.
        let (_, report, refined) = mesh_case_refined(&mut c, options).expect(name);
        assert!(
            report.validity.is_valid(),
            "{name}: {:?}",
            report.validity.defects
        );
        assert!(refined.stages[0].surface.edge_points > 0, "{name}");
        let q = &refined.stretched[0];
        assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{name}: {q:?}");
    }
}

/// The ONERA M6 body alone in its own half-sphere far field with its wake found and shed
/// (`wakes = "auto"`), its skin refined for y⁺ = 1 at Re = 11.7·10⁶ on the mean aerodynamic
/// chord (646 in the file's millimetres): a first layer of 1.55·10⁻³, about 1/40,000 of the
/// wing's spacing. A volume point went in a rounding (1.2·10⁻¹³) from a column point at the
/// tip: among tets of no volume the point lay in a tet the column point was not on, so the
/// neighbours' clearance never saw it, and the pair failed the validity check. Candidates
/// are now kept clear of the kernel's nearest point. With the wake: the wake's free tip edge
/// took edge points (the layers' distribution) and cut the sheet into slivers recovery could
/// not match, and a fan of flat tets lay on the symmetry plane at the root, each on one
/// boundary face, which the peel took only one of (it now follows the fan).
#[test]
fn the_m6_body_with_its_wake_at_y_plus_one_in_its_half_sphere_is_valid_with_the_first_layer_asked()
{
    let Some(path) = slow_file("onera_m6_wing_sharp_te.stp") else {
        return;
    };
    let mut c = cad_case(
        &path,
        "farfield = { shape = \"half-sphere\", size = 50 }\nwakes = \"auto\"\n\n[[refine]]\n\
         [[refine.source]]\nfaces = [\"body\"]\nyplus = 1\nreynolds = 11.7e6\nchord = 646\n\
         growth = 1.2\nconstant = 3\n",
    );
    let first = c.refinement.stages[0].sources[0].distribution.first;
    assert!((first / 1.5486e-3 - 1.0).abs() < 1e-3, "{first}");
    let (mesh, report, refined) =
        mesh_case_refined(&mut c, VolumeOptions::default()).expect("meshes");
    assert_valid(&mesh, &report);
    let q = &refined.stretched[0];
    assert!(q.wall_nodes > 5000, "{q:?}");
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!((q.first_layer_ratio.p10 - 1.0).abs() < 0.1, "{q:?}");
    assert!(q.max_dihedral.p50 < 100.0, "{q:?}");
    // The wake is there, between cells on both sides, and no tet lies flat on the symmetry
    // plane (four corners on y = 0: no volume, though rounding gives it a sign).
    let two_sided = tetrafoil::mesh::validity::two_sided_boundary_faces(&mesh);
    let wake: Vec<usize> = (0..mesh.boundary.len())
        .filter(|&t| mesh.markers[mesh.boundary_marker[t] as usize].name == "wake_1")
        .collect();
    assert!(wake.len() > 100 && wake.iter().all(|&t| two_sided[t]));
    let flat = (mesh.tets.iter())
        .filter(|t| t.iter().all(|&v| mesh.points[v as usize].y.abs() < 1e-9))
        .count();
    assert_eq!(flat, 0, "tets lying flat on the symmetry plane");
}

/// The wing-fuselage body (`wing_fuselage_2solids.step`: two mirror solids, each half a
/// fuselage, a wing and its fillets) in a box, in two stages as the seed paper advises for
/// surfaces meeting at about right angles: the wings with their tips, trailing-edge bases and
/// fillets, then the fuselage. Both stacks reach the junction: the first layer on each wall
/// within its stack's thickness of the other stage's wall is as asked.
#[test]
fn both_layer_stacks_reach_the_wing_fuselage_junction() {
    let Some(path) = slow_file("wing_fuselage_2solids.step") else {
        return;
    };
    let wings = wall_stage("8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19", 0.5);
    let fuselage = wall_stage("6, 7", 0.5);
    let mut c = cad_case(
        &path,
        &format!("farfield = {{ shape = \"box\", size = 5 }}\n\n{wings}{fuselage}"),
    );
    // The ids as `tetrafoil check --farfield box:5 --faces` lists them: faces 6 and 7 are the
    // fuselage's halves (the body's whole length, each named for its solid), 15 and 19 the
    // wing tips.
    let faces = c.model.face_summaries();
    for f in [6, 7] {
        assert!(faces[f].max[0] - faces[f].min[0] > 440.0, "{:?}", faces[f]);
        assert!(faces[f].name.starts_with("Part "), "{:?}", faces[f]);
    }
    for f in [15, 19] {
        assert!(
            (faces[f].min[1].abs() - 400.0).abs() < 1e-6,
            "{:?}",
            faces[f]
        );
    }
    let (mesh, report, refined) =
        mesh_case_refined(&mut c, VolumeOptions::default()).expect("meshes");
    assert_valid(&mesh, &report);
    assert_eq!(refined.stretched.len(), 2);
    for q in &refined.stretched {
        let j = &q.junction_first_layer_ratio;
        assert!(q.junction_nodes > 1000, "{q:?}");
        assert!((j.p50 - 1.0).abs() < 0.1, "{q:?}");
        assert!(j.p10 > 0.9 && j.p90 < 1.25, "{q:?}");
    }
}

/// Whether the slow tests run (said when not).
fn slow() -> bool {
    let on = std::env::var_os("TETRAFOIL_SLOW_TESTS").is_some();
    if !on {
        println!("skipped (slow; set TETRAFOIL_SLOW_TESTS=1)");
    }
    on
}

/// The jet sample's case (`samples/jet_step/case.toml`: every wall one stage, in a half box,
/// wakes shed from the tail, the wing and the pylon): valid, the first layer as asked,
/// nothing left out, the three wakes between cells on both sides.
#[test]
fn the_jet_sample_refined_from_every_wall_is_valid() {
    if !slow() {
        return;
    }
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/jet_step/case.toml");
    let mut case = tetrafoil::case::load_case(&path).expect("the jet case loads");
    let (mesh, report, refined) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert_valid(&mesh, &report);
    let q = &refined.stretched[0];
    println!("jet: {} tets; stretched {q:?}", mesh.tets.len());
    assert!(q.wall_nodes > 1000, "{q:?}");
    assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
    assert!((q.first_layer_ratio.p90 - 1.0).abs() < 0.25, "{q:?}");
    let s = &refined.stages[0].surface;
    assert_eq!(s.faces_kept_unrefined, 0, "{s:?}");
    let two_sided = tetrafoil::mesh::validity::two_sided_boundary_faces(&mesh);
    for wake in ["wake_1", "wake_2", "wake_3"] {
        let tris: Vec<usize> = (0..mesh.boundary.len())
            .filter(|&t| mesh.markers[mesh.boundary_marker[t] as usize].name == wake)
            .collect();
        assert!(
            !tris.is_empty() && tris.iter().all(|&t| two_sided[t]),
            "{wake}"
        );
    }
}

/// The jet sample's body (`samples/jet_step/jet.step`) in two stages, as the seed paper meshes
/// surfaces meeting at about right angles: fuselage, nacelle and T-tail, then wing, fin and
/// pylon. The second stage's column feet on the fin/fuselage junction split the first stage's
/// layer triangles on the fin into 172° slivers, and boundary recovery failed there with a
/// cascade of Steiner points, until each earlier stage ran a second pass over the later
/// stages' new nodes. Valid, each stage's first layer as asked, on its walls and beside the
/// other stage's. (Not yet asserted: every face takes its face points. The wing, the pylon
/// and the tail keep theirs out in one stage or the other, where the points fold the face
/// beside a trailing-edge root.)
#[test]
fn the_jet_in_two_stages_meets_at_its_junctions() {
    if !slow() {
        return;
    }
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/jet_step/jet.step");
    let bodies = wall_stage("\"fuselage\", \"nacelle\", \"tail\"", 0.01);
    let lifting = wall_stage("\"wing\", \"fin\", \"pylon\"", 0.01);
    let mut c = cad_case(
        &path,
        &format!("farfield = {{ shape = \"half-box\", size = 3 }}\n\n{bodies}{lifting}"),
    );
    let (mesh, report, refined) =
        mesh_case_refined(&mut c, VolumeOptions::default()).expect("meshes");
    assert_valid(&mesh, &report);
    assert_eq!(refined.stretched.len(), 2);
    for (q, s) in refined.stretched.iter().zip(&refined.stages) {
        println!("jet stage {:?}: {q:?}; {:?}", s.sources, s.surface);
        assert!(q.wall_nodes > 1000, "{q:?}");
        assert!((q.first_layer_ratio.p50 - 1.0).abs() < 0.1, "{q:?}");
        assert!(q.junction_nodes > 500, "{q:?}");
        assert!(
            (q.junction_first_layer_ratio.p50 - 1.0).abs() < 0.1,
            "{q:?}"
        );
    }
}
