//! Local re-tessellations: 2-3 and 3-2 flips and general edge removal (seed paper, "Face/edge
//! swapping"), plus the vertex-star and edge-ring queries they need.
//!
//! Everything goes through one primitive, [`Delaunay::retessellate`]: replace a set of tets
//! by another set that tiles the same polyhedron. It matches the new tets' faces with each
//! other and with the old region's outer faces by vertex sets, checks that the match is
//! exact and that every new finite tet is positively oriented (exact `orient`) *before*
//! touching the storage, then relinks. Adjacency, ghost count, constrained bits of the outer
//! faces and the vertex→tet hints are therefore right by construction, whatever the flip.
//!
//! Edge removal (Shewchuk, "Two discrete optimization algorithms for the topological
//! improvement of tetrahedral meshes"): the `n` tets around edge `ab` have a ring of vertices
//! `c_0 … c_{n-1}`; removing `ab` means choosing a triangulation of that ring polygon and
//! joining every triangle to `a` and to `b`. The triangulation maximising the minimum tet
//! score is found by Klincsek's O(n³) dynamic program over sub-chains `c_i … c_j`. A triangle
//! is usable only when both of its tets are positively oriented (exact), so the result is
//! always valid. A hull edge has [`INF`] in its ring; it can go only when its two hull faces
//! are coplanar, and then the ring triangle holding `INF` must be the ear `(c_0, c_k, INF)`
//! (any other choice would make a hull face out of an interior triangle), which leaves the
//! finite chain `c_0 … c_k` to the dynamic program.

use super::predicates::orient;
use super::storage::{flag, Tet, INF, NONE};
use super::Delaunay;

/// Largest number of tets around an edge that [`Delaunay::remove_edge`] considers (the
/// dynamic program is cubic in it; the paper stops at 7 for quality swaps, recovery uses more).
pub const MAX_RING: usize = 12;

/// A tet quality of four points (only called on positively oriented tets).
pub type Score<'a> = dyn Fn(&[f64; 3], &[f64; 3], &[f64; 3], &[f64; 3]) -> f64 + 'a;

/// A function that can serve as a [`Score`]: what the public edge removals take (by value).
pub trait TetScore: Fn(&[f64; 3], &[f64; 3], &[f64; 3], &[f64; 3]) -> f64 {}
impl<F: Fn(&[f64; 3], &[f64; 3], &[f64; 3], &[f64; 3]) -> f64> TetScore for F {}

/// What an edge removal gives: the created tets, or why nothing changed.
pub type Removal = Result<Vec<u32>, FlipError>;

/// Why a flip was refused (the triangulation is unchanged).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FlipError {
    #[error("edge {0}-{1} is not in the triangulation")]
    NoEdge(u32, u32),
    #[error("tet {tet} face {face} is not a live tet face")]
    InvalidFace { tet: u32, face: u8 },
    #[error("a face that would disappear is constrained")]
    Constrained,
    #[error("the flip involves hull (ghost) tets")]
    Ghost,
    #[error("no valid re-tessellation: some new tet would not be positively oriented")]
    Invalid,
    #[error("{0} tets around the edge (3 needed for a 3-2 flip, at most MAX_RING for removal)")]
    Degree(usize),
    #[error("no re-tessellation beats the present one")]
    NotBetter,
}

/// What an edge removal must keep in its new tessellation (input indices).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// Any triangulation of the ring.
    Any,
    /// The ring triangulation must contain this diagonal (the new edge must exist).
    Edge(u32, u32),
    /// The ring triangulation must contain this triangle (the new face must exist).
    Triangle(u32, u32, u32),
}

/// Is the permutation `p` of `0..4` even?
#[inline]
fn even(p: [usize; 4]) -> bool {
    let mut inv = 0;
    for i in 0..4 {
        for j in i + 1..4 {
            if p[i] > p[j] {
                inv += 1;
            }
        }
    }
    inv % 2 == 0
}

