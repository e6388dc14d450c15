//! Insertion: cavity search and re-triangulation (Bowyer–Watson).
//!
//! The cavity is grown breadth-first from the tet that contains the new point `p`: a
//! neighbour joins when it is in conflict with `p` (exact in-sphere with the symbolic
//! tie-break for finite tets; for ghost tets, `p` strictly beyond the hull face, or on its
//! plane and in conflict with the finite tet behind it). In a Delaunay triangulation the
//! conflict region is connected and star-shaped from `p`, so every boundary face joined to
//! `p` gives a positively oriented tet. The new tet for a boundary face is simply the cavity
//! tet's vertex list with the vertex opposite that face replaced by `p` — it keeps the
//! orientation, so no predicate is needed to build it. New tets are linked to each other
//! through the boundary edges they share (a small stamped hash table, no clearing).
//!
//! Constrained faces are never crossed. A triangulation with constraints is no longer
//! Delaunay, so the cavity may then not be star-shaped; it is repaired by removing, one at a
//! time, tets that would produce a flat or inverted tet or that lie across a constrained
//! face from another cavity tet, keeping only the part still connected to the tet holding
//! `p` (the approach of TetGen-style constrained insertion). If the tet holding `p` itself
//! must go, `p` lies on a constrained face and the insertion is refused.

use super::predicates::{in_sphere_perturbed, orient_replaced};
use super::storage::{flag, INF, NONE};
use super::{BFace, Delaunay, DelaunayError, Location};

impl Delaunay {
    /// Conflict test of tet `t` with point `p` (index `pi`).
    #[inline]
    fn conflict(&self, t: u32, pi: u32, p: &[f64; 3]) -> bool {
        let tet = &self.store.tets[t as usize];
        match tet.inf_pos() {
            None => in_sphere_perturbed(&self.points, &tet.v, pi, p),
            Some(k) => {
                let o = orient_replaced(&self.points, &tet.v, k, p);
                if o != 0.0 {
                    o > 0.0
                } else {
                    let behind = tet.n[k] >> 2;
                    in_sphere_perturbed(&self.points, &self.store.tets[behind as usize].v, pi, p)
                }
            }
        }
    }

    /// Insert point `pi` (already in `self.points`). Returns the number of destroyed tets;
    /// the created ones are in `self.scratch.new_ids`.
    pub(super) fn insert_index(&mut self, pi: u32, hint: u32) -> Result<usize, DelaunayError> {
        let p = self.points[pi as usize];
        let start = match self.walk(&p, hint) {
            Location::Vertex(of) => return Err(DelaunayError::Duplicate { index: pi, of }),
            Location::Tet(t) | Location::Outside(t) => t,
        };
        if self.store.tets.len() >= (u32::MAX / 4 - 64) as usize {
            return Err(DelaunayError::Capacity);
        }
        let mut sc = std::mem::take(&mut self.scratch);
        let r = self.insert_at(pi, &p, start, &mut sc);
        self.scratch = sc;
        r
    }

