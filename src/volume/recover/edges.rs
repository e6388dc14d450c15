//! Recovery of a missing surface edge (segment) `ab`.
//!
//! The segment is looked at from its end `a`: in the star of `a`, exactly one tet's cone
//! (closed) holds the direction to `b`, and the exact orientations of `b` against the three
//! faces of that cone at `a` say what the segment meets first — the interior of the opposite
//! face (no zero), an edge of it (one zero) or a vertex (two zeros: a vertex exactly on the
//! segment). A crossed face is flipped away 2-3 (it is always convex there: the segment joins
//! the two apexes only if it passes through the face); a crossed edge is removed by edge
//! removal, asking the ring triangulation for the diagonal `ab` when both are in the ring.
//! The same is tried from `b`. Flips that do not create the edge still change what is
//! crossed, so a few rounds are tried; then a Steiner point splits the segment (and the
//! surface triangles on it), and local Delaunay flips around it usually bring both halves
//! into the triangulation. A segment in a planar part of the hull whose crossing lies near
//! one end is split where it crosses, not halved towards that end (every half that keeps
//! the end would cross again). Recovered surface edges and faces are never flipped away
//! (`Surface::protects`), so the process is monotone.

use crate::volume::delaunay::predicates::orient;
use crate::volume::delaunay::{Delaunay, Keep, INF, MAX_RING};

use super::{quality, Ctx, RecoveryError};

/// What the segment from `a` towards `b` meets first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Cross {
    /// `ab` is an edge.
    Exists,
    /// The interior of face `face` (opposite `a`) of tet `tet`.
    Face(u32, u8),
    /// The interior of edge `xy`.
    Edge(u32, u32),
    /// A vertex exactly on the open segment.
    Vertex(u32),
}

/// The first thing the segment `a → b` crosses, or `None` if no finite tet around `a` holds
/// its direction (only possible for a segment leaving the hull: invalid input).
pub(super) fn first_crossing(dt: &mut Delaunay, a: u32, b: u32) -> Option<(Cross, u32)> {
    let pb = dt.point(b);
    for t in dt.tets_around_vertex(a) {
        if dt.is_ghost(t) {
            continue;
        }
        let v = dt.tet(t);
        if v.contains(&b) {
            return Some((Cross::Exists, t));
        }
        let i = v.iter().position(|&x| x == a)?;
        let mut zeros = [0usize; 3];
        let mut nz = 0;
        let mut ok = true;
        for j in 0..4 {
            if j == i {
                continue;
            }
            let mut q = [
                dt.point(v[0]),
                dt.point(v[1]),
                dt.point(v[2]),
                dt.point(v[3]),
            ];
            q[j] = pb;
            let s = orient(&q[0], &q[1], &q[2], &q[3]);
            if s < 0.0 {
                ok = false;
                break;
            }
            if s == 0.0 {
                zeros[nz] = j;
                nz += 1;
            }
        }
        if !ok {
            continue;
        }
        let rest: Vec<usize> = (0..4)
            .filter(|k| *k != i && !zeros[..nz].contains(k))
            .collect();
        return match nz {
            0 => Some((Cross::Face(t, i as u8), t)),
            1 => Some((Cross::Edge(v[rest[0]], v[rest[1]]), t)),
            2 => Some((Cross::Vertex(v[rest[0]]), t)),
            _ => continue,
        };
    }
    None
}

/// How a missing edge was dealt with.
pub(super) enum EdgeResult {
    /// The edge is in the triangulation.
    Present,
    /// The segment was split at this vertex (new Steiner point or an existing vertex lying
    /// on it); the two halves must be recovered.
    Split(u32),
}

/// Try to remove edge `xy` (not a surface edge) so that `ab` appears if possible.
pub(super) fn remove_crossing_edge(ctx: &mut Ctx, x: u32, y: u32, a: u32, b: u32) -> bool {
    if ctx.surface.protects(&[x, y]) {
        return false;
    }
    remove_edge_deep(ctx, x, y, Keep::Edge(a, b))
}

