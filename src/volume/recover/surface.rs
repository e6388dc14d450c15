//! The surface triangulation being recovered (triangles, and embedded segments: edges on no
//! triangle), with the lookups recovery needs: triangles by edge (splitting an edge splits every triangle on it — one for a free wake edge, two on a
//! shell, more on a junction of interfaces), the face set (what flips must not destroy) and
//! the vertex set (an existing vertex found on a surface edge may join the surface only if
//! it is not already a surface vertex).

use std::collections::{HashMap, HashSet};

/// A deleted triangle's slot (see [`Surface::replace_vertex`]).
pub(super) const DEAD: [u32; 3] = [u32::MAX; 3];

#[inline]
pub(super) fn edge_key(a: u32, b: u32) -> u64 {
    ((a.min(b) as u64) << 32) | a.max(b) as u64
}

#[inline]
fn face_key(t: [u32; 3]) -> [u32; 3] {
    let mut k = t;
    k.sort_unstable();
    k
}

pub(super) struct Surface<'a> {
    pub tris: &'a mut Vec<[u32; 3]>,
    pub parent: &'a mut Vec<u32>,
    /// Embedded segments (edges on no triangle) and the input segment each piece is from.
    pub segs: &'a mut Vec<[u32; 2]>,
    pub seg_parent: &'a mut Vec<u32>,
    /// Segment index by edge key.
    seg_index: HashMap<u64, usize>,
    /// Segment neighbours by vertex.
    seg_at: HashMap<u32, Vec<u32>>,
    by_edge: HashMap<u64, Vec<u32>>,
    faces: HashSet<[u32; 3]>,
    /// Triangles by vertex.
    vertices: HashMap<u32, Vec<u32>>,
    /// Triangles already recovered (constrained faces): never flipped.
    recovered: Vec<bool>,
}

impl<'a> Surface<'a> {
    pub fn new(
        tris: &'a mut Vec<[u32; 3]>,
        parent: &'a mut Vec<u32>,
        segs: &'a mut Vec<[u32; 2]>,
        seg_parent: &'a mut Vec<u32>,
    ) -> Self {
        if parent.len() != tris.len() {
            *parent = (0..tris.len() as u32).collect();
        }
        if seg_parent.len() != segs.len() {
            *seg_parent = (0..segs.len() as u32).collect();
        }
        let mut s = Surface {
            seg_index: HashMap::new(),
            seg_at: HashMap::new(),
            segs,
            seg_parent,
            by_edge: HashMap::with_capacity(tris.len() * 3 / 2 + 16),
            faces: HashSet::with_capacity(tris.len() + 16),
            vertices: HashMap::with_capacity(tris.len() / 2 + 16),
            recovered: vec![false; tris.len()],
            tris,
            parent,
        };
        for k in 0..s.tris.len() as u32 {
            s.add(k);
        }
        for i in 0..s.segs.len() {
            s.add_seg(i);
        }
        s
    }

    fn add_seg(&mut self, i: usize) {
        let [a, b] = self.segs[i];
        self.seg_index.insert(edge_key(a, b), i);
        self.seg_at.entry(a).or_default().push(b);
        self.seg_at.entry(b).or_default().push(a);
    }

    fn remove_seg(&mut self, i: usize) {
        let [a, b] = self.segs[i];
        self.seg_index.remove(&edge_key(a, b));
        for (x, y) in [(a, b), (b, a)] {
            if let Some(list) = self.seg_at.get_mut(&x) {
                list.retain(|&z| z != y);
            }
        }
    }

    /// Is `ab` an embedded segment?
    pub fn is_segment(&self, a: u32, b: u32) -> bool {
        self.seg_index.contains_key(&edge_key(a, b))
    }

    /// The other ends of the segments at `m`.
    pub fn segment_neighbours(&self, m: u32) -> Vec<u32> {
        self.seg_at.get(&m).cloned().unwrap_or_default()
    }

    /// Replace the segments `a m` and `m b` by `a b` (the Steiner point `m` is gone).
    pub fn join_segments(&mut self, a: u32, m: u32, b: u32) {
        let (Some(&i), Some(&j)) = (
            self.seg_index.get(&edge_key(a, m)),
            self.seg_index.get(&edge_key(m, b)),
        ) else {
            return;
        };
        self.remove_seg(i);
        self.remove_seg(j);
        self.segs[i] = [a, b];
        self.segs[j] = [u32::MAX; 2];
        self.add_seg(i);
    }

