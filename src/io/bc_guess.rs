//! The kind of boundary a marker group most likely is, guessed from its name and shape, for the
//! formats that carry a boundary-condition type (UGRID's `.mapbc`, CGNS's `BC_t`): a far field
//! for names with `farfield`, `inflow`, `outflow`, `inlet` or `outlet`; a symmetry plane for a
//! group whose name has `sym` and whose faces lie in one plane normal to an axis; a wall
//! otherwise. A solver's own setup may differ: the files are there to edit.

use super::names::Groups;
use crate::mesh::VolumeMesh;

/// A boundary-condition kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BoundaryKind {
    FarField,
    /// A symmetry plane normal to axis 0 (x), 1 (y) or 2 (z).
    Symmetry(usize),
    Wall,
}

/// The kind of marker group `k` (see the module's doc).
pub(crate) fn guess(m: &VolumeMesh, g: &Groups, k: usize) -> BoundaryKind {
    let name = g.names[k].to_ascii_lowercase();
    let far = ["farfield", "inflow", "outflow", "inlet", "outlet"];
    if far.iter().any(|f| name.contains(f)) {
        return BoundaryKind::FarField;
    }
    if name.contains("sym") {
        if let Some(axis) = plane_axis(m, g, k) {
            return BoundaryKind::Symmetry(axis);
        }
    }
    BoundaryKind::Wall
}

/// The axis whose coordinate every node of group `k`'s faces shares, if any.
fn plane_axis(m: &VolumeMesh, g: &Groups, k: usize) -> Option<usize> {
    let mut nodes = m
        .boundary_faces()
        .filter(|&(_, marker)| g.of[marker as usize] == k)
        .flat_map(|(f, _)| f.iter().map(|&v| m.points[v as usize].to_array()));
    let first = nodes.next()?;
    let mut same = [true; 3];
    for p in nodes {
        for a in 0..3 {
            same[a] &= p[a] == first[a];
        }
    }
    same.iter().position(|&s| s)
}
