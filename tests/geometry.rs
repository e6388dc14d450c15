//! The geometry interface's generic Newton methods on native surfaces and curves.

use glam::{DVec2, DVec3};
use tetrafoil::geometry::{Circle, CircleHint, Curve, Surface};
use tetrafoil_native::{FergusonCurve, FergusonSurface};

/// A wavy 7×5 grid surface of size ~2 × 1.
fn wavy() -> FergusonSurface {
    let grid: Vec<Vec<DVec3>> = (0..7)
        .map(|i| {
            (0..5)
                .map(|j| {
                    let (x, y) = (i as f64 / 3.0, j as f64 / 4.0);
                    DVec3::new(x, y, 0.15 * (2.0 * x).sin() * (3.0 * y).cos())
                })
                .collect()
        })
        .collect();
    FergusonSurface::interpolate(&grid).unwrap()
}

#[test]
fn projection_recovers_uv_everywhere_even_with_a_bad_hint() {
    let s = wavy();
    let b = Surface::bounds(&s);
    let e = b.extent();
    let mut worst: f64 = 0.0;
    // Interior points, points within 1e-3 of the borders, and the corners.
    let fractions = [0.0, 1e-3, 0.1, 0.37, 0.5, 0.81, 0.999, 1.0];
    for &fu in &fractions {
        for &fv in &fractions {
            let uv = DVec2::new(b.u.0 + fu * e.x, b.v.0 + fv * e.y);
            let p = Surface::point(&s, uv);
            let good = s.closest_uv(p, Some(uv + 0.01 * e)).unwrap();
            // The worst hint: the opposite corner of the parameter rectangle.
            let bad_hint = DVec2::new(b.u.0 + (1.0 - fu) * e.x, b.v.0 + (1.0 - fv) * e.y);
            let bad = s.closest_uv(p, Some(bad_hint)).unwrap();
            let none = s.closest_uv(p, None).unwrap();
            for got in [good, bad, none] {
                worst = worst.max((got - uv).abs().max_element());
            }
        }
    }
    assert!(worst < 1e-9, "worst (u,v) error {worst:e}");
}

#[test]
fn projection_of_an_off_surface_point_is_the_foot_of_the_normal() {
    let s = wavy();
    let uv = DVec2::new(0.8, 0.4);
    let p0 = Surface::point(&s, uv);
    let p = p0 + 0.05 * s.normal(uv);
    let got = s.closest_uv(p, None).unwrap();
    assert!((got - uv).length() < 1e-8, "got {got:?}, want {uv:?}");
}

#[test]
fn circle_intersections_lie_on_circle_and_surface() {
    let s = wavy();
    let size = 2.0_f64.hypot(1.0);
    let mut hits = 0;
    for (a_uv, b_uv) in [
        (DVec2::new(0.5, 0.3), DVec2::new(0.7, 0.3)),
        (DVec2::new(1.2, 0.6), DVec2::new(1.25, 0.75)),
        (DVec2::new(0.05, 0.05), DVec2::new(0.15, 0.02)),
    ] {
        let (a, b) = (Surface::point(&s, a_uv), Surface::point(&s, b_uv));
        let mid_uv = 0.5 * (a_uv + b_uv);
        // The inner side of front segment a→b: the surface normal crossed with the segment.
        let n = s.normal(mid_uv);
        let toward = n.cross(b - a);
        let delta = 1.1 * a.distance(b);
        let circle = Circle::equidistant(a, b, delta, toward).unwrap();
        let hint = CircleHint {
            uv: mid_uv,
            theta: 0.0,
            max_dtheta: 1.2,
        };
        let hit = s.intersect_circle(&circle, &hint).expect("an intersection");
        let on_surface = Surface::point(&s, hit.uv).distance(hit.point);
        let on_circle = circle.point(hit.theta).distance(hit.point);
        assert!(on_surface < 1e-9 * size && on_circle < 1e-9 * size);
        assert!((hit.point.distance(a) - delta).abs() < 1e-9 * size);
        assert!((hit.point.distance(b) - delta).abs() < 1e-9 * size);
        // On the inner side, not behind the segment.
        assert!((hit.point - 0.5 * (a + b)).dot(toward) > 0.0);
        hits += 1;
    }
    assert_eq!(hits, 3);
}

#[test]
fn circle_that_misses_the_surface_gives_none() {
    let s = wavy();
    // A small circle far above the surface.
    let c = Circle::new(DVec3::new(1.0, 0.5, 3.0), DVec3::Z, 0.1, DVec3::X).unwrap();
    let hint = CircleHint {
        uv: DVec2::new(1.0, 0.5),
        theta: 0.0,
        max_dtheta: 3.0,
    };
    assert!(s.intersect_circle(&c, &hint).is_none());
}

#[test]
fn curve_projection_with_and_without_hint() {
    let pts: Vec<DVec3> = (0..12)
        .map(|k| {
            let a = k as f64 * 0.5;
            DVec3::new(a.cos(), a.sin(), 0.1 * a)
        })
        .collect();
    let c = FergusonCurve::interpolate(&pts).unwrap();
    let (t0, t1) = Curve::range(&c);
    for k in 0..=20 {
        let t = t0 + (t1 - t0) * k as f64 / 20.0;
        let p = Curve::point(&c, t);
        for hint in [None, Some(t0), Some(t1), Some(t)] {
            let got = c.closest_parameter(p, hint).unwrap();
            assert!((got - t).abs() < 1e-9, "t {t} hint {hint:?} got {got}");
        }
    }
}
