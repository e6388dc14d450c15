mod common;

use common::{assert_close, central};
use glam::DVec3;
use tetrafoil_native::FergusonSurface;

/// A doubly curved, unevenly sampled grid: z = f(x, y) over a sheared lattice.
fn curved_grid() -> Vec<Vec<DVec3>> {
    let xs = [0.0, 0.4, 1.1, 1.5, 2.3];
    let ys = [0.0, 0.6, 0.9, 1.8];
    xs.iter()
        .map(|&x| {
            ys.iter()
                .map(|&y| DVec3::new(x + 0.2 * y, y, 0.3 * (x * 1.3).sin() * (y + 0.5).cos()))
                .collect()
        })
        .collect()
}

#[test]
fn passes_through_grid_points() {
    let grid = curved_grid();
    let s = FergusonSurface::interpolate(&grid).unwrap();
    assert_eq!(s.grid(), &grid[..]);
    assert_eq!(s.u_params().len(), 5);
    assert_eq!(s.v_params().len(), 4);
    let ((u0, u1), (v0, v1)) = s.bounds();
    assert_eq!((u0, v0), (0.0, 0.0));
    assert_eq!(u1, s.u_params()[4]);
    assert_eq!(v1, s.v_params()[3]);
    for (i, &u) in s.u_params().iter().enumerate() {
        for (j, &v) in s.v_params().iter().enumerate() {
            assert_close(s.point(u, v), grid[i][j], 1e-12, "grid point");
        }
    }
}

#[test]
fn params_are_averaged_chord_lengths() {
    let grid = curved_grid();
    let s = FergusonSurface::interpolate(&grid).unwrap();
    for i in 0..grid.len() - 1 {
        let avg: f64 = (0..4)
            .map(|j| grid[i][j].distance(grid[i + 1][j]))
            .sum::<f64>()
            / 4.0;
        let h = s.u_params()[i + 1] - s.u_params()[i];
        assert!((h - avg).abs() < 1e-12, "u interval {i}: {h} vs {avg}");
    }
    for j in 0..3 {
        let avg: f64 = (0..5)
            .map(|i| grid[i][j].distance(grid[i][j + 1]))
            .sum::<f64>()
            / 5.0;
        let h = s.v_params()[j + 1] - s.v_params()[j];
        assert!((h - avg).abs() < 1e-12, "v interval {j}: {h} vs {avg}");
    }
}

#[test]
fn uniform_affine_grid_reproduces_the_plane_exactly() {
    // grid[i][j] = o + a i + b j  =>  u_i = i |a|, v_j = j |b| and the surface
    // must be o + a u/|a| + b v/|b| everywhere (checks the tangent scaling).
    let o = DVec3::new(1.0, -2.0, 0.5);
    let a = DVec3::new(0.3, 0.1, 0.2);
    let b = DVec3::new(-0.1, 0.5, 0.05);
    let grid: Vec<Vec<DVec3>> = (0..4)
        .map(|i| (0..3).map(|j| o + a * i as f64 + b * j as f64).collect())
        .collect();
    let s = FergusonSurface::interpolate(&grid).unwrap();
    let (ea, eb) = (a / a.length(), b / b.length());
    for k in 0..=12 {
        for l in 0..=8 {
            let (u, v) = (k as f64 * 0.25 * a.length(), l as f64 * 0.25 * b.length());
            let d = s.derivs(u, v);
            assert_close(d.p, o + ea * u + eb * v, 1e-12, "point");
            assert_close(d.du, ea, 1e-12, "du");
            assert_close(d.dv, eb, 1e-12, "dv");
            assert!(d.duu.length() < 1e-10 && d.duv.length() < 1e-10 && d.dvv.length() < 1e-10);
        }
    }
}

#[test]
fn cylinder_is_reproduced_between_grid_lines() {
    let r = 1.5;
    let grid: Vec<Vec<DVec3>> = (0..16)
        .map(|i| {
            let a = std::f64::consts::PI * i as f64 / 15.0;
            (0..5)
                .map(|j| DVec3::new(r * a.cos(), r * a.sin(), 0.7 * j as f64))
                .collect()
        })
        .collect();
    let s = FergusonSurface::interpolate(&grid).unwrap();
    let ((u0, u1), (v0, v1)) = s.bounds();
    let mut worst = 0.0f64;
    for k in 0..=200 {
        for l in 0..=20 {
            let u = u0 + (u1 - u0) * k as f64 / 200.0;
            let v = v0 + (v1 - v0) * l as f64 / 20.0;
            let p = s.point(u, v);
            worst = worst.max((p.truncate().length() - r).abs() / r);
            assert!((p.z - v * 0.7 / ((v1 - v0) / 4.0)).abs() < 1e-12, "z drift");
        }
    }
    assert!(worst < 1e-3, "relative radius error {worst}");
}

