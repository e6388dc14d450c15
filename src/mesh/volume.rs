//! The finished volume mesh as the writers see it: tets with a region each, and boundary
//! triangles with a marker each (one marker per model face).

use glam::DVec3;

/// A named group of boundary triangles (one per model face) or of tets (one per region).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Marker {
    /// Model entity id (face id for boundary markers, region id for regions).
    pub id: usize,
    /// The entity's name, or `face_<id>` / `region_<id>`.
    pub name: String,
}

/// A tetrahedral mesh with boundary triangles and markers.
///
/// * Every tet is positively oriented (`orient3d > 0`, `mesh::quality::volume_sign`).
/// * Boundary triangles are faces of the tets; a triangle of a region's outer boundary has its
///   normal (right-hand rule) pointing out of the domain. Triangles of embedded faces (wakes,
///   baffles) and of interfaces between regions are listed once.
/// * `boundary_marker[k]` indexes `markers`; `tet_region[k]` indexes `regions`.
#[derive(Clone, Debug, Default)]
pub struct VolumeMesh {
    pub points: Vec<DVec3>,
    pub tets: Vec<[u32; 4]>,
    pub tet_region: Vec<u32>,
    pub boundary: Vec<[u32; 3]>,
    pub boundary_marker: Vec<u32>,
    pub markers: Vec<Marker>,
    pub regions: Vec<Marker>,
}

impl VolumeMesh {
    /// Corner points of tet `k`.
    pub fn tet_points(&self, k: usize) -> [DVec3; 4] {
        self.tets[k].map(|v| self.points[v as usize])
    }

    /// Corner points of boundary triangle `k`.
    pub fn triangle_points(&self, k: usize) -> [DVec3; 3] {
        self.boundary[k].map(|v| self.points[v as usize])
    }
}
