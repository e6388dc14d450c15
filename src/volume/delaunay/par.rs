//! Parallel insertion for the initial triangulation of a point set.
//!
//! The scheme is the one HXT describes (Marot, Pellerin, Remacle 2019): space is divided among
//! the threads by ranges of the Hilbert key, and a thread may only change what lies entirely
//! in its own range. There are no locks and no per-tet owner word; ownership follows from the
//! vertices alone:
//!
//! * every vertex carries the label of the key range it falls in (`part`); [`INF`] counts as
//!   belonging to every range;
//! * a tet is *owned* by thread `j` when all its vertices are labelled `j` (a tet has at least
//!   three finite vertices, so at most one thread owns it), and so is a face;
//! * thread `j` deletes only tets it owns, creates tets only from faces it owns, writes the
//!   neighbour slot of a face only when it owns the face, and marks (VISITED) only tets
//!   across a face it owns.
//!
//! A tet `u` across a face owned by `j` shares three `j`-labelled vertices with it, and each
//! other face of `u` shares two of them; so no other thread can own `u` or any of its faces,
//! nor reach it across a face it owns: `u` is stable while `j` reads it. The walk therefore
//! only steps into owned tets, and the cavity search only reads tets across owned faces; when
//! the walk would leave the owned region, or a tet in conflict is not owned, the insertion is
//! abandoned before anything was written (only transient flags are cleared) and the point is
//! *deferred*. Deferred points get further passes with the key ranges shifted by half a range
//! (so the old frontiers fall inside a range), then whatever is left is inserted serially.
//!
//! The threads share the tet, flag and vertex-hint arrays through `storage::SharedTets`, where
//! every access is one relaxed atomic load or store of one word: the discipline above is what
//! makes the triangulation right, and no slip in it could make the program unsound; par.rs
//! itself has no unsafe code.
//!
//! The result is exactly the serial result: internal vertex ids (which fix the symbolic
//! perturbation) are assigned by the BRIO order before any insertion, so the triangulation
//! is the unique Delaunay triangulation of the perturbed points whatever the insertion order.
//!
//! Slots: each pass appends a region of fresh slots sized for its points; threads take blocks
//! of it through an atomic cursor and recycle their own deleted tets. A thread that finds the
//! region exhausted stops and leaves its remaining points to the next pass. Unused slots join
//! the free list afterwards and the unused tail is cut off, so memory stays what the serial
//! kernel uses.
//!
//! With debug logging on (`tetrafoil --verbose`), each pass logs its workers' times and how
//! many points it deferred (to tune and to see the frontier cost).

use std::sync::atomic::{AtomicUsize, Ordering, Ordering::Relaxed};

use rayon::prelude::*;

use super::predicates::{in_sphere_perturbed, orient_replaced};
use super::sort::Rng;
use super::storage::{flag, SharedTets, Tet, INF, NONE};
use super::walk::visibility_walk;
use super::{BFace, Delaunay, Duplicate, Location, Scratch};

/// Fresh slots handed to a thread at a time.
const BLOCK: usize = 512;
/// Fresh slots per point reserved for a pass (a uniform point adds about 6.7 tets; a thread
/// that runs short stops and the next pass takes its rest).
const SLOTS_PER_POINT: f64 = 6.8;

/// The triangulation as the threads see it.
struct Shared<'a> {
    /// Tets, flags and vertex hints, read and written by all threads (one atomic word at a
    /// time; which thread may change what is the ownership discipline of the module docs).
    store: SharedTets<'a>,
    points: &'a [[f64; 3]],
    part: &'a [u8],
    /// The pass's pending points (internal ids).
    pending: &'a [u32],
    /// Hilbert keys by internal id, and the previous BRIO round (ascending keys): a walk
    /// that fails restarts next to the previous round's vertex nearest on the curve.
    keys: &'a [u64],
    prev: std::ops::Range<u32>,
    cursor: AtomicUsize,
    region_end: usize,
}

/// Why one parallel insertion did not happen.
enum Skip {
    /// The walk or the cavity reached a tet this thread does not own.
    Foreign,
    /// No fresh slots left in this pass.
    Full,
    /// The point equals this (internal) vertex.
    Duplicate(u32),
}

/// One thread's state and results for a pass.
struct Worker<'a> {
    sh: &'a Shared<'a>,
    me: u8,
    /// Runs of consecutive pending points (indices into the pass's list), each with a start
    /// tet found before the pass (or `NONE`).
    segments: Vec<(std::ops::Range<usize>, u32)>,
    sc: Scratch,
    rng: Rng,
    out: Out,
}

