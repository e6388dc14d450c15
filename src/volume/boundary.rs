//! The volume mesher's input: the surface mesh's triangles with the model face of each and the
//! embedded edges' segments with their model edge, on a compact point list (only nodes some
//! triangle or segment uses), and which region lies on each side of every face.

use crate::model::{EdgeId, FaceId, Model};
use crate::surface::SurfaceMesh;
use glam::DVec3;

/// No region on that side (outside the domain, or inside a cavity).
pub const OUTSIDE: u32 = u32::MAX;

/// Boundary triangles on compact points.
#[derive(Clone, Debug, Default)]
pub struct BoundaryInput {
    pub points: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    pub face_of: Vec<FaceId>,
    /// Embedded edges' segments, and the model edge of each.
    pub segments: Vec<[u32; 2]>,
    pub segment_edge: Vec<EdgeId>,
}

/// Collect the triangles of every face and the embedded segments, and renumber their nodes
/// compactly.
pub fn gather(surface: &SurfaceMesh) -> BoundaryInput {
    let mut compact = vec![u32::MAX; surface.points.len()];
    let mut out = BoundaryInput::default();
    // The compact id of surface node `n`, numbering it on first use.
    let mut id = |n: usize, points: &mut Vec<_>| {
        if compact[n] == u32::MAX {
            compact[n] = points.len() as u32;
            points.push(surface.points[n]);
        }
        compact[n]
    };
    for (t, &f) in surface.triangles.iter().zip(&surface.face_of) {
        let tri = t.map(|n| id(n, &mut out.points));
        out.triangles.push(tri);
        out.face_of.push(f);
    }
    for (s, &e) in surface.segments.iter().zip(&surface.segment_edge) {
        let seg = s.map(|n| id(n, &mut out.points));
        out.segments.push(seg);
        out.segment_edge.push(e);
    }
    out
}

/// Region on the front (`[0]`, where the triangle normal `Su × Sv` points) and back (`[1]`)
/// side of each face; [`OUTSIDE`] where no region is. A shell face whose use is not reversed
/// has its region behind it; an embedded face has its region on both sides.
pub fn face_sides(model: &Model) -> Vec<[u32; 2]> {
    let mut sides = vec![[OUTSIDE; 2]; model.faces.len()];
    for (r, region) in model.regions.iter().enumerate() {
        for shell in &region.shells {
            for fu in &shell.faces {
                let side = if fu.reversed { 0 } else { 1 };
                sides[fu.face][side] = r as u32;
            }
        }
        for &f in &region.embedded_faces {
            sides[f] = [r as u32; 2];
        }
    }
    sides
}
