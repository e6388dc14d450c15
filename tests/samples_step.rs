//! The shipped STEP sample `samples/wing_step/wing_in_box.step`: the `wing` sample's half-wing
//! built through OpenCASCADE (loft + boolean cut). It must read back as one named solid whose
//! volume is the box's minus the wing's, agree with the native wing, and pass `tetrafoil check`.

mod common;

use std::path::{Path, PathBuf};
use tetrafoil::samples::{wing_box, wing_sections, WING_STEP_FILE};
use tetrafoil_occt::CadModel;

fn shipped() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(WING_STEP_FILE)
}

fn box_volume() -> f64 {
    let (lo, hi) = wing_box();
    (0..3).map(|k| hi[k] - lo[k]).product()
}

/// The native `wing` sample's wing volume: box minus its fluid region's volume.
fn native_wing_volume() -> f64 {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/wing/case.toml");
    let case = tetrafoil::case::load_case(&path).unwrap();
    box_volume() - case.model.regions[0].shells[0].volume
}

#[test]
fn shipped_step_wing_reads_back_with_names_and_volume() {
    let _occt = common::occt::one_at_a_time();
    let cad = CadModel::read(shipped()).unwrap();
    let t = cad.topology();
    assert_eq!(t.solids.len(), 1);
    assert_eq!(t.solids[0].name.as_deref(), Some("fluid"));
    // Six box faces (the symmetry face with the root section as a hole), the wing's lofted
    // side (its seam is the trailing edge) and its planar tip cap.
    assert_eq!(t.faces.len(), 8);
    let named = |n: &str| {
        t.faces
            .iter()
            .filter(|f| f.name.as_deref() == Some(n))
            .count()
    };
    assert_eq!(
        (named("wing"), named("symmetry"), named("farfield")),
        (2, 1, 5)
    );
    let symmetry = t
        .faces
        .iter()
        .position(|f| f.name.as_deref() == Some("symmetry"))
        .unwrap();
    assert_eq!(t.faces[symmetry].loops.len(), 2, "root section hole");

    let fluid = cad.solid_volume_adaptive(0, 1e-9).unwrap().abs();
    let wing = box_volume() - fluid;
    let native = native_wing_volume();
    println!("STEP wing volume {wing:.6}, native wing volume {native:.6}");
    assert!(
        ((wing - native) / native).abs() < 0.02,
        "STEP wing volume {wing} vs native {native}"
    );
    // Our own boundary integrals agree with OCCT's on the curved, lofted faces.
    let model = common::occt::model(&common::occt::open(&shipped())).unwrap();
    let ours = model.regions[0].shells[0].volume;
    assert!(
        (ours - fluid).abs() < 1e-3 * wing,
        "model volume {ours} vs OCCT {fluid}"
    );
}

