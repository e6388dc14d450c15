//! Coincident stretches: two edges of one face loop that leave their common vertex together and
//! stay within the CAD's tolerance of each other for a while. The face then has a slit of no
//! width there; in (u,v) the two pcurves, each approximate within that tolerance, wander across
//! each other, so the loop is not a simple polygon and no triangulation of it exists
//! (spring_iges_msbo_solid.igs: the ground plane cuts the coil along its seam line, edge 5 runs
//! within 2e-2 of edge 4 for 48 units while both edges' tolerances are 5e-2 and more).
//!
//! The repair is topological, as the CAD says it should be: the stretch of the edge kept (the
//! one with the smaller tolerance) is split off as an edge of its own, the other edge is cut
//! short to end where the stretch ends, at one new vertex, and
//! - the face with the slit loses the stretch altogether (both sides of the slit);
//! - the kept edge's other face uses both pieces of it;
//! - the cut edge's other face uses the split-off piece in place of the lost part, with a pcurve
//!   projected onto its surface.
//!
//! The two faces beyond the slit then meet along one edge, and every later stage sees a simple
//! loop. The geometry moves by no more than the tolerance along the stretch: the face with the
//! slit loses the area between the two edges, the cut edge's other face gains or loses the
//! same strip; both are below `gap × length`, which is reported.

use super::{Edge, EdgeId, EdgeUse, FaceId, Model, Vertex, VertexId};
use crate::geometry::Curve;
use std::sync::Arc;

/// Samples along the edge that is cut short, from the common vertex to its far end.
const SAMPLES: usize = 2000;
/// Stretches shorter than this fraction of the model's diagonal are left to the surface front
/// (a tangent cusp; splitting would leave an edge far shorter than any spacing).
const MIN_LENGTH: f64 = 1e-2;
/// At most this many merges per model (each changes the topology; a guard against cycling).
const MAX_MERGES: usize = 64;

/// One merged stretch, for the loader's note.
#[derive(Clone, Debug, PartialEq)]
pub struct StretchMerge {
    /// The face that had the slit.
    pub face: FaceId,
    /// Where both edges start.
    pub vertex: VertexId,
    /// The edge whose stretch was kept, split at `new_vertex`; the stretch is `new_edge`.
    pub kept: EdgeId,
    /// The edge cut short to end at `new_vertex`.
    pub cut: EdgeId,
    pub new_edge: EdgeId,
    pub new_vertex: VertexId,
    /// Length of the stretch along the cut edge.
    pub length: f64,
    /// Largest distance between the two edges along the stretch.
    pub gap: f64,
    /// The tolerance the stretch was held to.
    pub tolerance: f64,
}

/// A stretch found, before the model is changed.
struct Stretch {
    face: FaceId,
    vertex: VertexId,
    kept: EdgeId,
    cut: EdgeId,
    /// Parameter on `kept` and on `cut` where the stretch ends.
    t_kept: f64,
    t_cut: f64,
    length: f64,
    gap: f64,
    tolerance: f64,
}

/// Merge every coincident stretch of the model; `tolerance(e)` is the CAD tolerance of edge
/// `e`. Returns what was merged; a stretch whose repair would need a pcurve that cannot be
/// projected is left as it is.
pub fn merge_coincident_stretches(
    model: &mut Model,
    tolerance: &dyn Fn(EdgeId) -> f64,
) -> Vec<StretchMerge> {
    let diag = diagonal(model);
    // Split-off pieces keep the tolerance of the edge they come from.
    let mut tols: Vec<f64> = (0..model.edges.len()).map(tolerance).collect();
    let mut done = Vec::new();
    let mut refused: Vec<(FaceId, VertexId)> = Vec::new();
    while done.len() < MAX_MERGES {
        let Some(s) = find_stretch(model, &|e: EdgeId| tols[e], diag, &refused) else {
            break;
        };
        match apply(model, &s) {
            Some(m) => {
                tols.push(tols[m.kept]);
                done.push(m);
            }
            None => refused.push((s.face, s.vertex)),
        }
    }
    done
}

