//! Surface, curve and pcurve evaluation against finite differences, projection round trips,
//! circle intersections.
mod common;

use common::{dist, norm, sub};
use tetrafoil_occt::{CadModel, OccSurface};

const FILES: &[&str] = &[
    "sliced_cylinder_rhino.step",     // planes, cylinders
    "hemisphere_cylinder_domain.stp", // spheres, cylinder, planes
    "gmsh_t20_component8.step",       // B-splines
    "torus_single_face.stp",          // doubly periodic
    "occt_screw.step",                // cones, tori
];

/// Interior sample parameters of a face: an n × n grid inside its UV bounds.
fn samples(s: &OccSurface, n: usize) -> Vec<[f64; 2]> {
    let ([u0, u1], [v0, v1]) = (s.u_range(), s.v_range());
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            // Off-centre fractions keep samples off the knots of symmetric B-splines, where
            // second derivatives jump and central differences are meaningless.
            let a = (i as f64 + 0.37) / n as f64;
            let b = (j as f64 + 0.61) / n as f64;
            out.push([u0 + a * (u1 - u0), v0 + b * (v1 - v0)]);
        }
    }
    out
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    dist(a, b) <= tol
}

fn scaled(a: [f64; 3], b: [f64; 3], h: f64) -> [f64; 3] {
    let d = sub(a, b);
    [d[0] / (2.0 * h), d[1] / (2.0 * h), d[2] / (2.0 * h)]
}

#[test]
fn surface_derivatives_match_finite_differences() {
    let Some(dir) = common::cad_dir() else { return };
    let mut kinds = std::collections::BTreeSet::new();
    for file in FILES {
        let m = common::load(&dir, file);
        for (f, face) in m.topology().faces.iter().enumerate() {
            kinds.insert(face.surface_kind.clone());
            let s = m.surface(f).unwrap();
            let hu = 1e-6 * (s.u_range()[1] - s.u_range()[0]);
            let hv = 1e-6 * (s.v_range()[1] - s.v_range()[0]);
            for [u, v] in samples(&s, 3) {
                let d = s.derivs(u, v).unwrap();
                let (pu, mu) = (s.derivs(u + hu, v).unwrap(), s.derivs(u - hu, v).unwrap());
                let (pv, mv) = (s.derivs(u, v + hv).unwrap(), s.derivs(u, v - hv).unwrap());
                let first = norm(d.du) + norm(d.dv);
                let second = norm(d.duu) + norm(d.duv) + norm(d.dvv) + first;
                let ctx = format!("{file} face {f} ({}) at ({u}, {v})", face.surface_kind);
                assert!(
                    close(scaled(pu.p, mu.p, hu), d.du, 1e-6 * first),
                    "du: {ctx}"
                );
                assert!(
                    close(scaled(pv.p, mv.p, hv), d.dv, 1e-6 * first),
                    "dv: {ctx}"
                );
                assert!(
                    close(scaled(pu.du, mu.du, hu), d.duu, 1e-5 * second),
                    "duu: {ctx}"
                );
                assert!(
                    close(scaled(pv.du, mv.du, hv), d.duv, 1e-5 * second),
                    "duv: {ctx}"
                );
                assert!(
                    close(scaled(pv.dv, mv.dv, hv), d.dvv, 1e-5 * second),
                    "dvv: {ctx}"
                );
            }
        }
    }
    for k in ["plane", "cylinder", "sphere", "bspline", "torus", "cone"] {
        assert!(kinds.contains(k), "no {k} face tested: {kinds:?}");
    }
}

/// Parameters equal modulo the surface's periods.
fn same_uv(s: &OccSurface, a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
    let per = [s.u_period(), s.v_period()];
    (0..2).all(|k| {
        let mut d = a[k] - b[k];
        if let Some(p) = per[k] {
            d -= p * (d / p).round();
        }
        d.abs() <= tol
    })
}

