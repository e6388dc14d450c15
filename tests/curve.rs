//! Curve meshing: node counts follow ∫ds/δ and shared edges carry one set of nodes.

mod common;

use glam::DVec3;
use tetrafoil::case::parse_case;
use tetrafoil::curve::{mesh_curves, SpacingIntegral};
use tetrafoil::geometry::Curve;
use tetrafoil::sizing::{SizingField, Source, SourceShape};
use tetrafoil_native::FergusonCurve;

#[test]
fn node_count_matches_the_spacing_integral_within_one() {
    let pts: Vec<DVec3> = (0..9)
        .map(|k| {
            let a = k as f64 * 0.4;
            DVec3::new(3.0 * a.cos(), 3.0 * a.sin(), a)
        })
        .collect();
    let curve = FergusonCurve::interpolate(&pts).unwrap();
    let mut field = SizingField::uniform(0.5);
    field.sources.push(Source {
        shape: SourceShape::Point(pts[4]),
        delta1: 0.02,
        r1: 0.1,
        r2: 0.5,
    });
    let range = Curve::range(&curve);
    let integral = SpacingIntegral::new(&curve, range, |p| field.spacing(p));
    // Independent check of the integral: a fine midpoint sum.
    let n = 200_000;
    let h = (range.1 - range.0) / n as f64;
    let brute: f64 = (0..n)
        .map(|i| {
            let t = range.0 + (i as f64 + 0.5) * h;
            Curve::derivs(&curve, t).d1.length() / field.spacing(Curve::point(&curve, t)) * h
        })
        .sum();
    assert!(
        (integral.total() - brute).abs() < 1e-4 * brute,
        "{} vs {brute}",
        integral.total()
    );
    let segments = (integral.total().round() as usize).max(1);
    let params = integral.equal_increments(segments);
    assert!((params.len() as f64 - 1.0 - integral.total()).abs() <= 1.0);
    // Equal increments: each segment holds 1/n of the integral (checked by brute force).
    for w in params.windows(2) {
        let m = 2000;
        let hh = (w[1] - w[0]) / m as f64;
        let part: f64 = (0..m)
            .map(|i| {
                let t = w[0] + (i as f64 + 0.5) * hh;
                Curve::derivs(&curve, t).d1.length() / field.spacing(Curve::point(&curve, t)) * hh
            })
            .sum();
        assert!(
            (part - integral.total() / segments as f64).abs() < 1e-3,
            "segment holds {part}"
        );
    }
}

#[test]
fn edges_of_the_cube_get_length_over_size_segments() {
    let case = parse_case(&common::unit_cube(0.2), "cube").unwrap();
    let mesh = mesh_curves(&case.model, &case.sizing).unwrap();
    for (e, m) in mesh.edges.iter().enumerate() {
        assert_eq!(m.nodes.len(), 6, "edge {e}");
        assert!((m.integral - 5.0).abs() < 1e-9);
        // End nodes are the edge's vertices.
        assert_eq!(m.nodes[0], case.model.edges[e].start);
        assert_eq!(*m.nodes.last().unwrap(), case.model.edges[e].end);
        for w in m.nodes.windows(2) {
            let len = mesh.points[w[0]].distance(mesh.points[w[1]]);
            assert!((len - 0.2).abs() < 1e-9);
        }
    }
    assert_eq!(mesh.points.len(), 8 + 12 * 4);
}

#[test]
fn faces_sharing_an_edge_see_the_same_nodes() {
    let case = parse_case(&common::box_with_cavity(0.35), "cavity").unwrap();
    let model = &case.model;
    let mesh = mesh_curves(model, &case.sizing).unwrap();
    // For each face, the nodes of its loops, located through its own surface and pcurves.
    let mut seen: std::collections::HashMap<usize, (usize, DVec3)> = Default::default();
    let mut shared = 0;
    for (f, face) in model.faces.iter().enumerate() {
        for u in face.loops.iter().flat_map(|l| &l.uses) {
            let em = &mesh.edges[u.edge];
            for (&node, &t) in em.nodes.iter().zip(&em.params) {
                let uv = model.use_uv(f, u, t).unwrap();
                let p = face.surface.point(uv);
                assert!(
                    p.distance(mesh.points[node]) < 1e-9,
                    "face {f} edge {}",
                    u.edge
                );
                if let Some(&(other, q)) = seen.get(&node) {
                    if other != f {
                        shared += 1;
                        assert!(p.distance(q) < 1e-9);
                    }
                } else {
                    seen.insert(node, (f, p));
                }
            }
        }
    }
    assert!(shared > 0);
}
