//! The small hash table that links the new tets of a cavity to each other (serial and parallel
//! insertion both use it). Every new tet has three faces through the new point, each across a
//! cavity-boundary edge from the face of one other new tet: the first of the two to offer the
//! edge waits in the table, the second meets it. A stamp per insertion marks the live slots,
//! so the table is never cleared between insertions.

use super::cavity::star_edge_key;

#[derive(Clone, Copy, Debug, Default)]
struct Slot {
    /// The edge (see `cavity::star_edge_key`).
    key: u64,
    /// The half-face (tet · 4 + face) waiting for its partner.
    half_face: u32,
    /// The insertion the slot belongs to; other stamps are empty slots.
    stamp: u32,
}

/// Open addressing with linear probing, sized to a power of two.
#[derive(Clone, Debug, Default)]
pub(super) struct EdgeTable {
    slots: Vec<Slot>,
    stamp: u32,
}

impl EdgeTable {
    /// Start linking a cavity with `faces` boundary faces: room for all their edges, a fresh
    /// stamp. Returns the shift that turns an edge key into its first slot.
    pub(super) fn start(&mut self, faces: usize) -> u32 {
        let need = (faces * 4).next_power_of_two().max(64);
        if self.slots.len() < need {
            self.slots = vec![Slot::default(); need];
            self.stamp = 0;
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.slots.iter_mut().for_each(|s| s.stamp = 0);
            self.stamp = 1;
        }
        64 - self.slots.len().trailing_zeros()
    }

    /// Offer half-face `me` across edge `key`, probing from slot `first`: the half-face that
    /// was waiting there, or `None` (then `me` waits for its partner).
    #[inline(always)]
    pub(super) fn meet(&mut self, key: u64, first: usize, me: u32) -> Option<u32> {
        let mask = self.slots.len() - 1;
        let mut h = first;
        loop {
            let s = &mut self.slots[h];
            if s.stamp != self.stamp {
                *s = Slot {
                    key,
                    half_face: me,
                    stamp: self.stamp,
                };
                return None;
            }
            if s.key == key {
                return Some(s.half_face);
            }
            h = (h + 1) & mask;
        }
    }

    /// Offer the three faces of new tet `id` (vertices `v`) through the new point — all but
    /// its cavity-boundary face `f` — and call `join(g, other)` for each face `g` whose
    /// partner half-face `other` was waiting (the caller links the two both ways).
    #[inline(always)]
    pub(super) fn offer(
        &mut self,
        v: &[u32; 4],
        f: usize,
        id: u32,
        shift: u32,
        mut join: impl FnMut(usize, u32),
    ) {
        for g in 0..4 {
            if g == f {
                continue;
            }
            let (key, h) = star_edge_key(v, f, g, shift);
            if let Some(other) = self.meet(key, h, id * 4 + g as u32) {
                join(g, other);
            }
        }
    }
}