fn diagonal(model: &Model) -> f64 {
    let mut lo = glam::DVec3::splat(f64::INFINITY);
    let mut hi = glam::DVec3::splat(f64::NEG_INFINITY);
    for v in &model.vertices {
        lo = lo.min(v.point);
        hi = hi.max(v.point);
    }
    if lo.x <= hi.x {
        lo.distance(hi)
    } else {
        0.0
    }
}

/// The faces that use edge `e`, one entry per use.
fn users(model: &Model, e: EdgeId) -> Vec<FaceId> {
    let mut out = Vec::new();
    for (f, face) in model.faces.iter().enumerate() {
        for lp in &face.loops {
            out.extend(lp.uses.iter().filter(|u| u.edge == e).map(|_| f));
        }
    }
    out
}

/// The first stretch of the model: consecutive uses of one loop meeting at a vertex, both
/// edges used once by that face and once by another (different) face.
fn find_stretch(
    model: &Model,
    tolerance: &dyn Fn(EdgeId) -> f64,
    diag: f64,
    refused: &[(FaceId, VertexId)],
) -> Option<Stretch> {
    for (f, face) in model.faces.iter().enumerate() {
        for lp in &face.loops {
            let n = lp.uses.len();
            for k in 0..n {
                let (u1, u2) = (&lp.uses[k], &lp.uses[(k + 1) % n]);
                let (a, b) = (u1.edge, u2.edge);
                if a == b {
                    continue;
                }
                let (ea, eb) = (&model.edges[a], &model.edges[b]);
                if ea.is_degenerate() || eb.is_degenerate() || ea.is_closed() || eb.is_closed() {
                    continue;
                }
                let vertex = model.use_vertices(u1).1;
                if refused.contains(&(f, vertex)) {
                    continue;
                }
                let (fa, fb) = (users(model, a), users(model, b));
                let other = |uses: &[FaceId]| match uses {
                    [p, q] if (*p == f) != (*q == f) => Some(if *p == f { *q } else { *p }),
                    _ => None,
                };
                let (Some(oa), Some(ob)) = (other(&fa), other(&fb)) else {
                    continue;
                };
                if oa == ob {
                    continue;
                }
                let tol = tolerance(a).max(tolerance(b));
                // The edge with the tighter tolerance is the better geometry: keep it.
                let (kept, cut) = if tolerance(a) <= tolerance(b) {
                    (a, b)
                } else {
                    (b, a)
                };
                if let Some(s) = measure(model, f, vertex, kept, cut, tol) {
                    if s.length >= MIN_LENGTH * diag {
                        return Some(s);
                    }
                }
            }
        }
    }
    None
}

/// Walk `cut` from `vertex` while it stays within `tol` of `kept`.
fn measure(
    model: &Model,
    face: FaceId,
    vertex: VertexId,
    kept: EdgeId,
    cut: EdgeId,
    tol: f64,
) -> Option<Stretch> {
    let (ek, ec) = (&model.edges[kept], &model.edges[cut]);
    let (ck, cc) = (ek.curve.as_ref()?, ec.curve.as_ref()?);
    let (tc0, tc1) = if ec.start == vertex {
        ec.range
    } else {
        (ec.range.1, ec.range.0)
    };
    let (tk0, tk1) = if ek.start == vertex {
        ek.range
    } else {
        (ek.range.1, ek.range.0)
    };
    let (klo, khi) = (tk0.min(tk1), tk0.max(tk1));
    let mut hint = tk0;
    let mut prev = cc.point(tc0);
    let mut length = 0.0;
    let mut last: Option<(f64, f64)> = None;
    let mut gap: f64 = 0.0;
    for i in 1..SAMPLES {
        let t = tc0 + (tc1 - tc0) * i as f64 / SAMPLES as f64;
        let p = cc.point(t);
        let s = ck.closest_parameter(p, Some(hint))?.clamp(klo, khi);
        // The kept edge ends inside the stretch: not a slit this repair handles.
        if (s - tk1).abs() <= 1e-9 * (khi - klo) {
            return None;
        }
        let d = ck.point(s).distance(p);
        if d > tol {
            break;
        }
        length += p.distance(prev);
        prev = p;
        hint = s;
        gap = gap.max(d);
        last = Some((s, t));
    }
    let (t_kept, t_cut) = last?;
    // The whole cut edge lies along the kept one: not a slit either.
    if (t_cut - tc1).abs() <= 2.0 * (tc1 - tc0).abs() / SAMPLES as f64 {
        return None;
    }
    Some(Stretch {
        face,
        vertex,
        kept,
        cut,
        t_kept,
        t_cut,
        length,
        gap,
        tolerance: tol,
    })
}

