//! Bowyer–Watson Delaunay tetrahedralisation with exact predicates.
//!
//! The volume mesher's kernel (DESIGN.md step 5, seed paper "Volume Mesh Generation"): points
//! are inserted one at a time; each insertion finds the tet containing the point by a walk,
//! grows the *cavity* of tets whose circumsphere contains the point, deletes it and fills it
//! with tets joining the point to the cavity's boundary faces.
//!
//! Design choices, and why:
//!
//! * **Ghost tets instead of an enclosing box.** Every convex-hull face is closed off by a
//!   tet whose fourth vertex is the symbolic vertex at infinity [`INF`]. Every face then has
//!   exactly two tets, insertion outside the hull is the same algorithm as inside, and there
//!   are no big-box vertices to delete (and no box-induced non-Delaunay hull) at the end. A
//!   ghost tet is in conflict with `p` when `p` is strictly beyond its hull face, or on the
//!   face's plane and in conflict with the finite tet behind it.
//! * **Flat storage** (see [`storage`]): 32 bytes + 1 flag byte per tet, neighbour references
//!   `tet * 4 + face`, free list through deleted slots.
//! * **Order:** BRIO rounds, Hilbert-sorted (`sort.rs`).
//! * **Location:** visibility walk from the last created tet with a random first face, so it
//!   terminates even in non-Delaunay (constrained) triangulations (`walk.rs`).
//! * **Cavity:** breadth-first growth with the exact perturbed in-sphere test; never crosses
//!   a constrained face; when constraints are present the cavity is shrunk until it is
//!   star-shaped from the new point (`cavity.rs`).
//! * **Degeneracies:** exact predicates plus a symbolic perturbation for cospherical points
//!   ([`predicates`]), so lattices and points on a sphere give valid triangulations.
//! * **Duplicates:** a point equal (bit for bit) to a vertex of the tet the walk ends in is
//!   reported and not inserted.
//! * **Memory:** about 38 bytes per finite tet for 10⁶ uniform points: the 32-byte record and
//!   flag byte, plus each vertex's 24-byte coordinates and 8 bytes of id maps shared by its
//!   ~6.7 tets ([`Delaunay::memory_bytes`] counts allocated capacity).
//! * **Threads:** the Hilbert sort runs on the current rayon pool, and so does the insertion of
//!   the large BRIO rounds of [`Delaunay::new`] (`par.rs`: space split among threads by
//!   Hilbert-key ranges, a thread only changes tets whose vertices all lie in its range,
//!   insertions that would reach further are deferred and finished serially). Batch and
//!   single insertion into an existing (possibly constrained) triangulation are serial.
//!
//! Vertex indices in the API are input indices (`point(i)` is input point `i`, whether or not
//! it was inserted; duplicates belong to no tet). Internally the coordinates are stored in
//! insertion order and tets refer to these internal ids: consecutive insertions then touch
//! neighbouring memory, which matters more than anything else for speed at 10⁶ points (the
//! input order is typically random with respect to space). Two `u32` maps translate.

mod cavity;
mod checker;
mod edge_table;
mod flips;
mod par;
pub mod predicates;
mod replace;
mod sort;
mod split;
pub mod storage;
mod walk;

pub use checker::{CheckError, CheckReport};
pub use flips::{FlipError, Keep, Removal, TetScore, MAX_RING};
pub use split::SplitOutcome;
pub use storage::INF;

use storage::{flag, Tet, TetStore, NONE};

/// BRIO rounds at least this large are inserted in parallel by [`Delaunay::from_vec`] when the
/// rayon pool has several threads (smaller rounds are over before threads would pay off).
pub const PARALLEL_MIN_ROUND: usize = 8192;

