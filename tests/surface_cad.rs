//! Surface meshing acceptance over the public CAD corpus (`../shared/cad`) at a size of 1/30 of
//! each model's bounding-box diagonal: faces meshed, every shell closed and manifold with
//! consistent orientation, no triangle inverted against its surface, total area against
//! OpenCASCADE's (BRepGProp), minimum angles and edge lengths against δ(midpoint).
//!
//! Each file carries the bar it reaches today. The bar is [`FULL`]; a file below it
//! says what is missing in a comment — never lower a bar without saying why.

mod common;
use common::corpus::cad_dir;
use std::collections::HashMap;
use tetrafoil::case::{case_from_cad, Case};
use tetrafoil::curve::mesh_curves;
use tetrafoil::surface::{mesh_surfaces, surface_quality, SurfaceOptions};
use tetrafoil_occt::CadModel;

/// What a file must reach.
#[derive(Clone, Copy, Debug)]
struct Bar {
    /// Faces allowed to fail.
    failed_faces: usize,
    /// Every shell closed and manifold (only meaningful with no failed face).
    closed: bool,
    /// Triangles allowed to point against their surface's normal.
    inverted: usize,
    /// |mesh area − CAD area| / CAD area of the meshed faces.
    area: f64,
    /// Fraction of triangles with minimum angle ≥ 25° or forced below (a CAD corner sharper
    /// than 25°, a gap narrower than the size floor).
    angles: f64,
    /// Fraction of edges with length in [0.6, 1.5]·δ(midpoint).
    lengths: f64,
}

/// The bar.
const FULL: Bar = Bar {
    failed_faces: 0,
    closed: true,
    inverted: 0,
    area: 0.005,
    angles: 0.99,
    lengths: 0.95,
};

/// A bar with every face meshed and every shell closed, below [`FULL`] in what it says.
const fn closed(inverted: usize, area: f64, angles: f64, lengths: f64) -> Bar {
    Bar {
        failed_faces: 0,
        closed: true,
        inverted,
        area,
        angles,
        lengths,
    }
}

/// The corpus files that are valid solids (or sew into them), each with its bar. Slow ones
/// (more than a few seconds in the dev profile) run only with `TETRAFOIL_SLOW_TESTS=1`.
/// Not listed: torus_single_face.stp and sphere_rhino_bspline.igs (the CAD import finds no
/// solid and sewing closes none), cube_fillet_open_shell.stp (open shell), and the IGES twin
/// of onera_m6_halfsphere_domain.stp (same faces and failures as the STEP).
fn corpus() -> Vec<(&'static str, Bar, bool)> {
    vec![
        ("box_colored_faces.stp", FULL, false),
        ("tet_rhino.step", FULL, false),
        ("sphere_revolved.step", FULL, false),
        ("sliced_cylinder_rhino.step", FULL, false),
        ("hemisphere_cylinder_domain.stp", FULL, false),
        ("box_open_shell_invalid.stp", FULL, false),
        ("cylinder_catia_trimmed.igs", FULL, false),
        // Full since the proximity limit resolves the thin strips the general fuse leaves
        // around the bolt heads (98.1% of angles before; 84 triangles forced). Two heads touch
        // the bracket's edge: their vertex, 2.7e-6 apart in its two loops' (u,v), is one front
        // vertex since the boundary merges such copies (until then face 71 failed).
        ("l_bracket_assembly.step", FULL, false),
        ("nist_ctc_01.stp", FULL, true),
        // Full since the reference area is BRepGProp's adaptive rule: its default rule is 5-7%
        // off on the two periodic side faces (1 and 7), 0.5% off in all.
        ("t106_turbine_cascade_shells.step", FULL, true),
        ("occt_screw.step", FULL, false),
        // Full since the proximity limit (98.4% of angles before).
        ("gmsh_part.step", FULL, false),
        // Missing: angles (98.7%, 8 triangles at CAD corners sharper than 25° counted as
        // forced), on the thin three-sided B-spline faces at the v = 18.47 rim (until 6 faces
        // failed).
        (
            "gmsh_t20_component8.step",
            closed(0, 0.005, 0.98, 0.95),
            true,
        ),
        // The proximity limit resolves the small fillets' strips. Since the surfaces grade at
        // 0.5 (not 0.25) the fillets' chords leave 0.56% of the area (0.60% with the curvature
        // limit's old wide samples) and 93.8% of the edges within the range, the rest in the
        // steeper grading off the fillets.
        (
            "crankshaft_kurbelwelle.stp",
            closed(0, 0.006, 0.99, 0.93),
            true,
        ),
        // The wings' edge lengths follow the curvature limit's grading off the leading edge less
        // evenly since it is sampled at its own spacing: 93.5% of the edges within the range
        // (94.95% with the old wide samples, 97.8% at the 0.25 grading).
        (
            "onera_m6_wing_sharp_te.stp",
            closed(0, 0.005, 0.99, 0.93),
            true,
        ),
        // Full since the proximity limit. 119 triangles below 25° are counted as forced: the
        // wing's blunt trailing-edge faces are 5.5e-3 wide, under the size floor (size/100).
        ("onera_m6_halfsphere_domain.stp", FULL, true),
        // As the ONERA wing: 88.9% of the edges within the range (94.8% with the old wide
        // samples, which also made 1.1x the triangles).
        (
            "wing_fuselage_2solids.step",
            closed(0, 0.005, 0.99, 0.88),
            true,
        ),
        // Meshed at 18 segments per circle (see `curvature_segments`). The loops' coincident
        // stretches at the ground ends (edges a CAD tolerance apart, crossing in (u,v)) are
        // merged at import (model::coincident), which changes the faces' boundary-integral
        // area by -0.01%; until then both coil faces failed.
        ("spring_iges_msbo_solid.igs", FULL, true),
    ]
}

