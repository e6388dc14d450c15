//! Flat tets lying on a boundary plane: four corners on one planar stretch of a model face,
//! two of the tet's faces being that face's triangles (a quad cut by one diagonal) and the
//! other two facing the domain (the same quad cut by the other diagonal). Such a tet has no
//! volume and a 180° dihedral angle, and no swap removes it: its two boundary faces are
//! constrained. It appears where points put on a plane (the refinement's face points on a
//! far-field wall) leave four coplanar points on the hull. Peeling it gives it to the outside
//! and takes its other two faces as the face's triangles: the boundary keeps its points, its
//! face and its plane, and the flat tet is gone.

use super::boundary::OUTSIDE;
use super::delaunay::Delaunay;
use crate::geometry::orient2d;
use crate::model::FaceId;
use glam::{DVec2, DVec3};
use std::collections::HashMap;

/// The fourth corner must lie this close to the plane of the others, in the tet's longest
/// edge, for the tet to count as lying on the face: evaluation noise on a plane, far below the
/// sag of any curved face at the mesh's own spacing.
const ON_PLANE: f64 = 1e-9;

/// Peel every domain tet lying flat on a boundary face (see the module doc); `triangles` are
/// the recovered boundary triangles, with `face_of` their model faces: the two a peel replaces
/// keep their indices and their face. Returns how many were peeled.
pub fn peel_flat_boundary_tets(
    dt: &mut Delaunay,
    region_of: &mut [u32],
    triangles: &mut [[u32; 3]],
    face_of: impl Fn(u32) -> FaceId,
) -> usize {
    let mut index: HashMap<[u32; 3], u32> = super::classify::triangle_index(triangles);
    // Peeling a tet puts its other two faces on the boundary, so a flat tet behind one of
    // them (a fan of flat tets round one edge on the plane, one boundary face each) may lie
    // on two boundary faces now: it is looked at again.
    let mut candidates: Vec<u32> = dt
        .tet_ids()
        .filter(|&t| !dt.is_ghost(t) && region_of[t as usize] != OUTSIDE)
        .collect();
    candidates.reverse();
    let mut peeled = 0;
    while let Some(t) = candidates.pop() {
        if !dt.is_live(t) || dt.is_ghost(t) || region_of[t as usize] == OUTSIDE {
            continue;
        }
        let Some(peel) = flat_on_boundary(dt, region_of, &index, &face_of, t) else {
            continue;
        };
        region_of[t as usize] = OUTSIDE;
        for f in 0..4u8 {
            // Only faces of a live tet are passed; the flags cannot fail here.
            let _ = dt.set_constrained(t, f, !peel.old_faces.contains(&f));
            if !peel.old_faces.contains(&f) {
                candidates.push(dt.neighbor(t, f).0);
            }
        }
        for (k, new) in peel.triangles.into_iter().zip(peel.new) {
            let mut old = triangles[k as usize];
            old.sort_unstable();
            index.remove(&old);
            triangles[k as usize] = new;
            let mut key = new;
            key.sort_unstable();
            index.insert(key, k);
        }
        peeled += 1;
    }
    peeled
}

/// What peeling tet `t` changes.
struct Peel {
    /// The tet's two faces on the boundary now.
    old_faces: [u8; 2],
    /// Their triangles' indices, and the triangles that replace them (the other two faces).
    triangles: [u32; 2],
    new: [[u32; 3]; 2],
}

/// `Some` when `t` lies flat on one boundary face: exactly two constrained faces, each with
/// the outside beyond it and a triangle of the same model face, the four corners on one plane,
/// and the quad convex (both diagonals inside it, by exact orientation in the plane), so the
/// other two faces cover the same piece of surface.
fn flat_on_boundary(
    dt: &Delaunay,
    region_of: &[u32],
    index: &HashMap<[u32; 3], u32>,
    face_of: &impl Fn(u32) -> FaceId,
    t: u32,
) -> Option<Peel> {
    let constrained: Vec<u8> = (0..4u8).filter(|&f| dt.is_constrained(t, f)).collect();
    let [f1, f2] = constrained[..] else {
        return None;
    };
    let mut tri = [0u32; 2];
    for (slot, f) in [f1, f2].into_iter().enumerate() {
        let (u, _) = dt.neighbor(t, f);
        if !(dt.is_ghost(u) || region_of[u as usize] == OUTSIDE) {
            return None;
        }
        let mut key = dt.face_vertices(t, f);
        key.sort_unstable();
        tri[slot] = *index.get(&key)?;
    }
    if face_of(tri[0]) != face_of(tri[1]) {
        return None;
    }
    let v = dt.tet(t);
    let p = v.map(|i| DVec3::from_array(dt.point(i)));
    // Face f is opposite vertex f: the shared edge is the other two, o1 and o2 the opposite
    // corners of the two boundary faces.
    let (o1, o2) = (f1 as usize, f2 as usize);
    let [e0, e1] = {
        let mut e = (0..4).filter(|&k| k != o1 && k != o2);
        [e.next()?, e.next()?]
    };
    let normal = (p[e1] - p[e0]).cross(p[o1] - p[e0]);
    let longest = (0..4)
        .flat_map(|a| (a + 1..4).map(move |b| (a, b)))
        .map(|(a, b)| p[a].distance(p[b]))
        .fold(0.0, f64::max);
    let height = (p[o2] - p[e0]).dot(normal.normalize_or_zero()).abs();
    if normal == DVec3::ZERO || height > ON_PLANE * longest {
        return None;
    }
    // Convex quad: o1, o2 on opposite sides of e0–e1 and e0, e1 on opposite sides of o1–o2,
    // in the coordinate plane the face's normal is most nearly along.
    let a = normal.abs();
    let flat = |x: DVec3| {
        if a.x >= a.y && a.x >= a.z {
            DVec2::new(x.y, x.z)
        } else if a.y >= a.z {
            DVec2::new(x.z, x.x)
        } else {
            DVec2::new(x.x, x.y)
        }
    };
    let q = p.map(flat);
    let across = |a: usize, b: usize, c: usize, d: usize| {
        let (s, t) = (orient2d(q[a], q[b], q[c]), orient2d(q[a], q[b], q[d]));
        (s > 0.0 && t < 0.0) || (s < 0.0 && t > 0.0)
    };
    if !(across(e0, e1, o1, o2) && across(o1, o2, e0, e1)) {
        return None;
    }
    Some(Peel {
        old_faces: [f1, f2],
        triangles: tri,
        new: [[v[o1], v[o2], v[e0]], [v[o1], v[o2], v[e1]]],
    })
}
