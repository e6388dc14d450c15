//! Sewing loose surfaces into closed shells and solids; healing reports.
mod common;

#[test]
fn sewing_catia_cylinder_gives_a_closed_solid() {
    let Some(dir) = common::cad_dir() else { return };
    let m = common::load(&dir, "cylinder_catia_trimmed.igs");
    assert!(m.check_solids().is_err());
    let (sewn, report) = m.sew(1e-3).unwrap();
    println!("{report:?}");
    let t = sewn.topology();
    assert_eq!(report.closed_shells, 1, "{report:?}");
    assert_eq!(report.solids_made, 1);
    assert_eq!(t.shells.len(), 1);
    assert!(t.shells[0].closed && t.free_edges.is_empty());
    assert_eq!(t.faces.len(), 4);
    sewn.check_solids().unwrap();
    assert!(
        sewn.solid_volume(0).unwrap() > 0.0,
        "sewn solid must be oriented outward"
    );
}

#[test]
fn sewing_onera_m6_iges_matches_the_step_domain() {
    let Some(dir) = common::cad_dir() else { return };
    let igs = common::load(&dir, "onera_m6_halfsphere_domain.igs");
    let (sewn, report) = igs.sew(1e-4).unwrap();
    println!("{report:?}");
    sewn.check_solids().unwrap();
    let step = common::load(&dir, "onera_m6_halfsphere_domain.stp");
    let (a, b) = (sewn.solid_volume(0).unwrap(), step.solid_volume(0).unwrap());
    assert_eq!(sewn.topology().faces.len(), step.topology().faces.len());
    assert!(((a - b) / b).abs() < 1e-4, "IGES {a} vs STEP {b}");
}

#[test]
fn unsewn_shells_report_what_sewing_did() {
    let Some(dir) = common::cad_dir() else { return };
    // The T106 slab's 7 shells sew into one; it keeps 2 free edges, so no solid is made and the
    // diagnosis says so.
    let m = common::load(&dir, "t106_turbine_cascade_shells.step");
    let (sewn, report) = m.sew(1e-3).unwrap();
    println!("t106: {report:?}");
    assert_eq!((report.before.shells, report.after.shells), (7, 1));
    assert!(report.after.edges < report.before.edges);
    assert_eq!(report.free_edges, 2);
    let err = sewn.check_solids().unwrap_err();
    assert!(
        err.to_string().contains("t106_turbine_cascade_shells.step"),
        "{err}"
    );
    // The filleted cube lacks faces: 40 edges stay free at any tolerance.
    let m = common::load(&dir, "cube_fillet_open_shell.stp");
    let (sewn, report) = m.sew(1e-2).unwrap();
    println!("cube_fillet: {report:?}");
    assert_eq!(report.free_edges, 40);
    assert_eq!(sewn.topology().free_edges.len(), 40);
    assert!(matches!(
        sewn.check_solids(),
        Err(tetrafoil_occt::CadError::NoSolid { open_shells: 1, .. })
    ));
}

#[test]
fn healing_reports_counts() {
    let Some(dir) = common::cad_dir() else { return };
    let m = common::load(&dir, "box_colored_faces.stp");
    let (healed, report) = m.heal(1e-7).unwrap();
    println!("{report:?}");
    assert_eq!(report.before, report.after);
    assert!(!report.changed());
    // Names survive healing and sewing.
    let names = |m: &tetrafoil_occt::CadModel| {
        let mut n: Vec<_> = m
            .topology()
            .faces
            .iter()
            .filter_map(|f| f.name.clone())
            .collect();
        n.sort();
        n
    };
    assert_eq!(names(&m).len(), 6);
    assert_eq!(names(&healed), names(&m));
    let (sewn, _) = m.sew(1e-6).unwrap();
    assert_eq!(names(&sewn), names(&m));
}
