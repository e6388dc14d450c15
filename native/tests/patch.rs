mod common;

use common::{assert_close, central};
use glam::DVec3;
use tetrafoil_native::FergusonPatch;

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn general_patch() -> (FergusonPatch, [[[DVec3; 2]; 2]; 4]) {
    let p = [
        [v(0.0, 0.0, 0.0), v(0.1, 1.0, 0.3)],
        [v(1.2, -0.1, 0.2), v(1.0, 1.1, -0.4)],
    ];
    let pu = [
        [v(1.5, 0.2, 0.9), v(0.7, -0.3, 0.0)],
        [v(0.8, 0.4, -1.1), v(1.3, 0.1, 0.5)],
    ];
    let pv = [
        [v(0.2, 0.9, -0.6), v(-0.1, 1.4, 0.2)],
        [v(0.3, 1.2, 0.7), v(-0.4, 0.8, 0.1)],
    ];
    let puv = [
        [v(0.5, -0.2, 0.3), v(-0.6, 0.1, 0.4)],
        [v(0.2, 0.7, -0.5), v(0.9, -0.3, 0.2)],
    ];
    (FergusonPatch::new(p, pu, pv, puv), [p, pu, pv, puv])
}

#[test]
fn reproduces_corner_data() {
    let (patch, [p, pu, pv, puv]) = general_patch();
    for i in 0..2 {
        for j in 0..2 {
            let d = patch.derivs(i as f64, j as f64);
            assert_close(d.p, p[i][j], 1e-12, "corner point");
            assert_close(d.du, pu[i][j], 1e-12, "corner u-tangent");
            assert_close(d.dv, pv[i][j], 1e-12, "corner v-tangent");
            assert_close(d.duv, puv[i][j], 1e-12, "corner twist");
            assert_eq!(patch.point(i as f64, j as f64), d.p);
        }
    }
}

#[test]
fn derivatives_match_finite_differences() {
    let (patch, _) = general_patch();
    let h = 1e-5;
    for (u, v) in [(0.3, 0.6), (0.81, 0.17), (0.5, 0.5), (-0.2, 1.3)] {
        let d = patch.derivs(u, v);
        assert_eq!(d.p, patch.point(u, v));
        assert_close(d.du, central(|x| patch.point(x, v), u, h), 1e-6, "du");
        assert_close(d.dv, central(|y| patch.point(u, y), v, h), 1e-6, "dv");
        assert_close(d.duu, central(|x| patch.derivs(x, v).du, u, h), 1e-6, "duu");
        assert_close(d.duv, central(|y| patch.derivs(u, y).du, v, h), 1e-6, "duv");
        assert_close(d.duv, central(|x| patch.derivs(x, v).dv, u, h), 1e-6, "dvu");
        assert_close(d.dvv, central(|y| patch.derivs(u, y).dv, v, h), 1e-6, "dvv");
    }
}

#[test]
fn bilinear_patch_on_plane_is_flat_and_bilinear() {
    // A non-parallelogram quad in the plane z = 2x - y + 1.
    let plane = |x: f64, y: f64| v(x, y, 2.0 * x - y + 1.0);
    let p = [
        [plane(0.0, 0.0), plane(0.2, 1.5)],
        [plane(2.0, -0.3), plane(2.5, 2.0)],
    ];
    let patch = FergusonPatch::bilinear(p);
    let normal = v(2.0, -1.0, -1.0);
    for k in 0..=8 {
        for l in 0..=8 {
            let (u, w) = (k as f64 / 8.0, l as f64 / 8.0);
            let d = patch.derivs(u, w);
            let expect = p[0][0] * ((1.0 - u) * (1.0 - w))
                + p[1][0] * (u * (1.0 - w))
                + p[0][1] * ((1.0 - u) * w)
                + p[1][1] * (u * w);
            assert_close(d.p, expect, 1e-12, "bilinear point");
            assert!((d.p.dot(normal) + 1.0).abs() < 1e-12, "off plane");
            assert!(d.duu.length() < 1e-12, "duu = {}", d.duu);
            assert!(d.dvv.length() < 1e-12, "dvv = {}", d.dvv);
            assert_close(d.duv, p[1][1] - p[1][0] - p[0][1] + p[0][0], 1e-12, "twist");
            assert!(d.du.dot(normal).abs() < 1e-12 && d.dv.dot(normal).abs() < 1e-12);
        }
    }
}

#[test]
fn bilinear_parallelogram_has_zero_twist() {
    let o = v(1.0, 2.0, 3.0);
    let (a, b) = (v(2.0, 0.0, 1.0), v(-0.5, 1.0, 0.0));
    let patch = FergusonPatch::bilinear([[o, o + b], [o + a, o + a + b]]);
    let d = patch.derivs(0.37, 0.71);
    assert_close(d.p, o + a * 0.37 + b * 0.71, 1e-12, "point");
    assert_close(d.du, a, 1e-12, "du");
    assert_close(d.dv, b, 1e-12, "dv");
    assert!(d.duv.length() < 1e-12);
}