/// Why a triangulation or an insertion could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DelaunayError {
    #[error("a tetrahedralisation needs at least 4 points, got {0}")]
    TooFewPoints(usize),
    #[error("all {0} points are coplanar (or collinear, or equal): no tetrahedron exists")]
    Degenerate(usize),
    #[error("point {index} has a non-finite coordinate {point:?}")]
    NonFinite { index: usize, point: [f64; 3] },
    #[error("point {index} duplicates vertex {of}")]
    Duplicate { index: u32, of: u32 },
    #[error(
        "point {index} lies on constrained face {face} of tet {tet}; split that face explicitly"
    )]
    OnConstrainedFace { index: u32, tet: u32, face: u8 },
    #[error("point {index} is outside the hull and constrained faces block its cavity there")]
    ConstraintBlocksHull { index: u32 },
    #[error("tet {tet} face {face} is not a live tet face")]
    InvalidFace { tet: u32, face: u8 },
    #[error("too many tetrahedra for 32-bit references")]
    Capacity,
    #[error("point {index} lies on a simplex {on:?} the caller protects")]
    Protected { index: u32, on: Vec<u32> },
    #[error("point {index} could not be inserted by a star split: {why}")]
    SplitFailed { index: u32, why: FlipError },
}

/// A point that was not inserted because it equals an existing vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Duplicate {
    /// Vertex (= input) index of the rejected point.
    pub index: u32,
    /// The vertex it coincides with.
    pub of: u32,
}

/// Result of [`Delaunay::locate`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// The point is inside or on the boundary of this finite tet.
    Tet(u32),
    /// The point is outside the convex hull, strictly beyond the hull face of this ghost tet.
    Outside(u32),
    /// The point coincides with this vertex.
    Vertex(u32),
}

/// What one insertion changed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InsertOutcome {
    /// Index of the new vertex.
    pub vertex: u32,
    /// Tets created (finite and ghost); all live after the insertion.
    pub created: Vec<u32>,
    /// Number of tets destroyed (their slots are recycled, possibly into `created`).
    pub destroyed: usize,
}

/// What a batch insertion changed.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct BatchOutcome {
    /// Vertex indices of the batch's points, in input order (duplicates included, see below).
    pub vertices: Vec<u32>,
    /// Points of the batch that were not inserted.
    pub duplicates: Vec<Duplicate>,
    /// Points of the batch that constrained faces keep out: exactly on a constrained face,
    /// or outside the hull where constraints block the cavity (not inserted).
    pub on_constrained_face: Vec<u32>,
    /// Live tets created by the batch, sorted.
    pub created: Vec<u32>,
    /// Number of tets that existed before the batch and were destroyed by it.
    pub destroyed: usize,
}

/// Per-insertion scratch buffers, kept to avoid allocation in the hot loop.
#[derive(Clone, Debug, Default)]
struct Scratch {
    cavity: Vec<u32>,
    touched: Vec<u32>,
    boundary: Vec<BFace>,
    new_ids: Vec<u32>,
    /// Links the new tets of a cavity around its boundary edges.
    table: edge_table::EdgeTable,
}

/// A face of the cavity boundary: the new tet it will carry and the tet outside it.
#[derive(Clone, Copy, Debug)]
struct BFace {
    /// Vertices of the new tet (the cavity tet's vertices with the new point at `face`).
    v: [u32; 4],
    /// Reference to the face as seen from outside the cavity.
    outer: u32,
    face: u8,
    constrained: bool,
}

impl BFace {
    /// Face `f` of cavity tet `tet`, seen from outside as `outer`, carrying the new tet that
    /// joins it to point `pi`: `tet`'s vertices with `pi` in place of the one opposite `f`,
    /// which keeps the orientation (serial and parallel insertion alike).
    #[inline(always)]
    fn new(tet: &Tet, f: usize, pi: u32, constrained: bool) -> Self {
        let mut v = tet.v;
        v[f] = pi;
        BFace {
            v,
            outer: tet.n[f],
            face: f as u8,
            constrained,
        }
    }
}

