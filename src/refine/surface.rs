//! Edge and face refinement (seed paper, "Edge refinement", "Face refinement"): before the
//! volume is tetrahedralised, the boundary gets the layers too. A model edge segment whose ends
//! span a site of the distribution gets a node where the curve's distance to the source equals
//! that site (bisection on the true curve), splitting the triangles on both sides; then a face
//! triangle that spans a site gets a point on the face at that distance — stepped in the
//! triangle's plane along the distance gradient, projected onto the surface through the trait,
//! and iterated until the distance is right — the triangle holding it is split in three (or two
//! and two, on an edge), and local diagonal swaps minimise the maximum angle.

use super::face_tris::{insert_edge_node, key, split_edge, FaceTris};
use super::field::{crowds, Candidate, StageField};
use super::source::Near;
use super::Stage;
use crate::curve::CurveMesh;
use crate::geometry::orient2d;
use crate::model::{EdgeId, FaceId, Model};
use crate::sizing::SizingField;
use crate::surface::SurfaceMesh;
use glam::{DVec2, DVec3};
use std::collections::{HashMap, HashSet};

/// Safety bounds.
const MAX_ROUNDS: usize = 200;
const BISECTIONS: usize = 48;
/// An edge point closer than this fraction of its layer spacing to the segment's end is not
/// a crossing of its site (those keep [`super::field::SITE_MARGIN`] from the ends).
const EDGE_NODE_GAP: f64 = 0.1;
/// An edge point whose distance is farther than this fraction of its layer spacing from its
/// site is not on it.
const EDGE_SITE_TOLERANCE: f64 = 0.3;
/// Steps of the in-plane walk to the wanted distance on a face.
const FACE_ITERATIONS: usize = 6;

/// What edge and face refinement did.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct SurfaceRefineReport {
    pub edge_points: usize,
    pub face_points: usize,
    pub face_rounds: usize,
    pub swaps: usize,
    /// Faces whose refined triangles failed the fold check, or boundary recovery in an
    /// earlier try, and were left unrefined.
    pub faces_kept_unrefined: usize,
}

impl SurfaceRefineReport {
    /// Adds `other`'s counts to these (a stage's second pass).
    pub fn add(&mut self, other: &SurfaceRefineReport) {
        self.edge_points += other.edge_points;
        self.face_points += other.face_points;
        self.face_rounds += other.face_rounds;
        self.swaps += other.swaps;
        self.faces_kept_unrefined = self.faces_kept_unrefined.max(other.faces_kept_unrefined);
    }
}

