//! Re-tessellation of a vertex's star, for removing or moving a vertex (boundary recovery's
//! Steiner point suppression), and of any set of tets by a caller's tiling of the same region
//! (directional refinement's prism layers).
//!
//! The caller proposes new tets for the region covered by the star of `v` (without `v`, to
//! delete it, or with `v` at a new place, to move it) and the faces to mark constrained
//! afterwards. [`Delaunay::retessellate`] already checks that the proposal matches the
//! star's outer faces exactly and that every new finite tet is positively oriented; here the
//! proposal must also be *locally consistent*: across every face, shared by two new tets or
//! by a new tet and the tet outside the star, the two opposite vertices lie strictly on
//! opposite sides (exact `orient`). Positive tets glued that way over a fixed closed boundary
//! tile exactly the old region — a fold would need some face with both apexes on one side —
//! so a refused proposal leaves everything unchanged and an accepted one is a valid
//! triangulation. Constrained faces strictly inside the star (the surface pieces at a
//! Steiner point) may disappear; outer faces keep their flags.

use std::collections::HashMap;

use super::flips::face_key;
use super::predicates::orient;
use super::storage::{INF, NONE};
use super::{Delaunay, FlipError};

impl Delaunay {
    /// Replace the star of vertex `v` (input indices throughout) by the tets `new`, with `v`
    /// moved to `at` first if given; then mark the faces `constrain` (each must be a face of a
    /// new tet) constrained. If no new tet has `v`, the vertex leaves the triangulation.
    /// Refused, with nothing changed, when the star touches the hull (ghost tets) or the
    /// proposal is not a valid tiling of the star (see the module docs).
    pub fn replace_star(
        &mut self,
        v: u32,
        new: &[[u32; 4]],
        at: Option<[f64; 3]>,
        constrain: &[[u32; 3]],
    ) -> Result<Vec<u32>, FlipError> {
        let Some(&vi) = self.internal_of.get(v as usize) else {
            return Err(FlipError::NoEdge(v, v));
        };
        self.star_search(vi, &mut |_| false);
        let old = self.star_buf.clone();
        if old.is_empty() {
            return Err(FlipError::NoEdge(v, v));
        }
        if old.iter().any(|&t| self.store.tets[t as usize].is_ghost()) {
            return Err(FlipError::Ghost);
        }
        let new_int = self.internal_tets(new)?;
        let n = self.internal_of.len();
        let mut cons_int = Vec::with_capacity(constrain.len());
        for f in constrain {
            if f.iter().any(|&x| x as usize >= n) {
                return Err(FlipError::Invalid);
            }
            let mut k = f.map(|x| self.internal_of[x as usize]);
            k.sort_unstable();
            cons_int.push(k);
        }
        let saved_point = self.points[vi as usize];
        if let Some(p) = at {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(FlipError::Invalid);
            }
            self.points[vi as usize] = p;
        }
        if let Err(e) = self.star_proposal_consistent(&old, &new_int, &cons_int) {
            self.points[vi as usize] = saved_point;
            return Err(e);
        }
        // Constrained faces between two star tets may go: clear them, restore on refusal.
        let saved_flags: Vec<u8> = old.iter().map(|&t| self.store.flags[t as usize]).collect();
        let mut cleared = 0;
        for &t in &old {
            for f in 0..4 {
                let u = self.store.tets[t as usize].n[f] >> 2;
                if old.contains(&u) && self.store.flags[t as usize] & (1 << f) != 0 {
                    self.store.flags[t as usize] &= !(1 << f);
                    cleared += 1;
                }
            }
        }
        let ids = match self.retessellate(&old, &new_int) {
            Ok(ids) => ids,
            Err(e) => {
                for (k, &t) in old.iter().enumerate() {
                    self.store.flags[t as usize] = saved_flags[k];
                }
                self.points[vi as usize] = saved_point;
                return Err(e);
            }
        };
        self.constrained_faces -= cleared / 2;
        for key in cons_int {
            'found: for &t in &ids {
                let tv = self.store.tets[t as usize].v;
                for f in 0..4 {
                    if face_key(&tv, f) == key {
                        // Cannot fail: `t` is live and `f` a face index.
                        let _ = self.set_constrained(t, f as u8, true);
                        break 'found;
                    }
                }
            }
        }
        if !new_int.iter().any(|t| t.contains(&vi)) {
            self.vtet[vi as usize] = NONE;
            self.inserted -= 1;
        }
        Ok(ids)
    }

    /// Replace the finite tets `old` by tets on the vertex sets `new` (input indices, in any
    /// order: each is ordered here to be positively oriented, by the exact predicate, and a
    /// flat one refuses the whole proposal). Refused, with nothing changed, unless the new tets
    /// tile exactly the region of `old` (see the module docs) with no constrained face inside
    /// it and keep every vertex of `old`; the outer faces keep their flags. Returns the new
    /// tet ids.
    pub fn replace_tets(&mut self, old: &[u32], new: &[[u32; 4]]) -> Result<Vec<u32>, FlipError> {
        if old
            .iter()
            .any(|&t| !self.store.is_live(t) || self.store.tets[t as usize].is_ghost())
        {
            return Err(FlipError::Ghost);
        }
        let mut new_int = self.internal_tets(new)?;
        // A vertex of the old tets that no new tet has would be left without a star.
        let kept = old.iter().all(|&t| {
            let v = self.store.tets[t as usize].v;
            v.iter().all(|x| new_int.iter().any(|n| n.contains(x)))
        });
        if !kept {
            return Err(FlipError::Invalid);
        }
        for v in &mut new_int {
            let p = |x: u32| &self.points[x as usize];
            let s = orient(p(v[0]), p(v[1]), p(v[2]), p(v[3]));
            if s == 0.0 {
                return Err(FlipError::Invalid);
            }
            if s < 0.0 {
                v.swap(2, 3);
            }
        }
        self.star_proposal_consistent(old, &new_int, &[])?;
        self.retessellate(old, &new_int)
    }

    /// [`Delaunay::replace_tets`] with a new vertex at `p`, which the tets `new` name by the
    /// index [`Delaunay::num_points`] gives before the call (at least one must). Returns that
    /// index and the new tet ids; refused, with nothing changed, as `replace_tets` is.
    pub fn replace_tets_with_point(
        &mut self,
        old: &[u32],
        new: &[[u32; 4]],
        p: [f64; 3],
    ) -> Result<(u32, Vec<u32>), FlipError> {
        let index = self.points.len() as u32;
        if !p.iter().all(|c| c.is_finite()) || !new.iter().any(|t| t.contains(&index)) {
            return Err(FlipError::Invalid);
        }
        self.push_point(p, index);
        let accepted = self.replace_tets(old, new);
        self.keep_point_if(index, accepted)
    }

    /// The end of an insertion of point `index` (pushed last): counted when the tets that
    /// take it were accepted, taken off again when not.
    fn keep_point_if(
        &mut self,
        index: u32,
        accepted: Result<Vec<u32>, FlipError>,
    ) -> Result<(u32, Vec<u32>), FlipError> {
        match accepted {
            Ok(ids) => {
                self.inserted += 1;
                Ok((index, ids))
            }
            Err(e) => {
                self.pop_point();
                Err(e)
            }
        }
    }

    /// Insert `p` into the region of the finite tets `cavity` (a set the caller chose, not
    /// the Bowyer–Watson cavity): the cavity is replaced by the cone from the new vertex over
    /// its outer faces. Directional refinement grows its columns this way, one point into the
    /// part of its column top's star above the finished layers, so every layer comes out as
    /// prisms. Where `p` does not see an outer face from inside (exact `orient`), the tet
    /// beyond joins the cavity if `may_grow` (given its id and vertices) allows it; refused, with nothing changed, when a
    /// face stays hidden, a constrained or hull face would have to be crossed, a vertex
    /// would be swallowed (its whole star in the cavity), or a constrained face lies inside
    /// the cavity. The outer faces keep their flags. Returns the
    /// new vertex (input index) and the created tets.
    pub fn insert_in_cavity(
        &mut self,
        p: [f64; 3],
        cavity: &[u32],
        may_grow: &dyn Fn(u32, [u32; 4]) -> bool,
    ) -> Result<(u32, Vec<u32>), FlipError> {
        /// Faces crossed to make the cavity star-shaped from `p`, at most.
        const GROWTH: usize = 64;
        if !p.iter().all(|c| c.is_finite()) || cavity.is_empty() {
            return Err(FlipError::Invalid);
        }
        let live = |t: u32| self.store.is_live(t) && !self.store.tets[t as usize].is_ghost();
        if !cavity.iter().all(|&t| live(t)) {
            return Err(FlipError::Ghost);
        }
        let mut cavity = cavity.to_vec();
        let mut grown = 0;
        loop {
            let mut hidden: Vec<u32> = Vec::new();
            for &t in &cavity {
                let tet = &self.store.tets[t as usize];
                for f in 0..4 {
                    let u = tet.n[f] >> 2;
                    if cavity.contains(&u) {
                        continue;
                    }
                    let mut q = tet.v.map(|x| self.points[x as usize]);
                    q[f] = p;
                    if orient(&q[0], &q[1], &q[2], &q[3]) <= 0.0 || in_a_row(&q, f) {
                        let crossable = !self.store.tets[u as usize].is_ghost()
                            && self.store.flags[t as usize] & (1 << f) == 0
                            && may_grow(u, self.store.tets[u as usize].v.map(|x| self.ext(x)));
                        if !crossable {
                            return Err(FlipError::Invalid);
                        }
                        hidden.push(u);
                    }
                }
            }
            if hidden.is_empty() {
                break;
            }
            grown += hidden.len();
            if grown > GROWTH {
                return Err(FlipError::Invalid);
            }
            hidden.sort_unstable();
            hidden.dedup();
            cavity.extend(hidden);
        }
        let index = self.points.len() as u32;
        self.push_point(p, index);
        let pi = self.internal_of[index as usize];
        let mut cone: Vec<[u32; 4]> = Vec::with_capacity(cavity.len() * 2 + 2);
        for &t in &cavity {
            let tet = &self.store.tets[t as usize];
            for f in 0..4 {
                if !cavity.contains(&(tet.n[f] >> 2)) {
                    // The tet with the corner opposite the outer face replaced by `p`:
                    // positive, since `p` sees the face from inside.
                    let mut v = tet.v;
                    v[f] = pi;
                    cone.push(v);
                }
            }
        }
        // A vertex with its whole star in the cavity would vanish from the triangulation.
        let kept = cavity.iter().all(|&t| {
            let v = self.store.tets[t as usize].v;
            v.iter().all(|x| cone.iter().any(|c| c.contains(x)))
        });
        if !kept {
            self.pop_point();
            return Err(FlipError::Invalid);
        }
        let accepted = self
            .star_proposal_consistent(&cavity, &cone, &[])
            .and_then(|()| self.retessellate(&cavity, &cone));
        self.keep_point_if(index, accepted)
    }

    /// A proposal's tets (input indices) in internal ids; refused if one names the vertex at
    /// infinity or no vertex at all.
    fn internal_tets(&self, new: &[[u32; 4]]) -> Result<Vec<[u32; 4]>, FlipError> {
        let n = self.internal_of.len();
        new.iter()
            .map(|t| {
                if t.iter().any(|&x| x == INF || x as usize >= n) {
                    return Err(FlipError::Invalid);
                }
                Ok(t.map(|x| self.internal_of[x as usize]))
            })
            .collect()
    }

    /// Positive tets, opposite apexes across every shared face and across every outer face
    /// (against the tet outside the star), and every face to constrain present.
    fn star_proposal_consistent(
        &self,
        old: &[u32],
        new: &[[u32; 4]],
        constrain: &[[u32; 3]],
    ) -> Result<(), FlipError> {
        let p = |x: u32| &self.points[x as usize];
        for t in new {
            if orient(p(t[0]), p(t[1]), p(t[2]), p(t[3])) <= 0.0 {
                return Err(FlipError::Invalid);
            }
        }
        // The vertex beyond each outer face of the star.
        let mut beyond: HashMap<[u32; 3], u32> = HashMap::new();
        for &t in old {
            let tet = &self.store.tets[t as usize];
            for f in 0..4 {
                let r = tet.n[f];
                if !old.contains(&(r >> 2)) {
                    let w = self.store.tets[(r >> 2) as usize].v[(r & 3) as usize];
                    beyond.insert(face_key(&tet.v, f), w);
                }
            }
        }
        let mut apexes: HashMap<[u32; 3], Vec<u32>> = HashMap::with_capacity(new.len() * 4);
        for t in new {
            for f in 0..4 {
                apexes.entry(face_key(t, f)).or_default().push(t[f]);
            }
        }
        for (key, list) in &apexes {
            let (x, y) = match list[..] {
                [x, y] => (x, y),
                [x] => match beyond.get(key) {
                    Some(&INF) => continue, // a hull face: nothing lies beyond it
                    Some(&y) => (x, y),
                    None => return Err(FlipError::Invalid),
                },
                _ => return Err(FlipError::Invalid),
            };
            let [a, b, c] = *key;
            let s1 = orient(p(a), p(b), p(c), p(x));
            let s2 = orient(p(a), p(b), p(c), p(y));
            if !((s1 > 0.0 && s2 < 0.0) || (s1 < 0.0 && s2 > 0.0)) {
                return Err(FlipError::Invalid);
            }
        }
        for key in constrain {
            if !new.iter().any(|t| (0..4).any(|f| face_key(t, f) == *key)) {
                return Err(FlipError::Invalid);
            }
        }
        Ok(())
    }
}