/// Edge removal of `xy`, keeping `keep` if the ring allows, else any valid one. When no
/// triangulation of the ring is valid, the ring is shrunk first (one level of the recursive
/// "n-to-m" flips): a 2-3 flip on a face `(x, y, c_i)` takes `c_i` out of the ring; then the
/// removal is tried again.
pub(super) fn remove_edge_deep(ctx: &mut Ctx, x: u32, y: u32, keep: Keep) -> bool {
    let try_remove = |ctx: &mut Ctx| {
        let ok = (keep != Keep::Any && ctx.dt.remove_edge_with(x, y, keep, quality).is_ok())
            || ctx.dt.remove_edge_with(x, y, Keep::Any, quality).is_ok();
        if ok {
            ctx.report.flips += 1;
        }
        ok
    };
    if try_remove(ctx) {
        return true;
    }
    for _ in 0..MAX_RING {
        let Some((tets, ring)) = ctx.dt.tets_around_edge(x, y) else {
            return false;
        };
        if !shrink_ring(ctx, x, y, &tets, &ring) {
            return false;
        }
        if try_remove(ctx) {
            return true;
        }
    }
    false
}

/// Take one vertex out of the ring of edge `xy`: a 2-3 flip on a face `(x, y, c_i)`, or the
/// removal of an edge `x c_i` or `y c_i` (which deletes that face) — the latter matters on
/// degenerate (coplanar) configurations where the 2-3 flip would make a flat tet.
fn shrink_ring(ctx: &mut Ctx, x: u32, y: u32, tets: &[u32], ring: &[u32]) -> bool {
    for (i, &t) in tets.iter().enumerate() {
        // Face (x, y, ring[i]) of tet i is the one it shares with tet i-1.
        let c = ring[i];
        if c == INF || ctx.surface.protects(&[x, y, c]) {
            continue;
        }
        let v = ctx.dt.tet(t);
        let Some(f) = (0..4).find(|&f| ![x, y, c].contains(&v[f])) else {
            continue;
        };
        if ctx.dt.flip23(t, f as u8).is_ok() {
            ctx.report.flips += 1;
            return true;
        }
    }
    for &c in ring {
        for e in [x, y] {
            if c == INF || ctx.surface.protects(&[e, c]) {
                continue;
            }
            if ctx.dt.remove_edge(e, c, quality).is_ok() {
                ctx.report.flips += 1;
                return true;
            }
        }
    }
    false
}

/// One round of flips against what the segment `from → to` meets first. Returns whether
/// something was flipped, or the vertex found on the segment.
fn flip_round(ctx: &mut Ctx, from: u32, to: u32, a: u32, b: u32) -> Result<Option<Cross>, ()> {
    let Some((cross, _)) = first_crossing(ctx.dt, from, to) else {
        return Err(());
    };
    match cross {
        Cross::Exists | Cross::Vertex(_) => Ok(Some(cross)),
        Cross::Edge(x, y) => Ok(remove_crossing_edge(ctx, x, y, a, b).then_some(cross)),
        Cross::Face(t, f) => {
            if ctx.dt.flip23(t, f).is_ok() {
                ctx.report.flips += 1;
                return Ok(Some(cross));
            }
            // Not convex: remove one of the face's edges instead (this deletes the face).
            let v = ctx.dt.face_vertices(t, f);
            for k in 0..3 {
                if remove_crossing_edge(ctx, v[k], v[(k + 1) % 3], a, b) {
                    return Ok(Some(cross));
                }
            }
            Ok(None)
        }
    }
}

/// Recover edge `ab` (both surface vertices), by flips first, then by splitting it.
pub(super) fn recover_edge(ctx: &mut Ctx, a: u32, b: u32) -> Result<EdgeResult, RecoveryError> {
    const ROUNDS: usize = 12;
    for _ in 0..ROUNDS {
        let mut progress = false;
        for (from, to) in [(a, b), (b, a)] {
            match flip_round(ctx, from, to, a, b) {
                Err(()) => return Err(ctx.edge_error(a, b, "the segment leaves the hull")),
                Ok(Some(Cross::Exists)) => return Ok(EdgeResult::Present),
                Ok(Some(Cross::Vertex(v))) => return split_at_vertex(ctx, a, b, v),
                Ok(Some(_)) => {
                    progress = true;
                    break;
                }
                Ok(None) => {}
            }
        }
        if !progress {
            break;
        }
    }
    if ctx.dt.has_edge(a, b) || super::hull::recover_in_hull_plane(ctx, a, b, remove_crossing_edge)
    {
        return Ok(EdgeResult::Present);
    }
    steiner_on_edge(ctx, a, b)
}

