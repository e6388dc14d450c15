//! `wing_step`: the `wing` sample's half-wing (same sections, span and far-field box) as a CAD
//! model built through OpenCASCADE — sections lofted into a solid, cut from the box — and
//! written as STEP (`samples/wing_step/wing_in_box.step`) by `examples/write_samples.rs` with
//! `tetrafoil_occt::build::wing_in_box` on these sections and this box. It exercises the CAD path with a
//! known answer: the fluid volume is the box's minus the wing's.

use super::wing::{section, BOX_HI, BOX_LO, N_SPAN, SEMISPAN};

/// Where the sample goes under the samples directory.
pub const WING_STEP_FILE: &str = "wing_step/wing_in_box.step";

/// The wing's closed sections, root to tip: trailing edge, upper surface to the leading
/// edge, lower surface back to the trailing edge (the first point repeated last).
pub fn wing_sections() -> Vec<Vec<[f64; 3]>> {
    (0..N_SPAN)
        .map(|i| {
            let y = SEMISPAN * i as f64 / (N_SPAN - 1) as f64;
            let upper = section(y, 1.0);
            let lower = section(y, -1.0);
            upper
                .iter()
                .rev()
                .chain(lower.iter().skip(1))
                .map(|p| p.to_array())
                .collect()
        })
        .collect()
}

/// The far-field box, low and high corners.
pub fn wing_box() -> ([f64; 3], [f64; 3]) {
    (BOX_LO.to_array(), BOX_HI.to_array())
}
