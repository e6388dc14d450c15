//! Point location by visibility walk.
//!
//! From the current tet, test the faces in an order that starts at a random face; step
//! through the first face that has the point strictly on its far side. Stop when no face
//! does (the point is in the closed tet) or when the step lands in a ghost tet (the point is
//! strictly outside the hull, beyond that ghost's hull face). The random start is what makes
//! the walk terminate with probability 1 even in non-Delaunay triangulations (constrained
//! faces), where a fixed face order can cycle; in a Delaunay triangulation any order works.
//! The face we just came through is skipped: the point is known to be on its near side.

use super::predicates::orient_replaced;
use super::storage::NONE;
use super::{Delaunay, Location};

impl Delaunay {
    /// A live starting tet: the hint if usable, else the last created, else any live tet.
    fn start_tet(&self, hint: u32) -> u32 {
        if hint != NONE && self.store.is_live(hint) {
            return hint;
        }
        if self.last != NONE && self.store.is_live(self.last) {
            return self.last;
        }
        (0..self.store.tets.len() as u32)
            .find(|&t| self.store.is_live(t))
            .expect("a triangulation always has live tets")
    }

    pub(super) fn walk(&mut self, p: &[f64; 3], hint: u32) -> Location {
        let mut t = self.start_tet(hint);
        let tets = &self.store.tets;
        let pts = &self.points;
        if let Some(k) = tets[t as usize].inf_pos() {
            // Start from the finite tet behind the ghost's hull face.
            t = tets[t as usize].n[k] >> 2;
        }
        let mut from = 4usize;
        'walk: loop {
            let tet = &tets[t as usize];
            let r = (self.rng.next() >> 62) as usize;
            for k in 0..4 {
                let f = (r + k) & 3;
                if f == from {
                    continue;
                }
                if orient_replaced(pts, &tet.v, f, p) < 0.0 {
                    let nr = tet.n[f];
                    t = nr >> 2;
                    from = (nr & 3) as usize;
                    if tets[t as usize].is_ghost() {
                        return Location::Outside(t);
                    }
                    continue 'walk;
                }
            }
            for &v in &tet.v {
                if pts[v as usize] == *p {
                    return Location::Vertex(v);
                }
            }
            return Location::Tet(t);
        }
    }
}