/// A Delaunay tetrahedralisation (with ghost tets closing the convex hull).
#[derive(Clone, Debug)]
pub struct Delaunay {
    /// Coordinates by internal id (insertion order).
    points: Vec<[f64; 3]>,
    /// Internal id → input index.
    input_of: Vec<u32>,
    /// Input index → internal id.
    internal_of: Vec<u32>,
    store: TetStore,
    ghosts: usize,
    duplicates: Vec<Duplicate>,
    last: u32,
    rng: sort::Rng,
    constrained_faces: usize,
    /// Vertices actually in the triangulation.
    inserted: usize,
    track_new: bool,
    destroyed_old: usize,
    scratch: Scratch,
    /// Internal vertex id → a live tet having it as a vertex (kept up to date by every
    /// operation that creates tets), so a vertex's star and an edge's tets are found without
    /// any search.
    vtet: Vec<u32>,
    /// Set once a flip or split has made the triangulation possibly non-Delaunay: insertion
    /// then always makes its cavity star-shaped (see `cavity.rs`).
    flipped: bool,
    /// Scratch list for vertex stars.
    star_buf: Vec<u32>,
    /// Internal vertex id → the value of `changes` when tets were last made around it, a
    /// face of its was constrained or freed, or it or a neighbour moved (0: not since the
    /// triangulation was built; missing entries are 0). A tet whose four vertices are all
    /// no newer than some count has the surroundings it had then: the same tets around
    /// each of its edges and across each of its faces, at the same places. The min-max
    /// swaps remember by it what they could not improve ([`Delaunay::unchanged_since`]).
    changed_at: Vec<u64>,
    /// Counts the operations that changed tets, points or constraints since construction.
    changes: u64,
}

/// The name used by the rest of the pipeline for a tetrahedralisation.
pub type Triangulation = Delaunay;

/// Triangulate `points`; see [`Delaunay::new`].
pub fn triangulate<P: Copy + Into<[f64; 3]>>(points: &[P]) -> Result<Delaunay, DelaunayError> {
    Delaunay::new(points)
}

impl Delaunay {
    /// Delaunay tetrahedralisation of `points` (vertex index = input index). Duplicates are
    /// skipped and listed in [`Delaunay::duplicates`]. Fails if fewer than four points, if a
    /// coordinate is not finite, or if all points are coplanar.
    pub fn new<P: Copy + Into<[f64; 3]>>(points: &[P]) -> Result<Self, DelaunayError> {
        let pts: Vec<[f64; 3]> = points.iter().map(|&p| p.into()).collect();
        Self::from_vec(pts)
    }

    /// As [`Delaunay::new`], taking ownership of the coordinates. When the current rayon pool
    /// has more than one thread, the large BRIO rounds are inserted in parallel (`par.rs`);
    /// the triangulation is the same either way.
    pub fn from_vec(points: Vec<[f64; 3]>) -> Result<Self, DelaunayError> {
        Self::from_vec_parallel(points, PARALLEL_MIN_ROUND)
    }

