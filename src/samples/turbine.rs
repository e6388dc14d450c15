//! `turbine`: one blade passage of a 20-blade turbine row (the seed paper's first example): a
//! sector of the annulus between hub (r = 1) and casing (r = 1.6), x from −1 to 2, with a
//! cambered blade from hub to casing (no tip gap).
//!
//! Coordinates: x is the axis; a point at radius r and angle θ is (x, r cos θ, r sin θ).
//! The blade section is a circular-arc camber line with 40° turning (axial inflow), chord 0.6,
//! carrying the closed-trailing-edge NACA 4-digit thickness (12 %). It is drawn in the
//! (x, s = rθ) plane and wrapped onto every cylinder r = const (θ = s/r), so all sections have
//! the same shape and (nearly) the same chord lengths between their points: the blade grid's
//! boundary lines then agree with the Ferguson curves through the same points to ~1e-9.
//! (Stacking at constant θ instead makes the chord lengths scale differently with r, and the
//! grid's averaged parameters put its root line ~7e-5 away from the root curve.)
//! Section points are evaluated exactly on each cylinder; the hub and casing are grid surfaces
//! sampling those cylinders, so the blade's root and tip curves lie on them only within the
//! interpolation error, ~3e-6 (see [`TOLERANCE`]).

use super::case_file::loops;
use super::wing::{cosine_stations, naca_thickness};
use super::CaseWriter;
use glam::DVec3;
use std::f64::consts::PI;

const BLADES: usize = 20;
const R_HUB: f64 = 1.0;
const R_CASING: f64 = 1.6;
const X_IN: f64 = -1.0;
const X_OUT: f64 = 2.0;
const CHORD: f64 = 0.6;
const TURNING_DEG: f64 = 40.0;
const THICKNESS: f64 = 0.12;
const N_CHORD: usize = 25;
const N_SPAN: usize = 5;
/// Grid sizes of the hub and casing: axial and tangential.
const N_AXIAL: usize = 13;
const N_THETA: usize = 13;
/// Edge-on-face tolerance: 1e-4 of the passage height (6e-5). The blade's root and tip curves
/// are Ferguson interpolants of points exactly on the cylinders, the hub and casing are Ferguson
/// grids of points exactly on them; the two differ by their interpolation errors (≤ 2.7e-6).
const TOLERANCE: f64 = 6e-5;

fn at(x: f64, r: f64, theta: f64) -> DVec3 {
    DVec3::new(x, r * theta.cos(), r * theta.sin())
}

/// The blade section in the (x, s = rθ) plane: suction side (`side = 1`) or pressure side
/// (`side = −1`), leading edge to trailing edge.
fn section_2d(side: f64) -> Vec<(f64, f64)> {
    let turning = TURNING_DEG.to_radians();
    // Circular arc of radius R through chord CHORD, tangent to x at the leading edge.
    let radius = CHORD / (2.0 * (turning / 2.0).sin());
    let n = cosine_stations(N_CHORD).len();
    cosine_stations(N_CHORD)
        .iter()
        .enumerate()
        .map(|(k, &xi)| {
            let phi = xi * turning;
            let camber = (radius * phi.sin(), -radius * (1.0 - phi.cos()));
            // Normal away from the arc's centre: the convex (suction) side.
            let normal = (phi.sin(), phi.cos());
            let t = if k == 0 || k == n - 1 {
                0.0
            } else {
                side * CHORD * naca_thickness(THICKNESS, xi)
            };
            (camber.0 + t * normal.0, camber.1 + t * normal.1)
        })
        .collect()
}