    fn insert_at(
        &mut self,
        pi: u32,
        p: &[f64; 3],
        start: u32,
        sc: &mut super::Scratch,
    ) -> Result<usize, DelaunayError> {
        sc.cavity.clear();
        sc.touched.clear();
        sc.boundary.clear();
        sc.new_ids.clear();
        if self.vtet.len() < self.points.len() {
            self.vtet.resize(self.points.len(), NONE);
        }
        if self.changed_at.len() < self.points.len() {
            self.changed_at.resize(self.points.len(), 0);
        }

        // 1. Grow the conflict region breadth-first.
        self.store.flags[start as usize] |= flag::IN_CAVITY;
        sc.cavity.push(start);
        for &w in &self.store.tets[start as usize].n {
            self.store.prefetch(w >> 2);
        }
        let mut any_constraint = 0u8;
        let mut i = 0;
        while i < sc.cavity.len() {
            let t = sc.cavity[i];
            i += 1;
            let ft = self.store.flags[t as usize];
            any_constraint |= ft;
            let tet = self.store.tets[t as usize];
            for (f, &nr) in tet.n.iter().enumerate() {
                let u = nr >> 2;
                let fu = self.store.flags[u as usize];
                if fu & flag::IN_CAVITY != 0 {
                    continue;
                }
                // Without constraints a tet found not in conflict never joins later, so the
                // boundary can be recorded on the fly (rebuilt below if constraints exist).
                if fu & flag::VISITED == 0 && ft & (1 << f) == 0 {
                    if self.conflict(u, pi, p) {
                        self.store.flags[u as usize] |= flag::IN_CAVITY;
                        sc.cavity.push(u);
                        for &w in &self.store.tets[u as usize].n {
                            self.store.prefetch(w >> 2);
                        }
                        continue;
                    }
                    self.store.flags[u as usize] |= flag::VISITED;
                    sc.touched.push(u);
                }
                sc.boundary
                    .push(BFace::new(&tet, f, pi, ft & (1 << f) != 0));
            }
        }

        // 2. With constraints around, make the cavity star-shaped from p, then rebuild the
        //    boundary from the final cavity.
        if any_constraint & flag::CONSTRAINED != 0 || self.flipped {
            if let Err(e) = self.repair_cavity(pi, p, sc) {
                for &t in sc.cavity.iter().chain(&sc.touched) {
                    self.store.flags[t as usize] &= !(flag::IN_CAVITY | flag::VISITED);
                }
                return Err(e);
            }
            sc.boundary.clear();
            for &t in &sc.cavity {
                let tet = self.store.tets[t as usize];
                let ft = self.store.flags[t as usize];
                for f in 0..4 {
                    let nr = tet.n[f];
                    if self.store.flags[(nr >> 2) as usize] & flag::IN_CAVITY == 0 {
                        sc.boundary
                            .push(BFace::new(&tet, f, pi, ft & (1 << f) != 0));
                    }
                }
            }
        }

        // 3. The boundary faces carry the new tets.
        for &u in &sc.touched {
            self.store.flags[u as usize] &= !flag::VISITED;
        }

        // 4. Recycle the cavity's slots, allocate the rest.
        let nd = sc.cavity.len();
        let nb = sc.boundary.len();
        for &t in &sc.cavity {
            let tet = &self.store.tets[t as usize];
            if tet.is_ghost() {
                self.ghosts -= 1;
            }
            if self.track_new && self.store.flags[t as usize] & flag::NEW == 0 {
                self.destroyed_old += 1;
            }
        }
        for k in 0..nb {
            let id = if k < nd {
                sc.cavity[k]
            } else {
                self.store.alloc()
            };
            sc.new_ids.push(id);
        }
        for k in nb..nd {
            self.store.free(sc.cavity[k]);
        }

        // 5. Write the new tets and link them.
        let shift = sc.table.start(nb);
        let new_flag = if self.track_new { flag::NEW } else { 0 };
        let now = self.next_change();
        for k in 0..nb {
            let b = sc.boundary[k];
            let id = sc.new_ids[k];
            let f = b.face as usize;
            {
                let tet = &mut self.store.tets[id as usize];
                tet.v = b.v;
                tet.n[f] = b.outer;
            }
            self.store.tets[(b.outer >> 2) as usize].n[(b.outer & 3) as usize] = id * 4 + f as u32;
            self.store.flags[id as usize] = new_flag | if b.constrained { 1 << f } else { 0 };
            if b.v.contains(&INF) {
                self.ghosts += 1;
            }
            for &x in &b.v {
                if x != INF {
                    self.vtet[x as usize] = id;
                    self.changed_at[x as usize] = now;
                }
            }
            let tets = &mut self.store.tets;
            sc.table.offer(&b.v, f, id, shift, |g, other| {
                tets[id as usize].n[g] = other;
                tets[(other >> 2) as usize].n[(other & 3) as usize] = id * 4 + g as u32;
            });
        }
        self.last = sc.new_ids[nb - 1];
        self.inserted += 1;
        Ok(nd)
    }

