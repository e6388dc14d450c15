mod common;

use common::{assert_close, central};
use glam::DVec3;
use tetrafoil_native::FergusonCurve;

fn wiggly_points() -> Vec<DVec3> {
    vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.5, 0.1),
        DVec3::new(1.7, 1.9, -0.3),
        DVec3::new(3.2, 2.1, 0.4),
        DVec3::new(3.9, 0.8, 1.2),
        DVec3::new(5.5, 1.0, 1.0),
    ]
}

#[test]
fn interpolates_every_point_at_chord_params() {
    let pts = wiggly_points();
    let c = FergusonCurve::interpolate(&pts).unwrap();
    assert_eq!(c.points(), &pts[..]);
    assert_eq!(c.params().len(), pts.len());
    assert_eq!(c.params()[0], 0.0);
    let mut chord = 0.0;
    for (k, (&t, &p)) in c.params().iter().zip(&pts).enumerate() {
        if k > 0 {
            chord += pts[k - 1].distance(p);
        }
        assert!((t - chord).abs() <= 1e-12 * chord.max(1.0), "param {k}");
        assert_close(c.point(t), p, 1e-12, "node");
    }
    assert_eq!(c.range(), (0.0, chord));
}

#[test]
fn two_points_give_unit_speed_straight_line() {
    let a = DVec3::new(1.0, 2.0, 3.0);
    let b = DVec3::new(4.0, -2.0, 3.0); // distance 5
    let c = FergusonCurve::interpolate(&[a, b]).unwrap();
    assert_eq!(c.range(), (0.0, 5.0));
    for k in 0..=10 {
        let t = 0.5 * k as f64;
        let (p, d1, d2) = c.derivs(t);
        assert_close(p, a + (b - a) * (t / 5.0), 1e-12, "point");
        assert!((d1.length() - 1.0).abs() < 1e-12, "|C'| = {}", d1.length());
        assert!(d2.length() < 1e-12, "C'' = {d2}");
    }
}

#[test]
fn collinear_points_give_unit_speed_straight_line() {
    let dir = DVec3::new(1.0, 2.0, -2.0) / 3.0;
    let o = DVec3::new(-1.0, 0.5, 2.0);
    let dist = [0.0, 0.3, 1.7, 2.0, 4.5];
    let pts: Vec<DVec3> = dist.iter().map(|&s| o + dir * s).collect();
    let c = FergusonCurve::interpolate(&pts).unwrap();
    for k in 0..=45 {
        let t = 0.1 * k as f64;
        let (p, d1, d2) = c.derivs(t);
        assert_close(p, o + dir * t, 1e-12, "point");
        assert_close(d1, dir, 1e-12, "C'");
        assert!(d2.length() < 1e-10, "C'' = {d2}");
    }
}

#[test]
fn circle_is_reproduced_between_nodes() {
    let r = 2.0;
    let n = 16;
    let pts: Vec<DVec3> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            DVec3::new(r * a.cos(), r * a.sin(), 0.0)
        })
        .collect();
    let c = FergusonCurve::interpolate(&pts).unwrap();
    let (t0, t1) = c.range();
    let mut worst = 0.0f64;
    for k in 0..=1000 {
        let t = t0 + (t1 - t0) * k as f64 / 1000.0;
        let p = c.point(t);
        assert!(p.z.abs() < 1e-12);
        worst = worst.max((p.length() - r).abs() / r);
    }
    assert!(worst < 1e-3, "relative radius error {worst}");
}

#[test]
fn derivatives_match_finite_differences_in_every_segment() {
    let c = FergusonCurve::interpolate(&wiggly_points()).unwrap();
    let params = c.params().to_vec();
    for w in params.windows(2) {
        for frac in [0.13, 0.5, 0.87] {
            let t = w[0] + frac * (w[1] - w[0]);
            let (_, d1, d2) = c.derivs(t);
            assert_close(d1, central(|x| c.point(x), t, 1e-5), 1e-6, "C'");
            assert_close(d2, central(|x| c.derivs(x).1, t, 1e-5), 1e-6, "C''");
        }
    }
    // Extrapolation keeps using the end cubics, derivatives included.
    for t in [-0.7, params[params.len() - 1] + 0.9] {
        let (_, d1, d2) = c.derivs(t);
        assert_close(
            d1,
            central(|x| c.point(x), t, 1e-5),
            1e-6,
            "C' extrapolated",
        );
        assert_close(
            d2,
            central(|x| c.derivs(x).1, t, 1e-5),
            1e-6,
            "C'' extrapolated",
        );
    }
}

#[test]
fn c1_at_interior_nodes() {
    let c = FergusonCurve::interpolate(&wiggly_points()).unwrap();
    for (k, &t) in c.params().iter().enumerate().skip(1) {
        if k + 1 == c.params().len() {
            break;
        }
        let left = c.derivs(t - 1e-9);
        let right = c.derivs(t);
        assert_close(left.0, right.0, 1e-8, "C0");
        assert_close(left.1, right.1, 1e-7, "C1");
        assert_close(right.1, c.tangents()[k], 1e-12, "node tangent");
    }
}

#[test]
fn given_tangents_are_reproduced() {
    let pts = [
        DVec3::ZERO,
        DVec3::new(2.0, 1.0, 0.0),
        DVec3::new(3.0, 3.0, 1.0),
    ];
    let tans = [
        DVec3::new(0.0, 2.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -3.0),
    ];
    let c = FergusonCurve::with_tangents(&pts, &tans).unwrap();
    assert_eq!(c.tangents(), &tans[..]);
    for (k, &t) in c.params().iter().enumerate() {
        let (p, d1, _) = c.derivs(t);
        assert_close(p, pts[k], 1e-12, "point");
        assert_close(d1, tans[k], 1e-12, "tangent");
    }
    // Left limit at the interior node also sees the given tangent.
    let (_, d1, _) = c.derivs(c.params()[1] - 1e-9);
    assert_close(d1, tans[1], 1e-7, "left tangent");
}

#[test]
fn estimated_tangents_exact_for_parabola_in_chord_param() {
    // Three points: interpolation uses the parabola through them, so the
    // curve must stay on it (a planar quadratic in the chord parameter).
    let pts = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(3.0, 1.0, 0.0),
    ];
    let c = FergusonCurve::interpolate(&pts).unwrap();
    for &t in c.params() {
        let (_, _, d2) = c.derivs(t);
        // Single parabola: second derivative constant along the curve.
        assert_close(d2, c.derivs(0.0).2, 1e-12, "constant C''");
    }
}