pub fn turbine() -> String {
    let mut w = CaseWriter::new(
        "turbine",
        &[
            "One passage of a 20-blade turbine row (seed paper, first example): the 18-degree",
            "sector of the annulus hub r = 1, casing r = 1.6, x from -1 to 2 (x is the axis),",
            "with a blade from hub to casing: circular-arc camber, 40 degrees of turning,",
            "chord 0.6, NACA 4-digit 12 % thickness with a closed trailing edge, the same",
            "(x, r theta) profile on every radius. Hub, casing, inlet and outlet are grid",
            "surfaces; the periodic sides are planar patches.",
            "Counts: 12 vertices, 18 edges, 8 faces, 1 region, 1 shell.",
            "Tolerance 1e-4 x passage height: the blade root/tip curves are evaluated on the",
            "exact cylinders, the hub/casing grids only interpolate them.",
        ],
    );
    let half = PI / BLADES as f64;
    let thetas: Vec<f64> = (0..N_THETA)
        .map(|j| -half + 2.0 * half * j as f64 / (N_THETA - 1) as f64)
        .collect();
    let xs: Vec<f64> = (0..N_AXIAL)
        .map(|i| X_IN + (X_OUT - X_IN) * i as f64 / (N_AXIAL - 1) as f64)
        .collect();
    let radii: Vec<f64> = (0..N_SPAN)
        .map(|i| R_HUB + (R_CASING - R_HUB) * i as f64 / (N_SPAN - 1) as f64)
        .collect();
    let r_mid = 0.5 * (R_HUB + R_CASING);

    // Centre the section tangentially on θ = 0, for the same clearance to both periodic sides.
    let sides = [section_2d(1.0), section_2d(-1.0)];
    let (lo, hi) = sides
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &(_, s)| {
            (lo.min(s), hi.max(s))
        });
    let shift = -0.5 * (lo + hi);
    let blade = |sec: &[(f64, f64)]| -> Vec<Vec<DVec3>> {
        radii
            .iter()
            .map(|&r| {
                sec.iter()
                    .map(|&(x, s)| at(x, r, (s + shift) / r))
                    .collect()
            })
            .collect()
    };
    let suction = blade(&sides[0]);
    let pressure = blade(&sides[1]);
    let last = N_SPAN - 1;
    let le: Vec<DVec3> = suction.iter().map(|s| s[0]).collect();
    let te: Vec<DVec3> = suction.iter().map(|s| s[N_CHORD - 1]).collect();

    let height = R_CASING - R_HUB;
    let pitch_mid = 2.0 * half * r_mid;
    let diagonal = (height.powi(2) + pitch_mid.powi(2) + (X_OUT - X_IN).powi(2)).sqrt();
    w.mesh(diagonal / 20.0, TOLERANCE);
    w.line_source(le[0], le[last], 0.01, 0.02, 0.2);
    w.line_source(te[0], te[last], 0.01, 0.02, 0.2);

    w.part("The passage: corners (inlet/outlet, hub/casing, low/high theta).");
    for (xn, x) in [("in", X_IN), ("out", X_OUT)] {
        for (rn, r) in [("hub", R_HUB), ("cas", R_CASING)] {
            for (tn, t) in [("lo", -half), ("hi", half)] {
                w.vertex(&format!("{rn}_{xn}_{tn}"), at(x, r, t));
            }
        }
    }
    // Circular arcs (hub/casing at inlet/outlet): the grid lines of the hub, casing, inlet and
    // outlet surfaces, through the same points.
    for (xn, x) in [("in", X_IN), ("out", X_OUT)] {
        for (rn, r) in [("hub", R_HUB), ("cas", R_CASING)] {
            let name = format!("{rn}_{xn}");
            let pts: Vec<DVec3> = thetas.iter().map(|&t| at(x, r, t)).collect();
            w.curve(&name, &pts);
            w.edge(
                &name,
                &format!("{rn}_{xn}_lo"),
                &format!("{rn}_{xn}_hi"),
                Some(&name),
            );
        }
    }
    // Straight edges: axial along hub/casing, radial at inlet/outlet, on the periodic sides.
    for tn in ["lo", "hi"] {
        for rn in ["hub", "cas"] {
            w.edge(
                &format!("{rn}_{tn}"),
                &format!("{rn}_in_{tn}"),
                &format!("{rn}_out_{tn}"),
                None,
            );
        }
        for xn in ["in", "out"] {
            w.edge(
                &format!("{xn}_{tn}"),
                &format!("hub_{xn}_{tn}"),
                &format!("cas_{xn}_{tn}"),
                None,
            );
        }
    }

    w.part("The blade.");
    w.vertex("le_hub", le[0]);
    w.vertex("le_tip", le[last]);
    w.vertex("te_hub", te[0]);
    w.vertex("te_tip", te[last]);
    w.curve("le", &le);
    w.curve("te", &te);
    w.curve("hub_suction", &suction[0]);
    w.curve("hub_pressure", &pressure[0]);
    w.curve("tip_suction", &suction[last]);
    w.curve("tip_pressure", &pressure[last]);
    w.edge("le", "le_hub", "le_tip", Some("le"));
    w.edge("te", "te_hub", "te_tip", Some("te"));
    w.edge("hub_suction", "le_hub", "te_hub", Some("hub_suction"));
    w.edge("hub_pressure", "le_hub", "te_hub", Some("hub_pressure"));
    w.edge("tip_suction", "le_tip", "te_tip", Some("tip_suction"));
    w.edge("tip_pressure", "le_tip", "te_tip", Some("tip_pressure"));
    w.grid_surface("blade_suction", &suction);
    w.grid_surface("blade_pressure", &pressure);
    w.face(
        "blade_suction",
        "blade_suction",
        &loops(&[&["hub_suction", "te", "tip_suction", "le"]]),
    );
    w.face(
        "blade_pressure",
        "blade_pressure",
        &loops(&[&["hub_pressure", "te", "tip_pressure", "le"]]),
    );

    w.part("The passage walls: hub and casing with the blade's root and tip as holes.");
    for (rn, r, hole) in [
        ("hub", R_HUB, ["hub_suction", "hub_pressure"]),
        ("cas", R_CASING, ["tip_suction", "tip_pressure"]),
    ] {
        let grid: Vec<Vec<DVec3>> = xs
            .iter()
            .map(|&x| thetas.iter().map(|&t| at(x, r, t)).collect())
            .collect();
        let name = if rn == "hub" { "hub" } else { "casing" };
        w.grid_surface(name, &grid);
        let outer = [
            format!("{rn}_in"),
            format!("{rn}_hi"),
            format!("{rn}_out"),
            format!("{rn}_lo"),
        ];
        let outer: Vec<&str> = outer.iter().map(String::as_str).collect();
        w.face(name, name, &loops(&[&outer, &hole]));
    }
    for (xn, x) in [("in", X_IN), ("out", X_OUT)] {
        let grid: Vec<Vec<DVec3>> = [R_HUB, R_CASING]
            .iter()
            .map(|&r| thetas.iter().map(|&t| at(x, r, t)).collect())
            .collect();
        let name = if xn == "in" { "inlet" } else { "outlet" };
        w.grid_surface(name, &grid);
        let outer = [
            format!("hub_{xn}"),
            format!("{xn}_hi"),
            format!("cas_{xn}"),
            format!("{xn}_lo"),
        ];
        let outer: Vec<&str> = outer.iter().map(String::as_str).collect();
        w.face(name, name, &loops(&[&outer]));
    }
    for (tn, t) in [("lo", -half), ("hi", half)] {
        let name = format!("periodic_{tn}");
        w.patch_surface(
            &name,
            [
                [at(X_IN, R_HUB, t), at(X_IN, R_CASING, t)],
                [at(X_OUT, R_HUB, t), at(X_OUT, R_CASING, t)],
            ],
        );
        let outer = [
            format!("hub_{tn}"),
            format!("out_{tn}"),
            format!("cas_{tn}"),
            format!("in_{tn}"),
        ];
        let outer: Vec<&str> = outer.iter().map(String::as_str).collect();
        w.face(&name, &name, &loops(&[&outer]));
    }

    let faces: Vec<String> = [
        "hub",
        "casing",
        "inlet",
        "outlet",
        "periodic_lo",
        "periodic_hi",
        "blade_suction",
        "blade_pressure",
    ]
    .map(String::from)
    .to_vec();
    w.region("passage", &faces, &[]);
    w.finish()
}