/// Refine the edges and faces that are not sources of `stage`. `with_feet` adds the column
/// feet on the source's edges ([`super::feet`]); a stage's second pass, after later stages,
/// goes without: new feet there would split the later stages' layer triangles in turn.
#[allow(clippy::too_many_arguments)]
pub fn refine(
    model: &Model,
    mesh: &mut SurfaceMesh,
    curves: &mut CurveMesh,
    sizing: &SizingField,
    field: &StageField,
    stage: &Stage,
    unrefined: &HashSet<FaceId>,
    with_feet: bool,
) -> SurfaceRefineReport {
    let mut report = SurfaceRefineReport::default();
    let source_faces: HashSet<FaceId> =
        stage.sources.iter().flat_map(|s| s.faces.clone()).collect();
    let source_edges: HashSet<EdgeId> =
        stage.sources.iter().flat_map(|s| s.edges.clone()).collect();
    let mut faces: Vec<FaceTris> = (0..model.faces.len())
        .map(|_| FaceTris { tris: Vec::new() })
        .collect();
    for (t, &f) in mesh.triangles.iter().zip(&mesh.face_of) {
        faces[f].tris.push(*t);
    }
    let mut near: HashMap<usize, Vec<Near>> = HashMap::new();
    let near_of = |near: &mut HashMap<usize, Vec<Near>>, points: &[DVec3], v: usize| {
        near.entry(v)
            .or_insert_with(|| field.near(points[v]))
            .clone()
    };

    let embedded_faces: HashSet<FaceId> = (model.regions.iter())
        .flat_map(|r| r.embedded_faces.iter().copied())
        .collect();
    // Edges: which faces use each edge.
    let mut faces_of_edge: Vec<Vec<FaceId>> = vec![Vec::new(); model.edges.len()];
    for (f, face) in model.faces.iter().enumerate() {
        for l in &face.loops {
            for u in &l.uses {
                if !faces_of_edge[u.edge].contains(&f) {
                    faces_of_edge[u.edge].push(f);
                }
            }
        }
    }
    for (e, edge) in model.edges.iter().enumerate() {
        let Some(curve) = edge.curve.clone() else {
            continue;
        };
        if source_edges.contains(&e) || e >= curves.edges.len() {
            continue;
        }
        // Edges of source faces lie on the source: nothing to do.
        if !faces_of_edge[e].is_empty() && faces_of_edge[e].iter().all(|f| source_faces.contains(f))
        {
            continue;
        }
        // A free edge of an embedded face that is no source (a wake's tip side or far edge):
        // no face on it takes face points, so nodes there would only cut the sheet's
        // triangles into fans of slivers beside the layers, which recovery cannot match.
        if faces_of_edge[e]
            .iter()
            .all(|f| embedded_faces.contains(f) && !source_faces.contains(f))
        {
            continue;
        }
        let mut k = 0;
        let mut guard = 0;
        while k + 1 < curves.edges[e].nodes.len() && guard < 100_000 {
            guard += 1;
            let (na, nb) = (curves.edges[e].nodes[k], curves.edges[e].nodes[k + 1]);
            let (ta, tb) = (curves.edges[e].params[k], curves.edges[e].params[k + 1]);
            let (a, b) = (
                near_of(&mut near, &mesh.points, na),
                near_of(&mut near, &mesh.points, nb),
            );
            let mid = (mesh.points[na] + mesh.points[nb]) * 0.5;
            let demand = field.demand(&[&a, &b], sizing.spacing(mid));
            let Some((s, sites)) = demand else {
                k += 1;
                continue;
            };
            // The lowest site the segment spans, from its nearer end.
            let (lo_t, hi_t) = if a[s].phi <= b[s].phi {
                (ta, tb)
            } else {
                (tb, ta)
            };
            let site = sites[0];
            // φ(C(t)) − site changes sign between the ends: bisect on the true curve.
            let (mut lo, mut hi) = (lo_t, hi_t);
            for _ in 0..BISECTIONS {
                let m = 0.5 * (lo + hi);
                if field.sources[s].distance.near(curve.point(m)).phi < site {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            let t = 0.5 * (lo + hi);
            let p = curve.point(t);
            // The distance is continuous, so a crossing lies a margin of its layer from the
            // segment's ends and at its site. One that does not is where the computed distance
            // jumps (its foot changes facet): a node there would land on the end node or off
            // the site, and the lower piece would be bisected onto it again.
            let spacing = field.sources[s].distribution.spacing_at(site);
            let gap = p.distance(mesh.points[na]).min(p.distance(mesh.points[nb]));
            let off = (field.sources[s].distance.near(p).phi - site).abs();
            if !p.is_finite()
                || t == ta
                || t == tb
                || gap < EDGE_NODE_GAP * spacing
                || off > EDGE_SITE_TOLERANCE * spacing
            {
                k += 1;
                continue;
            }
            insert_edge_node(mesh, curves, &mut faces, &faces_of_edge[e], e, k, t, p);
            report.edge_points += 1;
            // Look at the lower piece again (it may span more sites).
        }
    }

    // Columns stand on edge nodes: the feet of face nodes on the source's edges join them.
    // Their lines start there too: the nearest source points of those nodes move to the edge
    // node, and their face points are found from the candidate, not from the node.
    let feet = with_feet.then(|| {
        super::feet::add_feet(
            model,
            mesh,
            curves,
            sizing,
            field,
            &mut faces,
            &faces_of_edge,
            &source_faces,
            &stage
                .sources
                .iter()
                .map(|s| !s.faces.is_empty())
                .collect::<Vec<_>>(),
        )
    });
    let snapped: HashSet<usize> = match feet {
        Some(feet) => {
            report.edge_points += feet.added;
            let snapped = feet.snapped.keys().copied().collect();
            near.extend(feet.snapped);
            snapped
        }
        None => HashSet::new(),
    };

    // Model-edge segments: never swapped, and the walk on a face stops at them.
    let model_edges: HashSet<(usize, usize)> = curves
        .edges
        .iter()
        .flat_map(|m| m.nodes.windows(2).map(|w| key(w[0], w[1])))
        .collect();

    for f in 0..model.faces.len() {
        // Embedded faces (wakes) get their edges refined but no face points yet: on the wing
        // sample at first = δ/100 the wake's points near the trailing-edge root made its
        // triangles cross each other.
        let embedded = model.regions.iter().any(|r| r.embedded_faces.contains(&f));
        if source_faces.contains(&f) || faces[f].tris.is_empty() || embedded {
            continue;
        }
        if unrefined.contains(&f) {
            report.faces_kept_unrefined += 1;
            continue;
        }
        let surface = model.faces[f].surface.clone();
        let before = faces[f].tris.clone();
        let first_new = mesh.points.len();
        let mut face_points = 0;
        let mut face_rounds = 0;
        for _ in 0..MAX_ROUNDS {
            let mut inserted = 0;
            let count = faces[f].tris.len();
            for ti in 0..count {
                let Some(&tri) = faces[f].tris.get(ti) else {
                    break;
                };
                let pos = tri.map(|v| mesh.points[v]);
                let nears = tri.map(|v| near_of(&mut near, &mesh.points, v));
                let refs: Vec<&[Near]> = nears.iter().map(|n| &n[..]).collect();
                let centre = (pos[0] + pos[1] + pos[2]) / 3.0;
                let delta = sizing.spacing(centre);
                let Some((s, sites)) = field.demand(&refs, delta) else {
                    continue;
                };
                let normal = (pos[1] - pos[0]).cross(pos[2] - pos[0]).normalize_or_zero();
                if normal == DVec3::ZERO {
                    continue;
                }
                let cands = field.candidates(s, &sites, &pos, &refs, centre, false);
                for c in cands {
                    let from_candidate = snapped.contains(&tri[c.from]);
                    let Some(p) =
                        on_face(field, s, &*surface, &c, pos, &nears, normal, from_candidate)
                    else {
                        continue;
                    };
                    let c = Candidate { point: p, ..c };
                    if try_insert(
                        &mut faces[f].tris,
                        &mut mesh.points,
                        &model_edges,
                        ti,
                        &c,
                        delta,
                        normal,
                    ) {
                        inserted += 1;
                        break;
                    }
                }
            }
            if inserted == 0 {
                break;
            }
            face_points += inserted;
            face_rounds += 1;
        }
        let swaps = swap_all(&mut faces[f].tris, &mesh.points, &model_edges);
        // A guard: every new triangle must face the way the original triangle nearest to it
        // did, and none may cross another (exact test). A face that fails keeps its unrefined
        // triangles (the new points are dropped from it) and is counted.
        if folds(&before, &faces[f].tris, &mesh.points)
            || crosses(&faces[f].tris, &mesh.points, first_new)
        {
            faces[f].tris = before;
            report.faces_kept_unrefined += 1;
            continue;
        }
        report.face_points += face_points;
        report.face_rounds += face_rounds;
        report.swaps += swaps;
    }
    // Faces whose boundary edges gained nodes but took no face point still need swaps.
    mesh.triangles.clear();
    mesh.face_of.clear();
    for (f, ft) in faces.into_iter().enumerate() {
        for t in ft.tris {
            mesh.triangles.push(t);
            mesh.face_of.push(f);
        }
    }
    report
}

/// The point of the face at distance `c.site` from source `s`, reached from the candidate's
/// vertex (or, `from_candidate`, from the candidate itself projected onto the face: its
/// vertex's line was moved onto an edge node) by steps along the distance gradient in the
/// triangle's plane, each projected onto the surface; `None` when the distance hardly changes
/// across the face or it does not settle.
#[allow(clippy::too_many_arguments)]
fn on_face(
    field: &StageField,
    s: usize,
    surface: &dyn crate::geometry::Surface,
    c: &Candidate,
    pos: [DVec3; 3],
    nears: &[Vec<Near>; 3],
    normal: DVec3,
    from_candidate: bool,
) -> Option<DVec3> {
    let site = c.site;
    // Start from the triangle vertex whose line the candidate lies on.
    let i = (0..3)
        .min_by(|&a, &b| {
            let da = (nears[a][s].foot + c.dir * site).distance(c.point);
            let db = (nears[b][s].foot + c.dir * site).distance(c.point);
            da.total_cmp(&db)
        })
        .unwrap_or(0);
    let mut p = pos[i];
    let mut phi = nears[i][s].phi;
    let mut g = c.dir;
    let mut uv: Option<DVec2> = None;
    if from_candidate {
        let w = surface.closest_uv(c.point, None)?;
        uv = Some(w);
        p = surface.point(w);
        phi = field.sources[s].distance.near(p).phi;
        if (phi - site).abs() < 1e-3 * c.spacing {
            return p.is_finite().then_some(p);
        }
    }
    for _ in 0..FACE_ITERATIONS {
        let gt = g - normal * g.dot(normal);
        let len2 = gt.length_squared();
        if len2 < 0.01 {
            return None;
        }
        let q = p + gt * ((site - phi) / len2);
        let w = match uv {
            Some(h) => crate::geometry::newton::project_local(surface, q, h)?,
            None => surface.closest_uv(q, None)?,
        };
        uv = Some(w);
        p = surface.point(w);
        let n = field.sources[s].distance.near(p);
        phi = n.phi;
        if n.dir != DVec3::ZERO && n.phi > 0.0 {
            g = n.dir;
        }
        if (phi - site).abs() < 1e-3 * c.spacing {
            return p.is_finite().then_some(p);
        }
    }
    ((phi - site).abs() < 0.1 * c.spacing && p.is_finite()).then_some(p)
}

/// Local 2-D frame of a plane with normal `n`.
fn frame(n: DVec3) -> (DVec3, DVec3) {
    let a = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let u = n.cross(a).normalize();
    (u, n.cross(u))
}

fn flat(p: DVec3, o: DVec3, (u, v): (DVec3, DVec3)) -> DVec2 {
    DVec2::new((p - o).dot(u), (p - o).dot(v))
}

/// Walk from triangle `start` to the one holding `c`'s point (in each triangle's plane),
/// never across a model edge; insert the point there if it keeps clear of the points around
/// and of the face's edges, then swap around it. True when inserted.
fn try_insert(
    tris: &mut Vec<[usize; 3]>,
    points: &mut Vec<DVec3>,
    model_edges: &HashSet<(usize, usize)>,
    start: usize,
    c: &Candidate,
    delta: f64,
    normal: DVec3,
) -> bool {
    let p = c.point;
    let mut t = start;
    let mut bary = [0.0; 3];
    let mut found = false;
    for _ in 0..64 {
        let [a, b, e] = tris[t].map(|v| points[v]);
        let n = (b - a).cross(e - a);
        if n.dot(normal) <= 0.0 {
            return false;
        }
        let area = n.length_squared();
        let w0 = (b - p).cross(e - p).dot(n) / area;
        let w1 = (e - p).cross(a - p).dot(n) / area;
        let w2 = 1.0 - w0 - w1;
        bary = [w0, w1, w2];
        let (k, &wmin) = bary
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(y.1))
            .unwrap_or((0, &0.0));
        if wmin >= 0.0 {
            found = true;
            break;
        }
        // Cross the edge opposite corner k, unless it is a model edge.
        let (x, y) = (tris[t][(k + 1) % 3], tris[t][(k + 2) % 3]);
        if model_edges.contains(&key(x, y)) {
            return false;
        }
        match tris
            .iter()
            .position(|u| u.contains(&x) && u.contains(&y) && *u != tris[t])
        {
            Some(u) => t = u,
            None => return false,
        }
    }
    if !found {
        return false;
    }
    let tri = tris[t];
    // Clear of the triangle's and its neighbours' points, in the metric.
    let mut around: Vec<usize> = tri.to_vec();
    for i in 0..3 {
        let (x, y) = (tri[i], tri[(i + 1) % 3]);
        if let Some(u) = tris
            .iter()
            .find(|u| u.contains(&x) && u.contains(&y) && **u != tri)
        {
            around.extend(u.iter().copied());
        }
    }
    if around.iter().any(|&v| crowds(c, points[v], delta)) {
        return false;
    }
    // Clear of the model edges of its triangle.
    for i in 0..3 {
        let (x, y) = (tri[i], tri[(i + 1) % 3]);
        if model_edges.contains(&key(x, y)) {
            let (a, b) = (points[x], points[y]);
            let d = b - a;
            let s = ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            if p.distance(a + d * s) < 0.5 * c.spacing {
                return false;
            }
        }
    }
    let (k, &wmin) = bary
        .iter()
        .enumerate()
        .min_by(|x, y| x.1.total_cmp(y.1))
        .unwrap_or((0, &0.0));
    let (x, y) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
    // On an edge (exactly: points of one line from a source node are collinear, and a
    // symmetric section puts such a line along an axis): both triangles are split there, 2
    // and 2. Split in three, the holding triangle would leave one of no area that no swap
    // removes (its quad has no convex diagonal). Anywhere else, even close to an edge, the
    // holding triangle alone is split in three, and the swaps remove the thin pieces.
    let on_edge = wmin == 0.0 || collinear(points[x], points[y], p);
    if on_edge {
        if model_edges.contains(&key(x, y)) || !splits_cleanly(tris, points, x, y, p, normal) {
            return false;
        }
        let m = points.len();
        points.push(p);
        split_edge(tris, x, y, m);
        swap_around(tris, points, model_edges, m);
        return true;
    }
    let m = points.len();
    points.push(p);
    tris[t] = [tri[0], tri[1], m];
    tris.push([tri[1], tri[2], m]);
    tris.push([tri[2], tri[0], m]);
    swap_around(tris, points, model_edges, m);
    true
}

/// Whether `a`, `b`, `c` lie on one line, exactly (`orient2d` is zero in each of the three
/// coordinate planes).
fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let planes: [fn(DVec3) -> DVec2; 3] = [
        |p| DVec2::new(p.x, p.y),
        |p| DVec2::new(p.y, p.z),
        |p| DVec2::new(p.z, p.x),
    ];
    planes.iter().all(|f| orient2d(f(a), f(b), f(c)) == 0.0)
}

