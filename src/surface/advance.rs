//! The advancing front on one face (seed paper, "Surface mesh generation"): take the shortest
//! front segment AB, find the ideal point at distance δ from A and B on the surface (a
//! circle–surface intersection), choose among it and nearby front vertices by 3-D triangle
//! quality, accept only what passes the exact (u,v) tests, and update the front.

use super::boundary::{Boundary, FaceVertex};
use super::front::Front;
use super::geometry2d::{inside_or_on, segments_cross};
use super::pole;
use crate::geometry::{newton, orient2d, Circle, CircleHint, Surface};
use crate::mesh::quality::{triangle_quality, volume_sign};
use crate::sizing::sources::distance_to_segment;
use crate::sizing::SizingField;
use glam::{DVec2, DVec3};
use std::collections::HashMap;

/// Tries per front segment before the face gives up.
const MAX_FAILURES: u32 = 6;
/// Times a face may undo the triangles around a stuck segment and try again.
const MAX_RETRIES: u32 = 12;
/// A new point closer than this fraction of δ to a front vertex is merged with it.
const MERGE: f64 = 0.55;
/// Largest allowed angle between the ideal direction and the circle solution.
const MAX_DTHETA: f64 = 1.1;
/// Front vertices must stay this fraction of δ away from a new triangle's new sides.
const CLEARANCE: f64 = 0.15;
/// From this many failures on, a segment relaxes the clearance and the last-resort quality
/// floor step by step, down to nothing on its last try: a strip or wedge narrower than the
/// clearance (nearly parallel or tangent edges) has only needles to offer, and the exact
/// (u,v) tests alone still keep the triangulation valid.
const RELAX_FROM: u32 = 3;

/// The share of the clearance and quality floor a segment that failed `fails` times keeps.
fn strictness(fails: u32) -> f64 {
    if fails < RELAX_FROM {
        1.0
    } else {
        let steps = (MAX_FAILURES - RELAX_FROM) as f64;
        (1.0 - (fails - RELAX_FROM + 1) as f64 / steps).max(0.0)
    }
}

/// Where the advancing front got stuck.
#[derive(Debug)]
pub struct Stuck {
    pub uv: DVec2,
    pub xyz: DVec3,
}

/// Triangles (local vertex ids, counter-clockwise in (u,v)) and the vertices they use.
#[derive(Debug)]
pub struct FaceTriangulation {
    pub vertices: Vec<FaceVertex>,
    pub triangles: Vec<[usize; 3]>,
}

pub fn advance(
    surface: &dyn Surface,
    sizing: &SizingField,
    boundary: Boundary,
) -> Result<FaceTriangulation, Stuck> {
    let mut front = Front::new(boundary.vertices, &boundary.segments, &boundary.slits);
    let mut triangles: Vec<[usize; 3]> = Vec::new();
    let mut retries = 0;
    let mut ideal = IdealCache::default();
    while let Some(s) = front.pop() {
        let [a, b] = front.segment(s);
        match choose(surface, sizing, &mut front, &mut ideal, a, b) {
            Some(c) => {
                triangles.push([a, b, c]);
                front.remove(s);
                front.add_or_cancel(a, c);
                front.add_or_cancel(c, b);
            }
            None => {
                front.failures[s] += 1;
                if front.failures[s] <= MAX_FAILURES {
                    front.push(s);
                    continue;
                }
                if retries < MAX_RETRIES {
                    // Undo the triangles around the stuck segment, wider each time, and let
                    // the front try again from a different shape.
                    retries += 1;
                    let (xa, xb) = (front.vertices[a].xyz, front.vertices[b].xyz);
                    let mid = 0.5 * (xa + xb);
                    let reach = sizing.spacing(mid).max(xa.distance(xb));
                    let radius = (0.6 + 0.4 * retries as f64) * reach;
                    unmesh_around(&mut front, &mut triangles, [a, b], mid, radius);
                    if front.is_alive(s) {
                        front.reset(s);
                    }
                    continue;
                }
                let v = &front.vertices[a];
                if log::log_enabled!(log::Level::Debug) {
                    let vb = &front.vertices[b];
                    log::debug!("stuck segment {a}->{b}: {:?} -> {:?}", v.uv, vb.uv);
                    for t in front.live_segments() {
                        let [p, q] = front.segment(t);
                        let (vp, vq) = (&front.vertices[p], &front.vertices[q]);
                        log::debug!(
                            "  front {p}->{q}: {:?} -> {:?} len {:.4e} fails {}",
                            vp.uv,
                            vq.uv,
                            vp.xyz.distance(vq.xyz),
                            front.failures[t]
                        );
                    }
                }
                return Err(Stuck {
                    uv: v.uv,
                    xyz: v.xyz,
                });
            }
        }
    }
    debug_assert!(front.is_empty());
    Ok(FaceTriangulation {
        vertices: front.vertices,
        triangles,
    })
}