/// An existing vertex `v` lies exactly on the open segment `ab`: it becomes a surface
/// vertex splitting the segment (refused if it already is one: the surface would overlap).
fn split_at_vertex(ctx: &mut Ctx, a: u32, b: u32, v: u32) -> Result<EdgeResult, RecoveryError> {
    if ctx.surface.is_vertex(v) {
        return Err(ctx.edge_error(a, b, &format!("surface vertex {v} lies on this edge")));
    }
    ctx.surface.split_edge(a, b, v);
    Ok(EdgeResult::Split(v))
}

/// A Steiner point closer than this fraction of its segment's length to a vertex would
/// coincide with it to rounding.
const COINCIDENT: f64 = 1e-9;
/// A Steiner point goes at a crossed vertex's projection only when that vertex lies at least
/// this fraction of the segment's length off it.
const SEPARATION: f64 = 0.02;

/// Split segment `ab` with a new vertex near the projection of the closest vertex of what
/// it crosses first (so both halves keep away from that vertex), else near the midpoint.
fn steiner_on_edge(ctx: &mut Ctx, a: u32, b: u32) -> Result<EdgeResult, RecoveryError> {
    let (pa, pb) = (ctx.dt.point(a), ctx.dt.point(b));
    let d = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
    let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let mut params = Vec::with_capacity(8);
    let first = first_crossing(ctx.dt, a, b);
    let hint = first.map(|(_, t)| t);
    let verts: Vec<u32> = match first {
        Some((Cross::Face(t, f), _)) => ctx.dt.face_vertices(t, f).to_vec(),
        Some((Cross::Edge(x, y), _)) => vec![x, y],
        _ => Vec::new(),
    };
    if let Some((cross, _)) = first {
        let mut best: Option<(f64, f64)> = None;
        for &v in &verts {
            let p = ctx.dt.point(v);
            let w = [p[0] - pa[0], p[1] - pa[1], p[2] - pa[2]];
            let t = (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd;
            let q = [w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]];
            let dist = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
            let better = match best {
                None => true,
                Some((k, _)) => dist < k,
            };
            if t > 0.2 && t < 0.8 && better {
                best = Some((dist, t));
            }
        }
        // A vertex hardly off the segment would get a new point right beside it; in a planar
        // part of the hull, where the crossing edge from that vertex also crosses the next
        // pieces of the fan, that repeats with each piece, closer every time.
        let beside = best.is_some_and(|(dist, _)| dist < SEPARATION * SEPARATION * dd);
        if let (Some((_, t)), false) = (best, beside) {
            params.push(t);
        } else if let Some(t) = match cross {
            Cross::Edge(x, y) => super::hull::crossing_parameter(ctx, a, b, x, y),
            _ => None,
        } {
            // In a planar part of the hull, a crossing hull edge next to an end stays
            // crossed by every half that keeps that end: the split goes where it crosses.
            params.push(t);
        }
    }
    params.extend([0.5, 0.45, 0.55, 0.4, 0.6, 0.35, 0.65]);
    for t in params {
        let m = [pa[0] + t * d[0], pa[1] + t * d[1], pa[2] + t * d[2]];
        // A crossed vertex lying on the segment to rounding (not exactly, or it would be a
        // split at a vertex) projects onto itself: a point there would be a second node at the
        // same place, which no solver can use. The next parameter goes elsewhere.
        let on_a_vertex = verts.iter().any(|&v| {
            let p = ctx.dt.point(v);
            let g = [p[0] - m[0], p[1] - m[1], p[2] - m[2]];
            g[0] * g[0] + g[1] * g[1] + g[2] * g[2] <= COINCIDENT * COINCIDENT * dd
        });
        if on_a_vertex {
            continue;
        }
        let surface = &ctx.surface;
        let protect = |s: &[u32]| surface.protects(s);
        match ctx.dt.insert_split(m, hint, &protect) {
            Ok(out) => {
                let v = out.vertex;
                ctx.report.steiner_on_edges += 1;
                ctx.surface.split_edge(a, b, v);
                let surface = &ctx.surface;
                let protect = |s: &[u32]| surface.protects(s);
                ctx.report.flips += ctx.dt.flip_around(v, &protect, 256);
                return Ok(EdgeResult::Split(v));
            }
            Err(_) => continue,
        }
    }
    Err(ctx.edge_error(a, b, "no Steiner point could be inserted on it"))
}
