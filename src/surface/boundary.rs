//! The initial front of one face: the curve-mesh nodes of its loops placed in the face's
//! parameter plane through the pcurves, as directed segments with the face on their left.

use super::SurfaceError;
use crate::curve::CurveMesh;
use crate::model::{FaceId, Model};
use crate::sizing::SizingField;
use glam::{DVec2, DVec3};

/// A vertex of one face's mesh. The same global node may appear twice with different (u,v)
/// (both sides of a seam).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceVertex {
    pub uv: DVec2,
    pub xyz: DVec3,
    /// Global node id; `None` for a vertex created inside the face.
    pub node: Option<usize>,
}

/// Vertices and directed boundary segments (face on the left) of one face.
#[derive(Clone)]
pub struct Boundary {
    pub vertices: Vec<FaceVertex>,
    pub segments: Vec<[usize; 2]>,
    /// Segments of a slit: a model edge the face's loop runs along and back (a wake's side
    /// edge imprinted on a symmetry plane). Both directions stay on the front, so the face is
    /// meshed on both sides of the edge and conforms to it.
    pub slits: Vec<[usize; 2]>,
}

/// Build the boundary of `face` from the curve mesh. Loops are oriented (outer
/// counter-clockwise, holes clockwise), so the face is on the left of every segment. A
/// degenerate edge (pole) is cut in (u,v) into as many zero-length pieces as the ring of
/// spacing δ around the pole needs (see [`super::pole`]).
pub fn face_boundary(
    model: &Model,
    curves: &CurveMesh,
    sizing: &SizingField,
    face: FaceId,
) -> Result<Boundary, SurfaceError> {
    let f = &model.faces[face];
    let bounds = f.surface.bounds();
    let mut b = Boundary {
        vertices: Vec::new(),
        segments: Vec::new(),
        slits: Vec::new(),
    };
    // The model edge each vertex's outgoing segment runs along.
    let mut along: Vec<usize> = Vec::new();
    for lp in f.loops.iter().filter(|l| !l.uses.is_empty()) {
        let first = b.vertices.len();
        // Where the loop goes on in (u,v): the last vertex, or a pole segment's far end (which
        // may lie a whole period away from its start, so must not be unwrapped back).
        let mut reference: Option<DVec2> = None;
        for u in &lp.uses {
            let em = &curves.edges[u.edge];
            let n = em.nodes.len();
            let uv_at = |i: usize| {
                model
                    .use_uv(face, u, em.params[i])
                    .ok_or_else(|| SurfaceError::Boundary {
                        face: model.face_ref(face).to_string(),
                        edge: model.edge_ref(u.edge).to_string(),
                        at: curves.points[em.nodes[i]],
                    })
            };
            let mut shift = DVec2::ZERO;
            // Walk the edge's nodes in loop direction, all but the last (the next use's first).
            for k in 0..n - 1 {
                let i = if u.reversed { n - 1 - k } else { k };
                let raw = uv_at(i)?;
                // Inside an edge, follow the pcurve from the previous node: a segment spanning
                // half a period or more (a coarse arc on a cylinder) is ambiguous to unwrap.
                if k > 0 {
                    let prev = if u.reversed { i + 1 } else { i - 1 };
                    if let (Some(pc), Some(r)) = (&u.pcurve, reference) {
                        reference = Some(follow(
                            pc.as_ref(),
                            em.params[prev],
                            em.params[i],
                            r,
                            &bounds,
                        ));
                    }
                }
                let uv = match reference {
                    Some(r) => crate::model::unwrap_near(raw, r, &bounds),
                    None => raw,
                };
                shift = uv - raw;
                reference = Some(uv);
                b.vertices.push(FaceVertex {
                    uv,
                    xyz: curves.points[em.nodes[i]],
                    node: Some(em.nodes[i]),
                });
                along.push(u.edge);
            }
            // Follow the pcurve to the edge's last node, so the next use's first node (the
            // same point) unwraps next to it rather than half a period away.
            let degenerate = model.edges[u.edge].is_degenerate();
            if let (false, Some(pc), Some(r)) = (degenerate, &u.pcurve, reference) {
                let (prev, last) = if u.reversed { (1, 0) } else { (n - 2, n - 1) };
                reference = Some(follow(
                    pc.as_ref(),
                    em.params[prev],
                    em.params[last],
                    r,
                    &bounds,
                ));
            }
            if degenerate && n == 2 {
                let start = *b.vertices.last().expect("pushed above");
                // The pcurve carries the whole sweep of the pole: same period shift as the start.
                let end = uv_at(if u.reversed { 0 } else { 1 })? + shift;
                let delta = sizing.spacing(start.xyz);
                let surface = f.surface.as_ref();
                let pieces = super::pole::pieces(surface, start.xyz, start.uv, end, delta);
                for k in 1..pieces {
                    b.vertices.push(FaceVertex {
                        uv: start.uv.lerp(end, k as f64 / pieces as f64),
                        ..start
                    });
                    along.push(u.edge);
                }
                reference = Some(end);
            }
        }
        let last = b.vertices.len();
        for k in first..last {
            let next = if k + 1 == last { first } else { k + 1 };
            b.segments.push([k, next]);
        }
    }
    let edges: Vec<usize> = b.segments.iter().map(|s| along[s[0]]).collect();
    merge_coincident_copies(&mut b, edges);
    Ok(b)
}

