//! Trailing edges found on a body, for `--wakes auto`: edges where two of the body's faces
//! meet in a thin wedge (the body's interior angle there below [`MAX_WEDGE_DEGREES`]) whose
//! outward bisector points downstream, grouped into open chains (one per wing, tail or fin).
//! A sharp leading edge fails the downstream test; a wing tip's cap meets the skin near 90°;
//! a smooth seam (a cylinder's) has no wedge.

use super::chain::{order_chain, Chain};
use crate::model::{EdgeId, FaceId, Model};
use glam::DVec3;
use std::collections::HashMap;

/// Largest interior angle of the body at a trailing edge (the ONERA M6's is about 15°).
pub const MAX_WEDGE_DEGREES: f64 = 60.0;
/// Smallest cosine between the wedge's outward bisector and the free stream: a trailing
/// edge swept up to 60° still sheds its wake.
const MIN_DOWNSTREAM: f64 = 0.5;
/// Places along an edge where the wedge is measured (fractions of its range).
const SAMPLES: [f64; 3] = [0.2, 0.5, 0.8];

/// The trailing-edge chains among the edges shared by two of `faces` (a region's boundary
/// faces), for a free stream along the unit vector `stream`. Chains that branch are left
/// out with a note.
pub(super) fn trailing_chains(
    model: &Model,
    region: usize,
    faces: &[FaceId],
    stream: DVec3,
) -> Vec<Chain> {
    // Each boundary face's side: true when its normal Su×Sv points out of the region.
    let sides: HashMap<FaceId, bool> = model
        .region_faces(region)
        .filter(|fu| faces.contains(&fu.face))
        .map(|fu| (fu.face, !fu.reversed))
        .collect();
    let mut users: HashMap<EdgeId, Vec<(FaceId, usize, usize)>> = HashMap::new();
    for &f in sides.keys() {
        for (l, lp) in model.faces[f].loops.iter().enumerate() {
            for (k, u) in lp.uses.iter().enumerate() {
                users.entry(u.edge).or_default().push((f, l, k));
            }
        }
    }
    let embedded: Vec<EdgeId> = (model.regions.iter())
        .flat_map(|r| &r.embedded_faces)
        .flat_map(|&f| &model.faces[f].loops)
        .flat_map(|l| l.uses.iter().map(|u| u.edge))
        .collect();
    let mut edges: Vec<EdgeId> = users
        .iter()
        // Two uses: two faces, or one face's seam (a skin lofted round a closed section, its
        // seam on the trailing edge).
        .filter(|(e, uses)| uses.len() == 2 && !embedded.contains(e))
        .filter(|(&e, uses)| {
            let out = |(f, l, k): (FaceId, usize, usize)| (f, l, k, sides[&f]);
            is_trailing(model, e, out(uses[0]), out(uses[1]), stream)
        })
        .map(|(&e, _)| e)
        .collect();
    edges.sort_unstable();
    let mut chains = Vec::new();
    for group in connected(model, &edges) {
        match order_chain(model, &group) {
            Ok(c) => chains.push(c),
            Err(m) => log::warn!(
                "trailing edges {}: {m}; no wake shed from them",
                group
                    .iter()
                    .map(|&e| model.edge_ref(e).to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
    }
    chains
}

/// Whether edge `e`, used by loop use (face, loop, use) `a` and `b` (each with whether the
/// face's normal points out of the region), is a trailing edge at every sample.
fn is_trailing(
    model: &Model,
    e: EdgeId,
    a: (FaceId, usize, usize, bool),
    b: (FaceId, usize, usize, bool),
    stream: DVec3,
) -> bool {
    let edge = &model.edges[e];
    let Some(curve) = &edge.curve else {
        return false;
    };
    let cos_wedge = MAX_WEDGE_DEGREES.to_radians().cos();
    SAMPLES.iter().all(|&s| {
        let t = edge.range.0 + (edge.range.1 - edge.range.0) * s;
        let tangent = curve.derivs(t).d1;
        // Into the face from the edge (the face lies left of its loop's uses in (u,v)), and
        // the normal out of the region (into the body).
        let side = |(f, l, k, out): (FaceId, usize, usize, bool)| -> Option<(DVec3, DVec3)> {
            let face = &model.faces[f];
            let u = &face.loops[l].uses[k];
            let uv = model.use_uv(f, u, t)?;
            let normal = face.surface.normal(uv);
            let along = if u.reversed { -tangent } else { tangent };
            let inward = normal.cross(along).normalize_or_zero();
            let out_of_region = if out { normal } else { -normal };
            (inward != DVec3::ZERO && normal != DVec3::ZERO).then_some((inward, out_of_region))
        };
        let (Some((m1, n1)), Some((m2, n2))) = (side(a), side(b)) else {
            return false;
        };
        // Each face bends towards the other's outside: the wedge between them is the body.
        let body_wedge = m2.dot(n1) > 0.0 && m1.dot(n2) > 0.0;
        let thin = m1.dot(m2) >= cos_wedge;
        let downstream = (-(m1 + m2)).normalize_or_zero().dot(stream) >= MIN_DOWNSTREAM;
        body_wedge && thin && downstream
    })
}

/// The edges in groups joined at shared vertices.
fn connected(model: &Model, edges: &[EdgeId]) -> Vec<Vec<EdgeId>> {
    let mut group: Vec<usize> = (0..edges.len()).collect();
    fn root(group: &mut [usize], mut i: usize) -> usize {
        while group[i] != i {
            group[i] = group[group[i]];
            i = group[i];
        }
        i
    }
    let mut at_vertex: HashMap<usize, usize> = HashMap::new();
    for (i, &e) in edges.iter().enumerate() {
        for v in [model.edges[e].start, model.edges[e].end] {
            if let Some(&j) = at_vertex.get(&v) {
                let (ri, rj) = (root(&mut group, i), root(&mut group, j));
                group[ri] = rj;
            } else {
                at_vertex.insert(v, i);
            }
        }
    }
    let mut groups: Vec<Vec<EdgeId>> = Vec::new();
    let mut index: HashMap<usize, usize> = HashMap::new();
    for (i, &e) in edges.iter().enumerate() {
        let r = root(&mut group, i);
        let g = *index.entry(r).or_insert_with(|| {
            groups.push(Vec::new());
            groups.len() - 1
        });
        groups[g].push(e);
    }
    groups
}