    /// Input segment of the segment `ab`, if it is one.
    pub fn segment_parent(&self, a: u32, b: u32) -> Option<u32> {
        Some(self.seg_parent[*self.seg_index.get(&edge_key(a, b))?])
    }

    fn add(&mut self, k: u32) {
        let t = self.tris[k as usize];
        if self.recovered.len() <= k as usize {
            self.recovered.resize(k as usize + 1, false);
        }
        for i in 0..3 {
            self.by_edge
                .entry(edge_key(t[i], t[(i + 1) % 3]))
                .or_default()
                .push(k);
            self.vertices.entry(t[i]).or_default().push(k);
        }
        self.faces.insert(face_key(t));
    }

    fn remove(&mut self, k: u32) {
        let t = self.tris[k as usize];
        for i in 0..3 {
            let key = edge_key(t[i], t[(i + 1) % 3]);
            if let Some(list) = self.by_edge.get_mut(&key) {
                list.retain(|&x| x != k);
                if list.is_empty() {
                    self.by_edge.remove(&key);
                }
            }
        }
        self.faces.remove(&face_key(t));
        for v in t {
            if let Some(list) = self.vertices.get_mut(&v) {
                list.retain(|&x| x != k);
            }
        }
    }

    /// All distinct edges (of triangles, and segments), each once.
    pub fn edges(&self) -> Vec<(u32, u32)> {
        let mut e: Vec<(u32, u32)> = self
            .by_edge
            .keys()
            .chain(self.seg_index.keys())
            .map(|&k| ((k >> 32) as u32, k as u32))
            .collect();
        e.sort_unstable();
        e.dedup();
        e
    }

    pub fn is_edge(&self, a: u32, b: u32) -> bool {
        self.by_edge.contains_key(&edge_key(a, b)) || self.is_segment(a, b)
    }

    pub fn is_vertex(&self, v: u32) -> bool {
        self.vertices.get(&v).is_some_and(|l| !l.is_empty())
            || self.seg_at.get(&v).is_some_and(|l| !l.is_empty())
    }

    /// The surface edges (and segments) at vertex `m`.
    pub fn edges_at(&self, m: u32) -> Vec<(u32, u32)> {
        let mut out: Vec<(u32, u32)> = self
            .segment_neighbours(m)
            .into_iter()
            .map(|v| (v, m))
            .collect();
        for &k in self.vertices.get(&m).map(|l| l.as_slice()).unwrap_or(&[]) {
            for v in self.tris[k as usize] {
                if v != m && !out.contains(&(v, m)) {
                    out.push((v, m));
                }
            }
        }
        out
    }

    /// A triangle having edge `ab` (for error messages).
    pub fn triangle_of_edge(&self, a: u32, b: u32) -> Option<u32> {
        self.by_edge.get(&edge_key(a, b))?.first().copied()
    }

    /// Is the simplex (2 or 3 input indices) a surface edge or triangle? Flips and splits
    /// must not destroy these.
    pub fn protects(&self, s: &[u32]) -> bool {
        match *s {
            [a, b] => self.is_edge(a, b),
            [a, b, c] => self.faces.contains(&face_key([a, b, c])),
            _ => false,
        }
    }

    /// Split edge `ab` at vertex `m`: every triangle `(…a b…)` becomes `(…a m…)` and
    /// `(…m b…)`, keeping its orientation and its parent, and a segment `ab` becomes `am`
    /// and `mb`. Returns the triangles now touching `m`.
    pub fn split_edge(&mut self, a: u32, b: u32, m: u32) -> Vec<u32> {
        if let Some(&i) = self.seg_index.get(&edge_key(a, b)) {
            self.remove_seg(i);
            self.segs[i] = [a, m];
            self.segs.push([m, b]);
            self.seg_parent.push(self.seg_parent[i]);
            self.add_seg(i);
            self.add_seg(self.segs.len() - 1);
        }
        let list = self
            .by_edge
            .get(&edge_key(a, b))
            .cloned()
            .unwrap_or_default();
        let mut out = Vec::with_capacity(list.len() * 2);
        for k in list {
            let t = self.tris[k as usize];
            self.remove(k);
            let mut t1 = t;
            let mut t2 = t;
            for i in 0..3 {
                let (x, y) = (t[i], t[(i + 1) % 3]);
                if (x == a && y == b) || (x == b && y == a) {
                    // The edge runs x → y in this triangle: (x, m, z) and (m, y, z).
                    t1[(i + 1) % 3] = m;
                    t2[i] = m;
                }
            }
            self.tris[k as usize] = t1;
            self.add(k);
            let k2 = self.tris.len() as u32;
            self.tris.push(t2);
            self.parent.push(self.parent[k as usize]);
            self.add(k2);
            out.push(k);
            out.push(k2);
        }
        out
    }

