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
        "{n} queries: {:.2} µs each (sum {s:.3})",
        dt / n as f64 * 1e6
    );
}
