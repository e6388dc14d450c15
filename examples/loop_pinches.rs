//! Where a face's boundary comes close to itself: for every face of a CAD file (loaded as
//! `tetrafoil mesh` loads it: sewn, fused), pairs of boundary samples on different edge uses
//! that are closer in 3-D than `FRACTION` of the diagonal (default 1e-3) while not near a shared
//! vertex, with their (u,v). Usage: cargo run --release --example loop_pinches -- FILE [FRACTION]
#[cfg(feature = "occt")]
fn main() {
    use tetrafoil::case::case_from_cad;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let fraction: f64 = args.get(1).map_or(1e-3, |a| a.parse().unwrap());
    let case = case_from_cad(std::path::Path::new(&args[0])).unwrap_or_else(|e| panic!("{e}"));
    let model = &case.model;
    // Edge and vertex tolerances of the file as read (ids match when nothing was sewn or fused).
    let raw = tetrafoil_occt::CadModel::read(&args[0]).unwrap();
    let tol = |e: usize| raw.topology().edges.get(e).map(|x| x.tolerance);
    let diag = case.controls.size * 20.0;
    let near = fraction * diag;
    // Boundary-integral area of each face of the model as loaded (after any repair) against
    // BRepGProp's area of the face as read (ids match when nothing was sewn or fused).
    let (mut total, mut total_cad) = (0.0, 0.0);
    for f in 0..model.faces.len() {
        let area = model.face_integrals(f).map(|i| i.area);
        let cad = raw
            .face_area(f)
            .ok()
            .filter(|_| raw.topology().faces.len() == model.faces.len());
        if let (Some(a), Some(c)) = (area, cad) {
            total += a;
            total_cad += c;
            println!(
                "face {f}: area from the boundary {a:.6e}, BRepGProp {c:.6e} ({:+.4}%)",
                100.0 * (a - c) / c
            );
        }
    }
    if total_cad > 0.0 {
        println!(
            "total: {total:.6e} vs {total_cad:.6e} ({:+.4}%)",
            100.0 * (total - total_cad) / total_cad
        );
    }
    if let Some(only) = args.get(2).map(|a| a.parse::<usize>().unwrap()) {
        for (l, lp) in model.faces[only].loops.iter().enumerate() {
            for u in &lp.uses {
                let e = &model.edges[u.edge];
                let (a, b) = model.use_vertices(u);
                let (t0, t1) = if u.reversed {
                    (e.range.1, e.range.0)
                } else {
                    e.range
                };
                println!(
                    "face {only} loop {l} edge {} rev {} v{a} {:?} uv {:?} -> v{b} {:?} uv {:?}",
                    u.edge,
                    u.reversed,
                    model.vertices[a].point,
                    model.use_uv(only, u, t0),
                    model.vertices[b].point,
                    model.use_uv(only, u, t1)
                );
            }
        }
    }
    for (f, face) in model.faces.iter().enumerate() {
        // Samples: (use index in the face, 3-D point, (u,v), edge).
        let mut samples = Vec::new();
        let mut k = 0;
        for lp in &face.loops {
            for u in &lp.uses {
                let e = &model.edges[u.edge];
                if e.is_degenerate() {
                    k += 1;
                    continue;
                }
                let n = 400;
                for i in 0..=n {
                    let t = e.range.0 + (e.range.1 - e.range.0) * i as f64 / n as f64;
                    let p = model.edge_point(u.edge, t);
                    let uv = model.use_uv(f, u, t);
                    samples.push((k, p, uv, u.edge, t));
                }
                k += 1;
            }
        }
        let vertices: Vec<_> = face
            .loops
            .iter()
            .flat_map(|l| l.uses.iter())
            .flat_map(|u| {
                let (a, b) = model.use_vertices(u);
                [model.vertices[a].point, model.vertices[b].point]
            })
            .collect();
        let mut worst: std::collections::BTreeMap<(usize, usize), (f64, f64, f64, usize)> =
            Default::default();
        for a in &samples {
            for b in &samples {
                if a.3 >= b.3 {
                    continue;
                }
                let d = a.1.distance(b.1);
                // Far from every vertex: a pinch, not a corner.
                let vd = vertices
                    .iter()
                    .map(|v| v.distance(a.1).min(v.distance(b.1)))
                    .fold(f64::INFINITY, f64::min);
                if d < near && vd > 10.0 * d.max(1e-9 * diag) {
                    let w = worst
                        .entry((a.3, b.3))
                        .or_insert((f64::INFINITY, 0.0, 0.0, 0));
                    w.3 += 1;
                    if d < w.0 {
                        *w = (d, a.4, b.4, w.3);
                    }
                }
            }
        }
        for ((ea, eb), (d, ta, tb, count)) in worst {
            println!(
                "face {f}: edges {ea} (t {ta:.4}) and {eb} (t {tb:.4}) come within {d:.3e} ({count} sample pairs below {near:.3e}); tolerances as read {:?} {:?}",
                tol(ea),
                tol(eb)
            );
        }
    }
}

#[cfg(not(feature = "occt"))]
fn main() {
    eprintln!("needs the occt feature");
}