/// Segments per circle of the curvature limit: tetrafoil's CAD default (12) except where the
/// 0.5% area bar needs more. The spring's coil is a tube of radius 2.5 (δ = 3.2 at 1/30 of the
/// diagonal): at 12 segments per circle its chords miss 0.9% of the tube's area, at 18 0.4%.
fn curvature_segments(file: &str) -> f64 {
    match file {
        "spring_iges_msbo_solid.igs" => 18.0,
        _ => tetrafoil::case::CURVATURE_SEGMENTS,
    }
}

/// Measured results of one file.
#[derive(Debug, Default)]
struct Measured {
    faces: usize,
    failed: usize,
    triangles: usize,
    open_edges: usize,
    inverted: usize,
    area_error: f64,
    angles: f64,
    lengths: f64,
    /// Triangles below 25° forced by a sharp CAD corner or a gap narrower than the size floor.
    forced: usize,
    /// Faces meshed in parts.
    split_faces: usize,
}

/// Mesh at 1/`fraction` of the diagonal with `segments` per circle in the curvature limit (0:
/// none).
fn measure(path: &std::path::Path, fraction: f64, segments: f64) -> Measured {
    measure_with(path, fraction, segments, SurfaceOptions::default())
}

/// The case at 1/`fraction` of the diagonal with `segments` per circle in the curvature limit;
/// the local limits are rebuilt for that size, as `tetrafoil mesh --size` does.
fn load(path: &std::path::Path, fraction: f64, segments: f64) -> Case {
    let mut case = case_from_cad(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let size = case.controls.size * 20.0 / fraction;
    case.controls.size = size;
    case.controls.curvature_segments = segments;
    case.sizing.uniform = size;
    case.sizing.set_local_limits(&case.model, &case.controls);
    case
}

/// [`measure`] with surface options (`keep_going` is always set).
fn measure_with(
    path: &std::path::Path,
    fraction: f64,
    segments: f64,
    options: SurfaceOptions,
) -> Measured {
    let case = load(path, fraction, segments);
    let model = &case.model;
    let curves = mesh_curves(model, &case.sizing).unwrap();
    let options = SurfaceOptions {
        keep_going: true,
        ..options
    };
    let (mesh, failures) = mesh_surfaces(model, &curves, &case.sizing, options).unwrap();
    for f in &failures {
        println!("  {f}");
    }
    let mut m = Measured {
        faces: model.faces.len(),
        failed: failures.len(),
        triangles: mesh.triangles.len(),
        split_faces: mesh.split_faces(),
        ..Default::default()
    };
    let p = |i: usize| mesh.points[i];

    // Shells: each edge used once in each direction once faces point out of the region.
    for r in 0..model.regions.len() {
        let region = &model.regions[r];
        for shell in &region.shells {
            let mut reversed = HashMap::new();
            for fu in &shell.faces {
                reversed.insert(fu.face, fu.reversed);
            }
            let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
            for (t, f) in mesh.triangles.iter().zip(&mesh.face_of) {
                let Some(&rev) = reversed.get(f) else {
                    continue;
                };
                let t = if rev { [t[0], t[2], t[1]] } else { *t };
                for k in 0..3 {
                    *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
                }
            }
            m.open_edges += directed
                .iter()
                .filter(|(&(a, b), &n)| n != 1 || directed.get(&(b, a)) != Some(&1))
                .count();
        }
    }

    // Orientation against the surface normal at the centroid's projection; area.
    let mut area = 0.0;
    for (t, &f) in mesh.triangles.iter().zip(&mesh.face_of) {
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let n = (b - a).cross(c - a);
        area += 0.5 * n.length();
        let surface = &model.faces[f].surface;
        let centroid = (a + b + c) / 3.0;
        if let Some(uv) = surface.closest_uv(centroid, None) {
            if surface.normal(uv).dot(n) < 0.0 {
                m.inverted += 1;
            }
        }
    }
    // Angles (forced ones counted apart) and lengths.
    let q = surface_quality(model, &mesh, &case.sizing);
    m.angles = q.angle_share();
    m.lengths = q.length_share();
    m.forced = q.forced_by_corner + q.forced_by_size_floor;

    // CAD area of the meshed faces (the model keeps the CAD's face ids, sewn or not).
    let cad = CadModel::read(path).unwrap();
    let cad = if cad.topology().solids.is_empty() {
        let diag = cad.bounding_box().unwrap().unwrap().diagonal();
        let sewn = [1e-6, 1e-4]
            .iter()
            .map(|r| cad.sew(r * diag).unwrap().0)
            .find(|s| !s.topology().solids.is_empty());
        sewn.expect("sews into a solid")
    } else if cad.topology().solids.len() >= 2 {
        // The loader imprints an assembly's contacts (general fuse) at the model tolerance.
        let diag = cad.bounding_box().unwrap().unwrap().diagonal();
        cad.fuse_solids(1e-6 * diag).unwrap().0
    } else {
        cad
    };
    let mut meshed = vec![false; model.faces.len()];
    for &f in &mesh.face_of {
        meshed[f] = true;
    }
    let cad_area: f64 = (0..model.faces.len())
        .filter(|&f| meshed[f])
        .map(|f| cad.face_area_adaptive(f, 1e-7).unwrap())
        .sum();
    m.area_error = (area - cad_area).abs() / cad_area;
    m
}

#[test]
fn corpus_surfaces_meet_their_bars() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let slow = std::env::var_os("TETRAFOIL_SLOW_TESTS").is_some();
    // TETRAFOIL_CAD_FILES=a.step,b.igs: only those files (slow or not).
    let only = std::env::var("TETRAFOIL_CAD_FILES").ok();
    let mut problems = Vec::new();
    for (file, bar, is_slow) in corpus() {
        let segments = curvature_segments(file);
        if let Some(only) = &only {
            if !only.split(',').any(|f| f == file) {
                continue;
            }
        } else if is_slow && !slow {
            println!("{file}: skipped (slow; set TETRAFOIL_SLOW_TESTS=1)");
            continue;
        }
        let start = std::time::Instant::now();
        let m = measure(&dir.join(file), 30.0, segments);
        println!(
            "{file}: faces {}/{} triangles {} open edges {} inverted {} area error {:.3}% \
             angles≥25° or forced {:.1}% ({} forced) lengths in [0.6,1.5]δ {:.1}% ({:.1} s)",
            m.faces - m.failed,
            m.faces,
            m.triangles,
            m.open_edges,
            m.inverted,
            100.0 * m.area_error,
            100.0 * m.angles,
            m.forced,
            100.0 * m.lengths,
            start.elapsed().as_secs_f64()
        );
        let mut fail = |what: String| problems.push(format!("{file}: {what}"));
        if m.failed > bar.failed_faces {
            fail(format!(
                "{} faces failed (bar {})",
                m.failed, bar.failed_faces
            ));
        }
        if bar.closed && m.open_edges > 0 {
            fail(format!("{} open or non-manifold edges", m.open_edges));
        }
        if m.inverted > bar.inverted {
            fail(format!(
                "{} inverted triangles (bar {})",
                m.inverted, bar.inverted
            ));
        }
        if m.area_error > bar.area {
            fail(format!(
                "area error {:.3}% (bar {:.3}%)",
                100.0 * m.area_error,
                100.0 * bar.area
            ));
        }
        if m.angles < bar.angles {
            fail(format!(
                "angles {:.2}% (bar {:.2}%)",
                100.0 * m.angles,
                100.0 * bar.angles
            ));
        }
        if m.lengths < bar.lengths {
            fail(format!(
                "lengths {:.2}% (bar {:.2}%)",
                100.0 * m.lengths,
                100.0 * bar.lengths
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// A uniform size coarser than the radius of periodic faces (no curvature limit): a half
/// circle meshed as one chord spans half the period in (u,v), and a short cone's apex has no
/// ring point at distance δ inside the face. Both used to leave fronts that could not close.
#[test]
fn coarse_uniform_size_on_periodic_faces() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let m = measure(&dir.join("hemisphere_cylinder_domain.stp"), 20.0, 0.0);
    println!("{m:?}");
    assert_eq!(m.failed, 0);
    assert_eq!(m.open_edges, 0);
    assert_eq!(m.inverted, 0);
}

/// The proximity limit finds a gap much narrower than its boundary sample step: face 9 of
/// gmsh_t20_component8 is a thin three-sided B-spline face whose base meets a side at a corner
/// of about 1°; 0.5 from that corner it is 0.011 wide while the base is sampled every 0.52.
/// Measured against the other side's polyline, not its nearest sample, the gap is seen (as one
/// narrower than the proximity limit's floor, size/10) and the spacing there drops to that
/// floor.
#[test]
fn proximity_limit_sees_a_gap_narrower_than_its_sample_step() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let case = case_from_cad(&dir.join("gmsh_t20_component8.step")).unwrap();
    let near_corner = glam::DVec3::new(-14.101, 188.500, -7.561);
    let proximity = case.sizing.proximity.as_ref().unwrap();
    assert!(proximity.floored_near(near_corner, 0.05), "gap not seen");
    let floor = case.controls.size / tetrafoil::case::PROXIMITY_FLOOR;
    let delta = case.sizing.spacing(near_corner);
    println!("δ {delta:.4} (proximity floor {floor:.4})");
    assert!(delta < 1.05 * floor, "δ {delta}");
}

/// sphere_revolved.step is one revolved face (seam, two poles) of ~2000 triangles: it is cut
/// into parts meshed concurrently, and the shell comes out closed with the quality of the face
/// meshed whole.
#[test]
fn large_single_face_is_split_and_keeps_its_quality() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let path = dir.join("sphere_revolved.step");
    let split = measure(&path, 30.0, tetrafoil::case::CURVATURE_SEGMENTS);
    let whole = measure_with(
        &path,
        30.0,
        tetrafoil::case::CURVATURE_SEGMENTS,
        SurfaceOptions {
            whole_faces: true,
            ..Default::default()
        },
    );
    println!("split: {split:?}\nwhole: {whole:?}");
    assert_eq!(split.split_faces, 1);
    assert_eq!(whole.split_faces, 0);
    assert_eq!((split.failed, split.open_edges, split.inverted), (0, 0, 0));
    assert!(split.area_error <= FULL.area);
    assert!(split.angles >= FULL.angles.max(whole.angles));
    assert!(split.lengths >= FULL.lengths.max(whole.lengths - 0.005));
}

/// At 1/35 of its diagonal, hemisphere_cylinder_domain.stp's symmetry plane holds most of its
/// triangles (over the split's 1200) in the graded band round the small body it is cut around,
/// far narrower than a density cell: the split's estimate must see them (from the cells'
/// centres it saw too few) and cut the face.
#[test]
fn a_face_crowded_round_a_small_body_is_split() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let m = measure(
        &dir.join("hemisphere_cylinder_domain.stp"),
        35.0,
        tetrafoil::case::CURVATURE_SEGMENTS,
    );
    println!("{m:?}");
    // 2 faces split since the curvature limit samples at its own spacing (1 before).
    assert!((1..=2).contains(&m.split_faces), "{m:?}");
    assert_eq!((m.failed, m.open_edges, m.inverted), (0, 0, 0));
    assert!(m.area_error <= FULL.area);
    assert!(m.angles >= FULL.angles && m.lengths >= FULL.lengths);
}

/// Which faces are split, and where, depends on the faces alone, and an OCCT surface's copies
/// for concurrent callers evaluate to the same bits: one thread and two (twice) give the same
/// sizing and mesh, to the bit.
#[test]
fn split_meshes_are_identical_on_one_and_two_threads() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let case = load(
                &dir.join("sphere_revolved.step"),
                30.0,
                tetrafoil::case::CURVATURE_SEGMENTS,
            );
            let curves = mesh_curves(&case.model, &case.sizing).unwrap();
            mesh_surfaces(
                &case.model,
                &curves,
                &case.sizing,
                SurfaceOptions::default(),
            )
            .unwrap()
            .0
        })
    };
    let one = on(1);
    assert_eq!(one.split_faces(), 1);
    for two in [on(2), on(2)] {
        assert_eq!(one.points, two.points);
        assert_eq!(one.triangles, two.triangles);
        assert_eq!(one.face_of, two.face_of);
    }
}

/// The constrained-Delaunay fallback (what a face gets when its advancing front cannot close)
/// meshes every face of the fast corpus files on its own: shells closed, nothing inverted,
/// the area at the bar, and after the same swaps and smoothing most triangles above
/// 25°.
#[test]
fn delaunay_fallback_alone_meshes_the_corpus_faces() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let options = SurfaceOptions {
        delaunay_only: true,
        ..Default::default()
    };
    for (file, _, slow) in corpus() {
        if slow {
            continue;
        }
        let m = measure_with(&dir.join(file), 30.0, curvature_segments(file), options);
        println!("{file}: {m:?}");
        assert_eq!((m.failed, m.open_edges, m.inverted), (0, 0, 0), "{file}");
        assert!(m.area_error <= FULL.area, "{file}: area {}", m.area_error);
        assert!(m.angles >= 0.75, "{file}: angles {}", m.angles);
    }
}
