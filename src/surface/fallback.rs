//! The face mesher's second method, for a face whose advancing front cannot close: a
//! constrained Delaunay triangulation of the boundary in the face's (u,v) (spade, exact
//! predicates), refined by splitting interior edges longer than the 3-D spacing allows at their
//! (u,v) middle, until none is. The result is then improved like a front's (swaps and
//! smoothing judged in 3-D). It needs no circle–surface intersection and no front tests, so it
//! closes wherever the boundary is a valid set of loops in (u,v) — a face whose parameter runs
//! over a huge range, a strip or a pocket the front wedges itself into.
//!
//! (u,v) is scaled by the surface's typical |Su| and |Sv| first, so that Delaunay's circles
//! are near circles in 3-D on faces whose parameters run at very different speeds (a revolved
//! face with v over 7·10⁴ and u over 2π).

use super::advance::FaceTriangulation;
use super::boundary::{Boundary, FaceVertex};
use crate::geometry::Surface;
use crate::sizing::SizingField;
use glam::DVec2;
use spade::handles::{FixedFaceHandle, FixedVertexHandle, InnerTag};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};
use std::collections::HashMap;

/// An interior edge longer than this many δ (3-D length against the spacing at its middle)
/// is split at its (u,v) middle: edges end between half and the whole of it.
const SPLIT: f64 = 1.5;
/// Split rounds before the fallback gives up (each round at least halves the longest edge).
const MAX_ROUNDS: usize = 60;

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// Why the fallback could not triangulate a face.
#[derive(Debug, PartialEq)]
pub enum Refusal {
    /// Two boundary vertices at one (u,v), or a boundary vertex on another's segment.
    Coincident(DVec2),
    /// Two boundary segments cross in (u,v).
    Crossing(DVec2),
    /// The loops do not have the face on their left everywhere (mixed orientation).
    Orientation(DVec2),
    /// The refinement did not settle (a surface degenerate inside the face).
    Runaway(DVec2),
}

impl Refusal {
    /// Where in (u,v) the problem lies.
    pub fn uv(&self) -> DVec2 {
        match self {
            Refusal::Coincident(p)
            | Refusal::Crossing(p)
            | Refusal::Orientation(p)
            | Refusal::Runaway(p) => *p,
        }
    }
}

