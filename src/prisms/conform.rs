//! Which candidate prisms can be merged and keep the mesh conforming: every side quad of a
//! merged prism must be met by one element with that quad as a face — another merged prism, or
//! a pyramid made of the two tets beyond it when they share their fourth point — or lie on the
//! boundary with both its triangles. A candidate that cannot be met is left as tets, which may
//! in turn let its neighbours' quads be met by pyramids; repeated until nothing changes.

use super::find::{sorted, Candidate};
use super::shape;
use crate::mesh::VolumeMesh;
use std::collections::HashMap;

const NONE: u32 = u32::MAX;

/// A pyramid: its base quad and apex in mesh order, and the two tets it replaces.
#[derive(Clone, Debug)]
pub(super) struct Pyramid {
    pub nodes: [u32; 5],
    pub tets: [u32; 2],
    pub region: u32,
}

/// The outcome: which candidates merge, the pyramids that meet them, and why the others do not.
#[derive(Clone, Debug, Default)]
pub(super) struct Conforming {
    pub accepted: Vec<bool>,
    pub pyramids: Vec<Pyramid>,
    /// Candidates left as tets because a side quad is too warped.
    pub refused_warp: usize,
    /// Candidates left as tets because a side quad could not be met conformingly.
    pub refused_unmatched: usize,
    pub rounds: usize,
}

/// The two tets on each face of the mesh (`NONE` where there is one).
fn face_tets(mesh: &VolumeMesh) -> HashMap<[u32; 3], [u32; 2]> {
    let mut faces: HashMap<[u32; 3], [u32; 2]> = HashMap::with_capacity(mesh.tets.len() * 2 + 16);
    for (k, t) in mesh.tets.iter().enumerate() {
        for f in crate::mesh::validity::OUTWARD_FACES {
            let e = faces.entry(sorted(f.map(|i| t[i]))).or_insert([NONE; 2]);
            if e[0] == NONE {
                e[0] = k as u32;
            } else {
                e[1] = k as u32;
            }
        }
    }
    faces
}

/// How a side quad is met.
enum Met {
    Boundary,
    Prism,
    Pyramid(Pyramid),
    Not,
}

pub(super) fn conform(mesh: &VolumeMesh, cands: &[Candidate], max_warp: f64) -> Conforming {
    let faces = face_tets(mesh);
    let boundary: HashMap<[u32; 3], u32> = (mesh.boundary.iter().zip(&mesh.boundary_marker))
        .map(|(&t, &m)| (sorted(t), m))
        .collect();
    let mut out = Conforming {
        accepted: vec![true; cands.len()],
        ..Default::default()
    };
    let mut owner = vec![NONE; mesh.tets.len()];
    for (c, cand) in cands.iter().enumerate() {
        let warped = cand.sides.iter().any(|s| {
            let q = quad_cycle(s);
            shape::warp_degrees(q.map(|v| mesh.points[v as usize])) > max_warp
        });
        if warped {
            out.accepted[c] = false;
            out.refused_warp += 1;
        } else {
            for &t in &cand.tets {
                owner[t as usize] = c as u32;
            }
        }
    }
    loop {
        out.rounds += 1;
        let mut changed = false;
        let mut claimed: HashMap<u32, u32> = HashMap::new();
        let mut pyramids: Vec<Pyramid> = Vec::new();
        for (c, cand) in cands.iter().enumerate() {
            if !out.accepted[c] {
                continue;
            }
            let mut mine: Vec<Pyramid> = Vec::new();
            let ok = cand.sides.iter().all(|side| {
                match met(mesh, &faces, &boundary, &owner, c as u32, side) {
                    Met::Boundary | Met::Prism => true,
                    Met::Pyramid(p) => {
                        let free = p.tets.iter().all(|t| {
                            !claimed.contains_key(t) && !mine.iter().any(|q| q.tets.contains(t))
                        });
                        if free {
                            mine.push(p);
                        }
                        free
                    }
                    Met::Not => false,
                }
            });
            if ok {
                for p in mine {
                    for &t in &p.tets {
                        claimed.insert(t, c as u32);
                    }
                    pyramids.push(p);
                }
            } else {
                out.accepted[c] = false;
                out.refused_unmatched += 1;
                for &t in &cand.tets {
                    owner[t as usize] = NONE;
                }
                changed = true;
            }
        }
        if !changed {
            out.pyramids = pyramids;
            return out;
        }
    }
}