/// Remove the triangles that touch `ends` or have a corner within `radius` of `centre`, and
/// give their area back to the front: each side x→y of a removed triangle cancels y→x on the
/// front or becomes a front segment itself.
fn unmesh_around(
    front: &mut Front,
    triangles: &mut Vec<[usize; 3]>,
    ends: [usize; 2],
    centre: DVec3,
    radius: f64,
) {
    let near = |v: usize| ends.contains(&v) || front.vertices[v].xyz.distance(centre) <= radius;
    let (gone, kept): (Vec<[usize; 3]>, Vec<[usize; 3]>) =
        triangles.iter().partition(|t| t.iter().any(|&v| near(v)));
    *triangles = kept;
    for t in gone {
        for k in 0..3 {
            front.add_or_cancel(t[k], t[(k + 1) % 3]);
        }
    }
}

/// The third vertex for segment a→b: an existing front vertex or a new one.
fn choose(
    surface: &dyn Surface,
    sizing: &SizingField,
    front: &mut Front,
    cache: &mut IdealCache,
    a: usize,
    b: usize,
) -> Option<usize> {
    let (va, vb) = (front.vertices[a], front.vertices[b]);
    let ab = va.xyz.distance(vb.xyz);
    if ab == 0.0 {
        return choose_at_pole(surface, sizing, front, a, b);
    }
    let mid = 0.5 * (va.xyz + vb.xyz);
    let delta = sizing.spacing(mid).clamp(0.55 * ab, 2.0 * ab);
    let fails = front.failures[front.find(a, b)?];
    let strict = strictness(fails);
    let clearance = CLEARANCE * strict;
    let ideal = cache.ideal_point(surface, (a, &va), (b, &vb), delta);

    // Candidates: front vertices near the ideal point (or near the segment when there is none),
    // and the front neighbours of a and b, which close pockets and pinches — however far once
    // the segment relaxes (a short segment in a narrow pocket whose other sides are long).
    let centre = ideal.map_or(mid, |p| p.xyz);
    let radius = if fails == 0 { 1.0 } else { 1.5 } * delta;
    let mut near = front.vertices_near(centre, radius.max(1.2 * ab));
    near.extend(
        front
            .neighbours(a)
            .chain(front.neighbours(b))
            .filter(|&c| strict < 1.0 || front.vertices[c].xyz.distance(mid) <= 2.0 * delta),
    );
    near.sort_unstable();
    near.dedup();
    let mut cands: Vec<(f64, usize)> = on_the_left(surface, front, a, b, near)
        .map(|c| (triangle_quality(va.xyz, vb.xyz, front.vertices[c].xyz), c))
        .collect();
    cands.sort_by(|x, y| y.0.total_cmp(&x.0));
    let existing_ok = |front: &Front, c: usize| {
        let v = front.vertices[c];
        valid(front, a, b, (v.uv, v.xyz), Some(c), clearance * delta)
            && faces_along_normal(surface, &va, &vb, &v)
    };

    if let Some(p) = ideal {
        let q_ideal = triangle_quality(va.xyz, vb.xyz, p.xyz);
        // A vertex where the ideal point would be closes the front: take it.
        let mut close: Vec<(f64, usize)> = cands
            .iter()
            .map(|&(_, c)| (front.vertices[c].xyz.distance(p.xyz), c))
            .filter(|&(d, _)| d <= MERGE * delta)
            .collect();
        close.sort_by(|x, y| x.0.total_cmp(&y.0));
        if let Some(&(_, c)) = close.iter().find(|&&(_, c)| existing_ok(front, c)) {
            return Some(c);
        }
        // An existing vertex nearly as good as the ideal point is preferred to a new one.
        if let Some(&(_, c)) = cands
            .iter()
            .find(|&&(q, c)| q >= 0.8 * q_ideal && existing_ok(front, c))
        {
            return Some(c);
        }
        let crowded = front
            .vertices_near(p.xyz, MERGE * delta)
            .into_iter()
            .any(|c| c != a && c != b);
        if !crowded && valid(front, a, b, (p.uv, p.xyz), None, clearance * delta) {
            return Some(front.add_vertex(p));
        }
    }
    // A decent existing vertex.
    if let Some(&(_, c)) = cands
        .iter()
        .find(|&&(q, c)| q >= 0.3 && existing_ok(front, c))
    {
        return Some(c);
    }
    // A smaller triangle squeezes into a tight spot.
    for shrink in [0.8, 0.65] {
        let small = (shrink * delta).max(0.55 * ab);
        if let Some(p) = cache.ideal_point(surface, (a, &va), (b, &vb), small) {
            let crowded = front
                .vertices_near(p.xyz, MERGE * shrink * delta)
                .into_iter()
                .any(|c| c != a && c != b);
            if !crowded && valid(front, a, b, (p.uv, p.xyz), None, clearance * shrink * delta) {
                return Some(front.add_vertex(p));
            }
        }
    }
    // Last resort: any valid existing vertex that does not make a needle.
    if let Some(&(_, c)) = cands
        .iter()
        .find(|&&(q, c)| q > 0.05 * strict && existing_ok(front, c))
    {
        return Some(c);
    }
    // On the segment's last try, a triangle facing backwards in 3-D is better than a face
    // that does not close: a vertex left a hair inside a curved rim (beyond the rim's chord
    // in 3-D) has no other way to be closed.
    if strict > 0.0 {
        return None;
    }
    cands
        .iter()
        .find(|&&(_, c)| {
            let v = front.vertices[c];
            valid(front, a, b, (v.uv, v.xyz), Some(c), 0.0)
        })
        .map(|&(_, c)| c)
}

