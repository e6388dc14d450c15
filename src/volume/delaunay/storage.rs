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
//!
//! The parallel insertion sees the same arrays through [`SharedTets`], one atomic word per
//! entry; the view (and the prefetch hint) is all the kernel's unsafe code.

use std::sync::atomic::{AtomicU32, AtomicU8, Ordering::Relaxed};

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
        if let Some(r) = self.tets.get(t as usize) {
            prefetch(r);
            // The flags have the tets' length (and a prefetch never faults).
            prefetch(self.flags.as_ptr().wrapping_add(t as usize));
        }
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

    /// The arrays as the parallel insertion's threads share them (with the vertex hints).
    pub fn shared<'a>(&'a mut self, vtet: &'a mut [u32]) -> SharedTets<'a> {
        SharedTets {
            tets: atomic_view(&mut self.tets),
            flags: atomic_view(&mut self.flags),
            vtet: atomic_view(vtet),
        }
    }

    /// Bytes held by the tet arrays (capacity, i.e. what is really allocated).
    pub fn bytes(&self) -> usize {
        self.tets.capacity() * std::mem::size_of::<Tet>() + self.flags.capacity()
    }
}

/// Start loading the cache line at `p` (a pure hint: nothing is read).
#[inline(always)]
fn prefetch<T>(p: *const T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: a prefetch reads nothing and never faults, whatever the address.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(p.cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

/// [`Tet`] with one atomic word per entry: the same 32 bytes, so the tet array can be viewed
/// as an array of these.
#[repr(C, align(32))]
struct AtomicTet {
    v: [AtomicU32; 4],
    n: [AtomicU32; 4],
}

/// A plain value type and its atomic twin of the same size, alignment and bit validity.
///
/// # Safety
/// `Self` and `Self::Atomic` must have the same layout, every bit pattern valid for one
/// valid for the other (so a `&mut [Self]` may be viewed as `&[Self::Atomic]`).
unsafe trait Atomic: Sized {
    type Atomic;
}
// SAFETY: the standard library documents `AtomicU8`/`AtomicU32` as having the size and bit
// validity of `u8`/`u32`; their alignments are checked equal below. `AtomicTet` is `Tet` with
// each `u32` replaced by an `AtomicU32`, both `repr(C, align(32))`.
unsafe impl Atomic for u8 {
    type Atomic = AtomicU8;
}
unsafe impl Atomic for u32 {
    type Atomic = AtomicU32;
}
unsafe impl Atomic for Tet {
    type Atomic = AtomicTet;
}
const _: () = {
    use std::mem::{align_of, size_of};
    assert!(align_of::<u8>() == align_of::<AtomicU8>());
    assert!(align_of::<u32>() == align_of::<AtomicU32>());
    assert!(size_of::<Tet>() == size_of::<AtomicTet>());
    assert!(align_of::<Tet>() == align_of::<AtomicTet>());
};

/// `s` as atomics for as long as it is borrowed: the exclusive borrow guarantees nothing else
/// reads or writes it non-atomically meanwhile.
fn atomic_view<T: Atomic>(s: &mut [T]) -> &[T::Atomic] {
    // SAFETY: same layout and bit validity (`Atomic`), same length; the `&mut` is given up
    // for the lifetime of the shared view, so every access through it is atomic.
    unsafe { &*(s as *mut [T] as *const [T::Atomic]) }
}

/// The tet, flag and vertex-hint arrays shared by the threads of the parallel insertion
/// (`par.rs`). Why atomics: threads read and write the same arrays at scattered places, and
/// which thread may touch which tet follows from `par.rs`'s ownership rules; with every
/// access one relaxed atomic load or store of one word, a mistake in those rules could give
/// a wrong triangulation but never undefined behaviour. Relaxed loads and stores are plain
/// moves on x86-64 and AArch64, so what the view adds is a bounds check per access; the end
/// of the pass (rayon's join) makes all writes visible to the thread that continues.
pub(crate) struct SharedTets<'a> {
    tets: &'a [AtomicTet],
    pub flags: &'a [AtomicU8],
    /// The vertex hints (`Delaunay::vtet`).
    pub vtet: &'a [AtomicU32],
}

impl SharedTets<'_> {
    /// Tet `t`, read word by word (8 loads: where only the vertices or one neighbour are
    /// needed, [`SharedTets::vertices`] and [`SharedTets::neighbour`] read less).
    #[inline(always)]
    pub fn get(&self, t: u32) -> Tet {
        let a = &self.tets[t as usize];
        Tet {
            v: [0, 1, 2, 3].map(|k| a.v[k].load(Relaxed)),
            n: [0, 1, 2, 3].map(|k| a.n[k].load(Relaxed)),
        }
    }
    #[inline(always)]
    pub fn vertices(&self, t: u32) -> [u32; 4] {
        let a = &self.tets[t as usize];
        [0, 1, 2, 3].map(|k| a.v[k].load(Relaxed))
    }
    /// The half-face across face `f` of tet `t`.
    #[inline(always)]
    pub fn neighbour(&self, t: u32, f: usize) -> u32 {
        self.tets[t as usize].n[f & 3].load(Relaxed)
    }
    #[inline(always)]
    pub fn set(&self, t: u32, tet: Tet) {
        let a = &self.tets[t as usize];
        for k in 0..4 {
            a.v[k].store(tet.v[k], Relaxed);
            a.n[k].store(tet.n[k], Relaxed);
        }
    }
    /// Point half-face `from` (`tet * 4 + face`) at half-face `to`.
    #[inline(always)]
    pub fn link(&self, from: u32, to: u32) {
        self.tets[(from >> 2) as usize].n[(from & 3) as usize].store(to, Relaxed);
    }
    /// As [`TetStore::prefetch`].
    #[inline(always)]
    pub fn prefetch(&self, t: u32) {
        if let Some(r) = self.tets.get(t as usize) {
            prefetch(r);
        }
    }
}