/// Whether splitting edge `xy` at `p` leaves every triangle on the edge as two triangles
/// facing along `normal`.
fn splits_cleanly(
    tris: &[[usize; 3]],
    points: &[DVec3],
    x: usize,
    y: usize,
    p: DVec3,
    normal: DVec3,
) -> bool {
    let facing = |a: DVec3, b: DVec3, c: DVec3| (b - a).cross(c - a).dot(normal) > 0.0;
    tris.iter().all(|t| {
        (0..3).all(|i| {
            let (a, b, r) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
            if !((a == x && b == y) || (a == y && b == x)) {
                return true;
            }
            let [a, b, r] = [a, b, r].map(|v| points[v]);
            facing(a, p, r) && facing(p, b, r)
        })
    })
}

fn max_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let ang = |p: DVec3, q: DVec3, r: DVec3| (q - p).angle_between(r - p);
    ang(a, b, c).max(ang(b, c, a)).max(ang(c, a, b))
}

/// Swap the diagonal of the quad of triangles `i`, `j` (sharing an edge) when it lowers the
/// largest angle and the quad is convex in its mean plane (exact `orient2d` there).
fn try_swap(
    tris: &mut [[usize; 3]],
    points: &[DVec3],
    model_edges: &HashSet<(usize, usize)>,
    i: usize,
    j: usize,
) -> bool {
    let (ti, tj) = (tris[i], tris[j]);
    // Shared edge a→b in ti, b→a in tj.
    let Some(k) = (0..3).find(|&k| {
        let (a, b) = (ti[k], ti[(k + 1) % 3]);
        (0..3).any(|l| tj[l] == b && tj[(l + 1) % 3] == a)
    }) else {
        return false;
    };
    let (a, b, c) = (ti[k], ti[(k + 1) % 3], ti[(k + 2) % 3]);
    let Some(d) = tj.iter().copied().find(|&v| v != a && v != b) else {
        return false;
    };
    if model_edges.contains(&key(a, b)) || c == d {
        return false;
    }
    let [pa, pb, pc, pd] = [a, b, c, d].map(|v| points[v]);
    let n = ((pb - pa).cross(pc - pa) + (pa - pb).cross(pd - pb)).normalize_or_zero();
    if n == DVec3::ZERO {
        return false;
    }
    let fr = frame(n);
    let [qa, qb, qc, qd] = [pa, pb, pc, pd].map(|p| flat(p, pa, fr));
    // New triangles (a, d, c) and (d, b, c) must both turn counter-clockwise.
    if orient2d(qa, qd, qc) <= 0.0 || orient2d(qd, qb, qc) <= 0.0 {
        return false;
    }
    // The projection rounds: a vertex exactly on the new diagonal (three points of one
    // source line) can still look convex there.
    if collinear(pa, pd, pc) || collinear(pd, pb, pc) {
        return false;
    }
    let old = max_angle(pa, pb, pc).max(max_angle(pb, pa, pd));
    let new = max_angle(pa, pd, pc).max(max_angle(pd, pb, pc));
    if new < old - 1e-9 {
        tris[i] = [a, d, c];
        tris[j] = [d, b, c];
        true
    } else {
        false
    }
}

