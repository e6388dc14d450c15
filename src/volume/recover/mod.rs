//! Boundary recovery (placeholder until the flip-based recovery lands): marks the surface
//! triangles that are already faces of the tetrahedralisation and fails on the first that
//! is not.

use super::delaunay::Delaunay;
use glam::DVec3;
use std::collections::HashMap;

#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct RecoveryReport {
    pub flips: usize,
    pub steiner_interior: usize,
    pub steiner_on_edges: usize,
    pub steiner_on_faces: usize,
    pub steiner_removed: usize,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("triangle {triangle} is not a face of the tetrahedralisation")]
pub struct RecoveryError {
    pub triangle: u32,
    pub at: [f64; 3],
}

impl RecoveryError {
    pub fn triangle(&self) -> u32 {
        self.triangle
    }
    pub fn location(&self) -> DVec3 {
        DVec3::from_array(self.at)
    }
}

pub fn recover_boundary(
    dt: &mut Delaunay,
    triangles: &mut Vec<[u32; 3]>,
    _parent: &mut Vec<u32>,
) -> Result<RecoveryReport, RecoveryError> {
    let mut faces: HashMap<[u32; 3], (u32, u8)> = HashMap::new();
    for t in dt.tet_ids().collect::<Vec<_>>() {
        for f in 0..4u8 {
            let mut k = dt.face_vertices(t, f);
            k.sort_unstable();
            faces.insert(k, (t, f));
        }
    }
    for (i, tri) in triangles.iter().enumerate() {
        let mut k = *tri;
        k.sort_unstable();
        match faces.get(&k) {
            Some(&(t, f)) => dt.set_constrained(t, f, true).expect("live face"),
            None => {
                return Err(RecoveryError {
                    triangle: i as u32,
                    at: dt.point(tri[0]),
                })
            }
        }
    }
    Ok(RecoveryReport::default())
}