#[test]
fn projection_returns_the_evaluated_parameters() {
    let Some(dir) = common::cad_dir() else { return };
    for file in FILES {
        let m = common::load(&dir, file);
        let size = common::model_size(&m);
        for f in 0..m.topology().faces.len() {
            let s = m.surface(f).unwrap();
            let span = (s.u_range()[1] - s.u_range()[0]).max(s.v_range()[1] - s.v_range()[0]);
            for uv in samples(&s, 4) {
                let p = s.point(uv[0], uv[1]).unwrap();
                let ctx = format!("{file} face {f} at {uv:?}");
                let got = s.project(p, None).unwrap();
                assert!(
                    close(s.point(got[0], got[1]).unwrap(), p, 1e-7 * size),
                    "{ctx}"
                );
                assert!(same_uv(&s, got, uv, 1e-6 * span), "{ctx}: got {got:?}");
                let hint = [uv[0] + 0.01 * span, uv[1] - 0.01 * span];
                let got = s.project(p, Some(hint)).unwrap();
                assert!(
                    same_uv(&s, got, uv, 1e-6 * span),
                    "{ctx} (hint): got {got:?}"
                );
            }
        }
    }
}

#[test]
fn projection_across_the_seam_of_periodic_faces() {
    let Some(dir) = common::cad_dir() else { return };
    for file in [
        "sphere_revolved.step",
        "torus_single_face.stp",
        "sliced_cylinder_rhino.step",
    ] {
        let m = common::load(&dir, file);
        for f in 0..m.topology().faces.len() {
            let s = m.surface(f).unwrap();
            let Some(period) = s.u_period() else { continue };
            let v = 0.5 * (s.v_range()[0] + s.v_range()[1]);
            // Points just either side of u = 0 (the seam), hinted from the other side.
            for (u, hint_u) in [(1e-3, period - 1e-3), (period - 1e-3, 1e-3)] {
                let p = s.point(u, v).unwrap();
                let got = s.project(p, Some([hint_u, v])).unwrap();
                assert!(
                    same_uv(&s, got, [u, v], 1e-8),
                    "{file} face {f}: {got:?} vs {u}"
                );
                let q = s.point(got[0], got[1]).unwrap();
                assert!(
                    dist(p, q) < 1e-7 * common::model_size(&m),
                    "{file} face {f}"
                );
            }
        }
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[test]
fn circle_intersections_lie_on_circle_and_surface() {
    let Some(dir) = common::cad_dir() else { return };
    let mut hits_total = 0;
    for file in FILES {
        let m = common::load(&dir, file);
        let size = common::model_size(&m);
        let tol = 1e-7 * size;
        for f in 0..m.topology().faces.len() {
            let s = m.surface(f).unwrap();
            for [u, v] in samples(&s, 2) {
                let d = s.derivs(u, v).unwrap();
                if norm(d.du) < 1e-9 || norm(d.dv) < 1e-9 {
                    continue;
                }
                // A circle about the point, in the plane of the normal and dv: it crosses the
                // surface near p ± r·dv.
                let axis = unit(d.du);
                let x_axis = unit(cross(axis, cross(d.dv, axis)));
                let local = (norm(d.du) * (s.u_range()[1] - s.u_range()[0]))
                    .min(norm(d.dv) * (s.v_range()[1] - s.v_range()[0]));
                let radius = (0.05 * local).min(0.01 * size);
                let hits = s.intersect_circle(d.p, axis, x_axis, radius).unwrap();
                let ctx = format!("{file} face {f} at ({u}, {v})");
                assert!(!hits.is_empty(), "{ctx}: no intersection");
                let y_axis = cross(axis, x_axis);
                for h in &hits {
                    let r = sub(h.point, d.p);
                    assert!((norm(r) - radius).abs() < tol, "{ctx}: off the circle");
                    assert!(dot(r, axis).abs() < tol, "{ctx}: off the circle's plane");
                    let on_circle = [0, 1, 2].map(|k| {
                        d.p[k] + radius * (h.theta.cos() * x_axis[k] + h.theta.sin() * y_axis[k])
                    });
                    assert!(dist(on_circle, h.point) < tol, "{ctx}: theta {}", h.theta);
                    let on_surface = s.point(h.uv[0], h.uv[1]).unwrap();
                    assert!(dist(on_surface, h.point) < tol, "{ctx}: off the surface");
                }
                hits_total += hits.len();
            }
        }
    }
    assert!(hits_total > 100, "{hits_total}");
}

#[test]
fn curves_and_pcurves_agree_with_surfaces() {
    let Some(dir) = common::cad_dir() else { return };
    for file in [
        "sphere_revolved.step",
        "hemisphere_cylinder_domain.stp",
        "gmsh_t20_component8.step",
    ] {
        let m = common::load(&dir, file);
        let size = common::model_size(&m);
        let t = m.topology();
        for (f, face) in t.faces.iter().enumerate() {
            let s = m.surface(f).unwrap();
            for (l, lp) in face.loops.iter().enumerate() {
                let seams: Vec<usize> = (0..lp.len()).filter(|&i| lp[i].seam).collect();
                if !seams.is_empty() {
                    // A seam occurs twice; its two pcurves are a period apart in u or v.
                    assert_eq!(seams.len() % 2, 0, "{file} face {f}");
                    let a = m.pcurve(f, l, seams[0]).unwrap();
                    let b = m.pcurve(f, l, seams[1]).unwrap();
                    let mid = 0.5 * (a.range()[0] + a.range()[1]);
                    let (pa, pb) = (a.point(mid).unwrap(), b.point(mid).unwrap());
                    let per = s.u_period().or(s.v_period()).unwrap();
                    let du = (pa[0] - pb[0]).abs();
                    let dv = (pa[1] - pb[1]).abs();
                    assert!(
                        (du - per).abs() < 1e-9 || (dv - per).abs() < 1e-9,
                        "{pa:?} {pb:?}"
                    );
                }
                for (k, eu) in lp.iter().enumerate() {
                    let edge = &t.edges[eu.edge];
                    let pc = m.pcurve(f, l, k).unwrap();
                    let curve = m.curve(eu.edge).unwrap();
                    assert_eq!(curve.is_none(), edge.degenerate, "{file} edge {}", eu.edge);
                    for i in 0..=4 {
                        let tt =
                            edge.t_range[0] + i as f64 / 4.0 * (edge.t_range[1] - edge.t_range[0]);
                        let uv = pc.point(tt).unwrap();
                        let on_surface = s.point(uv[0], uv[1]).unwrap();
                        let expected = match &curve {
                            Some(c) => c.point(tt).unwrap(),
                            None => t.vertices[edge.v0].point,
                        };
                        // Files understate tolerances: gmsh_t20's pcurves stray 5e-5 (1e-7 of
                        // the model) from edges declared at 1e-7.
                        let tol = (10.0 * edge.tolerance.max(face.tolerance)).max(1e-6 * size);
                        let gap = dist(on_surface, expected);
                        assert!(
                            gap < tol,
                            "{file} face {f} edge {}: {gap} at t = {tt}",
                            eu.edge
                        );
                        if let Some(c) = &curve {
                            let (back, gap) = c.project(expected, Some(tt)).unwrap();
                            assert!(
                                gap < 1e-7 && (back - tt).abs() < 1e-6,
                                "{file} edge {}",
                                eu.edge
                            );
                            let (back, _) = c.project(expected, None).unwrap();
                            let same = dist(c.point(back).unwrap(), expected) < 1e-7;
                            assert!(same, "{file} edge {}", eu.edge);
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn curve_derivatives_match_finite_differences() {
    let Some(dir) = common::cad_dir() else { return };
    let m: CadModel = common::load(&dir, "gmsh_t20_component8.step");
    for e in 0..m.topology().edges.len() {
        let Some(c) = m.curve(e).unwrap() else {
            continue;
        };
        let [a, b] = c.range();
        let h = 1e-6 * (b - a);
        for frac in [0.13, 0.41, 0.77] {
            let t = a + frac * (b - a);
            let d = c.derivs(t).unwrap();
            let (p, q) = (c.derivs(t + h).unwrap(), c.derivs(t - h).unwrap());
            let scale = norm(d.d1) + norm(d.d2);
            assert!(dist(scaled(p.p, q.p, h), d.d1) < 1e-6 * scale, "edge {e}");
            assert!(dist(scaled(p.d1, q.d1, h), d.d2) < 1e-5 * scale, "edge {e}");
        }
    }
}
