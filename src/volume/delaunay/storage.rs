//! Flat tetrahedron storage.
//!
//! Why this shape: the kernel spends its time following neighbour links and reading vertex
//! indices, so each tetrahedron is one 32-byte record (`[u32; 4]` vertices + `[u32; 4]`
//! neighbour references), two records per cache line. A neighbour reference encodes
//! `tet * 4 + face`, where `face` is the index of the *same* face seen from the neighbour
//! (the neighbour's vertex opposite it), so crossing a face and coming back never needs a
//! search. A separate byte per tet carries flags (constrained-face bits, deleted, and two
//! transient marks used while a cavity is being built). Deleted tets are chained into a free
//! list through their first neighbour slot, so recycling costs no extra memory.
//!
//! Face `i` of a tet is the face opposite its vertex `i`. A finite tet `[a, b, c, d]` is
//! stored positively oriented: `robust::orient3d(a, b, c, d) > 0`.

/// The vertex at infinity: every hull face is closed off by a "ghost" tet that has this
/// vertex in place of a real one.
pub const INF: u32 = u32::MAX;
/// "No tet" marker for the free list and empty hints.
pub(crate) const NONE: u32 = u32::MAX;

/// Flag bits (one byte per tet).
pub(crate) mod flag {
    /// Bits 0..3: face `i` is constrained (the cavity of an insertion never crosses it).
    pub const CONSTRAINED: u8 = 0x0f;
    /// The record is on the free list.
    pub const DELETED: u8 = 0x10;
    /// Transient: the tet belongs to the cavity being built.
    pub const IN_CAVITY: u8 = 0x20;
    /// Transient: the tet has been tested and is not in conflict.
    pub const VISITED: u8 = 0x40;
    /// Transient: the tet was created by the current batch (for batch reporting).
    pub const NEW: u8 = 0x80;
}

/// One tetrahedron: vertices and neighbour references (`tet * 4 + face`).
///
/// Aligned to 32 bytes so a record never straddles two cache lines.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C, align(32))]
pub(crate) struct Tet {
    pub v: [u32; 4],
    pub n: [u32; 4],
}

impl Tet {
    #[inline]
    pub fn inf_pos(&self) -> Option<usize> {
        self.v.iter().position(|&x| x == INF)
    }
    #[inline]
    pub fn is_ghost(&self) -> bool {
        self.v.contains(&INF)
    }
}

/// The tetrahedra of a triangulation, with a free list of recycled slots.
#[derive(Clone, Debug, Default)]
pub(crate) struct TetStore {
    pub tets: Vec<Tet>,
    pub flags: Vec<u8>,
    pub free_head: u32,
    /// Live records (finite + ghost).
    pub live: usize,
}

impl TetStore {
    pub fn with_capacity(n: usize) -> Self {
        TetStore {
            tets: Vec::with_capacity(n),
            flags: Vec::with_capacity(n),
            free_head: NONE,
            live: 0,
        }
    }

    /// A fresh or recycled slot; its contents are garbage until written.
    #[inline]
    pub fn alloc(&mut self) -> u32 {
        self.live += 1;
        if self.free_head != NONE {
            let t = self.free_head;
            self.free_head = self.tets[t as usize].n[0];
            self.flags[t as usize] = 0;
            t
        } else {
            let t = self.tets.len() as u32;
            self.tets.push(Tet::default());
            self.flags.push(0);
            t
        }
    }

    #[inline]
    pub fn free(&mut self, t: u32) {
        self.live -= 1;
        self.flags[t as usize] = flag::DELETED;
        self.tets[t as usize].n[0] = self.free_head;
        self.free_head = t;
    }

    #[inline]
    pub fn is_live(&self, t: u32) -> bool {
        (t as usize) < self.tets.len() && self.flags[t as usize] & flag::DELETED == 0
    }

    /// Hint the CPU to start loading tet `t` (and its flag byte): the cavity search knows
    /// which tets it will test next long before it reads them, and the tet array of a large
    /// triangulation does not fit in cache.
    #[inline(always)]
    pub fn prefetch(&self, t: u32) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
            if let Some(r) = self.tets.get(t as usize) {
                // SAFETY: prefetching is a pure hint; the pointers come from live references.
                unsafe {
                    _mm_prefetch::<_MM_HINT_T0>((r as *const Tet).cast());
                    _mm_prefetch::<_MM_HINT_T0>(self.flags.as_ptr().add(t as usize).cast());
                }
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = t;
    }

    /// Breadth-first growth of `list`, whose tets already bear flag `mark`: each listed tet
    /// is first shown to `stop` (which may end the search there, returning it), then each
    /// neighbour `u` across its face `f` that does not bear `mark` is marked and listed when
    /// `cross(tet, tet's flags, f, u)` says so. Vertex stars and cavity repair grow this way;
    /// the caller clears the marks.
    pub fn flood(
        &mut self,
        list: &mut Vec<u32>,
        mark: u8,
        mut stop: impl FnMut(&Tet) -> bool,
        mut cross: impl FnMut(&Tet, u8, usize, u32) -> bool,
    ) -> Option<u32> {
        let mut i = 0;
        while i < list.len() {
            let t = list[i];
            i += 1;
            let tet = self.tets[t as usize];
            if stop(&tet) {
                return Some(t);
            }
            let ft = self.flags[t as usize];
            for f in 0..4 {
                let u = tet.n[f] >> 2;
                if self.flags[u as usize] & mark == 0 && cross(&tet, ft, f, u) {
                    self.flags[u as usize] |= mark;
                    list.push(u);
                }
            }
        }
        None
    }

    /// Bytes held by the tet arrays (capacity, i.e. what is really allocated).
    pub fn bytes(&self) -> usize {
        self.tets.capacity() * std::mem::size_of::<Tet>() + self.flags.capacity()
    }
}
