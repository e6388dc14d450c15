//! `jet`: the seed paper's third example, a generic twin-engine executive jet, as the lofted
//! parts it is built from: a fuselage with a rounded nose and an upswept tail cone, a low swept
//! wing, a fin with a T-tail on top, and a nacelle on a pylon on each side of the rear
//! fuselage. Lengths in metres (fuselage 16 m, span 15 m); x aft, y to starboard, z up.
//! Only the starboard half is built: the sample is a half model on its symmetry plane.
//!
//! Each part is closed sections to loft through: rings (fuselage, nacelle) and NACA 4-digit
//! aerofoils with a closed trailing edge (wing, fin, tail, pylon). `examples/write_samples.rs`
//! lofts and fuses them through OpenCASCADE into the half body on the symmetry plane y = 0
//! (`samples/jet_step/jet.step`, faces named after the parts). Parts overlap where they join
//! (the wing root runs into the fuselage, the pylon into both), so the fuse makes the
//! junction curves.

use super::wing::{cosine_stations, naca_thickness};
use glam::DVec3;
use std::f64::consts::PI;

/// Where the sample goes under the samples directory.
pub const JET_STEP_FILE: &str = "jet_step/jet.step";

/// One lofted part: its name (the faces' marker), its sections in loft order, whether they
/// are rings (closed smooth curves, first point not repeated) or aerofoils (last point
/// repeating the first), and optional pointed ends.
#[derive(Debug, Clone, PartialEq)]
pub struct JetPart {
    pub name: &'static str,
    pub sections: Vec<Vec<DVec3>>,
    pub ring: bool,
    pub nose: Option<DVec3>,
    pub tail: Option<DVec3>,
}

/// Fuselage length; its radius on the cylindrical part.
pub const FUSELAGE_LENGTH: f64 = 16.0;
const FUSELAGE_RADIUS: f64 = 1.0;
/// Points around each ring; chordwise points per aerofoil side.
const RING_POINTS: usize = 24;
const CHORD_POINTS: usize = 21;

/// The fuselage's radius and centre height at station `x`: an elliptic nose over the first
/// 3 m, a cylinder to 10 m, then a cone closing to 0.15 m at the tail while its centre line
/// rises 0.6 m.
fn fuselage_station(x: f64) -> (f64, f64) {
    let r = if x < 3.0 {
        FUSELAGE_RADIUS * (1.0 - (1.0 - x / 3.0).powi(2)).sqrt()
    } else if x <= 10.0 {
        FUSELAGE_RADIUS
    } else {
        FUSELAGE_RADIUS * (1.0 - 0.85 * ((x - 10.0) / 6.0).powf(1.5))
    };
    let zc = if x <= 10.0 {
        0.0
    } else {
        0.6 * ((x - 10.0) / 6.0).powi(2)
    };
    (r, zc)
}

/// A ring of `RING_POINTS` points about the axis through `centre` along x, radius `r`,
/// starting 60° above the +y side (the seam, away from every junction).
fn ring(centre: DVec3, r: f64) -> Vec<DVec3> {
    (0..RING_POINTS)
        .map(|k| {
            let a = PI / 3.0 + 2.0 * PI * k as f64 / RING_POINTS as f64;
            centre + DVec3::new(0.0, r * a.cos(), r * a.sin())
        })
        .collect()
}

/// A closed aerofoil: leading edge `le`, chord along x, thickness ratio `t` measured along
/// `normal` (z for horizontal surfaces, y for the fin); upper side from the trailing edge to
/// the leading edge, then the lower side back, the trailing edge point repeated.
fn aerofoil(le: DVec3, chord: f64, t: f64, normal: DVec3) -> Vec<DVec3> {
    let xs = cosine_stations(CHORD_POINTS);
    let at = |x: f64, side: f64| {
        let h = if x == 0.0 || x == 1.0 {
            0.0
        } else {
            side * chord * naca_thickness(t, x)
        };
        le + DVec3::X * chord * x + normal * h
    };
    let upper = xs.iter().rev().map(|&x| at(x, 1.0));
    let lower = xs.iter().skip(1).map(|&x| at(x, -1.0));
    upper.chain(lower).collect()
}

/// A straight tapered surface between two span stations: leading edges and chords linear in
/// the span parameter, `n` sections.
fn tapered(
    root: (DVec3, f64, f64),
    tip: (DVec3, f64, f64),
    normal: DVec3,
    n: usize,
) -> Vec<Vec<DVec3>> {
    (0..n)
        .map(|i| {
            let s = i as f64 / (n - 1) as f64;
            let le = root.0.lerp(tip.0, s);
            let chord = root.1 + (tip.1 - root.1) * s;
            let t = root.2 + (tip.2 - root.2) * s;
            aerofoil(le, chord, t, normal)
        })
        .collect()
}

