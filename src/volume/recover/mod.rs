//! Boundary recovery: make every surface triangle a (constrained) face of the
//! tetrahedralisation (seed paper, "Boundary Recovery"; DESIGN.md step 5).
//!
//! Edges first, then faces, as in Weatherill–Hassan and TetGen: a triangle cannot be a face
//! before its edges are edges, and once they are, what blocks the triangle is only edges
//! crossing it (see `faces.rs`). Swaps (2-3, 3-2, general edge removal) are tried first; only
//! when they cannot, the surface is changed by a Steiner point on the missing edge or inside
//! the missing triangle (`edges.rs`, `faces.rs`), inserted by splitting the simplex holding
//! it so nothing already recovered is destroyed, followed by local Delaunay flips. The
//! surface triangles on a split edge or face are split with it (`surface.rs`), keeping their
//! orientation and their `parent`; new points lie on the segment or in the triangle's plane
//! (to rounding), so every original triangle is exactly tiled by its pieces.
//!
//! A missing segment in a planar part of the hull (a symmetry plane) is the 2-D problem:
//! every hull edge crossing it is flipped in Sloan's queue order (`hull.rs`) before a
//! Steiner point is tried.
//!
//! Recovered edges and faces are protected from every later flip or split, so the work only
//! moves forward; the number of Steiner points is bounded, and running out of budget, a
//! vertex lying on a surface edge or inside a surface triangle, or crossing surface pieces
//! are reported as [`RecoveryError`] naming the triangle.
//!
//! Then every boundary Steiner point is suppressed if it can be (`suppress.rs`): deleted by
//! re-filling its star without it, or moved off the surface into the volume (George's
//! boundary-preserving approach), so the input triangles come back exactly; the ones that
//! stay are counted in [`RecoveryReport::steiner_left_on_surface`].
//!
//! Embedded segments (edges of embedded model edges: free curves inside the volume) are
//! recovered like triangle edges ([`recover_boundary_and_segments`]). Nothing protects them
//! in the later stages yet (the kernel has constrained faces, not constrained edges):
//! `mesh_volume` counts those lost.

mod edges;
mod faces;
mod facet;
mod hull;
mod suppress;
mod surface;

use crate::volume::delaunay::Delaunay;

use edges::{recover_edge, EdgeResult};
use faces::{recover_face, FaceResult};
use surface::Surface;

/// What recovery did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct RecoveryReport {
    /// Flips performed (2-3, 3-2, edge removals, and Delaunay flips after Steiner points).
    pub flips: usize,
    /// Steiner points recovery added on surface edges (splitting the edge and its triangles)
    /// or on embedded segments.
    pub steiner_on_edges: usize,
    /// Steiner points recovery added inside surface triangles.
    pub steiner_on_faces: usize,
    /// Of those boundary Steiner points, how many were taken off the surface afterwards
    /// (deleted, or moved into the volume), giving the input triangles back.
    pub steiner_removed: usize,
    /// Of the removed ones, how many stay as interior points (moved off the surface into the
    /// volume because no tetrahedralisation without them was found locally).
    pub steiner_interior: usize,
    /// Boundary Steiner points still on the surface at the end:
    /// `steiner_on_edges + steiner_on_faces - steiner_removed`.
    pub steiner_left_on_surface: usize,
}

/// Why recovery failed: the surface triangle (index in the current `triangles`, and the
/// original triangle it came from) and its vertices' coordinates.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "boundary recovery failed at surface triangle {triangle} (from input triangle {parent}), \
     vertices {vertices:?} at {}, {} and {}: {why}",
    crate::geometry::Xyz(glam::DVec3::from_array(.points[0])),
    crate::geometry::Xyz(glam::DVec3::from_array(.points[1])),
    crate::geometry::Xyz(glam::DVec3::from_array(.points[2]))
)]
pub struct RecoveryError {
    pub triangle: usize,
    pub parent: u32,
    /// For a missing embedded segment: the input segment (then `triangle` and `parent` are
    /// `0`, not meaningful, and `vertices[2] == vertices[1]`).
    pub segment: Option<u32>,
    pub vertices: [u32; 3],
    pub points: [[f64; 3]; 3],
    /// Boxed to keep the error small (it travels through every recovery step's `Result`).
    pub why: Box<str>,
}