/// Swaps of the edges opposite a new node, spreading as they succeed.
fn swap_around(
    tris: &mut [[usize; 3]],
    points: &[DVec3],
    model_edges: &HashSet<(usize, usize)>,
    m: usize,
) {
    let mut stack: Vec<usize> = (0..tris.len()).filter(|&t| tris[t].contains(&m)).collect();
    let mut guard = 0;
    while let Some(t) = stack.pop() {
        guard += 1;
        if guard > 1000 || !tris[t].contains(&m) {
            continue;
        }
        let k = (0..3).find(|&k| tris[t][k] == m).unwrap_or(0);
        let (x, y) = (tris[t][(k + 1) % 3], tris[t][(k + 2) % 3]);
        let Some(u) =
            (0..tris.len()).find(|&u| u != t && tris[u].contains(&x) && tris[u].contains(&y))
        else {
            continue;
        };
        if try_swap(tris, points, model_edges, t, u) {
            stack.push(t);
            stack.push(u);
        }
    }
}

/// Max-angle swaps over a whole face until none helps; returns the number made.
fn swap_all(
    tris: &mut [[usize; 3]],
    points: &[DVec3],
    model_edges: &HashSet<(usize, usize)>,
) -> usize {
    let mut total = 0;
    for _ in 0..8 {
        let mut edges: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
        for (t, tri) in tris.iter().enumerate() {
            for k in 0..3 {
                edges
                    .entry(key(tri[k], tri[(k + 1) % 3]))
                    .or_default()
                    .push(t);
            }
        }
        let mut pairs: Vec<(usize, usize)> = edges
            .into_iter()
            .filter(|(e, ts)| ts.len() == 2 && !model_edges.contains(e))
            .map(|(_, ts)| (ts[0], ts[1]))
            .collect();
        pairs.sort_unstable();
        let mut made = 0;
        let mut touched = vec![false; tris.len()];
        for (i, j) in pairs {
            if touched[i] || touched[j] {
                continue;
            }
            if try_swap(tris, points, model_edges, i, j) {
                touched[i] = true;
                touched[j] = true;
                made += 1;
            }
        }
        total += made;
        if made == 0 {
            break;
        }
    }
    total
}