/// What a worker hands back.
#[derive(Default)]
struct Out {
    /// Recycled slots not reused (and, after the run, the rest of the fresh block).
    free: Vec<u32>,
    block: std::ops::Range<usize>,
    /// Where the walk starts: the last tet created or a segment's start tet; owned by this
    /// worker, so still live at the end (or `NONE`).
    last: u32,
    ghosts: isize,
    inserted: usize,
    deferred: Vec<u32>,
    duplicates: Vec<(u32, u32)>,
    /// Points deferred because the walk left the owned region (diagnostics).
    walk_fails: usize,
}

impl<'a> Worker<'a> {
    #[inline(always)]
    fn tet(&self, t: u32) -> Tet {
        self.sh.store.get(t)
    }
    #[inline(always)]
    fn flag(&self, t: u32) -> u8 {
        self.sh.store.flags[t as usize].load(Relaxed)
    }
    #[inline(always)]
    fn set_flag(&self, t: u32, f: u8) {
        self.sh.store.flags[t as usize].store(f, Relaxed)
    }
    #[inline(always)]
    fn mine(&self, v: u32) -> bool {
        v == INF || self.sh.part[v as usize] == self.me
    }
    fn run(mut self) -> Out {
        let segments = std::mem::take(&mut self.segments);
        let mut full = false;
        for (range, start) in segments {
            // The start tet was ours when found, so only we can have deleted it since (then
            // the walk goes on from our last tet, which is always live).
            if start != NONE && self.flag(start) & flag::DELETED == 0 {
                self.out.last = start;
            }
            for &pi in &self.sh.pending[range] {
                if full || self.out.last == NONE {
                    self.out.deferred.push(pi);
                    continue;
                }
                match self.insert(pi) {
                    Ok(()) => {}
                    Err(Skip::Duplicate(of)) => self.out.duplicates.push((pi, of)),
                    Err(Skip::Foreign) => self.out.deferred.push(pi),
                    Err(Skip::Full) => {
                        full = true;
                        self.out.deferred.push(pi);
                    }
                }
            }
        }
        self.out
    }

    /// The visibility walk of `walk.rs`, confined to owned tets: `None` when it would leave
    /// them. (Face f of an owned tet is ours, so the tet beyond it is stable while we read
    /// it; the walk steps in only if that tet is ours too.)
    fn walk(&mut self, p: &[f64; 3]) -> Option<Location> {
        let mut rng = self.rng.clone();
        let found = visibility_walk(
            self.sh.points,
            self.out.last,
            p,
            &mut rng,
            |t| self.tet(t),
            |u, from| self.mine(u.v[from]),
        );
        self.rng = rng;
        found
    }

    /// An owned tet at a vertex of the previous round next to `pi` on the Hilbert curve
    /// (so near it in space), to restart a walk that ran out of owned tets.
    fn restart_tet(&self, pi: u32) -> Option<u32> {
        let sh = self.sh;
        let (a, b) = (sh.prev.start as usize, sh.prev.end as usize);
        if a >= b {
            return None;
        }
        let key = sh.keys[pi as usize];
        let at = a + sh.keys[a..b].partition_point(|&k| k < key);
        [at, at.wrapping_sub(1), at + 1, at.wrapping_sub(2)]
            .into_iter()
            .filter(|&x| x >= a && x < b)
            .find_map(|x| {
                if sh.part[x] != self.me {
                    return None;
                }
                // Only the owner of x writes its entry.
                let t = sh.store.vtet[x].load(Relaxed);
                // The tet has x, so nobody else changes its vertices; use it if all are ours.
                let ours = |t| sh.store.vertices(t).iter().all(|&v| self.mine(v));
                (t != NONE && ours(t)).then_some(t)
            })
    }

    /// Conflict test, as `Delaunay::conflict`.
    #[inline]
    fn conflict(&self, t: u32, pi: u32, p: &[f64; 3]) -> bool {
        let (pts, store) = (self.sh.points, &self.sh.store);
        let v = store.vertices(t);
        match v.iter().position(|&x| x == INF) {
            None => in_sphere_perturbed(pts, &v, pi, p),
            Some(k) => {
                let o = orient_replaced(pts, &v, k, p);
                if o != 0.0 {
                    o > 0.0
                } else {
                    let behind = store.neighbour(t, k) >> 2;
                    in_sphere_perturbed(pts, &store.vertices(behind), pi, p)
                }
            }
        }
    }

