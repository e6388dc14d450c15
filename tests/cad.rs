//! CAD input end to end: `tetrafoil check` on every file of the public corpus
//! (`../shared/cad` next to the workspace root), and the imported model's orientation, areas
//! and volumes against OpenCASCADE's own (BRepGProp).

mod common;
use common::corpus::cad_dir;
use common::occt;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use tetrafoil_occt::CadModel;

fn cad_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| tetrafoil::cli::is_cad(p))
        .collect();
    files.sort();
    files
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

#[test]
fn check_every_corpus_file() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let files = cad_files(&dir);
    assert!(files.len() >= 20, "corpus has {} files", files.len());
    let (mut ok, mut refused) = (0, 0);
    for path in &files {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let out = occt::tetrafoil()
            // Not --quiet: the notes of loading (merged stretches) are counted below.
            .args(["check"])
            .arg(path)
            .arg("--json")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{name}: panic:\n{stderr}");
        assert_ne!(out.status.code(), Some(101), "{name}: panic exit");
        if !out.status.success() {
            let lower = stderr.to_lowercase();
            assert!(
                lower.contains("face") || lower.contains("edge"),
                "{name}: failure names no face or edge:\n{stderr}"
            );
            let first = stderr.lines().take(3).collect::<Vec<_>>().join(" | ");
            println!("{name}: refused: {first}");
            refused += 1;
            continue;
        }
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let count = |k: &str| v[k].as_u64().unwrap() as usize;
        let mut cad = CadModel::read(path).unwrap();
        if cad.topology().solids.len() >= 2 {
            // The loader imprints an assembly's contacts (general fuse) at the model tolerance.
            let diagonal = cad.bounding_box().unwrap().unwrap().diagonal();
            cad = cad.fuse_solids(1e-6 * diagonal).unwrap().0;
        }
        let t = cad.topology();
        if t.solids.is_empty() {
            // Sewn by the loader: same faces, now in solids.
            assert!(count("regions") >= 1, "{name}");
            assert_eq!(count("faces"), t.faces.len(), "{name}: faces after sewing");
        } else {
            let shells: usize = t.solids.iter().map(|s| s.shells.len()).sum();
            assert_eq!(count("regions"), t.solids.len(), "{name}: regions");
            assert_eq!(count("shells"), shells, "{name}: shells");
            assert_eq!(count("faces"), t.faces.len(), "{name}: faces");
            // A merged coincident stretch (model::coincident, said on stderr) adds one edge and
            // one vertex.
            let merged = stderr.matches("the slit is closed").count();
            if merged > 0 {
                println!("{name}: {merged} coincident stretches merged");
            }
            assert_eq!(count("edges"), t.edges.len() + merged, "{name}: edges");
            assert_eq!(
                count("vertices"),
                t.vertices.len() + merged,
                "{name}: vertices"
            );
            let step = name.ends_with(".stp") || name.ends_with(".step");
            if step && t.solids.len() == 1 {
                let text = std::fs::read_to_string(path).unwrap();
                assert_eq!(
                    count("faces"),
                    text.matches("ADVANCED_FACE").count(),
                    "{name}: faces vs ADVANCED_FACE"
                );
            }
        }
        println!(
            "{name}: ok: regions {} shells {} faces {} edges {} vertices {} degenerate {}",
            count("regions"),
            count("shells"),
            count("faces"),
            count("edges"),
            count("vertices"),
            count("degenerate_edges")
        );
        ok += 1;
    }
    println!("{ok} files checked, {refused} refused with a diagnosis");
    assert!(ok >= 10, "only {ok} files load");
}

#[test]
fn hemisphere_cylinder_volume_matches_occt() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let path = dir.join("hemisphere_cylinder_domain.stp");
    let cad = CadModel::read(&path).unwrap();
    let model = occt::model(&occt::open(&path)).unwrap();
    let ours = model.regions[0].shells[0].volume;
    let occt = cad.solid_volume(0).unwrap().abs();
    println!(
        "hemisphere_cylinder_domain: root {ours:.9e}, BRepGProp {occt:.9e}, rel {:.2e}",
        rel(ours, occt)
    );
    assert!(rel(ours, occt) < 1e-3, "volume {ours} vs OCCT {occt}");
}