#[test]
fn construction_volumes_are_consistent() {
    let _occt = common::occt::one_at_a_time();
    let dir = std::env::temp_dir().join(format!("tetrafoil-wing-step-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("wing_in_box.step");
    let (lo, hi) = wing_box();
    let built = tetrafoil_occt::build::wing_in_box(&wing_sections(), lo, hi, &path).unwrap();
    assert_eq!(
        (built.faces, built.wing_faces, built.symmetry_faces),
        (8, 2, 1)
    );
    // The cut removed exactly the lofted solid.
    let removed = box_volume() - built.fluid_volume;
    assert!(
        (removed - built.wing_volume).abs() < 1e-6 * built.wing_volume,
        "box - fluid = {removed}, loft volume {}",
        built.wing_volume
    );
    // The rebuilt file reads back like the shipped one (same counts and volume).
    let (fresh, ship) = (
        CadModel::read(&path).unwrap(),
        CadModel::read(shipped()).unwrap(),
    );
    assert_eq!(fresh.topology().counts(), ship.topology().counts());
    let (a, b) = (
        fresh.solid_volume_adaptive(0, 1e-9).unwrap(),
        ship.solid_volume_adaptive(0, 1e-9).unwrap(),
    );
    assert!((a - b).abs() < 1e-9 * a, "rebuilt {a} vs shipped {b}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn tetrafoil_check_accepts_the_step_wing() {
    let _occt = common::occt::one_at_a_time();
    let out = common::occt::tetrafoil()
        .args(["--quiet", "check"])
        .arg(shipped())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("faces 8"), "{stdout}");
    assert!(stdout.contains("region 'fluid'"), "{stdout}");
}

/// At size 0.5 with the curvature and proximity limits off, the wing's thin trailing edge is
/// meshed coarser than its thickness and the surface mesh crosses itself. The pipeline finds
/// the crossings, halves the spacing there and meshes the surfaces again: a valid mesh, with the
/// re-mesh reported (face, where, spacing asked for).
#[test]
fn a_surface_that_crosses_itself_is_meshed_again_finer_there() {
    let _occt = common::occt::one_at_a_time();
    use tetrafoil::case::{case_from_cad_with, ControlOverrides};
    let coarse = ControlOverrides {
        size: Some(0.5),
        curvature_segments: Some(0.0),
        proximity_cells: Some(0.0),
        ..Default::default()
    };
    let mut case = case_from_cad_with(&shipped(), &coarse).unwrap();
    let (mesh, report) =
        tetrafoil::pipeline::mesh_case(&mut case, Default::default()).expect("re-meshed");
    println!("{:#?}", report.surface_remeshes);
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let first = report
        .surface_remeshes
        .first()
        .expect("one re-mesh at least");
    assert!(first.crossings >= 1);
    assert_eq!(first.faces, ["face 6 'wing'"]);
    assert!(first.spacing <= 0.25, "{first:?}");
    // The crossing lies on the wing (chord 1 at the root, semispan 2).
    let [x, y, z] = first.at;
    assert!((0.0..1.7).contains(&x) && (0.0..=2.0).contains(&y) && z.abs() < 0.1);
    assert!(report.surface_remeshes.len() <= tetrafoil::pipeline::crossings::CROSSING_REMESHES);
    assert!(case.sizing.crossing_samples() >= first.crossings);
    assert!(!mesh.tets.is_empty());
}

fn shipped_jet() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(tetrafoil::samples::JET_STEP_FILE)
}

/// The jet's parts as the bridge lofts them.
fn jet_parts() -> Vec<tetrafoil_occt::build::LoftedPart> {
    (tetrafoil::samples::jet_parts().into_iter())
        .map(|p| tetrafoil_occt::build::LoftedPart {
            name: p.name.to_string(),
            sections: (p.sections.iter())
                .map(|s| s.iter().map(|q| q.to_array()).collect())
                .collect(),
            ring: p.ring,
            nose: p.nose.map(|q| q.to_array()),
            tail: p.tail.map(|q| q.to_array()),
        })
        .collect()
}

/// The shipped jet: one solid, every part's faces named after it and one face on the
/// symmetry plane; our boundary integrals give OpenCASCADE's volume.
#[test]
fn shipped_step_jet_reads_back_with_its_parts() {
    let _occt = common::occt::one_at_a_time();
    let cad = CadModel::read(shipped_jet()).unwrap();
    let t = cad.topology();
    assert_eq!(t.solids.len(), 1);
    let mut names: Vec<&str> = (t.faces.iter())
        .map(|f| f.name.as_deref().unwrap_or("?"))
        .collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(
        names,
        ["fin", "fuselage", "nacelle", "pylon", "symmetry", "tail", "wing"]
    );
    let on_plane = t
        .faces
        .iter()
        .filter(|f| f.name.as_deref() == Some("symmetry"));
    assert_eq!(on_plane.count(), 1);
    let occt = cad.solid_volume_adaptive(0, 1e-9).unwrap().abs();
    let model = common::occt::model(&common::occt::open(&shipped_jet())).unwrap();
    let ours = model.regions[0].shells[0].volume.abs();
    println!("jet half body: OCCT volume {occt:.6}, boundary integrals {ours:.6}");
    assert!(((ours - occt) / occt).abs() < 1e-3, "{ours} vs {occt}");
    // A 16 m fuselage of 1 m radius is about 40 m³ whole; the half body with its half wing,
    // fin, tail and one nacelle is some 24 m³.
    assert!((20.0..30.0).contains(&occt), "{occt}");
}

/// The sample's construction is repeatable: built again, the same faces and volume.
#[test]
fn rebuilt_jet_matches_the_shipped_file() {
    let _occt = common::occt::one_at_a_time();
    let dir = std::env::temp_dir().join(format!("tetrafoil-jet-step-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("jet.step");
    let built = tetrafoil_occt::build::lofted_body(&jet_parts(), true, &path).unwrap();
    assert_eq!((built.faces, built.symmetry_faces), (12, 1));
    // The fuse and the cut removed volume: the overlaps and the port side.
    assert!(built.volume < built.parts_volume);
    let (fresh, ship) = (
        CadModel::read(&path).unwrap(),
        CadModel::read(shipped_jet()).unwrap(),
    );
    assert_eq!(fresh.topology().counts(), ship.topology().counts());
    let (a, b) = (
        fresh.solid_volume_adaptive(0, 1e-9).unwrap(),
        ship.solid_volume_adaptive(0, 1e-9).unwrap(),
    );
    assert!((a - b).abs() < 1e-9 * a.abs(), "rebuilt {a} vs shipped {b}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The jet's half body in a half box: the symmetry plane found on the body, a valid mesh
/// whose volume is the box's less the body's (OpenCASCADE's), the faces named `farfield`,
/// `symmetry` and after the parts.
#[test]
fn the_jet_in_a_half_box_is_valid_and_holds_the_domain_volume() {
    let _occt = common::occt::one_at_a_time();
    use tetrafoil::case::{case_from_cad_with, ControlOverrides};
    let overrides = ControlOverrides {
        farfield: Some("half-box:3".parse().unwrap()),
        ..Default::default()
    };
    let mut case = case_from_cad_with(&shipped_jet(), &overrides).unwrap();
    let (m, report) = tetrafoil::pipeline::mesh_case(&mut case, Default::default()).unwrap();
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    let named = |name: &str| -> Vec<glam::DVec3> {
        let mut v: Vec<u32> = (m.boundary.iter().zip(&m.boundary_marker))
            .filter(|(_, &k)| m.markers[k as usize].name == name)
            .flat_map(|(t, _)| *t)
            .collect();
        v.sort_unstable();
        v.dedup();
        v.into_iter().map(|i| m.points[i as usize]).collect()
    };
    for part in ["fuselage", "wing", "fin", "tail", "nacelle", "pylon"] {
        assert!(!named(part).is_empty(), "no faces named {part}");
    }
    let symmetry = named("symmetry");
    assert!(
        symmetry.iter().all(|p| p.y.abs() < 1e-9),
        "symmetry off y = 0"
    );
    // The box from its far-field nodes (planar faces: the mesh holds it exactly).
    let far = named("farfield");
    let (lo, hi) = far.iter().fold(
        (glam::DVec3::splat(f64::MAX), glam::DVec3::splat(f64::MIN)),
        |(l, h), p| (l.min(*p), h.max(*p)),
    );
    assert!(lo.y.abs() < 1e-9, "the half box starts on the plane: {lo}");
    let body = CadModel::read(shipped_jet())
        .unwrap()
        .solid_volume_adaptive(0, 1e-9)
        .unwrap()
        .abs();
    let expected = (hi - lo).element_product() - body;
    let err = (report.validity.volume - expected).abs() / expected;
    println!(
        "jet in a half box: {} tets, volume {:.6} vs {expected:.6} ({err:.2e})",
        m.tets.len(),
        report.validity.volume
    );
    assert!(err < 1e-3, "domain volume error {err}");
    // The box dwarfs the body (24 m³ in 6.5·10⁵): the body the mesh leaves out, against
    // OpenCASCADE's. Its curved faces are facetted at the default spacing (1/20 of the
    // diagonal, thin tails and pylon included), so it comes out a few percent small.
    let meshed_body = (hi - lo).element_product() - report.validity.volume;
    println!("body: meshed {meshed_body:.4} m³, OCCT {body:.4} m³");
    assert!(
        meshed_body < body && meshed_body > 0.95 * body,
        "{meshed_body} vs {body}"
    );
}
