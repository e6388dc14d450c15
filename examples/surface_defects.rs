//! Where a CAD file's surface mesh falls short, face by face: failed faces, open or
//! non-manifold edges (with the faces of the triangles on them), triangles inverted against
//! their surface normal, and per face the share of triangles with minimum angle below 25°.
//! Same size as `tests/surface_cad.rs` (1/30 of the diagonal, curvature limit on).
//! Usage: cargo run --release --example surface_defects -- FILE [FRACTION]
#[cfg(feature = "occt")]
fn main() {
    use std::collections::HashMap;
    use tetrafoil::case::case_from_cad;
    use tetrafoil::curve::mesh_curves;
    use tetrafoil::mesh::quality::triangle_min_angle;
    use tetrafoil::surface::{mesh_surfaces, SurfaceOptions};

    let args: Vec<String> = std::env::args().skip(1).collect();
    let fraction: f64 = args.get(1).map_or(30.0, |a| a.parse().unwrap());
    let mut case = case_from_cad(std::path::Path::new(&args[0])).unwrap_or_else(|e| panic!("{e}"));
    let size = case.controls.size * 20.0 / fraction;
    case.controls.size = size;
    case.sizing.uniform = size;
    let model = &case.model;
    let curves = mesh_curves(model, &case.sizing).unwrap();
    let options = SurfaceOptions {
        keep_going: true,
        ..Default::default()
    };
    let (mesh, failures) = mesh_surfaces(model, &curves, &case.sizing, options).unwrap();
    for f in &failures {
        println!("failed: {f}");
    }
    let p = |i: usize| mesh.points[i];
    for (r, region) in model.regions.iter().enumerate() {
        for shell in &region.shells {
            let reversed: HashMap<usize, bool> = shell
                .faces
                .iter()
                .map(|fu| (fu.face, fu.reversed))
                .collect();
            let mut directed: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
            for (t, f) in mesh.triangles.iter().zip(&mesh.face_of) {
                let Some(&rev) = reversed.get(f) else {
                    continue;
                };
                let t = if rev { [t[0], t[2], t[1]] } else { *t };
                for k in 0..3 {
                    directed.entry((t[k], t[(k + 1) % 3])).or_default().push(*f);
                }
            }
            for (&(a, b), faces) in &directed {
                let back = directed.get(&(b, a));
                if faces.len() != 1 || back.map(|v| v.len()) != Some(1) {
                    println!(
                        "region {r}: edge {a}->{b} used {:?}, back {:?}, at {:?} .. {:?}",
                        faces,
                        back,
                        p(a),
                        p(b)
                    );
                }
            }
        }
    }
    // Per face: triangles below 25°, triangles, and how many of the bad ones have only
    // curve-mesh nodes (forced by the boundary).
    let mut bad = vec![(0usize, 0usize, 0usize); model.faces.len()];
    for (i, (t, &f)) in mesh.triangles.iter().zip(&mesh.face_of).enumerate() {
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let n = (b - a).cross(c - a);
        bad[f].1 += 1;
        let ang = triangle_min_angle(a, b, c);
        if ang < 25.0 {
            if std::env::var("FACE").is_ok_and(|v| v.parse() == Ok(f)) {
                let d = case.sizing.spacing((a + b + c) / 3.0);
                let len = [(b - a).length(), (c - b).length(), (a - c).length()];
                let longest = len.iter().copied().fold(0.0, f64::max);
                let floored = case
                    .sizing
                    .proximity
                    .as_ref()
                    .map(|pr| pr.floored_near((a + b + c) / 3.0, longest));
                println!("  bad {i}: min {ang:.1}° nodes {t:?} lengths {len:.3?} δ {d:.3} floored {floored:?} min_size {} at {a:.3}", case.controls.min_size);
            }
            bad[f].0 += 1;
            if t.iter().all(|&v| v < curves.points.len()) {
                bad[f].2 += 1;
            }
        }
        let surface = &model.faces[f].surface;
        let centroid = (a + b + c) / 3.0;
        if let Some(uv) = surface.closest_uv(centroid, None) {
            if surface.normal(uv).dot(n) < 0.0 {
                println!(
                    "inverted: triangle {i} face {f} nodes {t:?} uv {uv:?} at {centroid:?} \
                     min angle {ang:.2} area {:.3e}",
                    0.5 * n.length()
                );
            }
        }
    }
    // Per face: mesh area against the model's boundary-integral area (AREAS=1), worst first.
    if std::env::var("AREAS").is_ok() {
        let mut area = vec![0.0; model.faces.len()];
        for (t, &f) in mesh.triangles.iter().zip(&mesh.face_of) {
            area[f] += 0.5 * (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])).length();
        }
        let mut rows: Vec<(usize, f64, f64)> = (0..model.faces.len())
            .filter_map(|f| Some((f, area[f], model.face_integrals(f)?.area)))
            .collect();
        rows.sort_by(|a, b| (b.1 - b.2).abs().total_cmp(&(a.1 - a.2).abs()));
        let (mesh_total, cad_total): (f64, f64) = rows
            .iter()
            .map(|r| (r.1, r.2))
            .fold((0.0, 0.0), |s, r| (s.0 + r.0, s.1 + r.1));
        println!(
            "area: mesh {mesh_total:.6e} root {cad_total:.6e} ({:+.3}%)",
            100.0 * (mesh_total / cad_total - 1.0)
        );
        for (f, m, c) in rows.iter().take(12) {
            println!(
                "  face {f} {}: mesh {m:.6e} root {c:.6e} diff {:+.3e} ({:+.3}%)",
                model.face_ref(*f),
                m - c,
                100.0 * (m / c - 1.0)
            );
        }
    }
    for (f, (b, n, forced)) in bad.iter().enumerate() {
        if *b > 0 || std::env::var("ALL").is_ok() {
            println!("face {f}: {b}/{n} triangles below 25° ({forced} with boundary nodes only)");
        }
    }
}

#[cfg(not(feature = "occt"))]
fn main() {}
