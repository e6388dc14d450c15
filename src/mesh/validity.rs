//! The validity check every volume mesh passes before it is written: every tet positive
//! (exact `orient3d`; for a prism or pyramid, every tet of every split of it), the cells form a
//! manifold (a face — triangle or quad — has at most two cells), every exposed cell face is a
//! boundary face facing out, every boundary face is a cell face, the cells' volume equals the
//! volume the exposed faces enclose, and no node is unused or duplicated (nor a rounding away
//! from another node of its cell).

use super::quality::volume_sign;
use super::{CellKind, VolumeMesh};
use crate::prisms::shape;
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// Faces of a positively oriented tet `[0, 1, 2, 3]`, each listed so its normal (right-hand
/// rule) points out of the tet; face `i` is opposite vertex `i`.
pub const OUTWARD_FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// A face of a cell: three or four corners (`NO` in the fourth place of a triangle).
type Face = [u32; 4];
const NO: u32 = u32::MAX;

/// The faces of a cell in [`VolumeMesh`] order, each facing out of it (a tet's four, then a
/// repeat of its first that the caller skips). No allocation: this runs once per cell.
fn outward_faces(kind: CellKind, c: &[u32]) -> ([Face; 5], usize) {
    let tri = |a: usize, b: usize, d: usize| [c[a], c[b], c[d], NO];
    let quad = |a: usize, b: usize, d: usize, e: usize| [c[a], c[b], c[d], c[e]];
    let f = |i: usize| {
        tri(
            OUTWARD_FACES[i][0],
            OUTWARD_FACES[i][1],
            OUTWARD_FACES[i][2],
        )
    };
    match kind {
        CellKind::Tet => ([f(0), f(1), f(2), f(3), f(0)], 4),
        CellKind::Pyramid => (
            [
                quad(0, 3, 2, 1),
                tri(0, 1, 4),
                tri(1, 2, 4),
                tri(2, 3, 4),
                tri(3, 0, 4),
            ],
            5,
        ),
        CellKind::Prism => (
            [
                tri(0, 2, 1),
                tri(3, 4, 5),
                quad(0, 1, 4, 3),
                quad(1, 2, 5, 4),
                quad(2, 0, 3, 5),
            ],
            5,
        ),
    }
}

/// Per boundary face (in [`VolumeMesh::boundary_faces`] order), whether cells lie on both of
/// its sides: an embedded face (a wake) or an interface between regions, not the domain's
/// outside.
pub fn two_sided_boundary_faces(mesh: &VolumeMesh) -> Vec<bool> {
    let key = |f: &[u32]| {
        let mut k = [NO; 4];
        k[..f.len()].copy_from_slice(f);
        k.sort_unstable();
        k
    };
    let mut cells_on: HashMap<[u32; 4], u8> =
        mesh.boundary_faces().map(|(f, _)| (key(f), 0)).collect();
    for (kind, c, _) in mesh.cells() {
        let (faces, n) = outward_faces(kind, c);
        for f in &faces[..n] {
            if let Some(count) = cells_on.get_mut(&key(corners(f))) {
                *count = count.saturating_add(1);
            }
        }
    }
    mesh.boundary_faces()
        .map(|(f, _)| cells_on[&key(f)] >= 2)
        .collect()
}

fn corners(f: &Face) -> &[u32] {
    if f[3] == NO {
        &f[..3]
    } else {
        &f[..]
    }
}

/// `Σ (a−o)·((b−o)×(c−o)) / 6` over a face's triangles (a quad fanned from its centroid): the
/// face's share of the volume it bounds, seen from `o`.
fn volume_share(points: &[DVec3], f: &[u32], o: DVec3) -> f64 {
    let at = |i: usize| points[f[i] as usize] - o;
    if f.len() == 3 {
        return at(0).dot(at(1).cross(at(2))) / 6.0;
    }
    let p = [at(0), at(1), at(2), at(3)];
    let m = (p[0] + p[1] + p[2] + p[3]) / 4.0;
    (0..4)
        .map(|i| m.dot(p[i].cross(p[(i + 1) % 4])) / 6.0)
        .sum()
}

