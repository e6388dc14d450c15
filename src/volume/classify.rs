//! Which region each tet belongs to. Tets are grouped into connected pieces across
//! unconstrained faces (after boundary recovery, the constrained faces are exactly the surface
//! triangles); each recovered triangle then tells, by its model face and which side the piece
//! lies on, the region of that piece. A piece touching the convex hull is outside; a piece all
//! of whose triangles say "no region" is a cavity or the outside.

use super::boundary::OUTSIDE;
use super::delaunay::Delaunay;
use std::collections::HashMap;

/// A piece of the tetrahedralisation whose boundary triangles disagree about its region: the
/// surface mesh is not a consistent boundary there (self-intersecting, or faces oriented
/// against their shells).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SideConflict {
    /// A boundary triangle (index into the recovered triangle list) with the minority vote.
    pub triangle: u32,
    pub says: u32,
    pub majority: u32,
}

/// Region of every tet slot ([`OUTSIDE`] for ghosts, exterior and cavity tets, free slots).
///
/// `triangle_of` maps a sorted face key to its triangle index, `triangles` gives the
/// triangle's orientation, `sides[triangle]` the regions on its front and back side.
pub fn classify(
    dt: &Delaunay,
    triangles: &[[u32; 3]],
    triangle_of: &HashMap<[u32; 3], u32>,
    sides: impl Fn(u32) -> [u32; 2],
) -> Result<Vec<u32>, SideConflict> {
    let n = dt.slot_count();
    let mut piece = vec![u32::MAX; n];
    let mut result = vec![OUTSIDE; n];
    let mut stack = Vec::new();
    let mut members = Vec::new();
    let mut next_piece = 0u32;
    for seed in dt.tet_ids().chain(dt.ghost_ids()) {
        if piece[seed as usize] != u32::MAX {
            continue;
        }
        let id = next_piece;
        next_piece += 1;
        piece[seed as usize] = id;
        stack.push(seed);
        members.clear();
        let mut touches_hull = false;
        let mut votes: HashMap<u32, (usize, u32)> = HashMap::new();
        while let Some(t) = stack.pop() {
            members.push(t);
            touches_hull |= dt.is_ghost(t);
            for f in 0..4u8 {
                if dt.is_constrained(t, f) {
                    if let Some(vote) = side_of(dt, t, f, triangles, triangle_of, &sides) {
                        let e = votes.entry(vote.1).or_insert((0, vote.0));
                        e.0 += 1;
                    }
                    continue;
                }
                let (u, _) = dt.neighbor(t, f);
                if piece[u as usize] == u32::MAX {
                    piece[u as usize] = id;
                    stack.push(u);
                }
            }
        }
        let region = if touches_hull {
            OUTSIDE
        } else {
            let (&majority, _) = votes
                .iter()
                .max_by_key(|(r, (c, _))| (*c, u32::MAX - **r))
                .unwrap_or((&OUTSIDE, &(0, 0)));
            if let Some((&says, &(_, triangle))) = votes.iter().find(|(r, _)| **r != majority) {
                return Err(SideConflict {
                    triangle,
                    says,
                    majority,
                });
            }
            majority
        };
        for &t in &members {
            result[t as usize] = if dt.is_ghost(t) { OUTSIDE } else { region };
        }
    }
    Ok(result)
}

/// The (triangle, region) vote of constrained face `f` of tet `t`: the region on `t`'s side.
pub fn side_of(
    dt: &Delaunay,
    t: u32,
    f: u8,
    triangles: &[[u32; 3]],
    triangle_of: &HashMap<[u32; 3], u32>,
    sides: &impl Fn(u32) -> [u32; 2],
) -> Option<(u32, u32)> {
    let fv = dt.face_vertices(t, f);
    let mut key = fv;
    key.sort_unstable();
    let &k = triangle_of.get(&key)?;
    let tri = triangles[k as usize];
    // `face_vertices` is counter-clockwise seen from outside `t`: if the triangle runs the same
    // way, its normal points away from `t`, so `t` is behind it.
    let same_way = (0..3).any(|r| [tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]] == fv);
    let s = sides(k);
    Some((k, if same_way { s[1] } else { s[0] }))
}

/// Sorted vertex triple → triangle index.
pub fn triangle_index(triangles: &[[u32; 3]]) -> HashMap<[u32; 3], u32> {
    triangles
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let mut key = *t;
            key.sort_unstable();
            (key, k as u32)
        })
        .collect()
}
