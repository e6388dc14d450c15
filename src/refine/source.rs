//! The distance function of a refinement source (seed paper: "every point in space can be
//! assigned a scalar value φ, the distance to the nearest point on a specified curve or
//! surface"): the source's own mesh — triangles of its faces, segments of its edges — in an
//! R*-tree (the paper uses an ADT), the nearest facet found there, then the foot refined onto
//! the true geometry through the geometry traits (`closest_uv`, `closest_parameter`), so native
//! and CAD sources behave alike.

use crate::curve::CurveMesh;
use crate::model::{EdgeId, FaceId, Model};
use glam::{DVec2, DVec3};
use rstar::{PointDistance, RTree, RTreeObject, AABB};

/// Below this fraction of the source's shortest element, a point counts as lying on the source
/// (its nearest-point line has no direction of its own).
const ON_SOURCE: f64 = 1e-9;

/// One element of a source's mesh.
#[derive(Clone, Debug)]
struct Element {
    corners: [DVec3; 3],
    /// A triangle of a face (with its corners' (u,v)), or a segment of an edge (with its
    /// ends' curve parameters; `corners[2] == corners[1]`).
    kind: Kind,
}

#[derive(Clone, Debug)]
enum Kind {
    /// `nodes` index the source's node normals.
    Triangle {
        face: FaceId,
        uv: [DVec2; 3],
        nodes: [u32; 3],
    },
    Segment {
        edge: EdgeId,
        t: [f64; 2],
    },
}

impl RTreeObject for Element {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        let lo = self.corners[0].min(self.corners[1]).min(self.corners[2]);
        let hi = self.corners[0].max(self.corners[1]).max(self.corners[2]);
        AABB::from_corners(lo.to_array(), hi.to_array())
    }
}

impl PointDistance for Element {
    fn distance_2(&self, p: &[f64; 3]) -> f64 {
        let p = DVec3::from_array(*p);
        p.distance_squared(self.closest(p).0)
    }
}

impl Element {
    /// Closest point of the element to `p`, and its barycentric weights.
    fn closest(&self, p: DVec3) -> (DVec3, [f64; 3]) {
        let [a, b, c] = self.corners;
        match self.kind {
            Kind::Segment { .. } => {
                let (q, s) = closest_on_segment(p, a, b);
                (q, [1.0 - s, s, 0.0])
            }
            Kind::Triangle { .. } => closest_on_triangle(p, a, b, c),
        }
    }
}

/// What the distance function says of a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Near {
    /// Distance to the source.
    pub phi: f64,
    /// The nearest point of the source.
    pub foot: DVec3,
    /// Unit direction from the foot to the point, or (on the source) the source's unit normal
    /// there for a face, zero for an edge: the caller picks a side.
    pub dir: DVec3,
    /// Unit tangent of the source curve at the foot for a curve source; zero for a face.
    pub along: DVec3,
}

/// The distance function of one source: some faces and edges of the model.
pub struct SourceDistance<'m> {
    model: &'m Model,
    tree: RTree<Element>,
    on_source: f64,
    /// Per source node: the angle-weighted normal of the source's triangles around it,
    /// oriented into the region, and whether those triangles lie on more than one face (a
    /// ridge or corner of the source, where no one surface normal serves).
    node_normal: Vec<(DVec3, bool)>,
}

/// The normal of a face's triangles that points into the region it bounds (`Su × Sv`
/// points out of the region unless the face use is reversed); +1 for an embedded face, whose
/// two sides are both in the region.
fn into_region(model: &Model, f: FaceId) -> f64 {
    for r in &model.regions {
        for s in &r.shells {
            if let Some(u) = s.faces.iter().find(|u| u.face == f) {
                return if u.reversed { 1.0 } else { -1.0 };
            }
        }
    }
    1.0
}