/// The two positions of `0..4` other than `i` and `j`, increasing.
#[inline]
fn others(i: usize, j: usize) -> (usize, usize) {
    let mut r = (0..4).filter(|&k| k != i && k != j);
    (r.next().unwrap_or(0), r.next().unwrap_or(0))
}

/// Sorted vertex triple of face `f` of `v`.
#[inline]
pub(super) fn face_key(v: &[u32; 4], f: usize) -> [u32; 3] {
    let mut k = [v[(f + 1) % 4], v[(f + 2) % 4], v[(f + 3) % 4]];
    k.sort_unstable();
    k
}

/// Triangulation of a polygon (ring order) maximising the minimum of `eval` over its
/// triangles (`eval` is `None` for an unusable triangle). Triangles are returned in ring
/// order. A 2-gon (an edge) has the empty triangulation with value +∞.
fn best_triangulation(
    poly: &[u32],
    eval: &mut dyn FnMut(u32, u32, u32) -> Option<f64>,
) -> Option<(f64, Vec<[u32; 3]>)> {
    let n = poly.len();
    if n < 2 {
        return None;
    }
    if n == 2 {
        return Some((f64::INFINITY, Vec::new()));
    }
    // best[i * n + j]: (value, apex k) for the sub-polygon c_i … c_j closed by c_j c_i.
    let mut best: Vec<Option<(f64, usize)>> = vec![None; n * n];
    for i in 0..n - 1 {
        best[i * n + i + 1] = Some((f64::INFINITY, 0));
    }
    for len in 2..n {
        for i in 0..n - len {
            let j = i + len;
            let mut choice: Option<(f64, usize)> = None;
            for k in i + 1..j {
                let (Some((l, _)), Some((r, _))) = (best[i * n + k], best[k * n + j]) else {
                    continue;
                };
                let Some(t) = eval(poly[i], poly[k], poly[j]) else {
                    continue;
                };
                let v = l.min(r).min(t);
                let better = match choice {
                    None => true,
                    Some((c, _)) => v > c,
                };
                if better {
                    choice = Some((v, k));
                }
            }
            best[i * n + j] = choice;
        }
    }
    let (value, _) = best[n - 1]?;
    let mut tris = Vec::with_capacity(n - 2);
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j - i < 2 {
            continue;
        }
        let (_, k) = best[i * n + j]?;
        tris.push([poly[i], poly[k], poly[j]]);
        stack.push((i, k));
        stack.push((k, j));
    }
    Some((value, tris))
}

impl Delaunay {
    /// A live tet having internal vertex `v`, from the hint array (a scan only if the hint
    /// were ever stale, which the kernel's bookkeeping rules out); `None` for a vertex that is
    /// not in the triangulation (never inserted, or removed by [`Delaunay::replace_star`]).
    pub(super) fn vertex_tet_int(&self, v: u32) -> Option<u32> {
        let t = self.vtet.get(v as usize).copied().unwrap_or(NONE);
        if t == NONE {
            return None;
        }
        if t != NONE && self.store.is_live(t) && self.store.tets[t as usize].v.contains(&v) {
            return Some(t);
        }
        debug_assert!(false, "stale vertex hint for {v}");
        (0..self.store.tets.len() as u32)
            .find(|&t| self.store.is_live(t) && self.store.tets[t as usize].v.contains(&v))
    }

    /// Breadth-first search of the star of internal vertex `v` (finite and ghost tets),
    /// stopping at the first tet for which `stop` holds (returned). The visited tets are left
    /// in `self.star_buf`.
    pub(super) fn star_search(
        &mut self,
        v: u32,
        stop: &mut dyn FnMut(&Tet) -> bool,
    ) -> Option<u32> {
        let mut out = std::mem::take(&mut self.star_buf);
        out.clear();
        let mut found = None;
        if let Some(t0) = self.vertex_tet_int(v) {
            self.store.flags[t0 as usize] |= flag::VISITED;
            out.push(t0);
            found = self
                .store
                .flood(&mut out, flag::VISITED, stop, |tet, _, f, _| tet.v[f] != v);
            for &t in &out {
                self.store.flags[t as usize] &= !flag::VISITED;
            }
        }
        self.star_buf = out;
        found
    }