/// Root face areas (Green's theorem on the boundary) against BRepGProp, face by face.
fn compare_areas(dir: &Path, file: &str) -> (f64, f64, Vec<String>) {
    let cad = CadModel::read(dir.join(file)).unwrap();
    let model = occt::model(&occt::open(&dir.join(file))).unwrap();
    let (mut sum_root, mut sum_occt) = (0.0, 0.0);
    let mut bad = Vec::new();
    for f in 0..model.faces.len() {
        let a = model.face_integrals(f).map_or(f64::NAN, |i| i.area);
        let b = cad.face_area(f).unwrap();
        sum_root += a;
        sum_occt += b;
        if rel(a, b).is_nan() || rel(a, b) >= 1e-3 {
            bad.push(format!(
                "face {f} ({}): root {a:.6e} occt {b:.6e}",
                cad.topology().faces[f].surface_kind
            ));
        }
    }
    println!(
        "{file}: area root {sum_root:.9e}, BRepGProp {sum_occt:.9e}, rel {:.2e}; faces off by > 1e-3: {bad:?}",
        rel(sum_root, sum_occt)
    );
    (sum_root, sum_occt, bad)
}

#[test]
fn face_areas_match_occt() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    for file in [
        "sliced_cylinder_rhino.step",
        "gmsh_part.step",
        "occt_screw.step",
    ] {
        let (a, b, _) = compare_areas(&dir, file);
        assert!(rel(a, b) < 1e-3, "{file}: total area {a} vs OCCT {b}");
    }
}

/// `Model::orient` must agree with the orientation OCCT stores in the file (for valid solids).
#[test]
fn orientation_agrees_with_occt() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let mut compared = 0;
    for path in cad_files(&dir) {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let Ok(cad) = CadModel::read(&path) else {
            continue;
        };
        if cad.check_solids().is_err() {
            continue;
        }
        let Ok(model) = occt::model(&occt::open(&path)) else {
            continue;
        };
        let t = cad.topology();
        for (r, solid) in t.solids.iter().enumerate() {
            let occt: HashMap<usize, bool> = solid
                .shells
                .iter()
                .flat_map(|&s| t.shells[s].faces.iter().copied())
                .collect();
            // A face listed twice with both orientations (an internal face) says nothing.
            let ours: HashMap<usize, bool> = model
                .region_faces(r)
                .map(|fu| (fu.face, fu.reversed))
                .collect();
            let disagree: Vec<usize> = ours
                .iter()
                .filter(|(f, rev)| occt.get(f).is_some_and(|o| o != *rev))
                .map(|(f, _)| *f)
                .collect();
            assert!(
                disagree.is_empty(),
                "{name}: region {r}: faces {disagree:?} oriented against OCCT"
            );
        }
        compared += 1;
    }
    println!("orientation agrees with OCCT on {compared} files");
    assert!(compared >= 8);
}

#[test]
fn two_solids_give_two_regions() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let path = dir.join("wing_fuselage_2solids.step");
    let cad = CadModel::read(&path).unwrap();
    let model = occt::model(&occt::open(&path)).unwrap();
    assert_eq!(model.regions.len(), 2);
    for (r, region) in model.regions.iter().enumerate() {
        let occt = cad.solid_volume(r).unwrap().abs();
        println!(
            "wing_fuselage region {r} {:?}: root {:.6e} occt {occt:.6e}",
            region.name, region.shells[0].volume
        );
        assert!(rel(region.shells[0].volume, occt) < 1e-3);
    }
}

#[test]
fn imported_pcurves_follow_their_edges() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    for file in [
        "box_colored_faces.stp",
        "sliced_cylinder_rhino.step",
        "sphere_revolved.step",
    ] {
        let cad = CadModel::read(dir.join(file)).unwrap();
        let model = occt::imported(&occt::open(&dir.join(file))).unwrap();
        let size = cad.bounding_box().unwrap().unwrap().diagonal();
        let mut worst: f64 = 0.0;
        for face in &model.faces {
            for u in face.loops.iter().flat_map(|l| &l.uses) {
                let e = &model.edges[u.edge];
                let (Some(c), Some(pc)) = (&e.curve, &u.pcurve) else {
                    continue;
                };
                for k in 0..=8 {
                    let t = e.range.0 + (e.range.1 - e.range.0) * k as f64 / 8.0;
                    let d = face.surface.point(pc.point(t)).distance(c.point(t));
                    worst = worst.max(d);
                }
            }
        }
        println!("{file}: pcurve vs edge curve, worst {worst:.3e} (size {size:.3e})");
        assert!(
            worst < 1e-4 * size,
            "{file}: pcurves off their edges by {worst}"
        );
    }
}

