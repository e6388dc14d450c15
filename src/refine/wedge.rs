//! The open wedge of the domain at the nodes of a curve source: the direction a node's column
//! takes when the line to a tet's centre runs too close to a wall.
//!
//! A curve that runs along a concave corner of the domain (a box's edge, a wing/body junction)
//! has the domain on one side only, within an angle of about 90°. The tets touching the curve
//! there mostly lie against one of the two walls, so a point on the line from the curve to the
//! tet's centre, a layer out, sits within half a layer of that wall and is refused; without
//! these roots no column starts, and the tets between the walls' packed face points and the
//! isotropic interior stay slivers. The wedge's bisector, the mean inward normal of the walls
//! around the node (each triangle weighted by its angle there), is as far from both walls as a
//! line can be.

use crate::volume::delaunay::{Delaunay, INF};
use crate::volume::OUTSIDE;
use glam::DVec3;
use std::collections::HashMap;

/// The bisector (unit, across the curve) of the domain's wedge at each node in `roots` (a
/// kernel vertex on a curve source, with the curve's tangent there) that has boundary faces
/// around it.
pub fn curve_wedges(
    dt: &mut Delaunay,
    region_of: &[u32],
    roots: &[(u32, DVec3)],
) -> HashMap<u32, DVec3> {
    let mut out = HashMap::new();
    for &(v, along) in roots {
        let mut sum = DVec3::ZERO;
        for t in dt.tets_around_vertex(v) {
            if dt.is_ghost(t) || region_of.get(t as usize) == Some(&OUTSIDE) {
                continue;
            }
            sum += inward_walls_at(dt, t, v);
        }
        let across = sum - along * sum.dot(along);
        if let Some(b) = across.try_normalize() {
            out.insert(v, b);
        }
    }
    out
}

/// The inward normals of tet `t`'s boundary faces that have vertex `v`, each weighted by the
/// face's angle at `v` (radians).
fn inward_walls_at(dt: &Delaunay, t: u32, v: u32) -> DVec3 {
    let point = |i: u32| DVec3::from_array(dt.point(i));
    let mut sum = DVec3::ZERO;
    for f in 0..4u8 {
        let face = dt.face_vertices(t, f);
        if !dt.is_constrained(t, f) || !face.contains(&v) || face.contains(&INF) {
            continue;
        }
        // The kernel orders a face counter-clockwise seen from outside the tet: its
        // right-hand normal points out, so the inward normal is its opposite (no sign test).
        let [p0, p1, p2] = face.map(point);
        let Some(inward) = (p2 - p0).cross(p1 - p0).try_normalize() else {
            continue;
        };
        let k = face.iter().position(|&w| w == v).unwrap_or(0);
        let at = [p0, p1, p2][k];
        let (a, b) = (
            [p0, p1, p2][(k + 1) % 3] - at,
            [p0, p1, p2][(k + 2) % 3] - at,
        );
        sum += inward * a.angle_between(b);
    }
    sum
}
