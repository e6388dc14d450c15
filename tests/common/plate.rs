//! The hybrid test mesh: the unit cube refined from its bottom face (a flat plate's layers,
//! beside four side walls) and grouped into prisms and pyramids.

use tetrafoil::case::parse_case;
use tetrafoil::mesh::VolumeMesh;
use tetrafoil::pipeline::{mesh_case_refined, prisms_stage};
use tetrafoil::prisms::PrismReport;
use tetrafoil::progress::Reporter;
use tetrafoil::samples;
use tetrafoil::volume::VolumeOptions;

/// The refinement stage from the bottom face `zmin`.
pub const STAGE: &str = r#"
[[refine]]
[[refine.source]]
faces = ["zmin"]
first = 0.004
growth = 1.2
constant = 3
"#;

/// The cube sample's case text.
pub fn cube_text() -> String {
    samples::all()
        .into_iter()
        .find(|(n, _)| *n == "cube")
        .map(|(_, t)| t)
        .expect("the cube sample")
}

/// The cube refined from its bottom and grouped, with `[mesh] prisms = true` in the case file.
pub fn plate() -> (VolumeMesh, PrismReport) {
    let text = cube_text().replacen("size = ", "prisms = true\nsize = ", 1) + STAGE;
    let mut case = parse_case(&text, "plate.toml").expect("loads");
    assert!(case.controls.prisms);
    let (mut mesh, mut volume, _) =
        mesh_case_refined(&mut case, VolumeOptions::default()).expect("meshes");
    assert!(mesh.prisms.is_empty());
    let report = prisms_stage(&case, &mut mesh, &mut volume, Reporter::default())
        .expect("the case asks for prisms");
    assert!(volume.validity.is_valid(), "{:?}", volume.validity.defects);
    assert_eq!(volume.validity.prisms, mesh.prisms.len());
    (mesh, report)
}