    /// A tet having the edge of internal vertices `a`, `b`.
    pub(super) fn edge_tet_int(&mut self, a: u32, b: u32) -> Option<u32> {
        self.star_search(a, &mut |t: &Tet| t.v.contains(&b))
    }

    /// The tets around edge `ab` (internal ids) starting from `t0` (which has both), and the
    /// ring `c_i` such that `tets[i]` is `(a, b, c_i, c_{i+1})` up to an even permutation,
    /// i.e. with the orientation of the stored tet. `INF` may appear in the ring.
    pub(super) fn edge_ring_int(&self, t0: u32, a: u32, b: u32) -> (Vec<u32>, Vec<u32>) {
        let mut tets = Vec::with_capacity(8);
        let mut ring = Vec::with_capacity(8);
        let mut t = t0;
        loop {
            let tet = &self.store.tets[t as usize];
            let i = tet.v.iter().position(|&x| x == a).unwrap_or(0);
            let j = tet.v.iter().position(|&x| x == b).unwrap_or(0);
            let (k, l) = others(i, j);
            let (x, xpos) = if even([i, j, k, l]) {
                (tet.v[k], k)
            } else {
                (tet.v[l], l)
            };
            tets.push(t);
            ring.push(x);
            // Across the face opposite x: the tet (a, b, y, z).
            t = tet.n[xpos] >> 2;
            if t == t0 || tets.len() > 4096 {
                break;
            }
        }
        (tets, ring)
    }

    /// Replace the tets `old` by tets with the vertex lists `new` (internal ids), which must
    /// tile the same region: refused (nothing changed) unless every new face is matched
    /// exactly once — by another new tet or by an outer face of `old` — every outer face is
    /// used, no constrained face of `old` lies inside the region, and every new finite tet is
    /// positively oriented. Returns the new tet ids (recycling `old`'s slots).
    pub(super) fn retessellate(
        &mut self,
        old: &[u32],
        new: &[[u32; 4]],
    ) -> Result<Vec<u32>, FlipError> {
        const OUTER: u32 = 1 << 31;
        for v in new {
            if !v.contains(&INF) {
                let p = |i: usize| &self.points[v[i] as usize];
                if orient(p(0), p(1), p(2), p(3)) <= 0.0 {
                    return Err(FlipError::Invalid);
                }
            }
        }
        let mut outer: Vec<([u32; 3], u32, bool)> = Vec::with_capacity(old.len() * 2 + 2);
        for &t in old {
            let tet = &self.store.tets[t as usize];
            let fl = self.store.flags[t as usize];
            for f in 0..4 {
                let c = fl & (1 << f) != 0;
                if old.contains(&(tet.n[f] >> 2)) {
                    if c {
                        return Err(FlipError::Constrained);
                    }
                    continue;
                }
                outer.push((face_key(&tet.v, f), tet.n[f], c));
            }
        }
        outer.sort_unstable_by_key(|o| o.0);
        let mut faces: Vec<([u32; 3], u32)> = Vec::with_capacity(new.len() * 4);
        for (k, v) in new.iter().enumerate() {
            for f in 0..4 {
                faces.push((face_key(v, f), (k * 4 + f) as u32));
            }
        }
        faces.sort_unstable();
        let mut links = vec![NONE; new.len() * 4];
        let mut used = vec![false; outer.len()];
        let mut i = 0;
        while i < faces.len() {
            let key = faces[i].0;
            if i + 1 < faces.len() && faces[i + 1].0 == key {
                if i + 2 < faces.len() && faces[i + 2].0 == key {
                    return Err(FlipError::Invalid);
                }
                links[faces[i].1 as usize] = faces[i + 1].1;
                links[faces[i + 1].1 as usize] = faces[i].1;
                i += 2;
            } else {
                let j = outer
                    .binary_search_by_key(&key, |o| o.0)
                    .map_err(|_| FlipError::Invalid)?;
                if used[j] {
                    return Err(FlipError::Invalid);
                }
                used[j] = true;
                links[faces[i].1 as usize] = OUTER | j as u32;
                i += 1;
            }
        }
        if used.iter().any(|&u| !u) {
            return Err(FlipError::Invalid);
        }
        // Apply.
        for &t in old {
            if self.store.tets[t as usize].is_ghost() {
                self.ghosts -= 1;
            }
        }
        let ids: Vec<u32> = (0..new.len())
            .map(|k| {
                if k < old.len() {
                    old[k]
                } else {
                    self.store.alloc()
                }
            })
            .collect();
        for &t in old.iter().skip(new.len()) {
            self.store.free(t);
        }
        if self.vtet.len() < self.points.len() {
            self.vtet.resize(self.points.len(), NONE);
        }
        if self.changed_at.len() < self.points.len() {
            self.changed_at.resize(self.points.len(), 0);
        }
        let now = self.next_change();
        for (k, v) in new.iter().enumerate() {
            let id = ids[k];
            let mut fl = 0u8;
            let mut n = [0u32; 4];
            for (f, nf) in n.iter_mut().enumerate() {
                let l = links[k * 4 + f];
                if l & OUTER != 0 {
                    let (_, r, c) = outer[(l & !OUTER) as usize];
                    *nf = r;
                    self.store.tets[(r >> 2) as usize].n[(r & 3) as usize] = id * 4 + f as u32;
                    if c {
                        fl |= 1 << f;
                    }
                } else {
                    *nf = ids[(l >> 2) as usize] * 4 + (l & 3);
                }
            }
            self.store.tets[id as usize] = Tet { v: *v, n };
            self.store.flags[id as usize] = fl;
            if v.contains(&INF) {
                self.ghosts += 1;
            }
            for &x in v {
                if x != INF {
                    self.vtet[x as usize] = id;
                    self.changed_at[x as usize] = now;
                }
            }
        }
        self.last = ids[0];
        self.flipped = true;
        Ok(ids)
    }

