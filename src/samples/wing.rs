//! `wing`: a swept, tapered NACA 0012 half-wing on a symmetry plane inside a far-field box, with
//! a flat wake sheet behind its trailing edge.
//!
//! Sections are geometrically similar (scaled and translated), so every chordwise grid line of
//! the wing surfaces has chord parameters proportional to the averaged ones, and every spanwise
//! line is straight with uniformly spaced nodes: the grid's boundary lines are then exactly the
//! Ferguson curves through the same points, which the edges use.

use super::case_file::{loops, RefineSource};
use super::CaseWriter;
use glam::DVec3;
use std::f64::consts::PI;

const ROOT_CHORD: f64 = 1.0;
const TAPER: f64 = 0.5;
pub(crate) const SEMISPAN: f64 = 2.0;
const LE_SWEEP_DEG: f64 = 30.0;
const THICKNESS: f64 = 0.12;
/// Chordwise points per side (cosine spacing) and spanwise sections.
const N_CHORD: usize = 25;
pub(crate) const N_SPAN: usize = 5;
/// Far-field box and wake end.
pub(crate) const BOX_LO: DVec3 = DVec3::new(-5.0, 0.0, -5.0);
pub(crate) const BOX_HI: DVec3 = DVec3::new(10.0, 6.0, 5.0);

/// NACA 4-digit half-thickness with the closed trailing edge (last coefficient −0.1036), per
/// unit chord.
pub(crate) fn naca_thickness(t: f64, x: f64) -> f64 {
    5.0 * t
        * (0.2969 * x.sqrt() - 0.1260 * x - 0.3516 * x * x + 0.2843 * x.powi(3)
            - 0.1036 * x.powi(4))
}

/// Cosine-spaced chord stations 0 = x₀ < … < x_{n−1} = 1.
pub(crate) fn cosine_stations(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| {
            if k == n - 1 {
                1.0
            } else {
                0.5 * (1.0 - (PI * k as f64 / (n - 1) as f64).cos())
            }
        })
        .collect()
}

/// The section at span station `y`, upper (`side = 1`) or lower (`side = −1`), LE to TE.
pub(crate) fn section(y: f64, side: f64) -> Vec<DVec3> {
    let chord = ROOT_CHORD * (1.0 - (1.0 - TAPER) * y / SEMISPAN);
    let x_le = y * LE_SWEEP_DEG.to_radians().tan();
    let xs = cosine_stations(N_CHORD);
    xs.iter()
        .enumerate()
        .map(|(k, &x)| {
            // Exactly closed at both ends, so upper and lower share LE and TE points.
            let z = if k == 0 || k == N_CHORD - 1 {
                0.0
            } else {
                side * chord * naca_thickness(THICKNESS, x)
            };
            DVec3::new(x_le + chord * x, y, z)
        })
        .collect()
}

/// The wing sample's text.
pub fn wing() -> String {
    let mut w = CaseWriter::new("wing", &WING_ABOUT);
    build_wing(&mut w);
    w.finish()
}

/// The seed paper's second example: the wing sample refined from its leading and trailing
/// edges (the leading edge's spacing half the trailing edge's), then from its skin and wake.
pub fn wing_refined() -> String {
    let mut about = WING_ABOUT.to_vec();
    about.extend([
        "Refined as in the seed paper: a first stage from the leading and trailing edges",
        "(first spacing 0.001 at the leading edge, twice that at the trailing edge), then",
        "a second from the wing's skin and the wake sheet (first 0.002, 3 equal layers,",
        "growth 1.2), whose nodes grow layers on both sides.",
    ]);
    let mut w = CaseWriter::new("wing_refined", &about);
    build_wing(&mut w);
    let curve = |name, first| RefineSource {
        faces: &[],
        curves: std::slice::from_ref(name),
        first,
        growth: 1.2,
        constant: None,
    };
    w.refine_stage(&[curve(&"le", 0.001), curve(&"te", 0.002)]);
    w.refine_stage(&[RefineSource {
        faces: &["wing_upper", "wing_lower", "wing_tip", "wake"],
        curves: &[],
        first: 0.002,
        growth: 1.2,
        constant: Some(3),
    }]);
    w.finish()
}

