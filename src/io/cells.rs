//! Cells in the node order and type numbers of VTK (and SU2, which uses VTK's): the mesh's own
//! order is Gmsh's and CGNS's, where a prism's bottom triangle turns counter-clockwise seen
//! from its top; VTK's wedge turns the other way.

use crate::mesh::CellKind;

/// VTK cell type of a volume cell.
pub(crate) fn vtk_type(kind: CellKind) -> u8 {
    match kind {
        CellKind::Tet => 10,
        CellKind::Pyramid => 14,
        CellKind::Prism => 13,
    }
}

/// A cell's nodes in VTK's order.
pub(crate) fn vtk_order(kind: CellKind, c: &[u32]) -> Vec<usize> {
    match kind {
        CellKind::Prism => [0, 2, 1, 3, 5, 4].map(|i| c[i] as usize).to_vec(),
        _ => c.iter().map(|&v| v as usize).collect(),
    }
}

/// The tets of a cell's first split (itself for a tet): what the per-cell quality fields
/// measure for prisms and pyramids. No allocation: this runs once per cell of a large mesh.
pub(crate) fn split_tets(kind: CellKind, c: &[u32]) -> impl Iterator<Item = [u32; 4]> {
    let (tets, n) = match kind {
        CellKind::Tet => ([[c[0], c[1], c[2], c[3]]; 3], 1),
        CellKind::Pyramid => {
            let a = [c[0], c[1], c[2], c[4]];
            ([a, [c[0], c[2], c[3], c[4]], a], 2)
        }
        CellKind::Prism => (
            [
                [c[0], c[1], c[2], c[3]],
                [c[1], c[2], c[3], c[4]],
                [c[2], c[3], c[4], c[5]],
            ],
            3,
        ),
    };
    tets.into_iter().take(n)
}
