//! The validity check every volume mesh passes before it is written: every tet positive
//! (exact `orient3d`), the tets form a manifold (a face has at most two tets), every exposed
//! tet face is a boundary triangle facing out, every boundary triangle is a tet face, the
//! tets' volume equals the volume the exposed faces enclose, and no node is unused or
//! duplicated (nor a rounding away from another node of its tet).

use super::quality::volume_sign;
use super::VolumeMesh;
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// Faces of a positively oriented tet `[0, 1, 2, 3]`, each listed so its normal (right-hand
/// rule) points out of the tet; face `i` is opposite vertex `i`.
pub const OUTWARD_FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// What the check measured.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct ValidityReport {
    pub tets: usize,
    pub boundary_triangles: usize,
    /// Sum of the tets' volumes.
    pub volume: f64,
    /// Volume enclosed by the exposed faces (divergence theorem).
    pub enclosed_volume: f64,
    /// Everything wrong (empty for a valid mesh); at most [`MAX_DEFECTS`] are listed.
    pub defects: Vec<String>,
    pub defect_count: usize,
}

pub const MAX_DEFECTS: usize = 20;

/// Two nodes of one tet closer than this fraction of the mesh's bounding-box diagonal are one
/// point to rounding (the thinnest layers asked of the refinement are some 10⁻⁶ of it).
const COINCIDENT: f64 = 1e-10;

impl ValidityReport {
    pub fn is_valid(&self) -> bool {
        self.defect_count == 0
    }
    fn defect(&mut self, what: String) {
        self.defect_count += 1;
        if self.defects.len() < MAX_DEFECTS {
            self.defects.push(what);
        }
    }
}

fn key(mut k: [u32; 3]) -> [u32; 3] {
    k.sort_unstable();
    k
}

/// Run every check on `mesh`.
pub fn check(mesh: &VolumeMesh) -> ValidityReport {
    let mut r = ValidityReport {
        tets: mesh.tets.len(),
        boundary_triangles: mesh.boundary.len(),
        ..Default::default()
    };
    let n = mesh.points.len();
    let mut used = vec![false; n];
    // face key -> (number of tets, outward orientation from the last tet seen)
    let mut faces: HashMap<[u32; 3], (u32, [u32; 3])> = HashMap::with_capacity(mesh.tets.len() * 2);
    for (k, t) in mesh.tets.iter().enumerate() {
        if t.iter().any(|&v| v as usize >= n) {
            r.defect(format!("tet {k} refers to a node that does not exist"));
            continue;
        }
        let p = mesh.tet_points(k);
        if volume_sign(p) <= 0.0 {
            r.defect(format!(
                "tet {k} {t:?} is inverted or flat (exact orient3d)"
            ));
        }
        r.volume += (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0;
        for &v in t {
            used[v as usize] = true;
        }
        for f in OUTWARD_FACES {
            let tri = f.map(|i| t[i]);
            let e = faces.entry(key(tri)).or_insert((0, tri));
            e.0 += 1;
            e.1 = tri;
        }
    }
    let boundary: HashSet<[u32; 3]> = mesh.boundary.iter().map(|&t| key(t)).collect();
    for (k, t) in mesh.boundary.iter().enumerate() {
        match faces.get(&key(*t)) {
            None => r.defect(format!(
                "boundary triangle {k} {t:?} (marker {}) is not a face of any tet",
                marker_name(mesh, k)
            )),
            Some(&(1, out)) if !same_cycle(out, *t) => r.defect(format!(
                "boundary triangle {k} (marker {}) faces into the domain",
                marker_name(mesh, k)
            )),
            _ => {}
        }
    }
    let mut exposed = 0.0;
    for (k, &(count, out)) in &faces {
        if count > 2 {
            r.defect(format!("face {k:?} is shared by {count} tets"));
        } else if count == 1 {
            if !boundary.contains(k) {
                r.defect(format!(
                    "face {k:?} bounds the mesh but is not a boundary triangle"
                ));
            }
            let [a, b, c] = out.map(|v| mesh.points[v as usize]);
            exposed += a.dot(b.cross(c)) / 6.0;
        }
    }
    r.enclosed_volume = exposed;
    let scale = r.volume.abs().max(exposed.abs()).max(f64::MIN_POSITIVE);
    if (r.volume - exposed).abs() > 1e-9 * scale {
        r.defect(format!(
            "tet volume {} differs from the enclosed volume {}",
            r.volume, exposed
        ));
    }
    let unused = used.iter().filter(|&&u| !u).count();
    if unused > 0 {
        r.defect(format!("{unused} nodes belong to no tet"));
    }
    // Nodes a rounding apart (a cascade of boundary Steiner points halving one spot): every
    // tet on both is of no volume in all but the exact sign.
    let (lo, hi) = mesh.points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let tiny = COINCIDENT * (hi - lo).length();
    let mut close: HashSet<(u32, u32)> = HashSet::new();
    for t in &mesh.tets {
        for i in 0..4 {
            for j in i + 1..4 {
                let (a, b) = (t[i].min(t[j]), t[i].max(t[j]));
                let (pa, pb) = (mesh.points[a as usize], mesh.points[b as usize]);
                if pa != pb && pa.distance(pb) < tiny && close.insert((a, b)) {
                    r.defect(format!(
                        "nodes {a} and {b} are {:.1e} apart at {} (coincident to rounding)",
                        pa.distance(pb),
                        crate::geometry::Xyz(pa)
                    ));
                }
            }
        }
    }
    let mut seen: HashMap<[u64; 3], usize> = HashMap::with_capacity(n);
    for (i, p) in mesh.points.iter().enumerate() {
        if let Some(j) = seen.insert(bits(*p), i) {
            r.defect(format!(
                "nodes {j} and {i} coincide at {}",
                crate::geometry::Xyz(*p)
            ));
        }
    }
    r
}

fn bits(p: DVec3) -> [u64; 3] {
    // +0.0 and -0.0 are the same point.
    [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits)
}

fn same_cycle(a: [u32; 3], b: [u32; 3]) -> bool {
    (0..3).any(|r| [b[r], b[(r + 1) % 3], b[(r + 2) % 3]] == a)
}

fn marker_name(mesh: &VolumeMesh, k: usize) -> &str {
    mesh.boundary_marker
        .get(k)
        .and_then(|&m| mesh.markers.get(m as usize))
        .map(|m| m.name.as_str())
        .unwrap_or("?")
}