/// True when a triangle holding a point from `first_new` on crosses another triangle of the
/// face (face points near a curved model edge have been seen to overlap their neighbours).
fn crosses(tris: &[[usize; 3]], points: &[DVec3], first_new: usize) -> bool {
    let coords: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
    let tris32: Vec<[u32; 3]> = tris.iter().map(|t| t.map(|v| v as u32)).collect();
    let new = (0..tris.len()).filter(|&k| tris[k].iter().any(|&v| v >= first_new));
    crate::volume::intersect::crossing_among(&coords, &tris32, new).is_some()
}

/// True when a triangle of `after` faces against the triangle of `before` whose centroid is
/// nearest its own, or has no area.
fn folds(before: &[[usize; 3]], after: &[[usize; 3]], points: &[DVec3]) -> bool {
    let normal = |t: &[usize; 3]| {
        let [a, b, c] = t.map(|v| points[v]);
        (b - a).cross(c - a)
    };
    let centre = |t: &[usize; 3]| ((points[t[0]] + points[t[1]] + points[t[2]]) / 3.0).to_array();
    let tree: rstar::RTree<rstar::primitives::GeomWithData<[f64; 3], usize>> =
        rstar::RTree::bulk_load(
            before
                .iter()
                .enumerate()
                .map(|(k, t)| rstar::primitives::GeomWithData::new(centre(t), k))
                .collect(),
        );
    after.iter().any(|t| {
        let n = normal(t);
        if n.length_squared() == 0.0 {
            return true;
        }
        match tree.nearest_neighbor(&centre(t)) {
            Some(o) => n.dot(normal(&before[o.data])) <= 0.0,
            None => false,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit square in z = 0 as two triangles on its diagonal 0–2.
    fn unit_square() -> (Vec<DVec3>, Vec<[usize; 3]>) {
        let points = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        (points, vec![[0, 1, 2], [0, 2, 3]])
    }

    /// A face candidate at `point` (layer spacing 0.01).
    fn candidate_at(point: DVec3) -> Candidate {
        Candidate {
            point,
            site: 0.1,
            dir: DVec3::X,
            along: DVec3::ZERO,
            spacing: 0.01,
            source: 0,
            from: 0,
        }
    }

    /// A point on a line from a source node can land on a triangle's edge to the last bit
    /// (a symmetric section puts such a line along an axis). Exactly on it, the edge splits, 2
    /// and 2, not its triangle in three with a needle no swap removes; a rounding off it, the
    /// swaps remove the thin piece. Either way: four triangles, none a needle.
    #[test]
    fn a_point_on_an_edge_splits_the_edge_not_its_triangle() {
        for offset in [0.0, 1e-13, -1e-13] {
            let (mut points, mut tris) = unit_square();
            let c = candidate_at(DVec3::new(0.37 + offset, 0.37 - offset, 0.0));
            let inserted = try_insert(
                &mut tris,
                &mut points,
                &HashSet::new(),
                0,
                &c,
                0.01,
                DVec3::Z,
            );
            assert!(inserted, "offset {offset}");
            assert_eq!(tris.len(), 4, "offset {offset}: {tris:?}");
            for t in &tris {
                let [a, b, e] = t.map(|v| points[v]);
                assert!((b - a).cross(e - a).z > 0.01, "offset {offset}: {t:?}");
                assert!(max_angle(a, b, e) < 170f64.to_radians(), "{t:?}");
            }
            let area: f64 = tris
                .iter()
                .map(|t| {
                    let [a, b, e] = t.map(|v| points[v]);
                    0.5 * (b - a).cross(e - a).z
                })
                .sum();
            assert!((area - 1.0).abs() < 1e-12);
        }
    }

    /// On a model edge the point is refused: the edge's nodes belong to the curve mesh.
    #[test]
    fn a_point_on_a_model_edge_is_refused() {
        let (mut points, mut tris) = unit_square();
        let c = candidate_at(DVec3::new(0.5, 0.5, 0.0));
        let edges = HashSet::from([key(0, 2)]);
        assert!(!try_insert(
            &mut tris,
            &mut points,
            &edges,
            0,
            &c,
            0.01,
            DVec3::Z
        ));
        assert_eq!(tris.len(), 2);
        assert_eq!(points.len(), 4);
    }
}
