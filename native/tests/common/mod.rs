//! Helpers shared by the integration tests.
#![allow(dead_code)]

use glam::DVec3;

/// Asserts `|a - b| <= tol * max(|a|, |b|, 1)`.
#[track_caller]
pub fn assert_close(a: DVec3, b: DVec3, tol: f64, what: &str) {
    let scale = a.length().max(b.length()).max(1.0);
    assert!(
        (a - b).length() <= tol * scale,
        "{what}: {a} vs {b} (diff {:e}, tol {:e})",
        (a - b).length(),
        tol * scale
    );
}

/// Central difference of `f` at `x` with step `h`.
pub fn central(f: impl Fn(f64) -> DVec3, x: f64, h: f64) -> DVec3 {
    (f(x + h) - f(x - h)) / (2.0 * h)
}