    /// As [`Delaunay::from_vec`], inserting every BRIO round of at least `min_round` points in
    /// parallel on the current rayon pool (`usize::MAX`: all serial). Small values exercise the
    /// parallel path on small inputs (tests); [`Delaunay::from_vec`] uses a size where the
    /// threads pay for themselves.
    pub fn from_vec_parallel(
        points: Vec<[f64; 3]>,
        min_round: usize,
    ) -> Result<Self, DelaunayError> {
        let n = points.len();
        if n < 4 {
            return Err(DelaunayError::TooFewPoints(n));
        }
        if n >= (u32::MAX / 8) as usize {
            return Err(DelaunayError::Capacity);
        }
        for (index, p) in points.iter().enumerate() {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(DelaunayError::NonFinite { index, point: *p });
            }
        }
        let (order, keys) = sort::brio_order_keys(&points, 0x5EED);
        let sorted: Vec<[f64; 3]> = {
            use rayon::prelude::*;
            order
                .par_iter()
                .with_min_len(1 << 14)
                .map(|&i| points[i as usize])
                .collect()
        };
        drop(points);
        let mut internal_of = vec![0u32; n];
        for (k, &i) in order.iter().enumerate() {
            internal_of[i as usize] = k as u32;
        }
        let ids: Vec<u32> = (0..n as u32).collect();
        let first = Self::initial_simplex(&sorted, &ids).ok_or(DelaunayError::Degenerate(n))?;
        drop(ids);
        // About 6.7 tets per vertex for uniform points (plus ghosts); reserve to avoid
        // repeated reallocation.
        let mut d = Delaunay {
            store: TetStore::with_capacity(n * 27 / 4 + 64),
            points: sorted,
            input_of: order,
            internal_of,
            ghosts: 0,
            duplicates: Vec::new(),
            last: NONE,
            rng: sort::Rng::new(0xC0FFEE),
            constrained_faces: 0,
            inserted: 4,
            track_new: false,
            destroyed_old: 0,
            scratch: Scratch::default(),
            vtet: vec![NONE; n],
            flipped: false,
            star_buf: Vec::new(),
            changed_at: Vec::new(),
            changes: 0,
        };
        d.make_first_tet(first);
        let parallel = rayon::current_num_threads() > 1;
        let starts = sort::brio_round_starts(n);
        for (k, &s) in starts.iter().enumerate() {
            let e = starts.get(k + 1).copied().unwrap_or(n);
            let round: Vec<u32> = (s as u32..e as u32)
                .filter(|i| !first.contains(i))
                .collect();
            let serial = if parallel && round.len() >= min_round.max(1) {
                let prev = if k > 0 {
                    starts[k - 1] as u32..s as u32
                } else {
                    0..0
                };
                d.insert_parallel(&round, &keys, prev)
            } else {
                round
            };
            for i in serial {
                if let Err(DelaunayError::Duplicate { index, of }) = d.insert_index(i, NONE) {
                    let dup = Duplicate {
                        index: d.ext(index),
                        of: d.ext(of),
                    };
                    d.duplicates.push(dup);
                }
            }
        }
        Ok(d)
    }

    /// Four affinely independent points, taken early in the insertion order.
    fn initial_simplex(pts: &[[f64; 3]], order: &[u32]) -> Option<[u32; 4]> {
        let a = order[0];
        let pa = pts[a as usize];
        let b = *order.iter().find(|&&i| pts[i as usize] != pa)?;
        let pb = pts[b as usize];
        let collinear = |p: &[f64; 3]| {
            let o2 = |i: usize, j: usize| {
                robust::orient2d(
                    robust::Coord { x: pa[i], y: pa[j] },
                    robust::Coord { x: pb[i], y: pb[j] },
                    robust::Coord { x: p[i], y: p[j] },
                )
            };
            o2(0, 1) == 0.0 && o2(1, 2) == 0.0 && o2(2, 0) == 0.0
        };
        let c = *order.iter().find(|&&i| !collinear(&pts[i as usize]))?;
        let pc = pts[c as usize];
        let d = *order
            .iter()
            .find(|&&i| predicates::orient(&pa, &pb, &pc, &pts[i as usize]) != 0.0)?;
        if predicates::orient(&pa, &pb, &pc, &pts[d as usize]) > 0.0 {
            Some([a, b, c, d])
        } else {
            Some([a, b, d, c])
        }
    }

    /// The first finite tet and its four ghosts.
    fn make_first_tet(&mut self, v: [u32; 4]) {
        let mut ids = [0u32; 5];
        let mut tets = [Tet::default(); 5];
        tets[0].v = v;
        for i in 0..4 {
            let mut g = v;
            g[i] = INF;
            // Swap two other vertices: the ghost sees the face from the other side.
            g.swap((i + 1) % 4, (i + 2) % 4);
            tets[i + 1].v = g;
        }
        for id in &mut ids {
            *id = self.store.alloc();
        }
        // Link faces with equal vertex sets (tiny, quadratic is fine).
        let face_key = |t: &Tet, f: usize| {
            let mut k: Vec<u32> = (0..4).filter(|&j| j != f).map(|j| t.v[j]).collect();
            k.sort_unstable();
            k
        };
        for a in 0..5 {
            for fa in 0..4 {
                for b in 0..5 {
                    if a == b {
                        continue;
                    }
                    for fb in 0..4 {
                        if face_key(&tets[a], fa) == face_key(&tets[b], fb) {
                            tets[a].n[fa] = ids[b] * 4 + fb as u32;
                        }
                    }
                }
            }
        }
        for k in 0..5 {
            self.store.tets[ids[k] as usize] = tets[k];
        }
        for &x in &v {
            self.vtet[x as usize] = ids[0];
        }
        self.ghosts = 4;
        self.last = ids[0];
    }

    /// Internal id → input index (INF stays INF).
    #[inline]
    fn ext(&self, v: u32) -> u32 {
        if v == INF {
            INF
        } else {
            self.input_of[v as usize]
        }
    }

    #[inline]
    fn ext4(&self, v: [u32; 4]) -> [u32; 4] {
        v.map(|x| self.ext(x))
    }

    /// Number of points given so far (inserted or not).
    pub fn num_points(&self) -> usize {
        self.points.len()
    }

    /// Coordinates of input point `v`.
    pub fn point(&self, v: u32) -> [f64; 3] {
        self.points[self.internal_of[v as usize] as usize]
    }

    /// Points that were rejected as duplicates, by [`Delaunay::new`] and later batches
    /// (a rejected single [`Delaunay::insert`] is not recorded: it returns the error).
    pub fn duplicates(&self) -> &[Duplicate] {
        &self.duplicates
    }

    /// Number of finite tets.
    pub fn num_tets(&self) -> usize {
        self.store.live - self.ghosts
    }

    /// Number of ghost tets = number of convex-hull faces.
    pub fn num_hull_faces(&self) -> usize {
        self.ghosts
    }

    /// Number of vertices in the triangulation.
    pub fn num_vertices(&self) -> usize {
        self.inserted
    }

    /// Bytes allocated by the triangulation's arrays (tets, flags, points).
    pub fn memory_bytes(&self) -> usize {
        self.store.bytes()
            + self.points.capacity() * std::mem::size_of::<[f64; 3]>()
            + (self.input_of.capacity() + self.internal_of.capacity()) * 4
    }

    /// Number of tet slots (live, ghost or free): every tet id is below it, so callers can
    /// keep per-tet data in a plain vector.
    pub fn slot_count(&self) -> usize {
        self.store.tets.len()
    }

    /// Ids of the live finite tets.
    pub fn tet_ids(&self) -> impl Iterator<Item = u32> + '_ {
        let s = &self.store;
        (0..s.tets.len() as u32).filter(move |&t| {
            s.flags[t as usize] & flag::DELETED == 0 && !s.tets[t as usize].is_ghost()
        })
    }

    /// Vertex indices of the live finite tets (positively oriented).
    pub fn tets(&self) -> impl Iterator<Item = [u32; 4]> + '_ {
        self.tet_ids()
            .map(move |t| self.ext4(self.store.tets[t as usize].v))
    }

    /// Ids of the live ghost tets (one per hull face; the hull face is opposite [`INF`]).
    pub fn ghost_ids(&self) -> impl Iterator<Item = u32> + '_ {
        let s = &self.store;
        (0..s.tets.len() as u32).filter(move |&t| {
            s.flags[t as usize] & flag::DELETED == 0 && s.tets[t as usize].is_ghost()
        })
    }

    /// Is `t` a live tet (finite or ghost)?
    pub fn is_live(&self, t: u32) -> bool {
        self.store.is_live(t)
    }

    /// Is `t` a ghost tet (has [`INF`] as a vertex)?
    pub fn is_ghost(&self, t: u32) -> bool {
        self.store.tets[t as usize].is_ghost()
    }

    /// Vertices of tet `t` (may contain [`INF`] for a ghost).
    pub fn tet(&self, t: u32) -> [u32; 4] {
        self.ext4(self.store.tets[t as usize].v)
    }

    /// The tet across face `face` of `t`, and the index of that face in it.
    pub fn neighbor(&self, t: u32, face: u8) -> (u32, u8) {
        let r = self.store.tets[t as usize].n[face as usize];
        (r >> 2, (r & 3) as u8)
    }

    /// Vertices of face `face` of `t`, ordered so that they appear counter-clockwise seen
    /// from outside `t` (`orient(face, v_face) > 0` is the convention of `t`).
    pub fn face_vertices(&self, t: u32, face: u8) -> [u32; 3] {
        const F: [[usize; 3]; 4] = [[2, 1, 3], [0, 2, 3], [1, 0, 3], [0, 1, 2]];
        let v = self.tet(t);
        let f = F[face as usize];
        [v[f[0]], v[f[1]], v[f[2]]]
    }

    /// The live tet and face whose face has vertex set `{a, b, c}` (linear scan; meant for
    /// tests and diagnostics).
    pub fn find_face(&self, a: u32, b: u32, c: u32) -> Option<(u32, u8)> {
        let mut key = [a, b, c].map(|x| self.internal_of[x as usize]);
        key.sort_unstable();
        for t in 0..self.store.tets.len() as u32 {
            if !self.store.is_live(t) {
                continue;
            }
            let v = self.store.tets[t as usize].v;
            for f in 0..4 {
                let mut k = [v[(f + 1) % 4], v[(f + 2) % 4], v[(f + 3) % 4]];
                k.sort_unstable();
                if k == key {
                    return Some((t, f as u8));
                }
            }
        }
        None
    }

    fn check_face(&self, t: u32, face: u8) -> Result<(), DelaunayError> {
        if face > 3 || !self.store.is_live(t) {
            return Err(DelaunayError::InvalidFace { tet: t, face });
        }
        Ok(())
    }

    /// Mark face `face` of tet `t` (and the same face of its neighbour) constrained: no later
    /// insertion's cavity crosses it, so the face survives every insertion (a point exactly on
    /// it is refused with [`DelaunayError::OnConstrainedFace`]).
    pub fn set_constrained(&mut self, t: u32, face: u8, on: bool) -> Result<(), DelaunayError> {
        self.check_face(t, face)?;
        let (u, g) = self.neighbor(t, face);
        let was = self.is_constrained(t, face);
        for (x, f) in [(t, face), (u, g)] {
            let fl = &mut self.store.flags[x as usize];
            if on {
                *fl |= 1 << f;
            } else {
                *fl &= !(1 << f);
            }
        }
        if was != on {
            let tet = self.store.tets[t as usize].v;
            let now = self.next_change();
            for k in (0..4).filter(|&k| k != face as usize) {
                self.stamp(tet[k], now);
            }
        }
        match (was, on) {
            (false, true) => self.constrained_faces += 1,
            (true, false) => self.constrained_faces -= 1,
            _ => {}
        }
        Ok(())
    }

    /// The count of changes made so far (tets made, points moved, faces constrained or
    /// freed): a moment to compare with in [`Delaunay::unchanged_since`].
    pub fn changes(&self) -> u64 {
        self.changes
    }

    /// Whether the live tet `t` and its surroundings (the tets around each of its edges and
    /// across each of its faces, their points and constrained faces) are as they were when
    /// [`Delaunay::changes`] returned `at`. A slot recycled since then holds a newer tet, whose
    /// vertices are stamped newer: it answers no.
    pub fn unchanged_since(&self, t: u32, at: u64) -> bool {
        self.store.tets[t as usize]
            .v
            .iter()
            .all(|&x| x == INF || self.changed_at.get(x as usize).is_none_or(|&c| c <= at))
    }

    /// Start a change: the count it is stamped with.
    pub(super) fn next_change(&mut self) -> u64 {
        self.changes += 1;
        self.changes
    }

    /// Stamp internal vertex `x` (not `INF`) as changed at `now`.
    #[inline]
    pub(super) fn stamp(&mut self, x: u32, now: u64) {
        if x == INF {
            return;
        }
        if self.changed_at.len() <= x as usize {
            self.changed_at
                .resize(self.points.len().max(x as usize + 1), 0);
        }
        self.changed_at[x as usize] = now;
    }

    /// Is face `face` of `t` constrained?
    pub fn is_constrained(&self, t: u32, face: u8) -> bool {
        self.store.flags[t as usize] & (1 << face) != 0
    }

    /// Locate `p` starting from tet `hint` (any live tet id, or `None` for the last created).
    pub fn locate(&mut self, p: [f64; 3], hint: Option<u32>) -> Location {
        match self.walk(&p, hint.unwrap_or(NONE)) {
            Location::Vertex(v) => Location::Vertex(self.ext(v)),
            other => other,
        }
    }

    /// Insert one point; `hint` is a tet near it (or `None`).
    pub fn insert(
        &mut self,
        p: [f64; 3],
        hint: Option<u32>,
    ) -> Result<InsertOutcome, DelaunayError> {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(DelaunayError::NonFinite {
                index: self.points.len(),
                point: p,
            });
        }
        if self.points.len() >= (u32::MAX / 8) as usize {
            return Err(DelaunayError::Capacity);
        }
        let i = self.points.len() as u32;
        self.push_point(p, i);
        match self.insert_index(i, hint.unwrap_or(NONE)) {
            Ok(destroyed) => Ok(InsertOutcome {
                vertex: i,
                created: self.scratch.new_ids.clone(),
                destroyed,
            }),
            Err(e) => {
                self.pop_point();
                Err(match e {
                    DelaunayError::Duplicate { index, of } => DelaunayError::Duplicate {
                        index,
                        of: self.ext(of),
                    },
                    e => e,
                })
            }
        }
    }

    /// Insert many points (BRIO/Hilbert order internally). Duplicates and points lying
    /// exactly on a constrained face are reported, not inserted; everything else is.
    pub fn insert_batch<P: Copy + Into<[f64; 3]>>(
        &mut self,
        points: &[P],
    ) -> Result<BatchOutcome, DelaunayError> {
        let base = self.points.len();
        for (k, &p) in points.iter().enumerate() {
            let p: [f64; 3] = p.into();
            if !p.iter().all(|c| c.is_finite()) {
                return Err(DelaunayError::NonFinite {
                    index: base + k,
                    point: p,
                });
            }
        }
        if base + points.len() >= (u32::MAX / 8) as usize {
            return Err(DelaunayError::Capacity);
        }
        let batch: Vec<[f64; 3]> = points.iter().map(|&p| p.into()).collect();
        let order = sort::brio_order(&batch, base as u64 + 1);
        self.internal_of.resize(base + batch.len(), 0);
        for &k in &order {
            let internal = self.points.len() as u32;
            self.points.push(batch[k as usize]);
            self.input_of.push(base as u32 + k);
            self.internal_of[base + k as usize] = internal;
        }
        let mut out = BatchOutcome {
            vertices: (base as u32..(base + points.len()) as u32).collect(),
            ..Default::default()
        };
        self.track_new = true;
        self.destroyed_old = 0;
        let mut created = Vec::new();
        let mut result = Ok(());
        for i in base as u32..(base + batch.len()) as u32 {
            match self.insert_index(i, NONE) {
                Ok(_) => created.extend_from_slice(&self.scratch.new_ids),
                Err(DelaunayError::Duplicate { index, of }) => {
                    let dup = Duplicate {
                        index: self.ext(index),
                        of: self.ext(of),
                    };
                    out.duplicates.push(dup);
                    self.duplicates.push(dup);
                }
                Err(
                    DelaunayError::OnConstrainedFace { index, .. }
                    | DelaunayError::ConstraintBlocksHull { index },
                ) => {
                    out.on_constrained_face.push(self.ext(index));
                }
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
        }
        self.track_new = false;
        created.sort_unstable();
        created.dedup();
        created.retain(|&t| self.store.is_live(t) && self.store.flags[t as usize] & flag::NEW != 0);
        for &t in &created {
            self.store.flags[t as usize] &= !flag::NEW;
        }
        out.created = created;
        out.destroyed = self.destroyed_old;
        result.map(|_| out)
    }

    /// Undo the last [`Delaunay::push_point`] (a refused insertion).
    fn pop_point(&mut self) {
        self.points.pop();
        self.input_of.pop();
        self.internal_of.pop();
        self.vtet.truncate(self.points.len());
        self.changed_at.truncate(self.points.len());
    }

    fn push_point(&mut self, p: [f64; 3], input: u32) {
        let internal = self.points.len() as u32;
        self.points.push(p);
        self.input_of.push(input);
        if self.internal_of.len() <= input as usize {
            self.internal_of.resize(input as usize + 1, 0);
        }
        self.internal_of[input as usize] = internal;
    }

    /// Run the full validity check, including local Delaunayhood of every unconstrained
    /// interior face (see [`CheckReport`] and [`CheckError`]).
    pub fn check(&self) -> Result<CheckReport, CheckError> {
        checker::check(self, true)
    }

    /// The validity check without the Delaunay criterion: for triangulations where constrained
    /// faces have blocked cavities, so some unconstrained faces need not be locally Delaunay.
    pub fn check_valid(&self) -> Result<CheckReport, CheckError> {
        checker::check(self, false)
    }
}
