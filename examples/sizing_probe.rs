//! Times `SizingField::spacing` on a CAD case at 20 000 random points of its bounding box:
//! `cargo run --release --example sizing_probe -- part.step`.
use std::time::Instant;
use tetrafoil::case::case_from_cad;
fn main() {
    let path = std::env::args().nth(1).expect("CAD file");
    let case = case_from_cad(std::path::Path::new(&path)).unwrap();
    let pts: Vec<glam::DVec3> = case.model.vertices.iter().map(|v| v.point).collect();
    let lo = pts
        .iter()
        .fold(glam::DVec3::splat(f64::MAX), |a, b| a.min(*b));
    let hi = pts
        .iter()
        .fold(glam::DVec3::splat(f64::MIN), |a, b| a.max(*b));
    let mut x = 12345u64;
    let mut rnd = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let n = 20000;
    let q: Vec<glam::DVec3> = (0..n)
        .map(|_| lo + (hi - lo) * glam::DVec3::new(rnd(), rnd(), rnd()))
        .collect();
    let t = Instant::now();
    let mut s = 0.0;
    for p in &q {
        s += case.sizing.spacing(*p);
    }
    let dt = t.elapsed().as_secs_f64();
    println!(
        "{n} queries in the box: {:.2} µs each (sum {s:.3})",
        dt / n as f64 * 1e6
    );
    // On the edges, where curve meshing asks (and samples crowd).
    let mut on_edges = Vec::new();
    for e in &case.model.edges {
        if let Some(c) = &e.curve {
            for i in 0..=32 {
                on_edges.push(c.point(e.range.0 + (e.range.1 - e.range.0) * i as f64 / 32.0));
            }
        }
    }
    let t = Instant::now();
    let mut s = 0.0;
    for p in &on_edges {
        s += case.sizing.spacing(*p);
    }
    let dt = t.elapsed().as_secs_f64();
    println!(
        "{} queries on the edges: {:.2} µs each (sum {s:.3})",
        on_edges.len(),
        dt / on_edges.len() as f64 * 1e6
    );
}
