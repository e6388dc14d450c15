//! Column feet on the source's edges. A face beside a source (a symmetry plane beside a wing
//! root or a wake root, a wing skin beside a leading-edge curve) gets its layer points on the
//! lines from its nodes to their nearest source points. When that nearest point lies inside a
//! segment of the model edge between face and source, the column stands over the middle of the
//! segment, and its lowest point makes a triangle with the segment whose angle there nears
//! 180° as the layers thin (a wake root segment of 0.7 under a first layer of 0.002): the
//! volume's boundary recovery cannot take such a triangle without a cascade of Steiner points,
//! and the tets beside it are as flat. The foot joins the edge as a node instead, so every
//! column stands on an edge node and the layer triangles beside the edge are right-angled.
//! A foot too near an edge node to split the segment moves to that node: two columns a few
//! hundredths of δ apart would make the same flat triangles between them.

use super::face_tris::{insert_edge_node, FaceTris};
use super::field::StageField;
use super::source::Near;
use crate::curve::CurveMesh;
use crate::model::{EdgeId, FaceId, Model};
use crate::sizing::SizingField;
use crate::surface::SurfaceMesh;
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// A foot splits a segment only between these fractions of it: no piece shorter than a
/// quarter of the segment it came from.
const SPLIT_RANGE: (f64, f64) = (0.25, 0.75);
/// How far (a fraction of the segment's length) a foot may lie from the segment's chord and
/// still count as on it (the chord of a curved edge lies off the curve by its sagitta).
const ON_CHORD: f64 = 0.05;

/// What [`add_feet`] did.
pub(super) struct Feet {
    /// Edge nodes added.
    pub added: usize,
    /// The nearest source points of the nodes whose feet moved onto an edge node (one entry
    /// per source, as `StageField::near` gives them).
    pub snapped: HashMap<usize, Vec<Near>>,
}

/// Add, as edge nodes, the feet of the nodes of the faces to be refined (not sources, not
/// embedded) that lie within the layers' reach and whose nearest point on a face source
/// (`face_source[s]`) falls inside a segment of a model edge between a source face and the
/// face; move every such foot onto its edge node. Curve sources grow no columns (their points
/// come from the elements), and feet on a curve would only crowd it with nodes.
#[allow(clippy::too_many_arguments)]
pub(super) fn add_feet(
    model: &Model,
    mesh: &mut SurfaceMesh,
    curves: &mut CurveMesh,
    sizing: &SizingField,
    field: &StageField,
    faces: &mut [FaceTris],
    faces_of_edge: &[Vec<FaceId>],
    source_faces: &HashSet<FaceId>,
    face_source: &[bool],
) -> Feet {
    let on_source = |e: EdgeId| faces_of_edge[e].iter().any(|f| source_faces.contains(f));
    let mut added = 0;
    let mut snapped: HashMap<usize, Vec<Near>> = HashMap::new();
    // A segment splits once: the halves hold a foot's node and split no further (later feet
    // on them move to their nearest node), so a face with many layer points beside the edge
    // (a thin first layer) cannot crowd it with nodes.
    let before: HashSet<usize> = curves
        .edges
        .iter()
        .flat_map(|c| c.nodes.iter().copied())
        .collect();
    for f in 0..model.faces.len() {
        let embedded = model.regions.iter().any(|r| r.embedded_faces.contains(&f));
        if source_faces.contains(&f) || embedded {
            continue;
        }
        let edges: Vec<EdgeId> = model.faces[f]
            .loops
            .iter()
            .flat_map(|l| l.uses.iter().map(|u| u.edge))
            .filter(|&e| e < curves.edges.len() && model.edges[e].curve.is_some() && on_source(e))
            .collect();
        if edges.is_empty() {
            continue;
        }
        let mut nodes: Vec<usize> = faces[f].tris.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        for v in nodes {
            let p = mesh.points[v];
            let delta = sizing.spacing(p);
            let mut nears = field.near(p);
            let mut moved = false;
            for (s, near) in nears.iter_mut().enumerate() {
                let reach = field.sources[s].distribution.reach(delta);
                if !face_source[s] || near.phi <= 0.0 || near.phi >= reach {
                    continue;
                }
                for &e in &edges {
                    let Some(at) = segment_holding(mesh, curves, e, near.foot) else {
                        continue;
                    };
                    let kept = |n: usize| before.contains(&curves.edges[e].nodes[n]);
                    if kept(at.0)
                        && kept(at.0 + 1)
                        && foot_on_edge(mesh, curves, faces, &faces_of_edge[e], model, e, at)
                    {
                        added += 1;
                    }
                    if let Some(node) = nearest_node(mesh, curves, e, near.foot) {
                        near.foot = node;
                        moved = true;
                    }
                    break;
                }
            }
            if moved {
                snapped.insert(v, nears);
            }
        }
    }
    Feet { added, snapped }
}

