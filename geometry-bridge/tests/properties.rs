//! Areas and volumes against closed-form values.
mod common;

use std::f64::consts::PI;

#[test]
fn hemisphere_cylinder_domain_volume_and_areas() {
    let Some(dir) = common::cad_dir() else { return };
    let m = common::load(&dir, "hemisphere_cylinder_domain.stp");
    // The file holds a quarter of the sphere of radius R = 100 (the half sphere, halved again
    // by the symmetry plane y = 0) minus half of the body: a hemispherical nose of radius r =
    // 0.5 on a cylinder, total length L = 10.
    let (big_r, r, l) = (100.0_f64, 0.5_f64, 10.0_f64);
    let body = 2.0 / 3.0 * PI * r.powi(3) + PI * r * r * (l - r);
    let expected = PI * big_r.powi(3) / 3.0 - body / 2.0;
    let v = m.solid_volume(0).unwrap();
    assert!(
        ((v - expected) / expected).abs() < 1e-3,
        "volume {v} vs {expected}"
    );
    assert!(
        ((v - expected) / expected).abs() < 1e-8,
        "volume {v} vs {expected}"
    );
    let areas: Vec<f64> = (0..5).map(|f| m.face_area(f).unwrap()).collect();
    // Outer quarter sphere, nose quarter sphere, half cylinder, two planes.
    let outer = PI * big_r * big_r;
    let nose = PI * r * r;
    let cyl = PI * r * (l - r);
    let outflow = PI * big_r * big_r / 2.0 - PI * r * r / 2.0;
    let symmetry = PI * big_r * big_r / 2.0 - (2.0 * r * (l - r) + PI * r * r / 2.0);
    let total: f64 = areas.iter().sum();
    let expected_total = outer + nose + cyl + outflow + symmetry;
    assert!(
        ((total - expected_total) / expected_total).abs() < 1e-6,
        "{total} vs {expected_total}"
    );
    for want in [outer, nose, cyl, outflow, symmetry] {
        assert!(
            areas.iter().any(|a| ((a - want) / want).abs() < 1e-6),
            "no face of area {want} in {areas:?}"
        );
    }
}

#[test]
fn tetrahedron_volume_matches_vertex_determinant() {
    let Some(dir) = common::cad_dir() else { return };
    let m = common::load(&dir, "tet_rhino.step");
    let p: Vec<[f64; 3]> = m.topology().vertices.iter().map(|v| v.point).collect();
    assert_eq!(p.len(), 4);
    let (a, b, c) = (
        common::sub(p[1], p[0]),
        common::sub(p[2], p[0]),
        common::sub(p[3], p[0]),
    );
    let det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0]);
    let expected = det.abs() / 6.0;
    let v = m.solid_volume(0).unwrap();
    assert!(
        ((v - expected) / expected).abs() < 1e-9,
        "{v} vs {expected}"
    );
}

#[test]
fn sphere_volume_and_bounding_box() {
    let Some(dir) = common::cad_dir() else { return };
    let m = common::load(&dir, "sphere_revolved.step");
    let v = m.solid_volume(0).unwrap();
    let expected = 4.0 / 3.0 * PI * 125.0;
    assert!(
        ((v - expected) / expected).abs() < 1e-9,
        "{v} vs {expected}"
    );
    let bb = m.bounding_box().unwrap().unwrap();
    let (lo, hi) = (bb.min, bb.max);
    for k in 0..3 {
        assert!(
            (lo[k] + 5.0).abs() < 1e-5 && (hi[k] - 5.0).abs() < 1e-5,
            "{lo:?} {hi:?}"
        );
    }
}