/// Change the model as the module says; `None` (model untouched) when the split-off piece has
/// no pcurve on the cut edge's other face.
fn apply(model: &mut Model, s: &Stretch) -> Option<StretchMerge> {
    let v = s.vertex;
    let ek = model.edges[s.kept].clone();
    let curve: Arc<dyn Curve> = ek.curve.clone()?;
    let p = model.vertices.len();
    let point = curve.point(s.t_kept);
    // The split-off piece, from the common vertex to the new one (in the kept edge's direction).
    let (near, far) = if ek.start == v {
        (
            Edge {
                name: ek.name.clone(),
                curve: Some(curve.clone()),
                range: (ek.range.0, s.t_kept),
                start: v,
                end: p,
            },
            Edge {
                range: (s.t_kept, ek.range.1),
                start: p,
                ..ek.clone()
            },
        )
    } else {
        (
            Edge {
                name: ek.name.clone(),
                curve: Some(curve.clone()),
                range: (s.t_kept, ek.range.1),
                start: p,
                end: v,
            },
            Edge {
                range: (ek.range.0, s.t_kept),
                end: p,
                ..ek.clone()
            },
        )
    };
    let near_id = model.edges.len();
    let cut_other = users(model, s.cut).into_iter().find(|&f| f != s.face)?;
    let pcurve = {
        let surface = model.faces[cut_other].surface.as_ref();
        let reach = 4.0 * s.tolerance + 1e-9 * diagonal(model);
        let pc = super::project_pcurve(surface, curve.as_ref(), near.range, reach).ok()?;
        Arc::new(pc) as Arc<dyn crate::geometry::Curve2d>
    };

    // Commit: vertex, edges, then every loop.
    let cut_started_at_v = model.edges[s.cut].start == v;
    model.vertices.push(Vertex { name: None, point });
    model.edges[s.kept] = far;
    model.edges.push(near);
    {
        let ec = &mut model.edges[s.cut];
        if ec.start == v {
            ec.range.0 = s.t_cut;
            ec.start = p;
        } else {
            ec.range.1 = s.t_cut;
            ec.end = p;
        }
    }
    let near_starts_at_v = model.edges[near_id].start == v;
    for (f, face) in model.faces.iter_mut().enumerate() {
        for lp in &mut face.loops {
            let mut uses = Vec::with_capacity(lp.uses.len() + 1);
            for u in lp.uses.drain(..) {
                if u.edge == s.kept {
                    // Traversal order of the two pieces: the near piece first when the use
                    // leaves the common vertex.
                    let kept_piece = EdgeUse { ..u.clone() };
                    let near_piece = EdgeUse {
                        edge: near_id,
                        ..u.clone()
                    };
                    let leaves_v = (ek.start == v) != u.reversed;
                    if f == s.face {
                        uses.push(kept_piece);
                    } else if leaves_v {
                        uses.push(near_piece);
                        uses.push(kept_piece);
                    } else {
                        uses.push(kept_piece);
                        uses.push(near_piece);
                    }
                } else if u.edge == s.cut && f != s.face {
                    // The cut edge's other face: the piece stands in for the lost part.
                    let leaves_v = cut_started_at_v != u.reversed;
                    let piece = EdgeUse {
                        edge: near_id,
                        reversed: near_starts_at_v != leaves_v,
                        pcurve: Some(pcurve.clone()),
                    };
                    if leaves_v {
                        uses.push(piece);
                        uses.push(u);
                    } else {
                        uses.push(u);
                        uses.push(piece);
                    }
                } else {
                    uses.push(u);
                }
            }
            lp.uses = uses;
        }
    }
    Some(StretchMerge {
        face: s.face,
        vertex: v,
        kept: s.kept,
        cut: s.cut,
        new_edge: near_id,
        new_vertex: p,
        length: s.length,
        gap: s.gap,
        tolerance: s.tolerance,
    })
}
