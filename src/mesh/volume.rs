//! The finished volume mesh as the writers see it: cells (tets, and after grouping prisms and
//! pyramids) with a region each, and boundary faces (triangles, and quads where a prism's or a
//! pyramid's side is on the boundary) with a marker each (one marker per model face).

use glam::DVec3;

/// A named group of boundary triangles (one per model face) or of tets (one per region).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Marker {
    /// Model entity id (face id for boundary markers, region id for regions).
    pub id: usize,
    /// The entity's name, or `face_<id>` / `region_<id>`.
    pub name: String,
}

/// Where a point sits in the stretched layers of a refinement stage: the column it belongs to
/// (named by its root, the node it grows from, as the Delaunay kernel numbered it — the
/// surface mesh's order — and the side of a two-sided source it grows into) and its level (0
/// at the root). Three columns at two consecutive levels span a triangular prism.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LayerTag {
    pub stage: u16,
    pub source: u16,
    pub root: u32,
    pub below: bool,
    pub level: u32,
}

/// A tetrahedral (or, after `prisms::group`, hybrid) mesh with boundary faces and markers.
///
/// * Every tet is positively oriented (`orient3d > 0`, `mesh::quality::volume_sign`).
/// * A prism `[a, b, c, a', b', c']` stacks triangle `(a', b', c')` on `(a, b, c)` (edges
///   a–a', b–b', c–c'); `(a, b, c)` turns counter-clockwise seen from the top (Gmsh's and
///   CGNS's order; VTK's and SU2's turn the other way, their writers reorder). A pyramid
///   `[a, b, c, d, e]` has base quad `(a, b, c, d)` turning counter-clockwise seen from apex
///   `e`. Every tet of every split of a prism or a pyramid is positive.
/// * Boundary quads face out of the domain like boundary triangles.
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
    pub prisms: Vec<[u32; 6]>,
    pub prism_region: Vec<u32>,
    pub pyramids: Vec<[u32; 5]>,
    pub pyramid_region: Vec<u32>,
    pub boundary_quads: Vec<[u32; 4]>,
    pub quad_marker: Vec<u32>,
    /// Per point, its place in the stretched layers (empty for a mesh without refinement).
    pub point_layer: Vec<Option<LayerTag>>,
}

/// The kinds of cell a mesh holds, in the order the writers list them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellKind {
    Tet,
    Pyramid,
    Prism,
}

impl VolumeMesh {
    /// Corner points of tet `k`.
    pub fn tet_points(&self, k: usize) -> [DVec3; 4] {
        self.tets[k].map(|v| self.points[v as usize])
    }

    /// Every cell: tets, then pyramids, then prisms, with its kind, nodes and region.
    pub fn cells(&self) -> impl Iterator<Item = (CellKind, &[u32], u32)> {
        let tets =
            (self.tets.iter().zip(&self.tet_region)).map(|(c, &r)| (CellKind::Tet, &c[..], r));
        let pyramids = (self.pyramids.iter().zip(&self.pyramid_region))
            .map(|(c, &r)| (CellKind::Pyramid, &c[..], r));
        let prisms = (self.prisms.iter().zip(&self.prism_region))
            .map(|(c, &r)| (CellKind::Prism, &c[..], r));
        tets.chain(pyramids).chain(prisms)
    }

    /// Number of cells of every kind.
    pub fn cell_count(&self) -> usize {
        self.tets.len() + self.pyramids.len() + self.prisms.len()
    }

    /// Whether the mesh holds cells other than tets.
    pub fn is_hybrid(&self) -> bool {
        !self.prisms.is_empty() || !self.pyramids.is_empty()
    }

    /// Every boundary face: triangles, then quads, with its nodes and marker.
    pub fn boundary_faces(&self) -> impl Iterator<Item = (&[u32], u32)> {
        let tris = (self.boundary.iter().zip(&self.boundary_marker)).map(|(f, &m)| (&f[..], m));
        let quads = (self.boundary_quads.iter().zip(&self.quad_marker)).map(|(f, &m)| (&f[..], m));
        tris.chain(quads)
    }

    /// Number of boundary faces of both kinds.
    pub fn boundary_face_count(&self) -> usize {
        self.boundary.len() + self.boundary_quads.len()
    }

    /// Corner points of boundary triangle `k`.
    pub fn triangle_points(&self, k: usize) -> [DVec3; 3] {
        self.boundary[k].map(|v| self.points[v as usize])
    }

    /// Each kind of cell (with its region) ordered by its lowest node, ties kept in their
    /// order. The meshers leave cells in insertion order, scattered over the nodes; in this
    /// order cells that share nodes sit together, so a solver's sweep over the cells walks
    /// the nodes' memory in order, and compressed formats find the repeats (binary VTU's
    /// connectivity deflates to about 30% less).
    pub fn order_cells(&mut self) {
        by_lowest_node(&mut self.tets, &mut self.tet_region);
        by_lowest_node(&mut self.pyramids, &mut self.pyramid_region);
        by_lowest_node(&mut self.prisms, &mut self.prism_region);
    }
}

fn by_lowest_node<const N: usize>(cells: &mut Vec<[u32; N]>, regions: &mut Vec<u32>) {
    use rayon::prelude::*;
    let mut both: Vec<([u32; N], u32)> =
        cells.iter().copied().zip(regions.iter().copied()).collect();
    both.par_sort_by_key(|(c, _)| c.iter().copied().min());
    (*cells, *regions) = both.into_iter().unzip();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_ordered_by_their_lowest_node_with_their_regions() {
        let mut m = VolumeMesh {
            tets: vec![[9, 4, 7, 8], [3, 5, 6, 2], [6, 4, 5, 9], [1, 8, 7, 6]],
            tet_region: vec![0, 1, 2, 3],
            prisms: vec![[5, 6, 7, 8, 9, 10], [0, 1, 2, 3, 4, 5]],
            prism_region: vec![7, 8],
            ..Default::default()
        };
        m.order_cells();
        // Lowest nodes 4, 2, 4, 1: the two tets at 4 keep their order.
        assert_eq!(
            m.tets,
            [[1, 8, 7, 6], [3, 5, 6, 2], [9, 4, 7, 8], [6, 4, 5, 9]]
        );
        assert_eq!(m.tet_region, [3, 1, 0, 2]);
        assert_eq!(m.prisms[0], [0, 1, 2, 3, 4, 5]);
        assert_eq!(m.prism_region, [8, 7]);
    }
}