/// What the wing sample's header says of it.
const WING_ABOUT: [&str; 11] = [
    "A swept, tapered half-wing of NACA 0012 sections (closed trailing edge): root",
    "chord 1, taper 0.5, semispan 2, leading-edge sweep 30 degrees, root on the",
    "symmetry plane y = 0, in the far-field box x -5..10, y 0..6, z -5..5. Upper and",
    "lower surfaces interpolate 5 sections x 25 cosine-spaced points; the tip is a",
    "flat patch trimmed by the tip section. A flat wake sheet runs from the trailing",
    "edge to x = 10 over the span: an embedded face of the fluid region. Its root and",
    "outflow edges are imprinted on the far field: the symmetry plane is split along",
    "z = 0 (inflow cut, root section, wake root) and so is the outflow plane (wake",
    "outflow edge, then on to the side wall), so the volume mesh conforms to the wake",
    "from both sides; its tip edge is free in the volume.",
    "Counts: 16 vertices, 26 edges, 12 faces, 1 region (1 shell, 1 embedded face).",
];

/// The wing, its far field and its wake, into `w`.
fn build_wing(w: &mut CaseWriter) {
    let spans: Vec<f64> = (0..N_SPAN)
        .map(|i| SEMISPAN * i as f64 / (N_SPAN - 1) as f64)
        .collect();
    let upper: Vec<Vec<DVec3>> = spans.iter().map(|&y| section(y, 1.0)).collect();
    let lower: Vec<Vec<DVec3>> = spans.iter().map(|&y| section(y, -1.0)).collect();
    let last = N_SPAN - 1;
    let (le_root, le_tip) = (upper[0][0], upper[last][0]);
    let (te_root, te_tip) = (upper[0][N_CHORD - 1], upper[last][N_CHORD - 1]);
    let le: Vec<DVec3> = upper.iter().map(|s| s[0]).collect();
    let te: Vec<DVec3> = upper.iter().map(|s| s[N_CHORD - 1]).collect();

    let diagonal = BOX_LO.distance(BOX_HI);
    w.mesh(diagonal / 20.0, 1e-6 * ROOT_CHORD);
    let chord_delta = 0.02 * ROOT_CHORD;
    w.line_source(le_root, le_tip, chord_delta, 0.05, 0.3);
    w.line_source(te_root, te_tip, chord_delta, 0.05, 0.3);

    let mut fluid = write_far_field(w);

    w.part("The wing.");
    for (name, p) in [
        ("le_root", le_root),
        ("le_tip", le_tip),
        ("te_root", te_root),
        ("te_tip", te_tip),
    ] {
        w.vertex(name, p);
    }
    // Each curve is a grid line of the surfaces: the very same points.
    w.curve("le", &le);
    w.curve("te", &te);
    w.curve("root_upper", &upper[0]);
    w.curve("root_lower", &lower[0]);
    w.curve("tip_upper", &upper[last]);
    w.curve("tip_lower", &lower[last]);
    w.edge("le", "le_root", "le_tip", Some("le"));
    w.edge("te", "te_root", "te_tip", Some("te"));
    w.edge("root_upper", "le_root", "te_root", Some("root_upper"));
    w.edge("root_lower", "le_root", "te_root", Some("root_lower"));
    w.edge("tip_upper", "le_tip", "te_tip", Some("tip_upper"));
    w.edge("tip_lower", "le_tip", "te_tip", Some("tip_lower"));
    w.grid_surface("wing_upper", &upper);
    w.grid_surface("wing_lower", &lower);
    // The tip section lies in the plane y = semispan: a flat patch around it, trimmed by it.
    let tip_chord = te_tip.x - le_tip.x;
    let margin = 0.1 * tip_chord;
    let tip_corner = |x: f64, z: f64| DVec3::new(x, SEMISPAN, z);
    let (x0, x1) = (le_tip.x - margin, te_tip.x + margin);
    w.patch_surface(
        "wing_tip_plane",
        [
            [tip_corner(x0, -margin), tip_corner(x0, margin)],
            [tip_corner(x1, -margin), tip_corner(x1, margin)],
        ],
    );
    w.face(
        "wing_upper",
        "wing_upper",
        &loops(&[&["root_upper", "te", "tip_upper", "le"]]),
    );
    w.face(
        "wing_lower",
        "wing_lower",
        &loops(&[&["root_lower", "te", "tip_lower", "le"]]),
    );
    w.face(
        "wing_tip",
        "wing_tip_plane",
        &loops(&[&["tip_upper", "tip_lower"]]),
    );
    fluid.extend(["wing_upper", "wing_lower", "wing_tip"].map(String::from));

    w.part("The wake: a flat sheet from the trailing edge to the outflow plane, embedded.");
    w.edge("wake_tip", "te_tip", "wake_out_tip", None);
    let (out_root, out_tip) = (wake_out(0.0), wake_out(SEMISPAN));
    w.patch_surface("wake_plane", [[te_root, te_tip], [out_root, out_tip]]);
    w.face(
        "wake",
        "wake_plane",
        &loops(&[&["te", "wake_tip", "wake_out", "wake_root"]]),
    );

    w.region("fluid", &fluid, &["wake"]);
}