    fn rollback(&self) {
        for &t in self.sc.cavity.iter().chain(&self.sc.touched) {
            self.set_flag(t, self.flag(t) & !(flag::IN_CAVITY | flag::VISITED));
        }
    }

    /// A slot for a new tet: a recycled one, else the current fresh block, else a new block.
    fn reserve(&mut self, need: usize) -> bool {
        let o = &mut self.out;
        while o.free.len() + o.block.len() < need {
            let s = self.sh.cursor.fetch_add(BLOCK, Ordering::Relaxed);
            if s >= self.sh.region_end {
                return false;
            }
            o.free.extend(o.block.clone().map(|x| x as u32));
            o.block = s..(s + BLOCK).min(self.sh.region_end);
        }
        true
    }

    fn alloc(&mut self) -> u32 {
        if let Some(t) = self.out.free.pop() {
            t
        } else {
            self.out.block.next().expect("reserved") as u32
        }
    }

    /// Bowyer–Watson insertion of `pi` using only owned tets (as `insert_at` without
    /// constraints, flips or batch tracking, which the initial triangulation never has).
    fn insert(&mut self, pi: u32) -> Result<(), Skip> {
        let p = self.sh.points[pi as usize];
        if self.sh.part[pi as usize] != self.me {
            return Err(Skip::Foreign);
        }
        let mut found = self.walk(&p);
        if found.is_none() {
            if let Some(t) = self.restart_tet(pi) {
                self.out.last = t;
                found = self.walk(&p);
            }
        }
        let start = match found {
            None => {
                self.out.walk_fails += 1;
                return Err(Skip::Foreign);
            }
            Some(Location::Vertex(of)) => return Err(Skip::Duplicate(of)),
            Some(Location::Tet(t) | Location::Outside(t)) => t,
        };
        let mut sc = std::mem::take(&mut self.sc);
        sc.cavity.clear();
        sc.touched.clear();
        sc.boundary.clear();
        sc.new_ids.clear();
        self.sc = sc;

        // 1. Conflict region, abandoned at the first tet in conflict that is not ours.
        self.set_flag(start, self.flag(start) | flag::IN_CAVITY);
        self.sc.cavity.push(start);
        let mut i = 0;
        while i < self.sc.cavity.len() {
            let t = self.sc.cavity[i];
            i += 1;
            let tet = self.tet(t);
            for (f, &nr) in tet.n.iter().enumerate() {
                let u = nr >> 2;
                let fu = self.flag(u);
                if fu & flag::IN_CAVITY != 0 {
                    continue;
                }
                if fu & flag::VISITED == 0 {
                    if self.conflict(u, pi, &p) {
                        let far = self.sh.store.vertices(u)[(nr & 3) as usize];
                        if !self.mine(far) {
                            self.rollback();
                            return Err(Skip::Foreign);
                        }
                        self.set_flag(u, fu | flag::IN_CAVITY);
                        self.sc.cavity.push(u);
                        for g in 0..4 {
                            self.sh.store.prefetch(self.sh.store.neighbour(u, g) >> 2);
                        }
                        continue;
                    }
                    self.set_flag(u, fu | flag::VISITED);
                    self.sc.touched.push(u);
                }
                self.sc.boundary.push(BFace::new(&tet, f, pi, false));
            }
        }
        let nd = self.sc.cavity.len();
        let nb = self.sc.boundary.len();
        if !self.reserve(nb.saturating_sub(nd)) {
            self.rollback();
            return Err(Skip::Full);
        }
        for k in 0..self.sc.touched.len() {
            let u = self.sc.touched[k];
            self.set_flag(u, self.flag(u) & !flag::VISITED);
        }

        // 2. Slots: the cavity's first, then fresh ones.
        for k in 0..nd {
            if self.sh.store.vertices(self.sc.cavity[k]).contains(&INF) {
                self.out.ghosts -= 1;
            }
        }
        for k in 0..nb {
            let id = if k < nd {
                self.sc.cavity[k]
            } else {
                self.alloc()
            };
            self.sc.new_ids.push(id);
        }
        for k in nb..nd {
            let t = self.sc.cavity[k];
            self.set_flag(t, flag::DELETED);
            self.out.free.push(t);
        }

        // 3. Write and link the new tets (same edge table as `insert_at`).
        let mut sc = std::mem::take(&mut self.sc);
        let shift = sc.table.start(nb);
        for k in 0..nb {
            let b = sc.boundary[k];
            let id = sc.new_ids[k];
            let f = b.face as usize;
            let store = &self.sh.store;
            // The new tet is put together here and stored once (its faces still waiting for
            // a partner are linked when the partner comes).
            let mut new = Tet {
                v: b.v,
                n: [NONE; 4],
            };
            new.n[f] = b.outer;
            store.link(b.outer, id * 4 + f as u32);
            self.set_flag(id, 0);
            if b.v.contains(&INF) {
                self.out.ghosts += 1;
            }
            for &x in &b.v {
                if x != INF {
                    // x is labelled ours, and only the owner writes its entry.
                    store.vtet[x as usize].store(id, Relaxed);
                }
            }
            sc.table.offer(&b.v, f, id, shift, |g, other| {
                new.n[g] = other;
                store.link(other, id * 4 + g as u32);
            });
            store.set(id, new);
        }
        self.out.last = sc.new_ids[nb - 1];
        self.sc = sc;
        self.out.inserted += 1;
        Ok(())
    }
}