/// Triangulate the face inside `boundary` (vertices first, in order: they are the fixed
/// ones), counter-clockwise in (u,v).
pub fn triangulate(
    surface: &dyn Surface,
    sizing: &SizingField,
    boundary: &Boundary,
) -> Result<FaceTriangulation, Refusal> {
    let scale = parameter_scale(surface, boundary);
    let at = |uv: DVec2| Point2::new(uv.x * scale.x, uv.y * scale.y);
    let mut cdt = Cdt::new();
    let mut vertices: Vec<FaceVertex> = boundary.vertices.clone();
    // Our vertex of each spade vertex (spade's handles are dense indices).
    let mut ours: Vec<usize> = Vec::new();
    let mut used = vec![false; vertices.len()];
    for s in &boundary.segments {
        used[s[0]] = true;
        used[s[1]] = true;
    }
    let mut handle = vec![None; vertices.len()];
    for (k, v) in vertices.iter().enumerate().filter(|(k, _)| used[*k]) {
        let h = cdt
            .insert(at(v.uv))
            .map_err(|_| Refusal::Coincident(v.uv))?;
        if h.index() < ours.len() {
            return Err(Refusal::Coincident(v.uv));
        }
        ours.push(k);
        handle[k] = Some(h);
    }
    // Segments by undirected pair: a slit (a segment and its reverse) is no border.
    let mut multiplicity: HashMap<(usize, usize), u32> = HashMap::new();
    for &[a, b] in &boundary.segments {
        *multiplicity.entry((a.min(b), a.max(b))).or_default() += 1;
    }
    for &[a, b] in &boundary.segments {
        let (ha, hb) = (handle[a].expect("used"), handle[b].expect("used"));
        if cdt.exists_constraint(ha, hb) {
            continue;
        }
        let middle = (vertices[a].uv + vertices[b].uv) / 2.0;
        if !cdt.can_add_constraint(ha, hb) {
            return Err(Refusal::Crossing(middle));
        }
        cdt.add_constraint(ha, hb);
        if !cdt.exists_constraint(ha, hb) {
            return Err(Refusal::Coincident(middle));
        }
    }
    let border = |cdt: &Cdt, ours: &[usize], e: spade::handles::FixedUndirectedEdgeHandle| {
        let [p, q] = cdt
            .undirected_edge(e)
            .vertices()
            .map(|v| ours[v.fix().index()]);
        cdt.is_constraint_edge(e) && multiplicity.get(&(p.min(q), p.max(q))) == Some(&1)
    };
    // Every segment must have the face's inside on its left.
    let inside = classify(&cdt, |e| border(&cdt, &ours, e));
    for &[a, b] in &boundary.segments {
        if multiplicity[&(a.min(b), a.max(b))] != 1 {
            continue;
        }
        let (ha, hb) = (handle[a].expect("used"), handle[b].expect("used"));
        let edge = cdt.get_edge_from_neighbors(ha, hb).expect("a constraint");
        let left_inside = edge
            .face()
            .as_inner()
            .is_some_and(|f| inside[f.fix().index()]);
        if !left_inside {
            return Err(Refusal::Orientation(
                (vertices[a].uv + vertices[b].uv) / 2.0,
            ));
        }
    }

    let xyz = |vertices: &[FaceVertex], ours: &[usize], h: FixedVertexHandle| {
        vertices[ours[h.index()]].xyz
    };
    for round in 0..MAX_ROUNDS {
        let inside = classify(&cdt, |e| border(&cdt, &ours, e));
        let is_inside = |f: Option<FixedFaceHandle<InnerTag>>| f.is_some_and(|f| inside[f.index()]);
        let mut splits: Vec<(f64, DVec2)> = Vec::new();
        for e in cdt.undirected_edges() {
            let d = e.as_directed();
            if cdt.is_constraint_edge(e.fix())
                || !is_inside(d.face().as_inner().map(|f| f.fix()))
                || !is_inside(d.rev().face().as_inner().map(|f| f.fix()))
            {
                continue;
            }
            let [p, q] = e.vertices().map(|v| v.fix());
            let (xp, xq) = (xyz(&vertices, &ours, p), xyz(&vertices, &ours, q));
            let ratio = xp.distance(xq) / sizing.spacing((xp + xq) / 2.0);
            if ratio > SPLIT {
                let [up, uq] = [p, q].map(|h| vertices[ours[h.index()]].uv);
                splits.push((ratio, (up + uq) / 2.0));
            }
        }
        // A triangle of three boundary segments has no interior edge to split: its centroid.
        for f in cdt.inner_faces().filter(|f| inside[f.fix().index()]) {
            let edges = f.adjacent_edges();
            if !edges
                .iter()
                .all(|e| cdt.is_constraint_edge(e.fix().as_undirected()))
            {
                continue;
            }
            let corners = f.vertices().map(|v| v.fix());
            let x = corners.map(|h| xyz(&vertices, &ours, h));
            let longest = x[0]
                .distance(x[1])
                .max(x[1].distance(x[2]))
                .max(x[2].distance(x[0]));
            let ratio = longest / sizing.spacing((x[0] + x[1] + x[2]) / 3.0);
            if ratio > SPLIT {
                let uv = corners.map(|h| vertices[ours[h.index()]].uv);
                splits.push((ratio, (uv[0] + uv[1] + uv[2]) / 3.0));
            }
        }
        if splits.is_empty() {
            break;
        }
        splits.sort_by(|a, b| b.0.total_cmp(&a.0));
        let before = vertices.len();
        for (_, uv) in splits {
            if encroaches(&cdt, at(uv)) {
                continue;
            }
            let Ok(h) = cdt.insert(at(uv)) else { continue };
            if h.index() < ours.len() {
                continue;
            }
            ours.push(vertices.len());
            vertices.push(FaceVertex {
                uv,
                xyz: surface.point(uv),
                node: None,
            });
        }
        if cdt.num_constraints() != constraint_count(&multiplicity) {
            // A new point fell on a boundary segment and split it.
            return Err(Refusal::Coincident(vertices.last().expect("pushed").uv));
        }
        if vertices.len() == before {
            // What is left to split lies against the boundary, which keeps its nodes.
            break;
        }
        if round + 1 == MAX_ROUNDS {
            return Err(Refusal::Runaway(
                vertices.last().map_or(DVec2::ZERO, |v| v.uv),
            ));
        }
    }
    if multiplicity.values().all(|&m| m == 1) {
        refine_angles(&mut cdt, &mut ours, &mut vertices, surface, scale);
    }
    Ok(collect(&cdt, &ours, vertices, |e| border(&cdt, &ours, e)))
}

/// Smallest angle the Delaunay refinement aims at (in the scaled (u,v), near 3-D).
const ANGLE_LIMIT_DEG: f64 = 25.0;