/// Copies of one node closer in (u,v) than this fraction of their shortest segment are one.
const SAME_UV: f64 = 1e-3;

/// One front vertex for copies of a node that (u,v) puts at the same place. A hole that touches
/// the outer loop at a vertex (a bolt head tangent to a plate's edge, imprinted by the general
/// fuse) has that vertex in both loops, each copy placed by its own pcurve, a few 1e-6 apart:
/// two vertices the front treats as distinct though they are one point, so the zero-angle cusps
/// beside them never close. Copies a period apart (seam) or a pole's pieces stay distinct:
/// their distance in (u,v) is that of whole segments. A segment that then runs back along
/// another cancels when the front is built, unless both run along the same model edge (a
/// slit the face must conform to: [`Boundary::slits`]). `edges`: each segment's model edge.
fn merge_coincident_copies(b: &mut Boundary, edges: Vec<usize>) {
    let n = b.vertices.len();
    let mut shortest = vec![f64::INFINITY; n];
    for &[p, q] in &b.segments {
        let len = b.vertices[p].uv.distance(b.vertices[q].uv);
        shortest[p] = shortest[p].min(len);
        shortest[q] = shortest[q].min(len);
    }
    let mut by_node: std::collections::HashMap<usize, Vec<usize>> = Default::default();
    for (k, v) in b.vertices.iter().enumerate() {
        if let Some(node) = v.node {
            by_node.entry(node).or_default().push(k);
        }
    }
    let mut target: Vec<usize> = (0..n).collect();
    for copies in by_node.values().filter(|c| c.len() > 1) {
        for (i, &k) in copies.iter().enumerate() {
            let keep = copies[..i].iter().copied().find(|&j| {
                target[j] == j
                    && b.vertices[j].uv.distance(b.vertices[k].uv)
                        <= SAME_UV * shortest[j].min(shortest[k])
            });
            if let Some(j) = keep {
                target[k] = j;
            }
        }
    }
    let (segments, edges): (Vec<[usize; 2]>, Vec<usize>) = (b.segments.iter())
        .map(|s| s.map(|k| target[k]))
        .zip(edges)
        .filter(|(s, _)| s[0] != s[1])
        .unzip();
    b.segments = segments;
    let edge_of: std::collections::HashMap<[usize; 2], usize> =
        b.segments.iter().copied().zip(edges).collect();
    b.slits = (b.segments.iter().copied())
        .filter(|&[p, q]| {
            edge_of
                .get(&[q, p])
                .is_some_and(|e| Some(e) == edge_of.get(&[p, q]))
        })
        .collect();
}

/// Steps per segment when following a pcurve across a periodic domain.
const FOLLOW_STEPS: usize = 8;

/// Where the pcurve goes from `t0` (at `from`, already unwrapped) to `t1`, unwrapped step by
/// step so no step is ambiguous.
fn follow(
    pc: &dyn crate::geometry::Curve2d,
    t0: f64,
    t1: f64,
    from: DVec2,
    bounds: &crate::geometry::SurfaceBounds,
) -> DVec2 {
    let mut at = crate::model::unwrap_near(pc.point(t0), from, bounds);
    // The pcurve's own point may sit a period away from `from` (projected node on a seam).
    let offset = from - at;
    for k in 1..=FOLLOW_STEPS {
        let t = t0 + (t1 - t0) * k as f64 / FOLLOW_STEPS as f64;
        at = crate::model::unwrap_near(pc.point(t), at, bounds);
    }
    at + offset
}