    /// 2-3 flip on internal data; see [`Delaunay::flip23`].
    pub(super) fn flip23_int(&mut self, t: u32, face: u8) -> Result<[u32; 3], FlipError> {
        if face > 3 || !self.store.is_live(t) {
            return Err(FlipError::InvalidFace { tet: t, face });
        }
        if self.is_constrained(t, face) {
            return Err(FlipError::Constrained);
        }
        let tet = self.store.tets[t as usize];
        let r = tet.n[face as usize];
        let u = self.store.tets[(r >> 2) as usize];
        if tet.is_ghost() || u.is_ghost() {
            return Err(FlipError::Ghost);
        }
        let d = tet.v[face as usize];
        let e = u.v[(r & 3) as usize];
        // Ring of the new edge d-e: the face's vertices, in the direction making (d, e, x, y)
        // positive.
        let f: Vec<u32> = (0..4)
            .filter(|&i| i != face as usize)
            .map(|i| tet.v[i])
            .collect();
        let p = |x: u32| &self.points[x as usize];
        let mut ring = [f[0], f[1], f[2]];
        if orient(p(d), p(e), p(ring[0]), p(ring[1])) < 0.0 {
            ring.swap(1, 2);
        }
        let new: Vec<[u32; 4]> = (0..3).map(|i| [d, e, ring[i], ring[(i + 1) % 3]]).collect();
        let ids = self.retessellate(&[t, r >> 2], &new)?;
        Ok([ids[0], ids[1], ids[2]])
    }

    /// Edge removal on internal ids; see [`Delaunay::remove_edge`]. `keep` in internal ids.
    pub(super) fn remove_edge_int(
        &mut self,
        a: u32,
        b: u32,
        keep: Keep,
        score: &Score<'_>,
    ) -> Removal {
        self.remove_edge_at(None, a, b, keep, f64::NEG_INFINITY, score)
    }

