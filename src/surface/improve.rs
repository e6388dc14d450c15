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

fn max_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let ang = |p: DVec3, q: DVec3, r: DVec3| (q - p).angle_between(r - p);
    ang(a, b, c).max(ang(b, c, a)).max(ang(c, a, b))
}

/// Swap the diagonal of two triangles sharing an interior edge when that lowers the larger of
/// their largest angles and both new triangles stay positive in (u,v).
pub fn swap_diagonals(t: &mut FaceTriangulation) {
    for _ in 0..SWAP_SWEEPS {
        let mut edge_tris: HashMap<(usize, usize), usize> = HashMap::new();
        for (i, tri) in t.triangles.iter().enumerate() {
            for k in 0..3 {
                edge_tris.insert((tri[k], tri[(k + 1) % 3]), i);
            }
        }
        let mut changed = false;
        let mut touched = vec![false; t.triangles.len()];
        for i in 0..t.triangles.len() {
            for k in 0..3 {
                let tri = t.triangles[i];
                let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
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
                let x = |v: usize| t.vertices[v].xyz;
                let uv = |v: usize| t.vertices[v].uv;
                // Same 3-D node on both sides (a seam or pole) would make a degenerate triangle.
                if t.vertices[c].node.is_some() && t.vertices[c].node == t.vertices[d].node {
                    continue;
                }
                let before = max_angle(x(a), x(b), x(c)).max(max_angle(x(b), x(a), x(d)));
                let after = max_angle(x(c), x(a), x(d)).max(max_angle(x(d), x(b), x(c)));
                if after < before - 1e-9
                    && orient2d(uv(c), uv(a), uv(d)) > 0.0
                    && orient2d(uv(d), uv(b), uv(c)) > 0.0
                {
                    t.triangles[i] = [c, a, d];
                    t.triangles[j] = [d, b, c];
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

/// Move each interior vertex to the projection of its neighbours' centroid when that keeps
/// every incident triangle positive in (u,v) and does not lower their worst quality.
pub fn smooth(t: &mut FaceTriangulation, surface: &dyn Surface, fixed: usize) {
    let n = t.vertices.len();
    let mut ring: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, tri) in t.triangles.iter().enumerate() {
        for &v in tri {
            ring[v].push(i);
        }
    }
    for _ in 0..SMOOTH_SWEEPS {
        for (v, tris) in ring.iter().enumerate().skip(fixed) {
            if tris.is_empty() {
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
