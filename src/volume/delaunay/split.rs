//! Point insertion by star splitting, and Lawson flips back towards Delaunay around a vertex.
//!
//! Boundary recovery must add Steiner points without destroying what is already recovered.
//! The Bowyer–Watson cavity of [`Delaunay::insert`] may remove any unconstrained edge and
//! face near the point, so recovery inserts instead by splitting only the simplex that
//! contains the point: its tet (1→4), the face it lies on (2→6), the edge it lies on (n→2n),
//! or, outside the hull, the visible ghost tets (beneath–beyond). Location is exact (the
//! orientations of the point against the containing tet's faces decide which simplex), and
//! every new tet is the old one with one vertex replaced by the point, so orientation is
//! kept. Then [`Delaunay::flip_around`] restores local Delaunayhood with 2-3 and 3-2 flips
//! (Joe's flip-based insertion), never flipping away a constrained face or anything the
//! caller protects.

use super::predicates::{insphere, orient_replaced};
use super::storage::{INF, NONE};
use super::{Delaunay, DelaunayError, FlipError, Keep, Location};

/// What [`Delaunay::insert_split`] did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SplitOutcome {
    /// Input index of the new vertex.
    pub vertex: u32,
    /// Vertices (input indices) of the simplex whose relative interior held the point:
    /// 4 (a tet), 3 (a face), 2 (an edge); empty when the point was outside the hull.
    pub on: Vec<u32>,
    /// Created tets (finite and ghost).
    pub created: Vec<u32>,
}