#[test]
fn case_file_can_name_a_cad_model() {
    let _occt = common::occt::one_at_a_time();
    let Some(dir) = cad_dir() else { return };
    let tmp = std::env::temp_dir().join(format!("tetrafoil-cad-case-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    std::fs::copy(dir.join("box_colored_faces.stp"), tmp.join("box.stp")).unwrap();
    let case = tmp.join("case.toml");
    std::fs::write(&case, "[mesh]\ncad = \"box.stp\"\ncurvature_segments = 0\n").unwrap();
    let c = tetrafoil::case::load_case(&case).unwrap();
    assert_eq!(c.model.regions.len(), 1);
    assert_eq!(c.model.faces.len(), 6);
    assert!(c.controls.size > 0.0 && c.sizing.curvature.is_none());
    std::fs::write(
        &case,
        "[mesh]\ncad = \"box.stp\"\n\n[[vertex]]\nname = \"a\"\npoint = [0, 0, 0]\n",
    )
    .unwrap();
    let e = tetrafoil::case::load_case(&case).err().unwrap().to_string();
    assert!(e.contains("mesh.cad") && e.contains("mixed"), "{e}");
    std::fs::write(&case, "[mesh]\ncad = \"missing.stp\"\n").unwrap();
    let e = tetrafoil::case::load_case(&case).err().unwrap().to_string();
    assert!(e.contains("missing.stp"), "{e}");
    std::fs::remove_dir_all(&tmp).ok();
}

/// Command-line controls replace the case's before its sizing is built, giving the field a
/// load at the case's own controls followed by a rebuild gave (the rebuild is no longer paid).
#[test]
fn control_overrides_give_the_rebuilt_sizing() {
    let _occt = common::occt::one_at_a_time();
    use tetrafoil::case::{case_from_cad, case_from_cad_with, ControlOverrides};
    let Some(dir) = cad_dir() else { return };
    let path = dir.join("hemisphere_cylinder_domain.stp");
    let default = case_from_cad(&path).unwrap();
    let overrides = ControlOverrides {
        size: Some(default.controls.size / 2.0),
        curvature_segments: Some(18.0),
        proximity_cells: Some(0.0),
        ..Default::default()
    };
    let once = case_from_cad_with(&path, &overrides).unwrap();
    let mut rebuilt = case_from_cad(&path).unwrap();
    overrides.apply(&mut rebuilt.controls);
    rebuilt.sizing.uniform = rebuilt.controls.size;
    rebuilt
        .sizing
        .set_local_limits(&rebuilt.model, &rebuilt.controls);
    assert_eq!(once.controls, rebuilt.controls);
    assert!(once.sizing.proximity.is_none());
    let mut changed = 0;
    for k in 0..500 {
        let t = k as f64 / 500.0;
        let p = glam::DVec3::new(
            -90.0 + 100.0 * t,
            50.0 * (7.0 * t).sin(),
            -100.0 + 200.0 * t,
        );
        assert_eq!(once.sizing.spacing(p), rebuilt.sizing.spacing(p), "at {p}");
        if once.sizing.spacing(p) != default.sizing.spacing(p) {
            changed += 1;
        }
    }
    assert!(changed > 400, "{changed} of 500 samples changed");
}

/// A STEP file written here: a tetrahedron solid (0,0,0), (1,0,0), (0,1,0), (0,0,1) and, in
/// the same representation, a `SHELL_BASED_SURFACE_MODEL` of one open triangle beside it (the
/// construction surfaces some CAD systems export with a part).
fn tet_with_construction_shell() -> String {
    let mut out: Vec<String> = Vec::new();
    let mut add = |e: String| -> usize {
        out.push(e);
        out.len() + 15
    };
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [3.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [3.0, 1.0, 0.0],
    ];
    let point = |add: &mut dyn FnMut(String) -> usize, x: [f64; 3]| {
        add(format!(
            "CARTESIAN_POINT('',({:.1},{:.1},{:.1}))",
            x[0], x[1], x[2]
        ))
    };
    let direction = |add: &mut dyn FnMut(String) -> usize, x: [f64; 3]| {
        let n = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        add(format!(
            "DIRECTION('',({},{},{}))",
            x[0] / n,
            x[1] / n,
            x[2] / n
        ))
    };
    let vertices: Vec<usize> = p
        .iter()
        .map(|&x| {
            let c = point(&mut add, x);
            add(format!("VERTEX_POINT('',#{c})"))
        })
        .collect();
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
    // Faces as vertex triples ordered with the outward normal by the right-hand rule.
    let solid_faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let mut face = |add: &mut dyn FnMut(String) -> usize, tri: [usize; 3]| -> usize {
        let mut oriented = Vec::new();
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            let edge = *edges.entry(key).or_insert_with(|| {
                let c = point(add, p[key.0]);
                let d = direction(add, sub(p[key.1], p[key.0]));
                let v = add(format!("VECTOR('',#{d},1.0)"));
                let line = add(format!("LINE('',#{c},#{v})"));
                add(format!(
                    "EDGE_CURVE('',#{},#{},#{line},.T.)",
                    vertices[key.0], vertices[key.1]
                ))
            });
            let sense = if a < b { ".T." } else { ".F." };
            oriented.push(add(format!("ORIENTED_EDGE('',*,*,#{edge},{sense})")));
        }
        let (u, w) = (sub(p[tri[1]], p[tri[0]]), sub(p[tri[2]], p[tri[0]]));
        let n = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let origin = point(add, p[tri[0]]);
        let axis = direction(add, n);
        let reference = direction(add, u);
        let placement = add(format!(
            "AXIS2_PLACEMENT_3D('',#{origin},#{axis},#{reference})"
        ));
        let plane = add(format!("PLANE('',#{placement})"));
        let list = oriented
            .iter()
            .map(|i| format!("#{i}"))
            .collect::<Vec<_>>()
            .join(",");
        let edge_loop = add(format!("EDGE_LOOP('',({list}))"));
        let bound = add(format!("FACE_OUTER_BOUND('',#{edge_loop},.T.)"));
        add(format!("ADVANCED_FACE('',(#{bound}),#{plane},.T.)"))
    };
    let faces: Vec<usize> = solid_faces.iter().map(|&t| face(&mut add, t)).collect();
    let list = |ids: &[usize]| {
        ids.iter()
            .map(|i| format!("#{i}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    let shell = add(format!("CLOSED_SHELL('',({}))", list(&faces)));
    let solid = add(format!("MANIFOLD_SOLID_BREP('tet',#{shell})"));
    let loose = face(&mut add, [4, 5, 6]);
    let open = add(format!("OPEN_SHELL('',(#{loose}))"));
    let surface_model = add(format!("SHELL_BASED_SURFACE_MODEL('',(#{open}))"));
    let header = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n\
        FILE_NAME('tet.step','2026-12-03T00:00:00',(''),(''),'','','');\n\
        FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
    let context = format!(
        "#1=APPLICATION_CONTEXT('automotive design');\n\
         #2=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#1);\n\
         #3=PRODUCT_CONTEXT('',#1,'mechanical');\n\
         #4=PRODUCT('part','part','',(#3));\n\
         #5=PRODUCT_DEFINITION_FORMATION('','',#4);\n\
         #6=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');\n\
         #7=PRODUCT_DEFINITION('design','',#5,#6);\n\
         #8=PRODUCT_DEFINITION_SHAPE('','',#7);\n\
         #9=SHAPE_DEFINITION_REPRESENTATION(#8,#10);\n\
         #10=SHAPE_REPRESENTATION('',(#{solid},#{surface_model}),#11);\n\
         #11=(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#12)) \
         GLOBAL_UNIT_ASSIGNED_CONTEXT((#13,#14,#15)) REPRESENTATION_CONTEXT('',''));\n\
         #12=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#13,'','');\n\
         #13=(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.));\n\
         #14=(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.));\n\
         #15=(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT());\n"
    );
    let body: String = out
        .iter()
        .enumerate()
        .map(|(i, e)| format!("#{}={e};\n", i + 16))
        .collect();
    format!("{header}{context}{body}ENDSEC;\nEND-ISO-10303-21;\n")
}

/// Construction geometry beside a solid (an open shell in the same file) is left out with a
/// note: the solid alone is meshed, and the note names the skipped face.
#[test]
fn open_shells_beside_a_solid_are_skipped_with_a_note() {
    let _occt = common::occt::one_at_a_time();
    let dir = std::env::temp_dir().join(format!("tetrafoil-construction-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tet_and_sheet.step");
    std::fs::write(&path, tet_with_construction_shell()).unwrap();
    let cad = CadModel::read(&path).unwrap();
    assert_eq!(cad.topology().solids.len(), 1, "the file's solid");
    assert_eq!(
        cad.topology().faces.len(),
        5,
        "four faces of the solid and the sheet"
    );
    assert_eq!(cad.faces_outside_solids().len(), 1);
    let case = tetrafoil::case::case_from_cad(&path).unwrap();
    assert_eq!(case.model.faces.len(), 4);
    assert_eq!(case.model.regions.len(), 1);
    let volume = case.model.regions[0].shells[0].volume;
    assert!((volume - 1.0 / 6.0).abs() < 1e-9, "volume {volume}");
    let out = occt::tetrafoil()
        .args(["mesh"])
        .arg(&path)
        .arg("-o")
        .arg(dir.join("tet.su2"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("1 face(s) belong to no solid and are not meshed"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A 10 × 10 × 10 box as six loose planar faces (no shared edges), its top lifted by `gap`.
fn gapped_box(gap: f64, name: &str) -> PathBuf {
    let (a, h) = (10.0, 10.0 + gap);
    let p = |x: f64, y: f64, z: f64| [x, y, z];
    let faces = vec![
        vec![p(0., 0., 0.), p(0., a, 0.), p(a, a, 0.), p(a, 0., 0.)],
        vec![p(0., 0., h), p(a, 0., h), p(a, a, h), p(0., a, h)],
        vec![p(0., 0., 0.), p(a, 0., 0.), p(a, 0., a), p(0., 0., a)],
        vec![p(0., a, 0.), p(0., a, a), p(a, a, a), p(a, a, 0.)],
        vec![p(0., 0., 0.), p(0., 0., a), p(0., a, a), p(0., a, 0.)],
        vec![p(a, 0., 0.), p(a, a, 0.), p(a, a, a), p(a, 0., a)],
    ];
    let path = std::env::temp_dir().join(format!("tetrafoil-{name}-{}.step", std::process::id()));
    tetrafoil_occt::build::loose_polygons(&faces, &path).unwrap();
    path
}

/// Loose faces a little further apart than 1e-4 of the diagonal (an export in loose
/// tolerances) are sewn at the wider steps; faces further apart than the widest step are
/// refused with the tolerances tried and the free edges named.
#[test]
fn loose_faces_are_sewn_at_growing_tolerances() {
    let _occt = common::occt::one_at_a_time();
    let diagonal = 300f64.sqrt();
    assert_eq!(tetrafoil::case::SEW_STEPS, [1e-6, 1e-4, 1e-3]);
    let path = gapped_box(4e-4 * diagonal, "gap-4e-4");
    let case = tetrafoil::case::case_from_cad(&path).expect("sewn at 1e-3 of the diagonal");
    assert_eq!(case.model.regions.len(), 1);
    let volume = case.model.regions[0].shells[0].volume.abs();
    assert!(rel(volume, 1000.0) < 1e-3, "volume {volume}");
    let mut case = case;
    let (_, report) = tetrafoil::pipeline::mesh_case(&mut case, Default::default()).unwrap();
    assert!(report.validity.is_valid(), "{:?}", report.validity.defects);
    assert!(rel(report.validity.volume, 1000.0) < 1e-2);
    std::fs::remove_file(&path).ok();

    let path = gapped_box(5e-3 * diagonal, "gap-5e-3");
    let err = tetrafoil::case::case_from_cad(&path)
        .err()
        .expect("too wide a gap to sew")
        .to_string();
    println!("{err}");
    assert!(err.contains("contains no solid"), "{err}");
    // 1e-6, 1e-4 and 1e-3 of the (gapped) box's diagonal, then the widest after healing.
    assert!(err.contains("1.737e-5 then 1.737e-3 then 1.737e-2 then 1.737e-2 after healing"));
    assert!(err.contains("free edge"), "{err}");
    std::fs::remove_file(&path).ok();
}