impl<'m> SourceDistance<'m> {
    /// From the surface mesh (`points`, `triangles`, `face_of`) and the curve mesh of `model`:
    /// the triangles of `faces` and the segments of `edges`.
    pub fn new(
        model: &'m Model,
        points: &[DVec3],
        triangles: &[[usize; 3]],
        face_of: &[FaceId],
        curves: &CurveMesh,
        faces: &[FaceId],
        edges: &[EdgeId],
    ) -> Self {
        let mut elements = Vec::new();
        let mut shortest = f64::INFINITY;
        let mut node_of: std::collections::HashMap<usize, u32> = Default::default();
        let mut node_normal: Vec<(DVec3, bool)> = Vec::new();
        let mut node_face: Vec<FaceId> = Vec::new();
        let picked: Vec<usize> = (0..triangles.len())
            .filter(|&k| faces.contains(&face_of[k]))
            .collect();
        let node_uv = node_parameters(model, points, triangles, face_of, &picked);
        let uvs: Vec<[DVec2; 3]> = picked
            .iter()
            .map(|&k| {
                triangles[k].map(|v| node_uv.get(&(face_of[k], v)).copied().unwrap_or(DVec2::NAN))
            })
            .collect();
        for (&k, uv) in picked.iter().zip(uvs) {
            let (t, f) = (triangles[k], face_of[k]);
            let corners = t.map(|v| points[v]);
            let sign = into_region(model, f);
            let mut nodes = [0u32; 3];
            for i in 0..3 {
                shortest = shortest.min(corners[i].distance(corners[(i + 1) % 3]));
                let id = *node_of.entry(t[i]).or_insert_with(|| {
                    node_normal.push((DVec3::ZERO, false));
                    node_face.push(f);
                    (node_normal.len() - 1) as u32
                });
                nodes[i] = id;
                let (p, q, r) = (corners[i], corners[(i + 1) % 3], corners[(i + 2) % 3]);
                let n = (q - p).cross(r - p).normalize_or_zero() * sign;
                let angle = (q - p).angle_between(r - p);
                let slot = &mut node_normal[id as usize];
                slot.0 += n * angle;
                slot.1 |= node_face[id as usize] != f;
            }
            elements.push(Element {
                corners,
                kind: Kind::Triangle { face: f, uv, nodes },
            });
        }
        for n in &mut node_normal {
            n.0 = n.0.normalize_or_zero();
        }
        for &e in edges {
            let Some(mesh) = curves.edges.get(e) else {
                continue;
            };
            for (w, t) in mesh.nodes.windows(2).zip(mesh.params.windows(2)) {
                let (a, b) = (points[w[0]], points[w[1]]);
                if a == b {
                    continue;
                }
                shortest = shortest.min(a.distance(b));
                elements.push(Element {
                    corners: [a, b, b],
                    kind: Kind::Segment {
                        edge: e,
                        t: [t[0], t[1]],
                    },
                });
            }
        }
        SourceDistance {
            model,
            tree: RTree::bulk_load(elements),
            on_source: ON_SOURCE * shortest.min(1.0),
            node_normal,
        }
    }

    /// True when the source has no elements (it names nothing meshed).
    pub fn is_empty(&self) -> bool {
        self.tree.size() == 0
    }

    /// Distance from `p` to the source, its foot and direction.
    pub fn near(&self, p: DVec3) -> Near {
        let Some(e) = self.tree.nearest_neighbor(&p.to_array()) else {
            return Near {
                phi: f64::INFINITY,
                foot: p,
                dir: DVec3::ZERO,
                along: DVec3::ZERO,
            };
        };
        let (facet_foot, w) = e.closest(p);
        let foot = self.on_geometry(e, p, facet_foot, w);
        let phi = p.distance(foot);
        let dir = if phi > self.on_source {
            (p - foot) / phi
        } else {
            match &e.kind {
                Kind::Triangle { face, uv, nodes } => {
                    // At a source node: its mean normal (a ridge's or corner's bisector), or
                    // the surface's own normal inside one face.
                    let corner = (0..3).find(|&k| w[k] > 1.0 - 1e-9);
                    let node = corner.map(|k| self.node_normal[nodes[k] as usize]);
                    let hint = uv[0] * w[0] + uv[1] * w[1] + uv[2] * w[2];
                    let facet = {
                        let [a, b, c] = e.corners;
                        (b - a).cross(c - a).normalize_or_zero() * into_region(self.model, *face)
                    };
                    match node {
                        Some((n, true)) if n != DVec3::ZERO => n,
                        _ => {
                            let n = self.model.faces[*face].surface.normal(hint);
                            if n.length_squared() > 0.5 && hint.is_finite() {
                                if n.dot(facet) < 0.0 {
                                    -n
                                } else {
                                    n
                                }
                            } else {
                                facet
                            }
                        }
                    }
                }
                Kind::Segment { .. } => DVec3::ZERO,
            }
        };
        let along = match &e.kind {
            Kind::Segment { .. } => (e.corners[1] - e.corners[0]).normalize_or_zero(),
            Kind::Triangle { .. } => DVec3::ZERO,
        };
        Near {
            phi,
            foot,
            dir,
            along,
        }
    }

    /// The facet's foot moved onto the true surface or curve, when the projection from the
    /// nearest corner's parameters lands no farther from `p` than the facet did (up to the
    /// facet's own chord error).
    fn on_geometry(&self, e: &Element, p: DVec3, facet: DVec3, w: [f64; 3]) -> DVec3 {
        let facet_d = p.distance(facet);
        let size = e.corners[0]
            .distance(e.corners[1])
            .max(e.corners[1].distance(e.corners[2]));
        let true_foot = match &e.kind {
            Kind::Triangle { face, uv, .. } => {
                let k = if w[0] >= w[1] && w[0] >= w[2] {
                    0
                } else if w[1] >= w[2] {
                    1
                } else {
                    2
                };
                if !uv[k].is_finite() {
                    return facet;
                }
                // A local projection from the nearest corner: the point is off the surface, so
                // a global projection would search the whole surface on every call.
                let surface = &self.model.faces[*face].surface;
                crate::geometry::newton::project_local(&**surface, p, uv[k])
                    .map(|uv| surface.point(uv))
            }
            Kind::Segment { edge, t } => {
                let edge = &self.model.edges[*edge];
                edge.curve.as_ref().and_then(|c| {
                    let hint = t[0] * w[0] + t[1] * w[1];
                    c.closest_parameter(p, Some(hint)).map(|s| {
                        let (lo, hi) = (
                            edge.range.0.min(edge.range.1),
                            edge.range.0.max(edge.range.1),
                        );
                        c.point(s.clamp(lo, hi))
                    })
                })
            }
        };
        match true_foot {
            Some(q)
                if q.is_finite()
                    && q.distance(facet) < size
                    && p.distance(q) <= facet_d + 0.1 * size =>
            {
                q
            }
            _ => facet,
        }
    }
}