impl Delaunay {
    /// Insert `p` by splitting the simplex that contains it (see the module docs); `hint` is
    /// a tet near `p`. `protect` sees the simplex's vertices (input indices) when the point
    /// lies on an edge (2) or a face (3): returning `true` refuses the insertion
    /// ([`DelaunayError::Protected`]). A point on a constrained face is refused too.
    pub fn insert_split(
        &mut self,
        p: [f64; 3],
        hint: Option<u32>,
        protect: &dyn Fn(&[u32]) -> bool,
    ) -> Result<SplitOutcome, DelaunayError> {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(DelaunayError::NonFinite {
                index: self.points.len(),
                point: p,
            });
        }
        let index = self.points.len() as u32;
        self.push_point(p, index);
        let pi = self.internal_of[index as usize];
        let r = self.split_at(pi, &p, hint.unwrap_or(NONE), protect);
        match r {
            Ok((on, created)) => {
                self.inserted += 1;
                Ok(SplitOutcome {
                    vertex: index,
                    on: on.into_iter().map(|x| self.ext(x)).collect(),
                    created,
                })
            }
            Err(e) => {
                self.pop_point();
                Err(e)
            }
        }
    }

    fn split_at(
        &mut self,
        pi: u32,
        p: &[f64; 3],
        hint: u32,
        protect: &dyn Fn(&[u32]) -> bool,
    ) -> Result<(Vec<u32>, Vec<u32>), DelaunayError> {
        let index = self.ext(pi);
        let (cavity, on) = match self.walk(p, hint) {
            Location::Vertex(of) => {
                return Err(DelaunayError::Duplicate {
                    index,
                    of: self.ext(of),
                })
            }
            Location::Tet(t) => {
                let tet = self.store.tets[t as usize];
                let o: Vec<f64> = (0..4)
                    .map(|f| orient_replaced(&self.points, &tet.v, f, p))
                    .collect();
                let on: Vec<u32> = (0..4).filter(|&f| o[f] > 0.0).map(|f| tet.v[f]).collect();
                if on.len() < 4 {
                    let ext: Vec<u32> = on.iter().map(|&x| self.ext(x)).collect();
                    if protect(&ext) {
                        return Err(DelaunayError::Protected { index, on: ext });
                    }
                }
                let cavity = match on.len() {
                    4 => vec![t],
                    3 => {
                        let f = (0..4).find(|&f| o[f] <= 0.0).unwrap_or(0);
                        if self.is_constrained(t, f as u8) {
                            return Err(DelaunayError::OnConstrainedFace {
                                index,
                                tet: t,
                                face: f as u8,
                            });
                        }
                        vec![t, self.store.tets[t as usize].n[f] >> 2]
                    }
                    2 => self.edge_ring_int(t, on[0], on[1]).0,
                    _ => {
                        let of = on.first().copied().unwrap_or(tet.v[0]);
                        return Err(DelaunayError::Duplicate {
                            index,
                            of: self.ext(of),
                        });
                    }
                };
                (cavity, on)
            }
            Location::Outside(g) => (self.visible_ghosts(g, p), Vec::new()),
        };
        // Each face of the cavity's boundary carries a new tet: the cavity tet with the vertex
        // opposite that face replaced by the point.
        let mut new = Vec::with_capacity(cavity.len() * 3);
        for &t in &cavity {
            let tet = self.store.tets[t as usize];
            for f in 0..4 {
                if !cavity.contains(&(tet.n[f] >> 2)) {
                    let mut v = tet.v;
                    v[f] = pi;
                    new.push(v);
                }
            }
        }
        match self.retessellate(&cavity, &new) {
            Ok(created) => Ok((on, created)),
            Err(FlipError::Constrained) => Err(DelaunayError::OnConstrainedFace {
                index,
                tet: cavity[0],
                face: 0,
            }),
            Err(why) => Err(DelaunayError::SplitFailed { index, why }),
        }
    }

    /// The ghost tets whose hull face `p` is strictly beyond, connected to ghost `g`.
    fn visible_ghosts(&self, g: u32, p: &[f64; 3]) -> Vec<u32> {
        let mut out = vec![g];
        let mut i = 0;
        while i < out.len() {
            let t = out[i];
            i += 1;
            let tet = self.store.tets[t as usize];
            let k = tet.inf_pos().unwrap_or(0);
            for f in 0..4 {
                if f == k {
                    continue;
                }
                let u = tet.n[f] >> 2;
                if out.contains(&u) {
                    continue;
                }
                let ut = &self.store.tets[u as usize];
                if let Some(ku) = ut.inf_pos() {
                    if orient_replaced(&self.points, &ut.v, ku, p) > 0.0 {
                        out.push(u);
                    }
                }
            }
        }
        out
    }

    /// Lawson flips around vertex `v` (input index): every face opposite `v` in its star whose
    /// far vertex is strictly inside the tet's circumsphere is flipped (2-3 when the two tets
    /// form a convex union, 3-2 when the reflex edge has degree 3), repeatedly, at most
    /// `limit` flips. Constrained faces and faces/edges for which `protect` (input indices,
    /// 3 or 2 of them) holds are never flipped away; hull faces are left alone. Returns the
    /// number of flips.
    pub fn flip_around(&mut self, v: u32, protect: &dyn Fn(&[u32]) -> bool, limit: usize) -> usize {
        let pv = self.internal_of[v as usize];
        self.star_search(pv, &mut |_| false);
        let mut stack: Vec<u32> = self.star_buf.clone();
        let mut flips = 0;
        while let Some(t) = stack.pop() {
            if flips >= limit {
                break;
            }
            if !self.store.is_live(t) {
                continue;
            }
            let tet = self.store.tets[t as usize];
            let Some(i) = tet.v.iter().position(|&x| x == pv) else {
                continue;
            };
            if tet.is_ghost() || self.is_constrained(t, i as u8) {
                continue;
            }
            let r = tet.n[i];
            let u = self.store.tets[(r >> 2) as usize];
            if u.is_ghost() {
                continue;
            }
            let w = u.v[(r & 3) as usize];
            let q = |x: u32| &self.points[x as usize];
            let (a, b, c, d) = (q(tet.v[0]), q(tet.v[1]), q(tet.v[2]), q(tet.v[3]));
            if insphere(a, b, c, d, q(w)) <= 0.0 {
                continue;
            }
            let face: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| tet.v[k]).collect();
            let fext: Vec<u32> = face.iter().map(|&x| self.ext(x)).collect();
            if protect(&fext) {
                continue;
            }
            let created = match self.flip23_int(t, i as u8) {
                Ok(ids) => Some(ids.to_vec()),
                Err(_) => self.flip32_towards(pv, w, &face, protect),
            };
            if let Some(ids) = created {
                flips += 1;
                stack.extend(ids);
            }
        }
        flips
    }

    /// The 3-2 flip that removes an edge of `face` whose ring is exactly {third vertex,
    /// `pv`, `w`} (the reflex edge of a non-convex pair), if any and not protected.
    fn flip32_towards(
        &mut self,
        pv: u32,
        w: u32,
        face: &[u32],
        protect: &dyn Fn(&[u32]) -> bool,
    ) -> Option<Vec<u32>> {
        for k in 0..3 {
            let (x, y) = (face[k], face[(k + 1) % 3]);
            let t0 = self.edge_tet_int(x, y)?;
            let (_, ring) = self.edge_ring_int(t0, x, y);
            if ring.len() != 3 || !ring.contains(&pv) || !ring.contains(&w) || ring.contains(&INF) {
                continue;
            }
            if protect(&[self.ext(x), self.ext(y)]) {
                continue;
            }
            if let Ok(ids) = self.remove_edge_int(x, y, Keep::Any, &|_, _, _, _| 1.0) {
                return Some(ids);
            }
        }
        None
    }
}