/// Where `foot` lies on edge `e`'s segments: the segment index and the fraction along it,
/// if it lies on one (within [`ON_CHORD`] of the chord).
fn segment_holding(
    mesh: &SurfaceMesh,
    curves: &CurveMesh,
    e: EdgeId,
    foot: DVec3,
) -> Option<(usize, f64)> {
    let nodes = &curves.edges[e].nodes;
    (0..nodes.len().saturating_sub(1)).find_map(|k| {
        let (a, b) = (mesh.points[nodes[k]], mesh.points[nodes[k + 1]]);
        let d = b - a;
        let len2 = d.length_squared();
        if len2 == 0.0 {
            return None;
        }
        let s = (foot - a).dot(d) / len2;
        ((0.0..=1.0).contains(&s) && foot.distance(a + d * s) <= ON_CHORD * len2.sqrt())
            .then_some((k, s))
    })
}

/// The node of edge `e` nearest `foot`, among the ends of the segment holding it.
fn nearest_node(mesh: &SurfaceMesh, curves: &CurveMesh, e: EdgeId, foot: DVec3) -> Option<DVec3> {
    let (k, _) = segment_holding(mesh, curves, e, foot)?;
    let nodes = &curves.edges[e].nodes;
    let (a, b) = (mesh.points[nodes[k]], mesh.points[nodes[k + 1]]);
    Some(if foot.distance(a) <= foot.distance(b) {
        a
    } else {
        b
    })
}

/// If the foot, at fraction `s` of segment `k` of edge `e`, lies within [`SPLIT_RANGE`] of it,
/// put a node at the nearest point of the true curve. True when added.
#[allow(clippy::too_many_arguments)]
fn foot_on_edge(
    mesh: &mut SurfaceMesh,
    curves: &mut CurveMesh,
    faces: &mut [FaceTris],
    faces_of_edge: &[FaceId],
    model: &Model,
    e: EdgeId,
    (k, s): (usize, f64),
) -> bool {
    let Some(curve) = model.edges[e].curve.clone() else {
        return false;
    };
    if s < SPLIT_RANGE.0 || s > SPLIT_RANGE.1 {
        return false;
    }
    let (na, nb) = (curves.edges[e].nodes[k], curves.edges[e].nodes[k + 1]);
    let (a, b) = (mesh.points[na], mesh.points[nb]);
    let (ta, tb) = (curves.edges[e].params[k], curves.edges[e].params[k + 1]);
    let foot = a + (b - a) * s;
    let Some(t) = curve.closest_parameter(foot, Some(ta + (tb - ta) * s)) else {
        return false;
    };
    // Strictly inside the segment, by parameter and by position.
    let p = curve.point(t);
    let sp = (p - a).dot(b - a) / (b - a).length_squared();
    let inside =
        (t - ta) * (tb - t) > 0.0 && sp > 0.5 * SPLIT_RANGE.0 && sp < 1.0 - 0.5 * SPLIT_RANGE.0;
    if !inside || !p.is_finite() {
        return false;
    }
    insert_edge_node(mesh, curves, faces, faces_of_edge, e, k, t, p);
    true
}
