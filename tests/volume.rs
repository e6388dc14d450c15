//! Volume meshing on native models: valid (exact orientation, conforming, volume equal to the
//! enclosed volume), the right regions, cavities left empty, edge lengths following δ.

mod common;

use tetrafoil::case::parse_case;
use tetrafoil::curve::mesh_curves;
use tetrafoil::mesh::VolumeMesh;
use tetrafoil::surface::{mesh_surfaces, SurfaceOptions};
use tetrafoil::volume::{mesh_volume, VolumeOptions, VolumeReport};

fn mesh(text: &str, name: &str) -> (VolumeMesh, VolumeReport) {
    let case = parse_case(text, name).unwrap();
    let curves = mesh_curves(&case.model, &case.sizing).unwrap();
    let (surface, _) = mesh_surfaces(
        &case.model,
        &curves,
        &case.sizing,
        SurfaceOptions::default(),
    )
    .unwrap();
    mesh_volume(
        &case.model,
        &surface,
        &case.sizing,
        VolumeOptions::default(),
    )
    .unwrap()
}

fn mean_edge(m: &VolumeMesh) -> f64 {
    let mut sum = 0.0;
    let mut n = 0;
    for t in &m.tets {
        for i in 0..4 {
            for j in i + 1..4 {
                sum += m.points[t[i] as usize].distance(m.points[t[j] as usize]);
                n += 1;
            }
        }
    }
    sum / n as f64
}

#[test]
fn unit_cube_is_valid_and_fills_its_volume() {
    let (m, r) = mesh(&common::unit_cube(0.2), "cube.toml");
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    assert!(
        (r.validity.volume - 1.0).abs() < 1e-12,
        "{}",
        r.validity.volume
    );
    assert!(r.interior.points > 20, "{:?}", r.interior);
    let e = mean_edge(&m);
    assert!((0.15..0.26).contains(&e), "mean edge {e}");
    assert_eq!(m.markers.len(), 6);
    assert!(m.tet_region.iter().all(|&r| r == 0));
    eprintln!("{r:#?}");
}

#[test]
fn cavity_is_left_empty() {
    let (m, r) = mesh(&common::box_with_cavity(0.5), "cavity.toml");
    assert!(r.validity.is_valid(), "{:?}", r.validity.defects);
    // box [0,4]^3 minus [1,2]^3 (see tests/common)
    eprintln!("volume {} markers {}", r.validity.volume, m.markers.len());
    assert!(
        (r.validity.volume - 63.0).abs() < 1e-9,
        "{}",
        r.validity.volume
    );
}