/// The point of the wake's outflow edge at span `y`.
fn wake_out(y: f64) -> DVec3 {
    DVec3::new(BOX_HI.x, y, 0.0)
}

/// The far-field box with its symmetry plane (y = 0) and outflow plane (x = max) split along
/// z = 0, so the root section, the wake's root edge and its outflow edge are edges of the
/// box's faces. Writes the root section's and wake's shared edges too (`root_upper`/`lower`
/// come from the wing). Returns the far-field face names.
fn write_far_field(w: &mut CaseWriter) -> Vec<String> {
    let (lo, hi) = (BOX_LO, BOX_HI);
    let at = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    w.part(
        "Far field: a box whose symmetry (y = 0) and outflow (x = max) faces are split along \
         z = 0, imprinting the root section and the wake's root and outflow edges.",
    );
    // Corners: `c_<x><y><z>` with 0 = min, 1 = max.
    let xs = [lo.x, hi.x];
    let ys = [lo.y, hi.y];
    let zs = [lo.z, hi.z];
    for (i, x) in xs.iter().enumerate() {
        for (j, y) in ys.iter().enumerate() {
            for (k, z) in zs.iter().enumerate() {
                w.vertex(&format!("c_{i}{j}{k}"), at(*x, *y, *z));
            }
        }
    }
    w.vertex("inflow_cut", at(lo.x, 0.0, 0.0));
    w.vertex("wake_out_root", wake_out(0.0));
    w.vertex("wake_out_tip", wake_out(SEMISPAN));
    w.vertex("outflow_side", at(hi.x, hi.y, 0.0));
    // Edges along x (by y, z), along y (by x, z), along z (by x, y; split at z = 0 where the
    // cuts meet them).
    for j in 0..2 {
        for k in 0..2 {
            w.edge(
                &format!("ex_{j}{k}"),
                &format!("c_0{j}{k}"),
                &format!("c_1{j}{k}"),
                None,
            );
        }
    }
    for i in 0..2 {
        for k in 0..2 {
            w.edge(
                &format!("ey_{i}{k}"),
                &format!("c_{i}0{k}"),
                &format!("c_{i}1{k}"),
                None,
            );
        }
    }
    w.edge("ez_01", "c_010", "c_011", None);
    let splits = [
        ("00", "inflow_cut"),
        ("10", "wake_out_root"),
        ("11", "outflow_side"),
    ];
    for (xy, mid) in splits {
        let (x, y) = (&xy[..1], &xy[1..]);
        w.edge(&format!("ez_{xy}_lo"), &format!("c_{x}{y}0"), mid, None);
        w.edge(&format!("ez_{xy}_hi"), mid, &format!("c_{x}{y}1"), None);
    }
    w.edge("inflow_cut", "inflow_cut", "le_root", None);
    w.edge("wake_root", "te_root", "wake_out_root", None);
    w.edge("wake_out", "wake_out_root", "wake_out_tip", None);
    w.edge("outflow_cut", "wake_out_tip", "outflow_side", None);

    let plane = |w: &mut CaseWriter, name: &str, c: [[DVec3; 2]; 2]| {
        w.patch_surface(&format!("{name}_plane"), c);
    };
    let mut faces = Vec::new();
    let mut face = |w: &mut CaseWriter, name: &str, c: [[DVec3; 2]; 2], edges: &[&str]| {
        plane(w, name, c);
        w.face(name, &format!("{name}_plane"), &loops(&[edges]));
        faces.push(name.to_string());
    };
    let (x0, x1, y1, z0, z1) = (lo.x, hi.x, hi.y, lo.z, hi.z);
    face(
        w,
        "symmetry_upper",
        [
            [at(x0, 0.0, 0.0), at(x0, 0.0, z1)],
            [at(x1, 0.0, 0.0), at(x1, 0.0, z1)],
        ],
        &[
            "inflow_cut",
            "root_upper",
            "wake_root",
            "ez_10_hi",
            "ex_01",
            "ez_00_hi",
        ],
    );
    face(
        w,
        "symmetry_lower",
        [
            [at(x0, 0.0, z0), at(x0, 0.0, 0.0)],
            [at(x1, 0.0, z0), at(x1, 0.0, 0.0)],
        ],
        &[
            "inflow_cut",
            "root_lower",
            "wake_root",
            "ez_10_lo",
            "ex_00",
            "ez_00_lo",
        ],
    );
    face(
        w,
        "outflow_upper",
        [
            [at(x1, 0.0, 0.0), at(x1, 0.0, z1)],
            [at(x1, y1, 0.0), at(x1, y1, z1)],
        ],
        &["wake_out", "outflow_cut", "ez_11_hi", "ey_11", "ez_10_hi"],
    );
    face(
        w,
        "outflow_lower",
        [
            [at(x1, 0.0, z0), at(x1, 0.0, 0.0)],
            [at(x1, y1, z0), at(x1, y1, 0.0)],
        ],
        &["wake_out", "outflow_cut", "ez_11_lo", "ey_10", "ez_10_lo"],
    );
    face(
        w,
        "inflow",
        [
            [at(x0, 0.0, z0), at(x0, 0.0, z1)],
            [at(x0, y1, z0), at(x0, y1, z1)],
        ],
        &["ez_00_lo", "ez_00_hi", "ey_01", "ez_01", "ey_00"],
    );
    face(
        w,
        "side",
        [
            [at(x0, y1, z0), at(x0, y1, z1)],
            [at(x1, y1, z0), at(x1, y1, z1)],
        ],
        &["ez_01", "ex_11", "ez_11_hi", "ez_11_lo", "ex_10"],
    );
    face(
        w,
        "bottom",
        [
            [at(x0, 0.0, z0), at(x0, y1, z0)],
            [at(x1, 0.0, z0), at(x1, y1, z0)],
        ],
        &["ex_00", "ey_10", "ex_10", "ey_00"],
    );
    face(
        w,
        "top",
        [
            [at(x0, 0.0, z1), at(x0, y1, z1)],
            [at(x1, 0.0, z1), at(x1, y1, z1)],
        ],
        &["ex_01", "ey_11", "ex_11", "ey_01"],
    );
    faces
}