    /// [`Delaunay::remove_edge_int`], refused with [`FlipError::NotBetter`] when (for
    /// `Keep::Any`) the best triangulation's minimum score is not above `better_than`. The
    /// ring is walked from tet `at` (which must have the edge), else from one found in `a`'s
    /// star.
    pub(super) fn remove_edge_at(
        &mut self,
        at: Option<u32>,
        a: u32,
        b: u32,
        keep: Keep,
        better_than: f64,
        score: &Score<'_>,
    ) -> Removal {
        let t0 = match at {
            Some(t) => t,
            None => self.edge_tet_int(a, b).unwrap_or(NONE),
        };
        if t0 == NONE
            || ![a, b]
                .iter()
                .all(|x| self.store.tets[t0 as usize].v.contains(x))
        {
            return Err(FlipError::NoEdge(self.ext(a), self.ext(b)));
        }
        let (tets, mut ring) = self.edge_ring_int(t0, a, b);
        let n = ring.len();
        if n > MAX_RING {
            return Err(FlipError::Degree(n));
        }
        // Faces around the edge disappear: none may be constrained.
        for &t in &tets {
            let tet = &self.store.tets[t as usize];
            for f in 0..4 {
                if tet.v[f] != a && tet.v[f] != b && self.is_constrained(t, f as u8) {
                    return Err(FlipError::Constrained);
                }
            }
        }
        let mut new: Vec<[u32; 4]> = Vec::with_capacity(2 * n);
        if let Some(pi) = ring.iter().position(|&x| x == INF) {
            ring.rotate_left(pi + 1); // INF last
            ring.pop();
            let k = ring.len() - 1;
            let pt = |x: u32| &self.points[x as usize];
            if k < 2 || orient(pt(a), pt(b), pt(ring[0]), pt(ring[k])) != 0.0 {
                return Err(FlipError::Invalid);
            }
            new.push([ring[0], ring[k], INF, b]);
            new.push([ring[k], ring[0], INF, a]);
        }
        let pts = &self.points;
        let mut eval = |x: u32, y: u32, z: u32| -> Option<f64> {
            let p = |v: u32| &pts[v as usize];
            if orient(p(x), p(y), p(z), p(b)) <= 0.0 || orient(p(y), p(x), p(z), p(a)) <= 0.0 {
                return None;
            }
            Some(score(p(x), p(y), p(z), p(b)).min(score(p(y), p(x), p(z), p(a))))
        };
        let pos = |x: u32| ring.iter().position(|&y| y == x);
        let tris = match keep {
            Keep::Any => match best_triangulation(&ring, &mut eval) {
                Some((value, _)) if value <= better_than => return Err(FlipError::NotBetter),
                other => other.map(|r| r.1),
            },
            Keep::Edge(u, v) => {
                let (Some(p), Some(q)) = (pos(u), pos(v)) else {
                    return Err(FlipError::Invalid);
                };
                let (p, q) = (p.min(q), p.max(q));
                let first = &ring[p..=q];
                let second: Vec<u32> = ring[q..].iter().chain(&ring[..=p]).copied().collect();
                match (
                    best_triangulation(first, &mut eval),
                    best_triangulation(&second, &mut eval),
                ) {
                    (Some((_, mut t1)), Some((_, t2))) => {
                        t1.extend(t2);
                        Some(t1)
                    }
                    _ => None,
                }
            }
            Keep::Triangle(u, v, w) => {
                let (Some(p), Some(q), Some(r)) = (pos(u), pos(v), pos(w)) else {
                    return Err(FlipError::Invalid);
                };
                let mut s = [p, q, r];
                s.sort_unstable();
                let [p, q, r] = s;
                let last: Vec<u32> = ring[r..].iter().chain(&ring[..=p]).copied().collect();
                let centre = eval(ring[p], ring[q], ring[r]);
                match (
                    centre,
                    best_triangulation(&ring[p..=q], &mut eval),
                    best_triangulation(&ring[q..=r], &mut eval),
                    best_triangulation(&last, &mut eval),
                ) {
                    (Some(_), Some((_, t1)), Some((_, t2)), Some((_, t3))) => {
                        let mut t = vec![[ring[p], ring[q], ring[r]]];
                        t.extend(t1);
                        t.extend(t2);
                        t.extend(t3);
                        Some(t)
                    }
                    _ => None,
                }
            }
        };
        let tris = tris.ok_or(FlipError::Invalid)?;
        for [x, y, z] in tris {
            new.push([x, y, z, b]);
            new.push([y, x, z, a]);
        }
        self.retessellate(&tets, &new)
    }