/// Would a new side from a or b to `c` run more than half a period of a periodic parameter?
/// Then `c` is the copy of its node beyond a seam (the same 3-D point a period away, near in
/// 3-D and a fine candidate there), and the triangle would stretch across the whole face in
/// (u,v), over parts meshed long ago — the front then crosses itself and cannot close.
fn wraps_round(surface: &dyn Surface, va: &FaceVertex, vb: &FaceVertex, c: DVec2) -> bool {
    let bounds = surface.bounds();
    let long = |d: f64, period: Option<f64>| period.is_some_and(|p| d.abs() > 0.5 * p);
    [va.uv, vb.uv]
        .iter()
        .any(|p| long(c.x - p.x, bounds.u_period) || long(c.y - p.y, bounds.v_period))
}

/// Does the triangle a, b, c (counter-clockwise in (u,v)) face along the surface normal in
/// 3-D too? Three nodes in a row on a boundary arc that bends out of the surface (a B-spline
/// rim) are a hair's breadth from collinear in (u,v), so the (u,v) tests pass either way, while
/// in 3-D the triangle stands across the surface and may face backwards. Exact `orient3d` of
/// the triangle against its centroid pushed along the normal at the (u,v) centroid; `true`
/// where the normal is undefined (a pole).
fn faces_along_normal(
    surface: &dyn Surface,
    a: &FaceVertex,
    b: &FaceVertex,
    c: &FaceVertex,
) -> bool {
    let n = surface.normal((a.uv + b.uv + c.uv) / 3.0);
    let Some(n) = n.try_normalize() else {
        return true;
    };
    let (pa, pb, pc) = (a.xyz, b.xyz, c.xyz);
    let scale = pa.distance(pb).max(pb.distance(pc)).max(pc.distance(pa));
    let tip = (pa + pb + pc) / 3.0 + n * scale;
    volume_sign([pa, pb, pc, tip]) > 0.0
}