/// A side quad's corners in cycle order, from its two triangles (which share its diagonal).
fn quad_cycle(side: &[[u32; 3]; 2]) -> [u32; 4] {
    let [x, y] = side;
    // The corner of y not on x, put between the two corners of x that y also has.
    let extra = y.iter().copied().find(|v| !x.contains(v)).unwrap_or(y[0]);
    let lone = x.iter().position(|v| !y.contains(v)).unwrap_or(0);
    // x = [lone, p, q] cyclically; the quad is lone, p, extra, q.
    let p = x[(lone + 1) % 3];
    let q = x[(lone + 2) % 3];
    [x[lone], p, extra, q]
}

/// How the side quad `side` of candidate `c` is met from beyond.
fn met(
    mesh: &VolumeMesh,
    faces: &HashMap<[u32; 3], [u32; 2]>,
    boundary: &HashMap<[u32; 3], u32>,
    owner: &[u32],
    c: u32,
    side: &[[u32; 3]; 2],
) -> Met {
    let beyond = |f: [u32; 3]| -> Option<u32> {
        let pair = faces.get(&sorted(f))?;
        pair.iter()
            .copied()
            .find(|&t| t != NONE && owner[t as usize] != c)
    };
    let listed = side.map(|f| boundary.get(&sorted(f)).copied());
    // Both triangles on the boundary with one marker, or neither.
    match listed {
        [Some(a), Some(b)] if a != b => return Met::Not,
        [Some(_), None] | [None, Some(_)] => return Met::Not,
        _ => {}
    }
    let across = side.map(beyond);
    match across {
        [None, None] => {
            if listed[0].is_some() {
                Met::Boundary
            } else {
                Met::Not
            }
        }
        [Some(u), Some(w)] if owner[u as usize] != NONE || owner[w as usize] != NONE => {
            if owner[u as usize] == owner[w as usize] && u != w {
                Met::Prism
            } else {
                Met::Not
            }
        }
        [Some(u), Some(w)] if u != w => {
            let apex =
                |t: u32, f: [u32; 3]| mesh.tets[t as usize].into_iter().find(|v| !f.contains(v));
            let (Some(a), Some(b)) = (apex(u, side[0]), apex(w, side[1])) else {
                return Met::Not;
            };
            if a != b || mesh.tet_region[u as usize] != mesh.tet_region[w as usize] {
                return Met::Not;
            }
            let q = quad_cycle(side);
            // The base turns counter-clockwise seen from the apex: the order whose splits are
            // positive.
            let reversed = [q[0], q[3], q[2], q[1]];
            for base in [q, reversed] {
                let nodes = [base[0], base[1], base[2], base[3], a];
                if shape::pyramid_is_valid(&nodes.map(|v| mesh.points[v as usize])) {
                    return Met::Pyramid(Pyramid {
                        nodes,
                        tets: [u, w],
                        region: mesh.tet_region[u as usize],
                    });
                }
            }
            Met::Not
        }
        _ => Met::Not,
    }
}

#[cfg(test)]
mod tests {
    use super::quad_cycle;

    #[test]
    fn a_quad_cycle_runs_round_its_two_triangles() {
        // Quad 1-2-3-4 cut by diagonal 1-3.
        let q = quad_cycle(&[[1, 2, 3], [1, 3, 4]]);
        let cyc = |q: [u32; 4]| {
            (0..4).any(|r| [q[r], q[(r + 1) % 4], q[(r + 2) % 4], q[(r + 3) % 4]] == [1, 2, 3, 4])
        };
        assert!(cyc(q) || cyc([q[0], q[3], q[2], q[1]]), "{q:?}");
    }
}