/// The jet's parts for its starboard half: the fuselage and fin whole (they straddle the
/// symmetry plane), the wing and tail from just across the plane, one nacelle and pylon.
/// Cut at y = 0 they make the half body; mirrored, the whole aircraft.
pub fn jet_parts() -> Vec<JetPart> {
    let fuselage_x = [
        0.15, 0.5, 1.0, 1.75, 2.5, 3.0, 5.0, 7.0, 9.0, 10.0, 11.5, 13.0, 14.5, 15.6,
    ];
    let fuselage = JetPart {
        name: "fuselage",
        sections: (fuselage_x.iter())
            .map(|&x| {
                let (r, zc) = fuselage_station(x);
                ring(DVec3::new(x, 0.0, zc), r)
            })
            .collect(),
        ring: true,
        nose: Some(DVec3::ZERO),
        tail: Some(DVec3::new(FUSELAGE_LENGTH, 0.0, fuselage_station(16.0).1)),
    };
    // Wing: low, 25° leading-edge sweep, 3° dihedral, from just across the symmetry plane
    // (inside the fuselage, so no face of it lies in that plane) to the tip.
    let semispan = 7.5;
    let wing_station = |y: f64| {
        let le = DVec3::new(
            5.5 + y * 25f64.to_radians().tan(),
            y,
            -0.5 + y * 3f64.to_radians().tan(),
        );
        let chord = 3.2 + (1.2 - 3.2) * y / semispan;
        let t = 0.13 + (0.10 - 0.13) * y / semispan;
        (le, chord, t)
    };
    let wing_sections = tapered(wing_station(-0.3), wing_station(semispan), DVec3::Z, 6);
    // Fin: from inside the tail cone (z = 0.5) to z = 2.9, 35° sweep; its tip section lies in
    // the T-tail's centre plane, inside it.
    let fin_le = |z: f64| DVec3::new(12.4 + (z - 0.5) * 35f64.to_radians().tan(), 0.0, z);
    let fin_chord = |z: f64| 2.6 + (1.2 - 2.6) * (z - 0.5) / 2.4;
    let fin_sections: Vec<Vec<DVec3>> = [0.5, 1.3, 2.1, 2.9]
        .iter()
        .map(|&z| aerofoil(fin_le(z), fin_chord(z), 0.10, DVec3::Y))
        .collect();
    // T-tail: a 2.2 m root chord around the fin's tip (whose trailing edge ends at 70% of
    // it, where the tail is still thick), 3 m semispan, 30° sweep.
    let tail_station = |y: f64| {
        let le = DVec3::new(13.7 + y * 30f64.to_radians().tan(), y, 2.9);
        (le, 2.2 + (0.8 - 2.2) * y / 3.0, 0.10)
    };
    let tail_sections = tapered(tail_station(-0.2), tail_station(3.0), DVec3::Z, 4);
    let mut parts = vec![
        fuselage,
        JetPart {
            name: "wing",
            sections: wing_sections,
            ring: false,
            nose: None,
            tail: None,
        },
        JetPart {
            name: "fin",
            sections: fin_sections,
            ring: false,
            nose: None,
            tail: None,
        },
        JetPart {
            name: "tail",
            sections: tail_sections,
            ring: false,
            nose: None,
            tail: None,
        },
    ];
    // A nacelle (flat inlet and exhaust faces) on a pylon on the side of the rear fuselage.
    let axis = DVec3::new(0.0, 2.0, 0.6);
    let nacelle = [
        (10.2, 0.38),
        (10.5, 0.46),
        (11.2, 0.50),
        (12.2, 0.49),
        (13.0, 0.44),
        (13.4, 0.40),
    ];
    parts.push(JetPart {
        name: "nacelle",
        sections: (nacelle.iter())
            .map(|&(x, r)| ring(axis + DVec3::X * x, r))
            .collect(),
        ring: true,
        nose: None,
        tail: None,
    });
    // The pylon runs from inside the fuselage (y = 0.4) to the nacelle's axis.
    let pylon = |y: f64| (DVec3::new(10.8, y, 0.55), 1.8, 0.10);
    parts.push(JetPart {
        name: "pylon",
        sections: tapered(pylon(0.4), pylon(2.0), DVec3::Z, 3),
        ring: false,
        nose: None,
        tail: None,
    });
    parts
}

/// The case file beside the jet's STEP file (`samples/jet_step/case.toml`): the half body in a
/// half box three body lengths out, refined from every wall in one stage.
pub fn jet_step_case() -> String {
    "# The seed paper's third example, a generic twin-engine executive jet (half model on its\n\
     # symmetry plane y = 0), read from the STEP file the project builds through OpenCASCADE\n\
     # (`make samples`; parts lofted and fused: src/samples/jet.rs).\n\
     [mesh]\n\
     cad = \"jet.step\"\n\
     # The flow domain: a half box 3 body lengths beyond the body, its faces named `farfield`\n\
     # and `symmetry`; the body's faces keep their part names.\n\
     farfield = { shape = \"half-box\", size = 3 }\n\
     # A wake sheet from every trailing edge (tail, wing, pylon), along +x to the far field.\n\
     wakes = \"auto\"\n\
     \n\
     # Stretched layers on every wall: 1 cm first layer, 3 equal layers, growth 1.25 up to the\n\
     # isotropic spacing.\n\
     [[refine]]\n\
     [[refine.source]]\n\
     faces = [\"fuselage\", \"nacelle\", \"pylon\", \"wing\", \"fin\", \"tail\"]\n\
     first = 0.01\n\
     growth = 1.25\n\
     constant = 3\n"
        .to_string()
}