#[test]
fn derivatives_match_finite_differences_in_several_patches() {
    let s = FergusonSurface::interpolate(&curved_grid()).unwrap();
    let (up, vp) = (s.u_params().to_vec(), s.v_params().to_vec());
    let h = 1e-5;
    for (i, fu) in [(0, 0.3), (1, 0.6), (3, 0.45)] {
        for (j, fv) in [(0, 0.7), (1, 0.2), (2, 0.55)] {
            let u = up[i] + fu * (up[i + 1] - up[i]);
            let v = vp[j] + fv * (vp[j + 1] - vp[j]);
            let d = s.derivs(u, v);
            assert_eq!(d.p, s.point(u, v));
            assert_close(d.du, central(|x| s.point(x, v), u, h), 1e-6, "du");
            assert_close(d.dv, central(|y| s.point(u, y), v, h), 1e-6, "dv");
            assert_close(d.duu, central(|x| s.derivs(x, v).du, u, h), 1e-6, "duu");
            assert_close(d.duv, central(|y| s.derivs(u, y).du, v, h), 1e-6, "duv");
            assert_close(d.duv, central(|x| s.derivs(x, v).dv, u, h), 1e-6, "dvu");
            assert_close(d.dvv, central(|y| s.derivs(u, y).dv, v, h), 1e-6, "dvv");
        }
    }
    // Extrapolation beyond the bounds uses the border patch consistently.
    let ((_, u1), (v0, _)) = s.bounds();
    let (u, v) = (u1 + 0.3, v0 - 0.2);
    let d = s.derivs(u, v);
    assert_close(d.du, central(|x| s.point(x, v), u, h), 1e-6, "du outside");
    assert_close(
        d.dvv,
        central(|y| s.derivs(u, y).dv, v, h),
        1e-6,
        "dvv outside",
    );
}

#[test]
fn c1_across_patch_borders() {
    let s = FergusonSurface::interpolate(&curved_grid()).unwrap();
    let (up, vp) = (s.u_params().to_vec(), s.v_params().to_vec());
    let eps = 1e-9;
    // Across interior u = u_i borders, at v values inside patches and on nodes.
    for &u in &up[1..up.len() - 1] {
        for v in [0.1, 0.75, vp[1], 1.3] {
            let (l, r) = (s.derivs(u - eps, v), s.derivs(u + eps, v));
            assert_close(l.p, r.p, 1e-8, "C0 across u");
            assert_close(l.du, r.du, 1e-7, "du across u");
            assert_close(l.dv, r.dv, 1e-7, "dv across u");
            assert_close(l.dvv, r.dvv, 1e-7, "dvv across u");
        }
    }
    // Across interior v = v_j borders.
    for &v in &vp[1..vp.len() - 1] {
        for u in [0.2, 0.9, up[2], 2.0] {
            let (l, r) = (s.derivs(u, v - eps), s.derivs(u, v + eps));
            assert_close(l.p, r.p, 1e-8, "C0 across v");
            assert_close(l.du, r.du, 1e-7, "du across v");
            assert_close(l.dv, r.dv, 1e-7, "dv across v");
            assert_close(l.duu, r.duu, 1e-7, "duu across v");
        }
    }
}

#[test]
fn grid_lines_match_ferguson_curves_with_same_params() {
    // With a grid whose u-chords are equal on every line, the averaged params
    // equal each line's own chord params, so the u-lines must coincide with
    // FergusonCurve interpolants of the same points.
    let grid: Vec<Vec<DVec3>> = (0..5)
        .map(|i| {
            let a = 0.4 * i as f64;
            (0..3)
                .map(|j| DVec3::new(a.cos(), a.sin(), 0.0) * 2.0 + DVec3::Z * j as f64)
                .collect()
        })
        .collect();
    let s = FergusonSurface::interpolate(&grid).unwrap();
    for j in 0..3 {
        let line: Vec<DVec3> = grid.iter().map(|row| row[j]).collect();
        let c = tetrafoil_native::FergusonCurve::interpolate(&line).unwrap();
        // Sample off the nodes: C'' jumps there, and the two parameter vectors
        // may differ in the last bit, selecting different sides.
        for k in 0..20 {
            let t = c.range().1 * (k as f64 + 0.5) / 20.0;
            let d = s.derivs(t, s.v_params()[j]);
            let (p, d1, d2) = c.derivs(t);
            assert_close(d.p, p, 1e-12, "line point");
            assert_close(d.du, d1, 1e-12, "line tangent");
            assert_close(d.duu, d2, 1e-10, "line curvature");
        }
    }
}

/// With given parameters the network interpolates at them, and reproduces a surface that is
/// quadratic in each parameter on an uneven grid (the tangent estimate is exact there).
#[test]
fn interpolate_with_params_keeps_the_given_parameterisation() {
    let f = |u: f64, v: f64| DVec3::new(u, v, 0.3 * u * u - 0.2 * u * v + 0.1 * v * v);
    let us = [-1.0, -0.2, 0.5, 2.0];
    let vs = [0.0, 0.3, 1.0];
    let grid: Vec<Vec<DVec3>> = us
        .iter()
        .map(|&u| vs.iter().map(|&v| f(u, v)).collect())
        .collect();
    let s = FergusonSurface::interpolate_with_params(&grid, &us, &vs).unwrap();
    assert_eq!(s.bounds(), ((-1.0, 2.0), (0.0, 1.0)));
    for (u, v) in [(-1.0, 0.0), (0.1, 0.7), (1.3, 0.45), (2.0, 1.0)] {
        assert!(s.point(u, v).distance(f(u, v)) < 1e-12, "at ({u}, {v})");
    }
    assert_eq!(
        FergusonSurface::interpolate_with_params(&grid, &[0.0, 1.0, 1.0, 2.0], &vs),
        Err(tetrafoil_native::NativeError::BadParams {
            axis: 'u',
            index: 1
        })
    );
    assert!(FergusonSurface::interpolate_with_params(&grid, &us, &vs[..2]).is_err());
}