/// The front vertices of `near` that could close segment a→b: not a or b nor a copy of their
/// node, not the copy of a node beyond a seam, and strictly left of a→b in (u,v).
fn on_the_left<'a>(
    surface: &'a dyn Surface,
    front: &'a Front,
    a: usize,
    b: usize,
    near: Vec<usize>,
) -> impl Iterator<Item = usize> + 'a {
    let (va, vb) = (front.vertices[a], front.vertices[b]);
    near.into_iter()
        .filter(move |&c| c != a && c != b && !same_node(&front.vertices[c], &va, &vb))
        .filter(move |&c| !wraps_round(surface, &va, &vb, front.vertices[c].uv))
        .filter(move |&c| orient2d(va.uv, vb.uv, front.vertices[c].uv) > 0.0)
}

/// Is `c` the same global node as `a` or `b` (another copy of a pole or seam node)? Such a
/// triangle would have no area in 3-D.
fn same_node(c: &FaceVertex, a: &FaceVertex, b: &FaceVertex) -> bool {
    c.node.is_some() && (c.node == a.node || c.node == b.node)
}

/// The third vertex for a zero-length piece a→b of a pole: the point at distance δ from the
/// pole straight into the face from the piece's middle, or a front vertex close to it. The
/// triangle itself is dropped when the face is assembled (two corners on the pole); what
/// matters is the front it leaves, whose sides pole–c become the fan around the pole.
fn choose_at_pole(
    surface: &dyn Surface,
    sizing: &SizingField,
    front: &mut Front,
    a: usize,
    b: usize,
) -> Option<usize> {
    let (va, vb) = (front.vertices[a], front.vertices[b]);
    let dir = pole::inward(va.uv, vb.uv)?;
    let mid_uv = 0.5 * (va.uv + vb.uv);
    let delta = sizing.spacing(va.xyz);
    let clearance = CLEARANCE * strictness(front.failures[front.find(a, b)?]);
    for shrink in [1.0, 0.8, 0.65] {
        let Some((uv, xyz)) = pole::ring_point(surface, va.xyz, mid_uv, dir, shrink * delta) else {
            continue;
        };
        let mut close: Vec<(f64, usize)> = front
            .vertices_near(xyz, MERGE * shrink * delta)
            .into_iter()
            .filter(|&c| c != a && c != b && !same_node(&front.vertices[c], &va, &vb))
            .filter(|&c| pole::within_piece(va.uv, vb.uv, front.vertices[c].uv))
            .map(|c| (front.vertices[c].xyz.distance(xyz), c))
            .collect();
        close.sort_by(|x, y| x.0.total_cmp(&y.0));
        for &(_, c) in &close {
            let v = front.vertices[c];
            if valid(
                front,
                a,
                b,
                (v.uv, v.xyz),
                Some(c),
                clearance * shrink * delta,
            ) {
                return Some(c);
            }
        }
        if close.is_empty() && valid(front, a, b, (uv, xyz), None, clearance * shrink * delta) {
            return Some(front.add_vertex(FaceVertex {
                uv,
                xyz,
                node: None,
            }));
        }
    }
    // No ring point inside the face (a coarse δ beyond the far side of a short cone): the
    // nearest valid front vertex, usually a neighbour along the edges leaving the pole.
    let mut near = front.vertices_near(va.xyz, 2.0 * delta);
    near.extend(front.neighbours(a).chain(front.neighbours(b)));
    near.sort_unstable();
    near.dedup();
    let mut cands: Vec<(f64, usize)> = on_the_left(surface, front, a, b, near)
        .map(|c| (front.vertices[c].xyz.distance(va.xyz), c))
        .collect();
    cands.sort_by(|x, y| x.0.total_cmp(&y.0));
    cands.into_iter().map(|(_, c)| c).find(|&c| {
        let v = front.vertices[c];
        valid(front, a, b, (v.uv, v.xyz), Some(c), clearance * delta)
    })
}