/// What the check measured.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct ValidityReport {
    pub tets: usize,
    pub prisms: usize,
    pub pyramids: usize,
    pub boundary_triangles: usize,
    pub boundary_quads: usize,
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

/// A face's corners sorted (a triangle's `NO` stays last).
fn key(mut k: Face) -> Face {
    k.sort_unstable();
    k
}

fn as_face(f: &[u32]) -> Face {
    [f[0], f[1], f[2], f.get(3).copied().unwrap_or(NO)]
}

/// Run every check on `mesh`.
pub fn check(mesh: &VolumeMesh) -> ValidityReport {
    let mut r = ValidityReport {
        tets: mesh.tets.len(),
        prisms: mesh.prisms.len(),
        pyramids: mesh.pyramids.len(),
        boundary_triangles: mesh.boundary.len(),
        boundary_quads: mesh.boundary_quads.len(),
        ..Default::default()
    };
    let n = mesh.points.len();
    let mut used = vec![false; n];
    // face key -> (number of cells, outward orientation from the last cell seen)
    let mut faces: HashMap<Face, (u32, Face)> = HashMap::with_capacity(mesh.cell_count() * 2);
    for (k, (kind, c, _)) in mesh.cells().enumerate() {
        if c.iter().any(|&v| v as usize >= n) {
            r.defect(format!("{kind:?} {k} refers to a node that does not exist"));
            continue;
        }
        let mut p = [DVec3::ZERO; 6];
        for (q, &v) in p.iter_mut().zip(c) {
            *q = mesh.points[v as usize];
        }
        let positive = match kind {
            CellKind::Tet => volume_sign([p[0], p[1], p[2], p[3]]) > 0.0,
            CellKind::Pyramid => shape::pyramid_is_valid(&[p[0], p[1], p[2], p[3], p[4]]),
            CellKind::Prism => shape::prism_is_valid(&[p[0], p[1], p[2], p[3], p[4], p[5]]),
        };
        if !positive {
            r.defect(format!(
                "{kind:?} {k} {c:?} is inverted or flat (exact orient3d)"
            ));
        }
        let (cell_faces, count) = outward_faces(kind, c);
        for f in &cell_faces[..count] {
            r.volume += volume_share(&mesh.points, corners(f), p[0]);
            let e = faces.entry(key(*f)).or_insert((0, *f));
            e.0 += 1;
            e.1 = *f;
        }
        for &v in c {
            used[v as usize] = true;
        }
    }
    let boundary: HashSet<Face> = mesh
        .boundary_faces()
        .map(|(f, _)| key(as_face(f)))
        .collect();
    for (k, (f, m)) in mesh.boundary_faces().enumerate() {
        let name = mesh
            .markers
            .get(m as usize)
            .map_or("?", |m| m.name.as_str());
        match faces.get(&key(as_face(f))) {
            None => r.defect(format!(
                "boundary face {k} {f:?} (marker {name}) is not a face of any cell"
            )),
            Some(&(1, out)) if !same_cycle(corners(&out), f) => r.defect(format!(
                "boundary face {k} (marker {name}) faces into the domain"
            )),
            _ => {}
        }
    }
    let mut exposed = 0.0;
    for (k, &(count, out)) in &faces {
        if count > 2 {
            r.defect(format!("face {:?} is shared by {count} cells", corners(k)));
        } else if count == 1 {
            if !boundary.contains(k) {
                r.defect(format!(
                    "face {:?} bounds the mesh but is not a boundary face",
                    corners(k)
                ));
            }
            exposed += volume_share(&mesh.points, corners(&out), DVec3::ZERO);
        }
    }
    r.enclosed_volume = exposed;
    let scale = r.volume.abs().max(exposed.abs()).max(f64::MIN_POSITIVE);
    if (r.volume - exposed).abs() > 1e-9 * scale {
        r.defect(format!(
            "cell volume {} differs from the enclosed volume {}",
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
    for (_, t, _) in mesh.cells() {
        for i in 0..t.len() {
            for j in i + 1..t.len() {
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

/// Whether `b` runs round the same cycle as `a`.
fn same_cycle(a: &[u32], b: &[u32]) -> bool {
    let n = a.len();
    n == b.len() && (0..n).any(|r| (0..n).all(|i| b[(r + i) % n] == a[i]))
}