    /// Shrink the cavity until it is star-shaped from `p` and crosses no constrained face.
    /// The cavity's first tet, the one holding `p`, stays first: the search starts from it.
    fn repair_cavity(
        &mut self,
        pi: u32,
        p: &[f64; 3],
        sc: &mut super::Scratch,
    ) -> Result<(), DelaunayError> {
        let start = sc.cavity[0];
        loop {
            let mut bad = NONE;
            'scan: for &t in &sc.cavity {
                let tet = self.store.tets[t as usize];
                let ft = self.store.flags[t as usize];
                for f in 0..4 {
                    let u = tet.n[f] >> 2;
                    let inside = self.store.flags[u as usize] & flag::IN_CAVITY != 0;
                    if inside {
                        if ft & (1 << f) != 0 {
                            // A constrained face inside the cavity: drop the tet on the far
                            // side of it from p.
                            let o = if tet.v.contains(&INF) {
                                -1.0
                            } else {
                                orient_replaced(&self.points, &tet.v, f, p)
                            };
                            bad = if o > 0.0 { u } else { t };
                            break 'scan;
                        }
                    } else {
                        // The new tet for this face is finite unless INF sits elsewhere.
                        let new_is_ghost =
                            tet.v.iter().enumerate().any(|(k, &x)| k != f && x == INF);
                        if !new_is_ghost && orient_replaced(&self.points, &tet.v, f, p) <= 0.0 {
                            bad = t;
                            break 'scan;
                        }
                    }
                }
            }
            if bad == NONE {
                bad = self.interior_vertex_tet(start, sc);
            }
            if bad == NONE {
                return Ok(());
            }
            if bad == start {
                // p lies on a constrained face of the tet that contains it.
                let tet = self.store.tets[start as usize];
                let ft = self.store.flags[start as usize];
                let face = (0..4)
                    .find(|&f| {
                        ft & (1 << f) != 0 && orient_replaced(&self.points, &tet.v, f, p) <= 0.0
                    })
                    .unwrap_or(0) as u8;
                return Err(DelaunayError::OnConstrainedFace {
                    index: pi,
                    tet: start,
                    face,
                });
            }
            if self.store.tets[bad as usize].is_ghost() {
                // Shrinking the hull part of the cavity could leave the hull non-convex.
                return Err(DelaunayError::ConstraintBlocksHull { index: pi });
            }
            // Remove `bad`, then keep only what is still connected to `start` without
            // crossing constrained faces.
            let fl = &mut self.store.flags[bad as usize];
            *fl = (*fl & !flag::IN_CAVITY) | flag::VISITED;
            sc.touched.push(bad);
            for &t in &sc.cavity {
                self.store.flags[t as usize] &= !flag::IN_CAVITY;
            }
            // Re-grow from `start` through the old members (membership test against the
            // small old list; this path only runs near constrained faces).
            let old = std::mem::take(&mut sc.cavity);
            let mut keep = Vec::with_capacity(old.len());
            self.store.flags[start as usize] |= flag::IN_CAVITY;
            keep.push(start);
            self.store.flood(
                &mut keep,
                flag::IN_CAVITY,
                |_| false,
                |_, ft, f, u| ft & (1 << f) == 0 && u != bad && old.contains(&u),
            );
            for &t in &old {
                if self.store.flags[t as usize] & flag::IN_CAVITY == 0 && t != bad {
                    self.store.flags[t as usize] |= flag::VISITED;
                    sc.touched.push(t);
                }
            }
            sc.cavity = keep;
        }
    }

    /// A cavity tet (not `start`) having a vertex that no boundary face of the cavity has,
    /// or `NONE`. Filling such a cavity would drop that vertex from the triangulation; in a
    /// Delaunay triangulation it cannot happen, after flips (non-Delaunay) it can.
    fn interior_vertex_tet(&self, start: u32, sc: &super::Scratch) -> u32 {
        let mut on_boundary: Vec<u32> = Vec::with_capacity(sc.cavity.len() * 3);
        for &t in &sc.cavity {
            let tet = &self.store.tets[t as usize];
            for f in 0..4 {
                if self.store.flags[(tet.n[f] >> 2) as usize] & flag::IN_CAVITY == 0 {
                    on_boundary.extend((0..4).filter(|&k| k != f).map(|k| tet.v[k]));
                }
            }
        }
        on_boundary.sort_unstable();
        on_boundary.dedup();
        for &t in &sc.cavity {
            for &x in &self.store.tets[t as usize].v {
                if x != INF && on_boundary.binary_search(&x).is_err() {
                    // Every tet around x is in the cavity; drop one that is not `start`.
                    return sc
                        .cavity
                        .iter()
                        .copied()
                        .find(|&u| u != start && self.store.tets[u as usize].v.contains(&x))
                        .unwrap_or(NONE);
                }
            }
        }
        NONE
    }
}

/// The key and first hash slot of the cavity-boundary edge that face `g` of a new star tet
/// (vertices `v`, the new point at position `f`) shares with a neighbouring new tet: the two
/// vertices at the positions other than `f` and `g`. Gluing the star's tets pairs the faces
/// with equal keys (serial and parallel insertion alike).
pub(super) fn star_edge_key(v: &[u32; 4], f: usize, g: usize, shift: u32) -> (u64, usize) {
    let (x, y) = match (f.min(g), f.max(g)) {
        (0, 1) => (2, 3),
        (0, 2) => (1, 3),
        (0, 3) => (1, 2),
        (1, 2) => (0, 3),
        (1, 3) => (0, 2),
        _ => (0, 1),
    };
    let (a, c) = (v[x], v[y]);
    let key = ((a.min(c) as u64) << 32) | a.max(c) as u64;
    (
        key,
        (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> shift) as usize,
    )
}
