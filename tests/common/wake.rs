//! The smallest mesh with a wake: two tets on either side of one triangle (marker "wake",
//! cells on both sides), the six outer triangles marker "outside".

use glam::DVec3;
use tetrafoil::mesh::{Marker, VolumeMesh};

pub fn two_tets_across_a_wake() -> VolumeMesh {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let marker = |id: usize, name: &str| Marker {
        id,
        name: name.into(),
    };
    VolumeMesh {
        points: vec![
            p(0., 0., 0.),
            p(1., 0., 0.),
            p(0., 1., 0.),
            p(0., 0., 1.),
            p(0., 0., -1.),
        ],
        tets: vec![[0, 1, 2, 3], [0, 2, 1, 4]],
        tet_region: vec![0, 0],
        boundary: vec![
            [1, 2, 3],
            [0, 3, 2],
            [0, 1, 3],
            [2, 1, 4],
            [0, 4, 1],
            [0, 2, 4],
            [0, 1, 2],
        ],
        boundary_marker: vec![0, 0, 0, 0, 0, 0, 1],
        markers: vec![marker(0, "outside"), marker(1, "wake")],
        regions: vec![marker(0, "fluid")],
        ..Default::default()
    }
}
