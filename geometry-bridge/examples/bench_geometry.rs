//! Throughput of OCCT projections and circle intersections on one B-spline face: one thread,
//! two rayon threads sharing one handle (which makes a copy for each thread inside), two threads
//! with an explicit deep copy each.
//! Usage: cargo run --release -p tetrafoil-occt --example bench_geometry -- [FILE]
use std::time::Instant;

use rayon::prelude::*;
use tetrafoil_occt::{CadModel, OccSurface};

const DEFAULT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../shared/cad/gmsh_t20_component8.step"
);

/// Work items: a point near the face (to project) and a circle about it (to intersect).
struct Item {
    p: [f64; 3],
    axis: [f64; 3],
    x_axis: [f64; 3],
    radius: f64,
}

fn items(s: &OccSurface, n: usize) -> Vec<Item> {
    let ([u0, u1], [v0, v1]) = (s.u_range(), s.v_range());
    let norm = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    (0..n * n)
        .map(|k| {
            let u = u0 + ((k / n) as f64 + 0.3) / n as f64 * (u1 - u0);
            let v = v0 + ((k % n) as f64 + 0.6) / n as f64 * (v1 - v0);
            let d = s.derivs(u, v).unwrap();
            let (du, dv) = (norm(d.du), norm(d.dv));
            let axis = d.du.map(|x| x / du);
            let x_axis = d.dv.map(|x| x / dv);
            let radius = 0.02 * (du * (u1 - u0)).min(dv * (v1 - v0));
            Item {
                p: d.p,
                axis,
                x_axis,
                radius,
            }
        })
        .collect()
}

fn rate(label: &str, n: usize, f: impl FnOnce()) {
    let t = Instant::now();
    f();
    let s = t.elapsed().as_secs_f64();
    println!("{label:<48} {:>10.0} /s  ({n} in {s:.3} s)", n as f64 / s);
}

fn main() {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| DEFAULT.to_string());
    let model = CadModel::read(&path).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    let Some(face) = model
        .topology()
        .faces
        .iter()
        .position(|f| f.surface_kind == "bspline")
    else {
        eprintln!("{path}: no B-spline face");
        std::process::exit(1)
    };
    let s = model.surface(face).unwrap();
    let work = items(&s, 40);
    let n = work.len();
    println!("{path}: face {face} (bspline), {n} items");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    type Op = fn(&OccSurface, &Item) -> usize;
    let project: Op = |s, it| s.project(it.p, None).map_or(0, |_| 1);
    let circle: Op = |s, it| {
        s.intersect_circle(it.p, it.axis, it.x_axis, it.radius)
            .map_or(0, |h| h.len())
    };
    // Two deep copies made up front, one per thread, so the timing excludes copying.
    let copies = [s.try_clone().unwrap(), s.try_clone().unwrap()];
    let (first, second) = work.split_at(n / 2);
    for (name, op) in [("projections", project), ("circle intersections", circle)] {
        // Warm-up: ShapeAnalysis_Surface builds its caches on first use.
        for c in std::iter::once(&s).chain(&copies) {
            work.iter().take(50).for_each(|it| {
                op(c, it);
            });
        }
        rate(&format!("{name}, 1 thread"), n, || {
            work.iter().for_each(|it| {
                op(&s, it);
            })
        });
        rate(&format!("{name}, 2 threads, one shared handle"), n, || {
            pool.install(|| {
                work.par_iter().for_each(|it| {
                    op(&s, it);
                })
            })
        });
        rate(&format!("{name}, 2 threads, a copy each"), n, || {
            pool.install(|| {
                rayon::join(
                    || {
                        first.iter().for_each(|it| {
                            op(&copies[0], it);
                        })
                    },
                    || {
                        second.iter().for_each(|it| {
                            op(&copies[1], it);
                        })
                    },
                )
            });
        });
    }
}