    // ----- public API (input indices) -----

    /// A live tet having vertex `v` (from the per-vertex hint; O(1)).
    pub fn vertex_tet(&self, v: u32) -> Option<u32> {
        self.vertex_tet_int(*self.internal_of.get(v as usize)?)
    }

    /// Every tet (finite and ghost) having vertex `v`: its star.
    pub fn tets_around_vertex(&mut self, v: u32) -> Vec<u32> {
        let Some(&vi) = self.internal_of.get(v as usize) else {
            return Vec::new();
        };
        self.star_search(vi, &mut |_| false);
        self.star_buf.clone()
    }

    /// A tet having edge `ab`, found by searching the star of `a`.
    pub fn edge_tet(&mut self, a: u32, b: u32) -> Option<u32> {
        let (ai, bi) = self.internal_pair(a, b);
        self.edge_tet_int(ai, bi)
    }

    /// Is `ab` an edge of the triangulation?
    pub fn has_edge(&mut self, a: u32, b: u32) -> bool {
        self.edge_tet(a, b).is_some()
    }

    /// The tets around edge `ab` in rotational order and the ring of vertices: tet `i` is
    /// `(a, b, ring[i], ring[i+1])` up to an even permutation (so, for a finite tet,
    /// `orient(a, b, ring[i], ring[i+1]) > 0`). The ring holds [`INF`] for a hull edge.
    pub fn tets_around_edge(&mut self, a: u32, b: u32) -> Option<(Vec<u32>, Vec<u32>)> {
        let (ai, bi) = self.internal_pair(a, b);
        let t0 = self.edge_tet_int(ai, bi)?;
        let (tets, ring) = self.edge_ring_int(t0, ai, bi);
        Some((tets, ring.into_iter().map(|x| self.ext(x)).collect()))
    }

    /// The tet and face index whose face is `{a, b, c}`, found around edge `ab` (no scan).
    pub fn find_face_near(&mut self, a: u32, b: u32, c: u32) -> Option<(u32, u8)> {
        let ci = *self.internal_of.get(c as usize)?;
        let (tets, _) = self.tets_around_edge(a, b)?;
        for t in tets {
            let tet = &self.store.tets[t as usize];
            if tet.v.contains(&ci) {
                // The face {a, b, c} is opposite the fourth vertex.
                let (ai, bi) = self.internal_pair(a, b);
                let f = (0..4).find(|&f| ![ai, bi, ci].contains(&tet.v[f]))?;
                return Some((t, f as u8));
            }
        }
        None
    }

    /// Internal ids of vertices `a` and `b`.
    fn internal_pair(&self, a: u32, b: u32) -> (u32, u32) {
        (self.internal_of[a as usize], self.internal_of[b as usize])
    }

    /// Move vertex `v` to `p`. The caller guarantees every tet around `v` stays positively
    /// oriented (e.g. by checking its star with exact `orient`).
    pub fn set_point(&mut self, v: u32, p: [f64; 3]) {
        let vi = self.internal_of[v as usize];
        self.points[vi as usize] = p;
        self.flipped = true;
        // Every tet with a vertex next to v may see its surroundings change shape.
        self.star_search(vi, &mut |_| false);
        let star = std::mem::take(&mut self.star_buf);
        let now = self.next_change();
        self.stamp(vi, now);
        for &t in &star {
            for x in self.store.tets[t as usize].v {
                self.stamp(x, now);
            }
        }
        self.star_buf = star;
    }