/// Delaunay refinement of the sized triangulation for its smallest angles (spade's, inside
/// the loops only, the boundary segments never split), its points placed on the surface.
/// Skipped where the boundary has a slit (a segment run both ways), whose two sides spade's
/// inside test would not tell apart.
fn refine_angles(
    cdt: &mut Cdt,
    ours: &mut Vec<usize>,
    vertices: &mut Vec<FaceVertex>,
    surface: &dyn Surface,
    scale: DVec2,
) {
    let parameters = spade::RefinementParameters::new()
        .keep_constraint_edges()
        .exclude_outer_faces(true)
        .with_angle_limit(spade::AngleLimit::from_deg(ANGLE_LIMIT_DEG))
        .with_max_additional_vertices(vertices.len() / 2 + 16);
    cdt.refine(parameters);
    for h in ours.len()..cdt.num_vertices() {
        let p = cdt.vertex(FixedVertexHandle::from_index(h)).position();
        let uv = DVec2::new(p.x / scale.x, p.y / scale.y);
        ours.push(vertices.len());
        vertices.push(FaceVertex {
            uv,
            xyz: surface.point(uv),
            node: None,
        });
    }
}

/// Whether `p` lies in the diametral circle of a boundary segment of the triangle holding
/// it: the boundary keeps its nodes (they are shared with the neighbouring faces), so a point
/// there would only make slivers against it, and a run of them would creep onto it.
fn encroaches(cdt: &Cdt, p: Point2<f64>) -> bool {
    let face = match cdt.locate(p) {
        spade::PositionInTriangulation::OnFace(f) => f,
        spade::PositionInTriangulation::OnEdge(e) => match cdt.directed_edge(e).face().as_inner() {
            Some(f) => f.fix(),
            None => return true,
        },
        _ => return true,
    };
    cdt.face(face).adjacent_edges().iter().any(|e| {
        if !cdt.is_constraint_edge(e.fix().as_undirected()) {
            return false;
        }
        let [a, b] = e.vertices().map(|v| v.position());
        (a.x - p.x) * (b.x - p.x) + (a.y - p.y) * (b.y - p.y) < 0.0
    })
}

/// Constraint edges the boundary makes (each undirected pair once).
fn constraint_count(multiplicity: &HashMap<(usize, usize), u32>) -> usize {
    multiplicity.len()
}

/// Inside flags of the inner faces (by index): crossing a border toggles, starting outside
/// from the convex hull.
fn classify(
    cdt: &Cdt,
    border: impl Fn(spade::handles::FixedUndirectedEdgeHandle) -> bool,
) -> Vec<bool> {
    let n = cdt.all_faces().len();
    let mut state: Vec<Option<bool>> = vec![None; n];
    let mut stack: Vec<(FixedFaceHandle<InnerTag>, bool)> = Vec::new();
    for e in cdt.convex_hull() {
        // Hull edges run with the outer face on their left: the inner face is across.
        if let Some(f) = e.rev().face().as_inner() {
            stack.push((f.fix(), border(e.fix().as_undirected())));
        }
    }
    while let Some((f, flag)) = stack.pop() {
        if state[f.index()].is_some() {
            continue;
        }
        state[f.index()] = Some(flag);
        for e in cdt.face(f).adjacent_edges() {
            if let Some(g) = e.rev().face().as_inner() {
                if state[g.fix().index()].is_none() {
                    stack.push((g.fix(), flag ^ border(e.fix().as_undirected())));
                }
            }
        }
    }
    // spade's face indices start with the outer face at 0; inner faces index the same space.
    state.into_iter().map(|s| s == Some(true)).collect()
}

/// The inside triangles on our vertex ids.
fn collect(
    cdt: &Cdt,
    ours: &[usize],
    vertices: Vec<FaceVertex>,
    border: impl Fn(spade::handles::FixedUndirectedEdgeHandle) -> bool,
) -> FaceTriangulation {
    let inside = classify(cdt, border);
    let triangles = cdt
        .inner_faces()
        .filter(|f| inside[f.fix().index()])
        .map(|f| f.vertices().map(|v| ours[v.fix().index()]))
        .collect();
    FaceTriangulation {
        vertices,
        triangles,
    }
}