    /// Split triangle `k` at an interior vertex `m` into three, keeping orientation and
    /// parent. Returns the three triangle indices.
    pub fn split_triangle(&mut self, k: u32, m: u32) -> [u32; 3] {
        let [a, b, c] = self.tris[k as usize];
        self.remove(k);
        self.tris[k as usize] = [a, b, m];
        self.add(k);
        let mut ids = [k, 0, 0];
        for (j, t) in [[b, c, m], [c, a, m]].into_iter().enumerate() {
            let id = self.tris.len() as u32;
            self.tris.push(t);
            self.parent.push(self.parent[k as usize]);
            self.add(id);
            ids[j + 1] = id;
        }
        ids
    }

    /// The triangles having vertex `m`.
    pub fn triangles_at(&self, m: u32) -> Vec<u32> {
        self.vertices.get(&m).cloned().unwrap_or_default()
    }

    /// Replace vertex `from` of triangle `k` by `to` (same slot, parent and orientation), or,
    /// when `to` is already one of its vertices (the triangle collapses), delete it: its slot
    /// becomes [`DEAD`], dropped when the list is compacted.
    pub fn replace_vertex(&mut self, k: u32, from: u32, to: u32) {
        let t = self.tris[k as usize];
        self.remove(k);
        if t.contains(&to) {
            self.tris[k as usize] = DEAD;
            return;
        }
        self.tris[k as usize] = t.map(|x| if x == from { to } else { x });
        self.add(k);
    }

    pub fn set_recovered(&mut self, k: u32) {
        self.recovered[k as usize] = true;
    }

    /// Edge `ab` as the diagonal of a quad inside one original triangle: exactly two
    /// triangles on it, same parent, neither recovered. Returns them and their third
    /// vertices `(t1, t2, c, d)`, `t1` running `a → b`.
    pub fn quad(&self, a: u32, b: u32) -> Option<(u32, u32, u32, u32)> {
        let list = self.by_edge.get(&edge_key(a, b))?;
        let [t1, t2] = list[..] else { return None };
        if self.parent[t1 as usize] != self.parent[t2 as usize]
            || self.recovered[t1 as usize]
            || self.recovered[t2 as usize]
        {
            return None;
        }
        let third = |t: [u32; 3]| t.into_iter().find(|&v| v != a && v != b);
        let runs_ab = |t: [u32; 3]| (0..3).any(|i| t[i] == a && t[(i + 1) % 3] == b);
        let (x, y) = (self.tris[t1 as usize], self.tris[t2 as usize]);
        let (t1, t2, x, y) = if runs_ab(x) {
            (t1, t2, x, y)
        } else {
            (t2, t1, y, x)
        };
        if !runs_ab(x) || runs_ab(y) {
            return None;
        }
        Some((t1, t2, third(x)?, third(y)?))
    }

    /// Flip the diagonal `ab` of the quad found by [`Surface::quad`] to `cd` (the caller
    /// checked that the quad is convex), keeping orientation: `(a, b, c)` and `(b, a, d)`
    /// become `(a, d, c)` and `(d, b, c)`.
    pub fn flip(&mut self, a: u32, b: u32, (t1, t2, c, d): (u32, u32, u32, u32)) {
        self.remove(t1);
        self.remove(t2);
        self.tris[t1 as usize] = [a, d, c];
        self.tris[t2 as usize] = [d, b, c];
        self.add(t1);
        self.add(t2);
    }
}
