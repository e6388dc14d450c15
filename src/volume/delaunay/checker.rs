//! Full validity check of a triangulation (exact predicates throughout).
//!
//! Checked: every neighbour reference is symmetric and joins equal vertex sets; constrained
//! bits agree on both sides of a face; every finite tet is positively oriented; every
//! unconstrained interior face is locally Delaunay under the same perturbed in-sphere test
//! the kernel uses (so the check is exact even for cospherical points); the hull (the finite
//! faces of the ghost tets) is locally convex, a closed surface with V − E + F = 2; and the
//! whole complex is a ball: V − E + F − T = 1.

use std::collections::HashSet;

use super::predicates::{in_sphere_perturbed, orient, orient_replaced};
use super::storage::{flag, INF};
use super::Delaunay;

/// Counts gathered by a successful [`Delaunay::check`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckReport {
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub tets: usize,
    pub hull_vertices: usize,
    pub hull_edges: usize,
    pub hull_faces: usize,
    pub constrained_faces: usize,
}

/// The first defect found by [`Delaunay::check`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CheckError {
    #[error(
        "tet {tet} face {face}: neighbour reference is not symmetric or joins different faces"
    )]
    Adjacency { tet: u32, face: u8 },
    #[error("tet {tet} face {face}: constrained flag differs between the two sides")]
    ConstraintFlag { tet: u32, face: u8 },
    #[error("tet {tet} {vertices:?} is not positively oriented")]
    Orientation { tet: u32, vertices: [u32; 4] },
    #[error("tet {tet} has {count} vertices at infinity")]
    Ghost { tet: u32, count: usize },
    #[error("face {face} of tet {tet} is not locally Delaunay (vertex {vertex} is inside)")]
    NotDelaunay { tet: u32, face: u8, vertex: u32 },
    #[error("hull is not convex at ghost tet {tet} (vertex {vertex} is beyond its face)")]
    NotConvex { tet: u32, vertex: u32 },
    #[error("Euler characteristic mismatch: {what}")]
    Euler { what: String },
}

pub(super) fn check(d: &Delaunay, delaunay: bool) -> Result<CheckReport, CheckError> {
    let tets = &d.store.tets;
    let flags = &d.store.flags;
    let pts = &d.points;
    let sorted_face = |v: &[u32; 4], f: usize| {
        let mut k = [v[(f + 1) % 4], v[(f + 2) % 4], v[(f + 3) % 4]];
        k.sort_unstable();
        k
    };
    let mut finite = 0usize;
    let mut ghosts = 0usize;
    let mut constrained = 0usize;
    let mut used = vec![false; pts.len()];
    let mut hull_used = vec![false; pts.len()];
    let mut edges: HashSet<u64> = HashSet::new();
    for t in 0..tets.len() as u32 {
        if flags[t as usize] & flag::DELETED != 0 {
            continue;
        }
        let tet = &tets[t as usize];
        let infs = tet.v.iter().filter(|&&x| x == INF).count();
        if infs > 1 {
            return Err(CheckError::Ghost {
                tet: t,
                count: infs,
            });
        }
        for f in 0..4 {
            let nr = tet.n[f];
            let (u, g) = (nr >> 2, (nr & 3) as usize);
            let ok = d.store.is_live(u)
                && tets[u as usize].n[g] == t * 4 + f as u32
                && sorted_face(&tet.v, f) == sorted_face(&tets[u as usize].v, g)
                && tets[u as usize].v[g] != tet.v[f];
            if !ok {
                return Err(CheckError::Adjacency {
                    tet: t,
                    face: f as u8,
                });
            }
            let cu = flags[u as usize] & (1 << g) != 0;
            let ct = flags[t as usize] & (1 << f) != 0;
            if cu != ct {
                return Err(CheckError::ConstraintFlag {
                    tet: t,
                    face: f as u8,
                });
            }
            if ct && t < u {
                constrained += 1;
            }
        }
        if infs == 1 {
            ghosts += 1;
            let k = tet.inf_pos().unwrap_or(0);
            for f in 0..4 {
                if f == k {
                    continue;
                }
                let nr = tet.n[f];
                let (u, g) = (nr >> 2, (nr & 3) as usize);
                let w = tets[u as usize].v[g];
                if w == INF || orient_replaced(pts, &tet.v, k, &pts[w as usize]) > 0.0 {
                    return Err(CheckError::NotConvex {
                        tet: t,
                        vertex: d.ext(w),
                    });
                }
            }
            for &v in &tet.v {
                if v != INF {
                    hull_used[v as usize] = true;
                }
            }
            continue;
        }
        finite += 1;
        let v = tet.v;
        let p = |i: usize| &pts[v[i] as usize];
        if orient(p(0), p(1), p(2), p(3)) <= 0.0 {
            return Err(CheckError::Orientation {
                tet: t,
                vertices: v,
            });
        }
        for &x in &v {
            used[x as usize] = true;
        }
        for i in 0..4 {
            for j in i + 1..4 {
                let (a, b) = (v[i].min(v[j]), v[i].max(v[j]));
                edges.insert(((a as u64) << 32) | b as u64);
            }
        }
        for f in 0..4 {
            if !delaunay || flags[t as usize] & (1 << f) != 0 {
                continue;
            }
            let nr = tet.n[f];
            let (u, g) = (nr >> 2, (nr & 3) as usize);
            let w = tets[u as usize].v[g];
            if w == INF {
                continue;
            }
            if in_sphere_perturbed(pts, &v, w, &pts[w as usize]) {
                return Err(CheckError::NotDelaunay {
                    tet: t,
                    face: f as u8,
                    vertex: w,
                });
            }
        }
    }
    // Hull surface: F ghost faces, each edge in two of them.
    if ghosts & 1 != 0 {
        return Err(CheckError::Euler {
            what: format!("odd number of hull faces {ghosts}"),
        });
    }
    let hv = hull_used.iter().filter(|&&b| b).count();
    let he = ghosts * 3 / 2;
    if hv as i64 - he as i64 + ghosts as i64 != 2 {
        return Err(CheckError::Euler {
            what: format!("hull V {hv} - E {he} + F {ghosts} != 2"),
        });
    }
    if ghosts != d.ghosts || finite + ghosts != d.store.live {
        return Err(CheckError::Euler {
            what: format!(
                "counters: {finite} finite + {ghosts} ghosts found, {} live / {} ghosts recorded",
                d.store.live, d.ghosts
            ),
        });
    }
    let nv = used.iter().filter(|&&b| b).count();
    let ne = edges.len();
    let nf = (4 * finite + ghosts) / 2;
    if nv as i64 - ne as i64 + nf as i64 - finite as i64 != 1 {
        return Err(CheckError::Euler {
            what: format!("V {nv} - E {ne} + F {nf} - T {finite} != 1"),
        });
    }
    if nv != d.num_vertices() {
        return Err(CheckError::Euler {
            what: format!("{nv} vertices in tets, {} expected", d.num_vertices()),
        });
    }
    Ok(CheckReport {
        vertices: nv,
        edges: ne,
        faces: nf,
        tets: finite,
        hull_vertices: hv,
        hull_edges: he,
        hull_faces: ghosts,
        constrained_faces: constrained,
    })
}