/// A BRIO round being inserted in parallel.
struct Round<'a> {
    /// Its points (internal ids), ascending keys.
    ids: &'a [u32],
    /// The previous round's internal ids.
    prev: std::ops::Range<u32>,
    /// Hilbert key by internal id.
    keys: &'a [u64],
    threads: usize,
}

impl Delaunay {
    /// Insert the points `ids` (internal ids, ascending Hilbert `keys` within the round) on
    /// the current rayon pool; returns the points left for serial insertion (in key order).
    pub(super) fn insert_parallel(
        &mut self,
        ids: &[u32],
        keys: &[u64],
        prev: std::ops::Range<u32>,
    ) -> Vec<u32> {
        debug_assert!(self.constrained_faces == 0 && !self.flipped && !self.track_new);
        let threads = rayon::current_num_threads().clamp(1, 255);
        let mut pending: Vec<u32> = ids.to_vec();
        let mut part = vec![0u8; self.points.len()];
        let mut pass = 0usize;
        while pending.len() >= 64 * threads && threads > 1 {
            let before = pending.len();
            let round = Round {
                ids,
                prev: prev.clone(),
                keys,
                threads,
            };
            pending = self.parallel_pass(&round, &pending, pass, &mut part);
            pass += 1;
            // Two passes: what the second leaves lies where both passes' frontiers meet
            // (with Hilbert ranges these are pieces of the same central planes, so further
            // shifts gain little); it is a small share and goes to the serial insertion.
            if pending.len() * 4 > before * 3 || pass >= 2 {
                break;
            }
        }
        pending
    }

