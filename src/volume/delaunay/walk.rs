//! Point location by visibility walk.
//!
//! From the current tet, test the faces in an order that starts at a random face; step
//! through the first face that has the point strictly on its far side. Stop when no face
//! does (the point is in the closed tet) or when the step lands in a ghost tet (the point is
//! strictly outside the hull, beyond that ghost's hull face). The random start is what makes
//! the walk terminate with probability 1 even in non-Delaunay triangulations (constrained
//! faces), where a fixed face order can cycle; in a Delaunay triangulation any order works.
//! The face we just came through is skipped: the point is known to be on its near side.

use std::borrow::Borrow;

use super::predicates::orient_replaced;
use super::sort::Rng;
use super::storage::{Tet, NONE};
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
        let start = self.start_tet(hint);
        let tets = &self.store.tets;
        visibility_walk(
            &self.points,
            start,
            p,
            &mut self.rng,
            |t| &tets[t as usize],
            |_, _| true,
        )
        .expect("a walk that may enter every tet always ends in a location")
    }
}

/// The visibility walk itself, over any tet storage (the serial kernel's, or the parallel
/// workers' shared one): `tet(t)` reads tet `t` (a reference into the serial store, a copy
/// read word by word from the shared one, see `storage::SharedTets`); `enter(u, from)` says
/// whether the walk may
/// step into tet `u` arriving through its face `from` — when not, the walk ends with `None`
/// (a parallel worker leaving the tets it owns).
pub(super) fn visibility_walk<T: Borrow<Tet>>(
    pts: &[[f64; 3]],
    start: u32,
    p: &[f64; 3],
    rng: &mut Rng,
    tet: impl Fn(u32) -> T,
    enter: impl Fn(&Tet, usize) -> bool,
) -> Option<Location> {
    let mut t = start;
    let first = tet(t);
    if let Some(k) = first.borrow().inf_pos() {
        // Start from the finite tet behind the ghost's hull face.
        let nr = first.borrow().n[k];
        t = nr >> 2;
        if !enter(tet(t).borrow(), (nr & 3) as usize) {
            return None;
        }
    }
    let mut from = 4usize;
    'walk: loop {
        let here = tet(t);
        let here = here.borrow();
        let r = (rng.next() >> 62) as usize;
        for k in 0..4 {
            let f = (r + k) & 3;
            if f == from {
                continue;
            }
            if orient_replaced(pts, &here.v, f, p) < 0.0 {
                let nr = here.n[f];
                let u = nr >> 2;
                from = (nr & 3) as usize;
                let next = tet(u);
                let next = next.borrow();
                if !enter(next, from) {
                    return None;
                }
                if next.is_ghost() {
                    return Some(Location::Outside(u));
                }
                t = u;
                continue 'walk;
            }
        }
        for &v in &here.v {
            if pts[v as usize] == *p {
                return Some(Location::Vertex(v));
            }
        }
        return Some(Location::Tet(t));
    }
}
