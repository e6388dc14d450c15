//! After the front closes: diagonal swaps that lower the largest angle (the seed paper's
//! criterion), then smoothing that moves interior vertices towards the centre of their
//! neighbours while staying on the surface and never folding a triangle in (u,v).

use super::advance::FaceTriangulation;
use crate::geometry::{orient2d, Surface};
use crate::mesh::quality::triangle_quality;
use glam::DVec3;
use std::collections::HashMap;

const SWAP_SWEEPS: usize = 4;
const SMOOTH_SWEEPS: usize = 3;

/// Largest angle of a triangle: one `acos` of the smallest corner cosine (acos falls, so
/// this is the largest of the three `angle_between`s, to the bit).
fn max_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let cos = |p: DVec3, q: DVec3, r: DVec3| {
        let (u, v) = (q - p, r - p);
        u.dot(v) / (u.length_squared() * v.length_squared()).sqrt()
    };
    let m = cos(a, b, c).min(cos(b, c, a)).min(cos(c, a, b));
    m.clamp(-1.0, 1.0).acos()
}

/// Swap the diagonal of two triangles sharing an interior edge when that lowers the larger of
/// their largest angles and both new triangles stay positive in (u,v). A `slit` edge (a model
/// edge inside the face, meshed from both sides) has triangles on both sides but stays.
pub fn swap_diagonals(t: &mut FaceTriangulation, slits: &[[usize; 2]]) {
    swap_where(t, None, slits);
}

/// [`swap_diagonals`] over the edges with an end in `near` only: after the parts of a split
/// face are merged, only the edges at the cut have triangles on both sides for the first time.
pub fn swap_diagonals_near(t: &mut FaceTriangulation, near: &[bool]) {
    swap_where(t, Some(near), &[]);
}

/// Diagonal swaps on every edge, or on the edges with an end in `near` (then only the
/// triangles at such vertices are looked at: both sides of such an edge are among them).
/// Each triangle's largest angle is computed once per sweep and kept up to date across swaps
/// (the swap test used to recompute it for every edge it looked at: most of the swap time).
fn swap_where(t: &mut FaceTriangulation, near: Option<&[bool]>, slits: &[[usize; 2]]) {
    let x = |t: &FaceTriangulation, v: usize| t.vertices[v].xyz;
    let eligible = |a: usize, b: usize| {
        near.is_none_or(|f| f[a] || f[b]) && !slits.contains(&[a, b]) && !slits.contains(&[b, a])
    };
    for _ in 0..SWAP_SWEEPS {
        let active: Vec<usize> = (0..t.triangles.len())
            .filter(|&i| near.is_none_or(|f| t.triangles[i].iter().any(|&v| f[v])))
            .collect();
        let mut edge_tris: HashMap<(usize, usize), usize, PairHash> =
            HashMap::with_capacity_and_hasher(3 * active.len(), PairHash);
        let mut worst = vec![f64::NAN; t.triangles.len()];
        for &i in &active {
            let tri = t.triangles[i];
            for k in 0..3 {
                edge_tris.insert((tri[k], tri[(k + 1) % 3]), i);
            }
            worst[i] = max_angle(x(t, tri[0]), x(t, tri[1]), x(t, tri[2]));
        }
        let mut changed = false;
        let mut touched = vec![false; t.triangles.len()];
        for &i in &active {
            for k in 0..3 {
                let tri = t.triangles[i];
                let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                if !eligible(a, b) {
                    continue;
                }
                let Some(&j) = edge_tris.get(&(b, a)) else {
                    continue;
                };
                if touched[i] || touched[j] || i == j {
                    continue;
                }
                let other = t.triangles[j];
                let Some(&d) = other.iter().find(|&&v| v != a && v != b) else {
                    continue;
                };
                let uv = |v: usize| t.vertices[v].uv;
                // Same 3-D node on both sides (a seam or pole) would make a degenerate triangle.
                if t.vertices[c].node.is_some() && t.vertices[c].node == t.vertices[d].node {
                    continue;
                }
                let before = worst[i].max(worst[j]);
                let first = max_angle(x(t, c), x(t, a), x(t, d));
                if first >= before - 1e-9 {
                    continue;
                }
                let second = max_angle(x(t, d), x(t, b), x(t, c));
                if first.max(second) < before - 1e-9
                    && orient2d(uv(c), uv(a), uv(d)) > 0.0
                    && orient2d(uv(d), uv(b), uv(c)) > 0.0
                {
                    t.triangles[i] = [c, a, d];
                    t.triangles[j] = [d, b, c];
                    worst[i] = first;
                    worst[j] = second;
                    touched[i] = true;
                    touched[j] = true;
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
}

/// A cheap hash for vertex-id pairs (the default SipHash cost as much as the swap tests).
#[derive(Clone, Copy, Default)]
struct PairHash;

impl std::hash::BuildHasher for PairHash {
    type Hasher = PairHasher;
    fn build_hasher(&self) -> PairHasher {
        PairHasher(0)
    }
}

#[derive(Default)]
struct PairHasher(u64);

impl std::hash::Hasher for PairHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
    fn write_u64(&mut self, i: u64) {
        // FxHash's step: rotate, xor, multiply by a large odd constant.
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// Move each interior vertex to the projection of its neighbours' centroid when that keeps
/// every incident triangle positive in (u,v) and does not lower their worst quality.
pub fn smooth(t: &mut FaceTriangulation, surface: &dyn Surface, fixed: usize) {
    smooth_vertices(t, surface, |v| v >= fixed);
}

/// [`smooth`] over the vertices `movable` accepts.
pub fn smooth_vertices(
    t: &mut FaceTriangulation,
    surface: &dyn Surface,
    movable: impl Fn(usize) -> bool,
) {
    let n = t.vertices.len();
    let mut ring: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, tri) in t.triangles.iter().enumerate() {
        for &v in tri {
            ring[v].push(i);
        }
    }
    for _ in 0..SMOOTH_SWEEPS {
        for (v, tris) in ring.iter().enumerate() {
            if tris.is_empty() || !movable(v) {
                continue;
            }
            let mut sum = DVec3::ZERO;
            let mut count = 0.0;
            for &ti in tris {
                for &w in &t.triangles[ti] {
                    if w != v {
                        sum += t.vertices[w].xyz;
                        count += 1.0;
                    }
                }
            }
            let target = sum / count;
            let old = t.vertices[v];
            let Some(uv) = crate::geometry::newton::project_local(surface, target, old.uv) else {
                continue;
            };
            let uv = crate::model::unwrap_near(uv, old.uv, &surface.bounds());
            let worst = |t: &FaceTriangulation| {
                tris.iter()
                    .map(|&ti| {
                        let [a, b, c] = t.triangles[ti];
                        let p = |k: usize| t.vertices[k];
                        if orient2d(p(a).uv, p(b).uv, p(c).uv) <= 0.0 {
                            -1.0
                        } else {
                            triangle_quality(p(a).xyz, p(b).xyz, p(c).xyz)
                        }
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            let before = worst(t);
            t.vertices[v].uv = uv;
            t.vertices[v].xyz = surface.point(uv);
            if worst(t) < before {
                t.vertices[v] = old;
            }
        }
    }
}