/// Typical |Su| and |Sv| over the boundary (medians: a pole's zero speed does not pull them).
fn parameter_scale(surface: &dyn Surface, boundary: &Boundary) -> DVec2 {
    let mut su = Vec::with_capacity(boundary.vertices.len());
    let mut sv = Vec::with_capacity(boundary.vertices.len());
    for v in &boundary.vertices {
        let d = surface.derivs(v.uv);
        su.push(d.du.length());
        sv.push(d.dv.length());
    }
    let median = |mut x: Vec<f64>| {
        x.retain(|s| s.is_finite() && *s > 0.0);
        if x.is_empty() {
            return 1.0;
        }
        x.sort_by(f64::total_cmp);
        x[x.len() / 2]
    };
    let (u, v) = (median(su), median(sv));
    // Only the ratio matters; keep the numbers near the parameters' own.
    let m = (u * v).sqrt();
    DVec2::new(u / m, v / m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{SurfaceBounds, SurfaceDerivs};
    use glam::DVec3;

    /// The plane z = 0 with (u,v) = (x, y/1000): v runs a thousand times slower.
    struct Stretched;
    impl Surface for Stretched {
        fn bounds(&self) -> SurfaceBounds {
            SurfaceBounds::rect((-10.0, 10.0), (-1e4, 1e4))
        }
        fn point(&self, uv: DVec2) -> DVec3 {
            DVec3::new(uv.x, uv.y * 1e-3, 0.0)
        }
        fn derivs(&self, uv: DVec2) -> SurfaceDerivs {
            SurfaceDerivs {
                p: self.point(uv),
                du: DVec3::X,
                dv: DVec3::Y * 1e-3,
                duu: DVec3::ZERO,
                duv: DVec3::ZERO,
                dvv: DVec3::ZERO,
            }
        }
    }

    fn square(with_hole: bool) -> Boundary {
        let mut vertices = Vec::new();
        let mut segments = Vec::new();
        let mut ring = |pts: &[(f64, f64)]| {
            let first = vertices.len();
            for &(x, y) in pts {
                vertices.push(FaceVertex {
                    uv: DVec2::new(x, y * 1e3),
                    xyz: DVec3::new(x, y, 0.0),
                    node: Some(vertices.len()),
                });
            }
            let n = pts.len();
            for k in 0..n {
                segments.push([first + k, first + (k + 1) % n]);
            }
        };
        // Sides cut at the spacing (0.1), as the curve mesh does.
        let side = |from: (f64, f64), to: (f64, f64), n: usize| {
            (0..n).map(move |k| {
                let t = k as f64 / n as f64;
                (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1))
            })
        };
        let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let outer: Vec<(f64, f64)> = (0..4)
            .flat_map(|k| side(corners[k], corners[(k + 1) % 4], 10))
            .collect();
        ring(&outer);
        if with_hole {
            let corners = [(0.4, 0.4), (0.4, 0.6), (0.6, 0.6), (0.6, 0.4)];
            let hole: Vec<(f64, f64)> = (0..4)
                .flat_map(|k| side(corners[k], corners[(k + 1) % 4], 2))
                .collect();
            ring(&hole);
        }
        Boundary {
            vertices,
            segments,
            slits: Vec::new(),
        }
    }

    fn area(t: &FaceTriangulation) -> f64 {
        t.triangles
            .iter()
            .map(|&[a, b, c]| {
                let x = |k: usize| t.vertices[k].xyz;
                0.5 * (x(b) - x(a)).cross(x(c) - x(a)).length()
            })
            .sum()
    }

    #[test]
    fn a_square_with_a_hole_is_covered_once_at_the_spacing() {
        let sizing = SizingField::uniform(0.1);
        let t = triangulate(&Stretched, &sizing, &square(true)).unwrap();
        assert!((area(&t) - 0.96).abs() < 1e-9, "area {}", area(&t));
        // Every triangle counter-clockwise in (u,v), every interior edge within SPLIT·δ.
        for &[a, b, c] in &t.triangles {
            let uv = |k: usize| t.vertices[k].uv;
            assert!(crate::geometry::orient2d(uv(a), uv(b), uv(c)) > 0.0);
        }
        let longest = t
            .triangles
            .iter()
            .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
            .filter(|&(p, q)| p >= 48 || q >= 48)
            .map(|(p, q)| t.vertices[p].xyz.distance(t.vertices[q].xyz))
            .fold(0.0, f64::max);
        assert!(longest <= SPLIT * 0.1 + 1e-12, "longest {longest}");
        assert!(t.triangles.len() > 100, "{} triangles", t.triangles.len());
    }

    #[test]
    fn crossing_loops_are_refused_with_where() {
        let mut b = square(false);
        // A hole that crosses the outer loop's right side.
        let first = b.vertices.len();
        for &(x, y) in &[(0.85, 0.45), (0.85, 0.55), (1.15, 0.55), (1.15, 0.45)] {
            b.vertices.push(FaceVertex {
                uv: DVec2::new(x, y * 1e3),
                xyz: DVec3::new(x, y, 0.0),
                node: None,
            });
        }
        for k in 0..4 {
            b.segments.push([first + k, first + (k + 1) % 4]);
        }
        let r = triangulate(&Stretched, &SizingField::uniform(0.1), &b);
        assert!(matches!(r, Err(Refusal::Crossing(_))), "{r:?}");
    }

    #[test]
    fn a_loop_running_clockwise_is_refused() {
        let mut b = square(false);
        for s in &mut b.segments {
            s.swap(0, 1);
        }
        let r = triangulate(&Stretched, &SizingField::uniform(0.1), &b);
        assert!(matches!(r, Err(Refusal::Orientation(_))), "{r:?}");
    }
}