/// (u,v) of the nodes of the picked triangles on their faces: one global projection per
/// connected piece of a face, then local ones from a neighbour's (u,v), breadth first.
fn node_parameters(
    model: &Model,
    points: &[DVec3],
    triangles: &[[usize; 3]],
    face_of: &[FaceId],
    picked: &[usize],
) -> std::collections::HashMap<(FaceId, usize), DVec2> {
    use std::collections::{HashMap, VecDeque};
    let mut neighbours: HashMap<(FaceId, usize), Vec<usize>> = HashMap::new();
    for &k in picked {
        let (t, f) = (triangles[k], face_of[k]);
        for i in 0..3 {
            let e = neighbours.entry((f, t[i])).or_default();
            e.push(t[(i + 1) % 3]);
            e.push(t[(i + 2) % 3]);
        }
    }
    let mut keys: Vec<(FaceId, usize)> = neighbours.keys().copied().collect();
    keys.sort_unstable();
    let mut uv: HashMap<(FaceId, usize), DVec2> = HashMap::new();
    for start in keys {
        if uv.contains_key(&start) {
            continue;
        }
        let surface = &model.faces[start.0].surface;
        let Some(w) = surface.closest_uv(points[start.1], None) else {
            continue;
        };
        uv.insert(start, w);
        let mut queue = VecDeque::from([start]);
        while let Some(key) = queue.pop_front() {
            let from = uv[&key];
            for &n in &neighbours[&key] {
                let nk = (key.0, n);
                if uv.contains_key(&nk) {
                    continue;
                }
                // On the surface: the hinted projection settles at once.
                if let Some(w) = surface.closest_uv(points[n], Some(from)) {
                    uv.insert(nk, w);
                    queue.push_back(nk);
                }
            }
        }
    }
    uv
}

/// Closest point of segment `ab` to `p` and its parameter in [0, 1].
fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> (DVec3, f64) {
    let d = b - a;
    let len2 = d.length_squared();
    if len2 == 0.0 {
        return (a, 0.0);
    }
    let s = ((p - a).dot(d) / len2).clamp(0.0, 1.0);
    (a + d * s, s)
}

/// Closest point of triangle `abc` to `p` (Voronoi regions of the corners, edges and face)
/// and its barycentric weights.
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, [f64; 3]) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let s = d1 / (d1 - d3);
        return (a + ab * s, [1.0 - s, s, 0.0]);
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let s = d2 / (d2 - d6);
        return (a + ac * s, [1.0 - s, 0.0, s]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let s = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * s, [0.0, 1.0 - s, s]);
    }
    let denom = va + vb + vc;
    if denom == 0.0 {
        // A degenerate triangle: the nearest of its edges.
        let cands = [
            closest_on_segment(p, a, b),
            closest_on_segment(p, b, c),
            closest_on_segment(p, c, a),
        ];
        let (k, &(q, s)) = cands
            .iter()
            .enumerate()
            .min_by(|x, y| p.distance(x.1 .0).total_cmp(&p.distance(y.1 .0)))
            .unwrap_or((0, &cands[0]));
        let mut w = [0.0; 3];
        w[k] = 1.0 - s;
        w[(k + 1) % 3] = s;
        return (q, w);
    }
    let v = vb / denom;
    let w = vc / denom;
    (a + ab * v + ac * w, [1.0 - v - w, v, w])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_point_of_a_triangle_in_each_region() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let (q, w) = closest_on_triangle(DVec3::new(0.25, 0.25, 2.0), a, b, c);
        assert!(q.distance(DVec3::new(0.25, 0.25, 0.0)) < 1e-15);
        assert!((w[0] - 0.5).abs() < 1e-15);
        let (q, _) = closest_on_triangle(DVec3::new(-1.0, -1.0, 0.3), a, b, c);
        assert_eq!(q, a);
        let (q, _) = closest_on_triangle(DVec3::new(1.0, 1.0, 0.0), a, b, c);
        assert!(q.distance(DVec3::new(0.5, 0.5, 0.0)) < 1e-15);
        let (q, _) = closest_on_triangle(DVec3::new(0.5, -2.0, 1.0), a, b, c);
        assert!(q.distance(DVec3::new(0.5, 0.0, 0.0)) < 1e-15);
    }
}
