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

/// A cell's nodes as the writers take them: the reader's `Vec<usize>`, or a view of a volume
/// mesh's cell.
pub trait CellNodes: Sync {
    fn node_count(&self) -> usize;
    fn nodes(&self) -> impl Iterator<Item = usize> + '_;
}

impl CellNodes for Vec<usize> {
    fn node_count(&self) -> usize {
        self.len()
    }

    fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.iter().copied()
    }
}

/// A cell's nodes in VTK's order (a view of the mesh's cell; no copy: a mesh has millions).
pub(crate) fn vtk_order(kind: CellKind, c: &[u32]) -> VtkCell<'_> {
    VtkCell { kind, nodes: c }
}

/// A volume cell seen in VTK's node order.
#[derive(Clone, Copy, Debug)]
pub(crate) struct VtkCell<'a> {
    kind: CellKind,
    nodes: &'a [u32],
}

impl CellNodes for VtkCell<'_> {
    fn node_count(&self) -> usize {
        self.nodes.len()
    }

    fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        const PRISM: [usize; 6] = [0, 2, 1, 3, 5, 4];
        let prism = self.kind == CellKind::Prism;
        (0..self.nodes.len()).map(move |i| self.nodes[if prism { PRISM[i] } else { i }] as usize)
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
