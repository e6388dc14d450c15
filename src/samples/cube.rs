//! `cube`: the unit cube; `cube_cavity`: the box [0,4]³ with a cube cavity [1.5,2.5]³.

use super::toml_writer::write_box;
use super::CaseWriter;
use glam::DVec3;

/// The unit cube [0,1]³: 8 vertices, 12 straight edges, 6 bilinear faces, one region.
pub fn cube() -> String {
    let mut w = CaseWriter::new(
        "cube",
        &[
            "The unit cube [0,1]^3: 8 vertices, 12 straight edges, 6 bilinear patches,",
            "one region. The smallest native solid; orientation is left to the loader.",
        ],
    );
    let (lo, hi) = (DVec3::ZERO, DVec3::ONE);
    w.mesh(lo.distance(hi) / 20.0, 1e-9);
    let faces = write_box(&mut w, "", lo, hi, &[]);
    w.region("solid", &faces, &[]);
    w.finish()
}

/// The box [0,4]³ with a cube cavity [1.5,2.5]³: two shells, one region.
pub fn cube_cavity() -> String {
    let mut w = CaseWriter::new(
        "cube_cavity",
        &[
            "The box [0,4]^3 with a cube cavity [1.5,2.5]^3: one region bounded by two",
            "shells (outer 'box_', cavity 'cavity_'), 16 vertices, 24 edges, 12 faces.",
            "Tests shell orientation: the cavity's normals must point into the cavity.",
        ],
    );
    let (lo, hi) = (DVec3::ZERO, DVec3::splat(4.0));
    w.mesh(lo.distance(hi) / 20.0, 1e-8);
    let mut faces = write_box(&mut w, "box_", lo, hi, &[]);
    faces.extend(write_box(
        &mut w,
        "cavity_",
        DVec3::splat(1.5),
        DVec3::splat(2.5),
        &[],
    ));
    w.region("fluid", &faces, &[]);
    w.finish()
}