    /// 2-3 flip: tet `t` and its neighbour across face `face` become three tets around the
    /// edge joining their opposite vertices. Refused unless the union of the two is strictly
    /// convex across that edge (all three new tets positively oriented, exactly), neither is a
    /// ghost, and the face is not constrained.
    pub fn flip23(&mut self, t: u32, face: u8) -> Result<[u32; 3], FlipError> {
        self.flip23_int(t, face)
    }

    /// 3-2 flip: the three tets around edge `ab` become two sharing the face of the ring.
    pub fn flip32(&mut self, a: u32, b: u32) -> Result<[u32; 2], FlipError> {
        let (ai, bi) = self.internal_pair(a, b);
        let Some(t0) = self.edge_tet_int(ai, bi) else {
            return Err(FlipError::NoEdge(a, b));
        };
        let (_, ring) = self.edge_ring_int(t0, ai, bi);
        if ring.len() != 3 || ring.contains(&INF) {
            return Err(FlipError::Degree(ring.len()));
        }
        let ids = self.remove_edge_int(ai, bi, Keep::Any, &|_, _, _, _| 1.0)?;
        Ok([ids[0], ids[1]])
    }

    /// Remove edge `ab`: the `n ≤ MAX_RING` tets around it are replaced by the `2(n-2)` tets
    /// over the triangulation of their ring that maximises the minimum `score` (a quality of
    /// four points, called only on positively oriented tets). Refused if no triangulation
    /// gives only positively oriented tets, if a face around the edge is constrained, or for
    /// a hull edge whose two hull faces are not coplanar. Returns the created tets.
    pub fn remove_edge(&mut self, a: u32, b: u32, score: impl TetScore) -> Removal {
        self.remove_edge_with(a, b, Keep::Any, score)
    }

    /// [`Delaunay::remove_edge`] only when the new tets' minimum `score` is above `current`
    /// (the quality stages pass the ring's present minimum); otherwise
    /// [`FlipError::NotBetter`] and nothing changes. `at`: a tet having the edge, when the
    /// caller has one: the ring is then walked from it, with no search of a vertex's star (the
    /// swaps of a stretched mesh, whose vertices have large stars, try every edge of every
    /// poor tet).
    pub fn remove_edge_if_better(
        &mut self,
        at: Option<u32>,
        a: u32,
        b: u32,
        current: f64,
        score: impl TetScore,
    ) -> Removal {
        let (ai, bi) = self.internal_pair(a, b);
        self.remove_edge_at(at, ai, bi, Keep::Any, current, &score)
    }

    /// The tets around edge `ab` of tet `t` and the ring, as [`Delaunay::tets_around_edge`]
    /// gives them, walked from `t` (no search).
    pub fn tets_around_edge_of_tet(&self, t: u32, a: u32, b: u32) -> (Vec<u32>, Vec<u32>) {
        let (ai, bi) = self.internal_pair(a, b);
        let (tets, ring) = self.edge_ring_int(t, ai, bi);
        (tets, ring.into_iter().map(|x| self.ext(x)).collect())
    }

    /// [`Delaunay::remove_edge`] constrained to keep an edge or a triangle of the ring (used
    /// by boundary recovery to create a missing edge or face).
    pub fn remove_edge_with(
        &mut self,
        a: u32,
        b: u32,
        keep: Keep,
        score: impl TetScore,
    ) -> Removal {
        let m = |x: u32| self.internal_of[x as usize];
        let keep = match keep {
            Keep::Any => Keep::Any,
            Keep::Edge(u, v) => Keep::Edge(m(u), m(v)),
            Keep::Triangle(u, v, w) => Keep::Triangle(m(u), m(v), m(w)),
        };
        let (ai, bi) = (m(a), m(b));
        self.remove_edge_int(ai, bi, keep, &score)
    }
}