/// Whether corner `f` of tet `q` lies in a row with two of the other corners (its angle
/// between them within [`IN_A_ROW`] of 180°): the tet then has a face of no area, which the
/// rounding of the coordinates may still give a positive volume, and no later move or swap
/// can repair it (the point sits on the edge between the other two).
fn in_a_row(q: &[[f64; 3]; 4], f: usize) -> bool {
    let at = glam::DVec3::from_array(q[f]);
    let others: Vec<glam::DVec3> = (0..4)
        .filter(|&k| k != f)
        .map(|k| glam::DVec3::from_array(q[k]) - at)
        .collect();
    let limit = (180.0 - IN_A_ROW).to_radians().cos();
    (0..3).any(|i| {
        let (u, w) = (others[i], others[(i + 1) % 3]);
        let len = u.length() * w.length();
        len > 0.0 && u.dot(w) < limit * len
    })
}

/// Degrees short of 180° within which a new point in a row with two corners of a face it is
/// coned over counts as not seeing that face ([`Delaunay::insert_in_cavity`]).
const IN_A_ROW: f64 = 1.0;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::volume::improve::max_dihedral;

    /// A point put on an edge of the cavity's outer faces (in a row with its two ends, up to
    /// rounding) must not be coned over those faces: the cavity grows until the edge is gone,
    /// so no tet has a face of no area.
    #[test]
    fn a_point_on_an_outer_edge_splits_it() {
        let mut pts: Vec<[f64; 3]> = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    let w = (i * 9 + j * 3 + k) as f64;
                    pts.push([
                        i as f64 + 0.13 * (w * 1.7).sin(),
                        j as f64 + 0.11 * (w * 2.3).cos(),
                        k as f64 + 0.12 * (w * 0.7).sin(),
                    ]);
                }
            }
        }
        let mut dt = Delaunay::new(&pts).unwrap();
        // An edge from the centre point (13) whose ring is all finite.
        let (a, b, ring) = (0..27u32)
            .filter(|&b| b != 13)
            .find_map(|b| {
                let (tets, _) = dt.tets_around_edge(13, b)?;
                tets.iter()
                    .all(|&t| !dt.is_ghost(t))
                    .then_some((13u32, b, tets))
            })
            .expect("an interior edge");
        let (pa, pb) = (dt.point(a), dt.point(b));
        let p = [0, 1, 2].map(|k| pa[k] + (pb[k] - pa[k]) / 3.0);
        let (v, _) = dt
            .insert_in_cavity(p, &ring[..1], &|_, _| true)
            .expect("inserted");
        dt.check_valid().unwrap();
        assert!(dt.tets_around_edge(a, b).is_none(), "edge {a}-{b} kept");
        assert!(dt.tets_around_edge(a, v).is_some());
        assert!(dt.tets_around_edge(v, b).is_some());
        for t in dt.tet_ids().filter(|&t| !dt.is_ghost(t)) {
            let q = dt.tet(t).map(|i| dt.point(i));
            let worst = max_dihedral(&q[0], &q[1], &q[2], &q[3]);
            assert!(worst < 179.0, "tet {t}: {worst}°");
        }
    }
}
