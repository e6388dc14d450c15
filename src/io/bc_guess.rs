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
    /// Cells on both sides of every face: inside the domain.
    Interior,
}

/// The kind of every marker group, [`guess`] with two-sided groups found [`BoundaryKind::Interior`].
pub(crate) fn guess_all(m: &VolumeMesh, g: &Groups) -> Vec<BoundaryKind> {
    let two_sided = crate::mesh::validity::two_sided_boundary_faces(m);
    let mut all_two_sided = vec![true; g.names.len()];
    for ((_, marker), both) in m.boundary_faces().zip(two_sided) {
        all_two_sided[g.of[marker as usize]] &= both;
    }
    (0..g.names.len())
        .map(|k| {
            if all_two_sided[k] {
                BoundaryKind::Interior
            } else {
                guess(m, g, k)
            }
        })
        .collect()
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