/// Ideal points already computed, by segment ends and δ. A segment that fails is tried
/// again, and again after the front is undone around it, with the same ends and δ; on trimmed
/// B-spline faces a miss (no point inside the face) costs a global intersection each time
/// (ONERA M6 wing: 602 misses, 152 distinct).
#[derive(Default)]
struct IdealCache(HashMap<(usize, usize, u64), Option<FaceVertex>>);

impl IdealCache {
    fn ideal_point(
        &mut self,
        surface: &dyn Surface,
        (a, va): (usize, &FaceVertex),
        (b, vb): (usize, &FaceVertex),
        delta: f64,
    ) -> Option<FaceVertex> {
        *self
            .0
            .entry((a, b, delta.to_bits()))
            .or_insert_with(|| ideal_point(surface, va, vb, delta))
    }
}

/// The point on the surface at distance δ from both ends, on the face side of a→b.
fn ideal_point(
    surface: &dyn Surface,
    va: &FaceVertex,
    vb: &FaceVertex,
    delta: f64,
) -> Option<FaceVertex> {
    let mid_uv = 0.5 * (va.uv + vb.uv);
    let d = surface.derivs(mid_uv);
    let n = d.normal_raw().normalize_or_zero();
    let toward = n.cross(vb.xyz - va.xyz);
    let circle = Circle::equidistant(va.xyz, vb.xyz, delta, toward)?;
    let bounds = surface.bounds();
    let hint_at = |uv: DVec2| CircleHint {
        uv: bounds.normalise(uv),
        theta: 0.0,
        max_dtheta: MAX_DTHETA,
    };
    // The triangle a, b, hit must face along the surface at both the segment and the hit.
    let faces_along = |hit: &crate::geometry::CircleHit| {
        let m = (vb.xyz - va.xyz).cross(hit.point - va.xyz);
        m.dot(n) > 0.0 && m.dot(surface.normal(hit.uv)) > 0.0
    };
    // First (u,v) hint: the step that moves S(mid) onto the circle's inner point, to first
    // order (least squares through the first fundamental form). On stretched B-spline
    // parameterisations (T106 blade, ONERA wing) the plain (u,v) perpendicular below misses,
    // Newton fails and the costly global intersection runs (T106 surfaces 7.4 s -> 1.1 s).
    let target = circle.point(0.0) - d.p;
    let (e, f, g) = d.first_form();
    let det = e * g - f * f;
    let mut found = None;
    if det > 1e-12 * (e * g) && det.is_finite() {
        let rhs = DVec2::new(d.du.dot(target), d.dv.dot(target));
        let step = DVec2::new(g * rhs.x - f * rhs.y, e * rhs.y - f * rhs.x) / det;
        found = newton::intersect_circle_near_hint(surface, &circle, &hint_at(mid_uv + step))
            .filter(faces_along);
    }
    // Then the segment's left normal in (u,v), scaled to the triangle's height, through the
    // surface's own (possibly global) intersection.
    let hit = match found {
        Some(h) => h,
        None => {
            let duv = vb.uv - va.uv;
            let ab = va.xyz.distance(vb.xyz).max(1e-300);
            let hint_uv = mid_uv + duv.perp() * (circle.radius / ab);
            match surface.intersect_circle(&circle, &hint_at(hint_uv)) {
                Some(h) => h,
                None => {
                    // The surface turns away from its tangent plane within much less than δ
                    // (a blunt leading edge, a fillet below the size floor): the circle's
                    // tangent-plane direction points off the sheet by nearly a right angle,
                    // beyond the bounded arc. Aim the circle at the sheet itself, through the
                    // surface point the (u,v) step reaches.
                    let toward = surface.point(hint_uv) - circle.centre;
                    let aimed = Circle::equidistant(va.xyz, vb.xyz, delta, toward)?;
                    newton::intersect_circle_near_hint(surface, &aimed, &hint_at(hint_uv))
                        .filter(faces_along)?
                }
            }
        }
    };
    // Keep the (u,v) on the same sheet as the segment across a periodic seam.
    let uv = crate::model::unwrap_near(hit.uv, mid_uv, &surface.bounds());
    Some(FaceVertex {
        uv,
        xyz: hit.point,
        node: None,
    })
}