    fn parallel_pass(
        &mut self,
        round: &Round,
        pending: &[u32],
        pass: usize,
        part: &mut [u8],
    ) -> Vec<u32> {
        let (keys, threads) = (round.keys, round.threads);
        let prev = round.prev.clone();
        let round = round.ids;
        let m = pending.len();
        // Key range boundaries: equal shares of the whole round, shifted from pass to pass by
        // a fraction of a share (0, 1/2, 1/4, 3/4, 1/8, …) so that each pass's frontiers cross
        // the earlier ones' instead of coinciding (ranges wrap around the curve's end).
        let offset = (pass as u32).reverse_bits() as f64 / 4_294_967_296.0;
        let r = round.len();
        let bounds: Vec<u64> = (0..threads)
            .map(|j| {
                if j == 0 && offset == 0.0 {
                    0
                } else {
                    let at = ((j as f64 + offset) / threads as f64 * r as f64) as usize;
                    keys[round[at.min(r - 1)] as usize]
                }
            })
            .collect();
        let label = |key: u64| -> u8 {
            let c = bounds.partition_point(|&b| b <= key);
            if c == 0 {
                (threads - 1) as u8
            } else {
                (c - 1) as u8
            }
        };
        let nv = part.len();
        part.par_iter_mut()
            .zip(&keys[..nv])
            .with_min_len(8192)
            .for_each(|(l, &k)| *l = label(k));

        // Segments: maximal runs of pending points with the same label, each with a start
        // tet found now (serially) by walking to one of its first points.
        let mut segments: Vec<Vec<(std::ops::Range<usize>, u32)>> = vec![Vec::new(); threads];
        let mut s = 0;
        while s < m {
            let j = part[pending[s] as usize];
            let mut e = s + 1;
            while e < m && part[pending[e] as usize] == j {
                e += 1;
            }
            let mut start = NONE;
            let mut probe = 0usize;
            while s + probe < e {
                let p = self.points[pending[s + probe] as usize];
                let t = match self.walk(&p, NONE) {
                    Location::Tet(t) | Location::Outside(t) => t,
                    Location::Vertex(v) => self.vtet[v as usize],
                };
                if t != NONE
                    && self.store.tets[t as usize]
                        .v
                        .iter()
                        .all(|&v| v == INF || part[v as usize] == j)
                {
                    start = t;
                    break;
                }
                probe = if probe == 0 { 1 } else { probe * 4 };
            }
            segments[j as usize].push((s..e, start));
            s = e;
        }

        // Fresh slots for the pass.
        let old_len = self.store.tets.len();
        let region = (m as f64 * SLOTS_PER_POINT) as usize + threads * BLOCK;
        // Filled in parallel: the first touch of these pages (and the kernel's zeroing of
        // them) is then shared by the threads instead of preceding the pass. Exact
        // reservation: memory stays what the serial kernel uses.
        fn grow<T: Copy + Send + Sync>(v: &mut Vec<T>, by: usize, x: T) {
            v.reserve_exact(by);
            v.par_extend(rayon::iter::repeat_n(x, by).with_min_len(1 << 14));
        }
        grow(&mut self.store.tets, region, Tet::default());
        grow(&mut self.store.flags, region, flag::DELETED);
        // The free list is handed out among the threads.
        let mut free: Vec<Vec<u32>> = vec![Vec::new(); threads];
        let mut k = 0;
        while self.store.free_head != NONE {
            let t = self.store.free_head;
            self.store.free_head = self.store.tets[t as usize].n[0];
            free[k % threads].push(t);
            k += 1;
        }

        let shared = Shared {
            store: self.store.shared(&mut self.vtet),
            points: &self.points,
            part,
            pending,
            keys,
            prev,
            cursor: AtomicUsize::new(old_len),
            region_end: old_len + region,
        };
        let workers: Vec<Worker> = segments
            .into_iter()
            .zip(free)
            .enumerate()
            .map(|(j, (segments, free))| Worker {
                sh: &shared,
                me: j as u8,
                segments,
                sc: Scratch::default(),
                rng: Rng::new(0xC0FFEE + j as u64 + 7 * pass as u64),
                out: Out {
                    free,
                    last: NONE,
                    ..Default::default()
                },
            })
            .collect();
        let debug = log::log_enabled!(log::Level::Debug);
        let t_pass = std::time::Instant::now();
        let done: Vec<Out> = workers
            .into_par_iter()
            .with_max_len(1)
            .map(|w| {
                let t0 = std::time::Instant::now();
                let me = w.me;
                let out = w.run();
                if debug {
                    log::debug!(
                        "  worker {me} on {:?}: {} inserted in {:.3} s",
                        rayon::current_thread_index(),
                        out.inserted,
                        t0.elapsed().as_secs_f64()
                    );
                }
                out
            })
            .collect();
        let used_end = shared.cursor.load(Ordering::Relaxed).min(old_len + region);

        // Merge: counters, duplicates, slots.
        let mut deferred = Vec::new();
        let mut spare = Vec::new();
        let mut last = NONE;
        let mut walk_fails = 0;
        for w in done {
            walk_fails += w.walk_fails;
            self.ghosts = (self.ghosts as isize + w.ghosts) as usize;
            self.inserted += w.inserted;
            for (index, of) in w.duplicates {
                let dup = Duplicate {
                    index: self.ext(index),
                    of: self.ext(of),
                };
                self.duplicates.push(dup);
            }
            deferred.extend(w.deferred);
            spare.extend(w.free);
            spare.extend(w.block.map(|x| x as u32));
            if w.last != NONE {
                last = w.last;
            }
        }
        self.store.tets.truncate(used_end);
        self.store.flags.truncate(used_end);
        spare.retain(|&t| (t as usize) < used_end);
        spare.sort_unstable_by(|a, b| b.cmp(a));
        for &t in &spare {
            self.store.flags[t as usize] = flag::DELETED;
            self.store.tets[t as usize].n[0] = self.store.free_head;
            self.store.free_head = t;
        }
        // Live count: the slots not deleted (fresh and recycled slots start deleted).
        self.store.live = self
            .store
            .flags
            .par_iter()
            .with_min_len(1 << 16)
            .filter(|&&f| f & flag::DELETED == 0)
            .count();
        if last != NONE {
            self.last = last;
        }
        deferred.sort_unstable_by_key(|&i| (keys[i as usize], i));
        if debug {
            log::debug!("  pass wall {:.3} s", t_pass.elapsed().as_secs_f64());
            log::debug!("pass {pass}: {m} points, {} deferred ({walk_fails} by the walk), slots {} of {region}", deferred.len(), used_end - old_len);
        }
        deferred
    }
}