/// Tet quality used to choose among edge-removal triangulations: volume over the cube of
/// the root-mean-square edge length, normalised to 1 for the regular tet (called only on
/// positively oriented tets).
pub(crate) fn quality(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let s = |p: &[f64; 3], q: &[f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let (u, v, w) = (s(a, d), s(b, d), s(c, d));
    let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    let l2 = |x: [f64; 3]| x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    let sum = l2(u) + l2(v) + l2(w) + l2(s(a, b)) + l2(s(b, c)) + l2(s(c, a));
    // Regular tet of edge 1: det = 1/√2, sum = 6.
    det.abs() / sum.powf(1.5) * 6f64.powf(1.5) * std::f64::consts::SQRT_2
}

/// Working state shared by edge and face recovery.
struct Ctx<'a, 'b> {
    pub dt: &'a mut Delaunay,
    pub surface: Surface<'b>,
    pub report: RecoveryReport,
}

impl Ctx<'_, '_> {
    pub fn face_error(&self, k: u32, why: &str) -> RecoveryError {
        let t = self.surface.tris[k as usize];
        RecoveryError {
            triangle: k as usize,
            parent: self.surface.parent[k as usize],
            segment: None,
            vertices: t,
            points: t.map(|v| self.dt.point(v)),
            why: why.into(),
        }
    }

    pub fn edge_error(&self, a: u32, b: u32, why: &str) -> RecoveryError {
        if let (None, Some(s)) = (
            self.surface.triangle_of_edge(a, b),
            self.surface.segment_parent(a, b),
        ) {
            return RecoveryError {
                triangle: 0,
                parent: 0,
                segment: Some(s),
                vertices: [a, b, b],
                points: [a, b, b].map(|v| self.dt.point(v)),
                why: format!("embedded segment {a}-{b}: {why}").into(),
            };
        }
        let k = self.surface.triangle_of_edge(a, b).unwrap_or(0);
        self.face_error(k, &format!("its edge {a}-{b}: {why}"))
    }
}

/// Make every triangle of `triangles` (input indices of `dt`'s points, all inserted) a face
/// of `dt`, marked constrained. Triangles may be split (new points are appended to `dt`);
/// `parent[k]` is the original triangle of triangle `k` (initialised to the identity if its
/// length does not match). Closed shells, interfaces (edges shared by more than two
/// triangles) and open embedded sheets (free edges inside the volume) are all handled the same.
pub fn recover_boundary(
    dt: &mut Delaunay,
    triangles: &mut Vec<[u32; 3]>,
    parent: &mut Vec<u32>,
) -> Result<RecoveryReport, RecoveryError> {
    recover_boundary_and_segments(dt, triangles, parent, &mut Vec::new(), &mut Vec::new())
}

/// [`recover_boundary`], and also make every segment of `segments` (embedded edges: free
/// curves inside the volume, on no triangle) an edge of `dt`. Segments are split by Steiner
/// points like triangle edges; `segment_parent[i]` is the input segment of segment `i`
/// (initialised to the identity if its length does not match).
pub fn recover_boundary_and_segments(
    dt: &mut Delaunay,
    triangles: &mut Vec<[u32; 3]>,
    parent: &mut Vec<u32>,
    segments: &mut Vec<[u32; 2]>,
    segment_parent: &mut Vec<u32>,
) -> Result<RecoveryReport, RecoveryError> {
    let n0 = triangles.len();
    // The input, to give the original triangles back where every Steiner point on them goes.
    let identity =
        |p: &[u32], n: usize| p.len() != n || p.iter().enumerate().all(|(k, &q)| q == k as u32);
    let original = identity(parent, n0).then(|| triangles.clone());
    let original_segments = identity(segment_parent, segments.len()).then(|| segments.clone());
    let first_steiner = dt.num_points() as u32;
    let surface = Surface::new(triangles, parent, segments, segment_parent);
    let mut ctx = Ctx {
        dt,
        surface,
        report: RecoveryReport::default(),
    };
    for k in 0..n0 as u32 {
        for v in ctx.surface.tris[k as usize] {
            if (v as usize) >= ctx.dt.num_points() || ctx.dt.vertex_tet(v).is_none() {
                return Err(ctx.face_error(k, &format!("vertex {v} is not in the triangulation")));
            }
        }
    }
    for i in 0..ctx.surface.segs.len() {
        let [a, b] = ctx.surface.segs[i];
        for v in [a, b] {
            if (v as usize) >= ctx.dt.num_points() || ctx.dt.vertex_tet(v).is_none() || a == b {
                return Err(ctx.edge_error(
                    a,
                    b,
                    &format!("vertex {v} is not in the triangulation"),
                ));
            }
        }
    }
    // Steiner budget: generous, but finite, so a pathological input fails instead of looping.
    let budget = 8 * n0 + 1000;
    let mut edge_work: Vec<(u32, u32)> = ctx.surface.edges();
    edge_work.reverse();
    // Faces in index order; a split triangle keeps its slot (re-examined after its new
    // edges) and appends the other pieces, so the scan reaches them too.
    let mut k = 0u32;
    loop {
        while let Some((a, b)) = edge_work.pop() {
            if !ctx.surface.is_edge(a, b) {
                continue; // split meanwhile; its halves are queued
            }
            if ctx.dt.has_edge(a, b) || facet::swap_to_existing(&mut ctx, a, b) {
                continue;
            }
            if steiner_count(&ctx.report) > budget {
                return Err(ctx.edge_error(a, b, "Steiner point budget exhausted"));
            }
            let r = recover_edge(&mut ctx, a, b)?;
            if let EdgeResult::Split(m) = r {
                // The halves, the edges joining m to the split triangles' third vertices, and
                // what the in-facet Delaunay swaps make.
                edge_work.extend(facet::delaunay_around(&mut ctx, m));
                edge_work.extend(ctx.surface.edges_at(m));
            }
        }
        if k as usize >= ctx.surface.tris.len() {
            break;
        }
        if steiner_count(&ctx.report) > budget {
            return Err(ctx.face_error(k, "Steiner point budget exhausted"));
        }
        // All edges are present here; a face split adds three edges and two triangles.
        match recover_face(&mut ctx, k)? {
            FaceResult::Present => {
                ctx.surface.set_recovered(k);
                k += 1;
            }
            FaceResult::Split(m) => {
                edge_work.extend(facet::delaunay_around(&mut ctx, m));
                edge_work.extend(ctx.surface.edges_at(m));
            }
        }
    }
    suppress::suppress_all(&mut ctx, first_steiner);
    let mut report = ctx.report;
    report.steiner_left_on_surface =
        report.steiner_on_edges + report.steiner_on_faces - report.steiner_removed;
    restore(triangles, parent, original.as_deref());
    restore(segments, segment_parent, original_segments.as_deref());
    Ok(report)
}

/// Drop the triangles (or segments) deleted by Steiner point suppression and group the rest
/// by parent in parent order; an original whose only piece is itself again gets its input
/// vertex order back (so with every Steiner point suppressed, `triangles` is the input list
/// and `parent` the identity).
fn restore<const N: usize>(
    triangles: &mut Vec<[u32; N]>,
    parent: &mut Vec<u32>,
    original: Option<&[[u32; N]]>,
) {
    let mut order: Vec<usize> = (0..triangles.len())
        .filter(|&k| triangles[k].iter().any(|&v| v != u32::MAX))
        .collect();
    order.sort_by_key(|&k| (parent[k], k));
    let mut tris = Vec::with_capacity(order.len());
    let mut par = Vec::with_capacity(order.len());
    let mut i = 0;
    while i < order.len() {
        let p = parent[order[i]];
        let mut j = i;
        while j < order.len() && parent[order[j]] == p {
            j += 1;
        }
        let sorted = |mut t: [u32; N]| {
            t.sort_unstable();
            t
        };
        match original.and_then(|o| o.get(p as usize)) {
            Some(&t0) if j == i + 1 && sorted(t0) == sorted(triangles[order[i]]) => {
                tris.push(t0);
                par.push(p);
            }
            _ => {
                for &k in &order[i..j] {
                    tris.push(triangles[k]);
                    par.push(p);
                }
            }
        }
        i = j;
    }
    *triangles = tris;
    *parent = par;
}

fn steiner_count(r: &RecoveryReport) -> usize {
    r.steiner_on_edges + r.steiner_on_faces
}