/// Exact (u,v) tests for the triangle a, b, c: c strictly left of a→b, the new sides a–c and
/// c–b cross no front segment, and no front vertex lies inside the triangle.
fn valid(
    front: &Front,
    a: usize,
    b: usize,
    c_pt: (DVec2, DVec3),
    c: Option<usize>,
    clearance: f64,
) -> bool {
    let (c_uv, c_xyz) = c_pt;
    let (pa, pb) = (front.vertices[a].uv, front.vertices[b].uv);
    let (xa, xb) = (front.vertices[a].xyz, front.vertices[b].xyz);
    if orient2d(pa, pb, c_uv) <= 0.0 {
        return false;
    }
    let same = |v: usize, x: Option<usize>| x == Some(v);
    for s in front.segments_near(&[pa, pb, c_uv]) {
        let [p, q] = front.segment(s);
        let (pp, pq) = (front.vertices[p].uv, front.vertices[q].uv);
        // The third vertex must keep clear of segments it does not end (a segment from
        // another copy of its node touches it in 3-D only).
        let c_node = c.and_then(|c| front.vertices[c].node);
        let ends_c =
            |v: usize| same(v, c) || (c_node.is_some() && front.vertices[v].node == c_node);
        if !ends_c(p)
            && !ends_c(q)
            && distance_to_segment(c_xyz, front.vertices[p].xyz, front.vertices[q].xyz) < clearance
        {
            return false;
        }
        if blocks((pa, Some(a)), (c_uv, c), (p, pp), (q, pq))
            || blocks((c_uv, c), (pb, Some(b)), (p, pp), (q, pq))
        {
            return false;
        }
        for v in [p, q] {
            if v == a || v == b || same(v, c) {
                continue;
            }
            let w = &front.vertices[v];
            if inside_or_on(pa, pb, c_uv, w.uv) {
                return false;
            }
            // Another copy of a corner's node (pole, seam) touches the sides in 3-D only.
            let copy = |x: usize| w.node.is_some() && w.node == front.vertices[x].node;
            if copy(a) || copy(b) || c.is_some_and(copy) {
                continue;
            }
            // A front vertex hugging a new side would leave a sliver behind.
            if distance_to_segment(w.xyz, xa, c_xyz).min(distance_to_segment(w.xyz, c_xyz, xb))
                < clearance
            {
                return false;
            }
        }
    }
    true
}

/// Does front segment p–q block the new side x–y (each end a vertex id, or None for the new
/// point)? A segment sharing an end with the side blocks only by running along it.
fn blocks(
    x: (DVec2, Option<usize>),
    y: (DVec2, Option<usize>),
    p: (usize, DVec2),
    q: (usize, DVec2),
) -> bool {
    // The side's end at vertex v, if v is one of its ends.
    let end_at = |v: usize| {
        if x.1 == Some(v) {
            Some((x.0, y.0))
        } else if y.1 == Some(v) {
            Some((y.0, x.0))
        } else {
            None
        }
    };
    match (end_at(p.0), end_at(q.0)) {
        (Some(_), Some(_)) => false,
        (Some((o, other)), None) => overlaps_from(o, other, q.1),
        (None, Some((o, other))) => overlaps_from(o, other, p.1),
        (None, None) => segments_cross(x.0, y.0, p.1, q.1),
    }
}

/// From a shared end `o`, do directions o→a and o→b coincide (collinear, same way)?
fn overlaps_from(o: DVec2, a: DVec2, b: DVec2) -> bool {
    orient2d(o, a, b) == 0.0 && (a - o).dot(b - o) > 0.0
}
