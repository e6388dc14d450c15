//! Geometry handles used from several threads give the single-thread answers.
mod common;

use rayon::prelude::*;
use tetrafoil_occt::{OccCurve, OccPcurve, OccSurface};

fn assert_send_sync<T: Send + Sync>() {}

#[test]
fn handles_are_send_and_sync() {
    assert_send_sync::<OccSurface>();
    assert_send_sync::<OccCurve>();
    assert_send_sync::<OccPcurve>();
}

/// Points on and slightly off a B-spline face, to project.
fn targets(s: &OccSurface, n: usize) -> Vec<[f64; 3]> {
    let ([u0, u1], [v0, v1]) = (s.u_range(), s.v_range());
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let u = u0 + (i as f64 + 0.3) / n as f64 * (u1 - u0);
            let v = v0 + (j as f64 + 0.7) / n as f64 * (v1 - v0);
            let d = s.derivs(u, v).unwrap();
            let off = 1e-3 * (i as f64 - j as f64);
            out.push([d.p[0] + off, d.p[1] - off, d.p[2] + 0.5 * off]);
        }
    }
    out
}

/// The first B-spline face of gmsh_t20_component8.step; `None` without the corpus.
fn bspline_surface() -> Option<OccSurface> {
    let dir = common::cad_dir()?;
    let m = common::load(&dir, "gmsh_t20_component8.step");
    let face = m
        .topology()
        .faces
        .iter()
        .position(|f| f.surface_kind == "bspline")
        .unwrap();
    Some(m.surface(face).unwrap())
}

#[test]
fn projections_from_two_threads_match_one_thread() {
    let Some(s) = bspline_surface() else { return };
    let pts = targets(&s, 30);
    let serial: Vec<[f64; 2]> = pts.iter().map(|&p| s.project(p, None).unwrap()).collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    // One shared handle (each thread gets a copy of its own inside) and explicit deep copies.
    let shared: Vec<[f64; 2]> = pool.install(|| {
        pts.par_iter()
            .map(|&p| s.project(p, None).unwrap())
            .collect()
    });
    let cloned: Vec<[f64; 2]> = pool.install(|| {
        pts.par_iter()
            .map_init(
                || s.try_clone().unwrap(),
                |c, &p| c.project(p, None).unwrap(),
            )
            .collect()
    });
    let span = (s.u_range()[1] - s.u_range()[0]).max(s.v_range()[1] - s.v_range()[0]);
    let mut worst = 0.0f64;
    for ((a, b), c) in serial.iter().zip(&shared).zip(&cloned) {
        for k in 0..2 {
            worst = worst.max((a[k] - b[k]).abs()).max((a[k] - c[k]).abs());
        }
    }
    println!(
        "{} projections; largest difference from single-thread: {worst:e}",
        pts.len()
    );
    assert!(worst <= 1e-9 * span, "{worst}");
}

/// Threads sharing one handle evaluate on copies made for them: the same bits as one thread.
#[test]
fn evaluations_on_a_shared_handle_are_exact_on_two_threads() {
    let Some(s) = bspline_surface() else { return };
    let ([u0, u1], [v0, v1]) = (s.u_range(), s.v_range());
    let uv: Vec<(f64, f64)> = (0..20_000)
        .map(|k| {
            let (a, b) = ((k % 141) as f64 / 141.0, (k / 141) as f64 / 142.0);
            (u0 + a * (u1 - u0), v0 + b * (v1 - v0))
        })
        .collect();
    let serial: Vec<_> = uv.iter().map(|&(u, v)| s.derivs(u, v)).collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let shared: Vec<_> = pool.install(|| uv.par_iter().map(|&(u, v)| s.derivs(u, v)).collect());
    assert!(serial.iter().all(|d| d.is_some()));
    assert_eq!(serial, shared);
}
