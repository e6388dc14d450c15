//! Steiner point suppression: after recovery, take each boundary Steiner point off the
//! surface again, so that the input triangles come back exactly (TetGen's "suppress Steiner
//! points"; George et al.'s boundary-preserving recovery, where what cannot be removed is
//! moved into the volume).
//!
//! A Steiner point `m` splits one or more original triangles (one for a point inside a
//! triangle; every triangle on the segment for a point on an edge). Its star is cut by the
//! surface pieces at `m` into *cells* (two for a point inside a shell triangle, one wedge
//! per pair of consecutive triangles around a segment, one cell with a slit for a free wake
//! edge). Suppressing `m` means:
//!
//! * re-triangulating the pieces at `m` without it, as a fan from a vertex `v` that every
//!   original triangle at `m` shares (any piece vertex for a point inside a triangle, the
//!   segment's neighbouring vertices for a point on an edge), so the fan stays in each
//!   original plane and the segment comes back;
//! * filling each cell again: as the cone from one of its boundary vertices (possible exactly
//!   when the cell is star-shaped from that vertex: every cone tet positively oriented), or,
//!   for at most one cell, as the cone from `m` itself moved strictly inside that cell.
//!
//! A Steiner point on an embedded segment `u w` (an edge on no triangle) is handled the same
//! way with `v` one of `u`, `w`, and the result must have the edge `u w`.
//!
//! Coning every cell from `v` is the edge collapse `m → v`. When every cell has a vertex
//! cone, `m` is deleted; when one cell has none, `m` is moved into it and stays as an
//! interior Steiner point, the surface being the input one either way. Otherwise `m` is
//! kept. Every orientation is decided by the exact `orient`, and the kernel's
//! [`Delaunay::replace_star`](crate::volume::delaunay::Delaunay::replace_star) re-checks the
//! whole proposal (positive tets, consistent sides across every face) before touching
//! anything, so a suppression never leaves an inverted tet. Stars touching the hull are left
//! alone.

use std::collections::HashMap;

use crate::volume::delaunay::predicates::orient;

use super::{quality, Ctx};

/// What became of one boundary Steiner point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Outcome {
    /// Removed from the triangulation.
    Deleted,
    /// Moved off the surface into the volume (now an interior Steiner point).
    Moved,
    /// Still on the surface.
    Kept,
}

/// The star tets of `m` on one side of the surface pieces, described by the faces bounding
/// them, each oriented with the cell on its positive side (`orient(face, inside) > 0`).
struct Cell {
    /// Faces of the star's outer boundary (opposite `m`).
    link: Vec<[u32; 3]>,
    /// Surface pieces at `m` (they contain `m`).
    pieces: Vec<[u32; 3]>,
}

/// A way to suppress `m`: the new tets, where `m` goes (if it stays), and the fan apex.
struct Plan {
    tets: Vec<[u32; 4]>,
    at: Option<[f64; 3]>,
    apex: u32,
    quality: f64,
}

/// Try to take every Steiner point with index `>= first` off the surface (later ones first,
/// a few passes, since removing one can free another). Counts go to `ctx.report`.
pub(super) fn suppress_all(ctx: &mut Ctx, first: u32) {
    const PASSES: usize = 3;
    for _ in 0..PASSES {
        let mut progress = false;
        for m in (first..ctx.dt.num_points() as u32).rev() {
            if !ctx.surface.is_vertex(m) {
                continue;
            }
            match suppress(ctx, m) {
                Outcome::Deleted => ctx.report.steiner_removed += 1,
                Outcome::Moved => {
                    ctx.report.steiner_removed += 1;
                    ctx.report.steiner_interior += 1;
                }
                Outcome::Kept => continue,
            }
            progress = true;
        }
        if !progress {
            break;
        }
    }
}

/// Suppress one boundary Steiner point `m` (see the module docs).
pub(super) fn suppress(ctx: &mut Ctx, m: u32) -> Outcome {
    let Some(cells) = cells(ctx, m) else {
        return Outcome::Kept;
    };
    let pieces = ctx.surface.triangles_at(m);
    // On an embedded segment `u m w`: only `u` and `w` may replace `m`, and `u w` must come
    // out as an edge.
    let segment = match ctx.surface.segment_neighbours(m)[..] {
        [] => None,
        [u, w] => Some((u, w)),
        _ => return Outcome::Kept,
    };
    let mut apexes = fan_apexes(ctx, m, &pieces);
    if let Some((u, w)) = segment {
        if pieces.is_empty() {
            apexes = vec![u, w];
        }
        apexes.retain(|&x| x == u || x == w);
    }
    let mut plans: Vec<Plan> = Vec::new();
    for v in apexes {
        // A bare segment's edge `u w` comes out only from cones at `u` or `w`.
        let cone_from_v_only = segment.is_some() && pieces.is_empty();
        if let Some(p) = plan(ctx, m, v, &cells, cone_from_v_only) {
            let has = |(u, w): (u32, u32)| p.tets.iter().any(|t| t.contains(&u) && t.contains(&w));
            if segment.is_none_or(has) {
                plans.push(p);
            }
        }
    }
    // Deletions first, then the best quality.
    plans.sort_by(|a, b| {
        (a.at.is_some(), -a.quality)
            .partial_cmp(&(b.at.is_some(), -b.quality))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for p in plans {
        let fan: Vec<[u32; 3]> = pieces
            .iter()
            .map(|&k| ctx.surface.tris[k as usize])
            .filter(|t| !t.contains(&p.apex))
            .map(|t| t.map(|x| if x == m { p.apex } else { x }))
            .collect();
        if ctx.dt.replace_star(m, &p.tets, p.at, &fan).is_ok() {
            for &k in &pieces {
                ctx.surface.replace_vertex(k, m, p.apex);
            }
            if let Some((u, w)) = segment {
                ctx.surface.join_segments(u, m, w);
            }
            return if p.at.is_some() {
                Outcome::Moved
            } else {
                Outcome::Deleted
            };
        }
    }
    Outcome::Kept
}

/// The star of `m` cut into cells by the constrained faces at `m` (the surface pieces);
/// `None` if the star touches the hull.
fn cells(ctx: &mut Ctx, m: u32) -> Option<Vec<Cell>> {
    let star = ctx.dt.tets_around_vertex(m);
    if star.is_empty() || star.iter().any(|&t| ctx.dt.is_ghost(t)) {
        return None;
    }
    let index: HashMap<u32, usize> = star.iter().enumerate().map(|(i, &t)| (t, i)).collect();
    let mut cell_of = vec![usize::MAX; star.len()];
    let mut cells = Vec::new();
    for s in 0..star.len() {
        if cell_of[s] != usize::MAX {
            continue;
        }
        let c = cells.len();
        let mut cell = Cell {
            link: Vec::new(),
            pieces: Vec::new(),
        };
        cell_of[s] = c;
        let mut stack = vec![star[s]];
        while let Some(t) = stack.pop() {
            let v = ctx.dt.tet(t);
            for f in 0..4u8 {
                if v[f as usize] == m {
                    cell.link.push(ctx.dt.face_vertices(t, f));
                    continue;
                }
                if ctx.dt.is_constrained(t, f) {
                    cell.pieces.push(ctx.dt.face_vertices(t, f));
                    continue;
                }
                let (u, _) = ctx.dt.neighbor(t, f);
                let i = *index.get(&u)?;
                if cell_of[i] == usize::MAX {
                    cell_of[i] = c;
                    stack.push(u);
                }
            }
        }
        cells.push(cell);
    }
    Some(cells)
}

/// Vertices a fan replacing `m` may start from: those shared by the pieces of every
/// original triangle at `m`, so that each original triangle's pieces stay in its plane.
fn fan_apexes(ctx: &Ctx, m: u32, pieces: &[u32]) -> Vec<u32> {
    let mut by_parent: HashMap<u32, Vec<u32>> = HashMap::new();
    for &k in pieces {
        let list = by_parent.entry(ctx.surface.parent[k as usize]).or_default();
        for x in ctx.surface.tris[k as usize] {
            if x != m && !list.contains(&x) {
                list.push(x);
            }
        }
    }
    let mut groups = by_parent.into_values();
    let Some(mut common) = groups.next() else {
        return Vec::new();
    };
    for g in groups {
        common.retain(|x| g.contains(x));
    }
    common.sort_unstable();
    common
}

/// The tets of the cone from `w` over the faces not containing `w`, and their minimum
/// quality; `None` unless every one is positively oriented. `at` moves `m` for the test.
fn cone(
    ctx: &Ctx,
    faces: &[[u32; 3]],
    w: u32,
    moved: Option<(u32, [f64; 3])>,
) -> Option<(Vec<[u32; 4]>, f64)> {
    let p = |x: u32| match moved {
        Some((m, at)) if x == m => at,
        _ => ctx.dt.point(x),
    };
    let mut tets = Vec::with_capacity(faces.len());
    let mut worst = f64::INFINITY;
    for f in faces {
        if f.contains(&w) {
            continue;
        }
        let [a, b, c, d] = [f[0], f[1], f[2], w].map(p);
        if orient(&a, &b, &c, &d) <= 0.0 {
            return None;
        }
        worst = worst.min(quality(&a, &b, &c, &d));
        tets.push([f[0], f[1], f[2], w]);
    }
    Some((tets, worst))
}

/// Suppression of `m` with the fan from `v`: every cell coned from its best vertex (from `v`
/// only, if `v_only`), or, if exactly one cell has no vertex cone, that cell coned from `m`
/// moved inside it.
fn plan(ctx: &Ctx, m: u32, v: u32, cells: &[Cell], v_only: bool) -> Option<Plan> {
    let mut tets = Vec::new();
    let mut worst = f64::INFINITY;
    let mut blocked: Option<Vec<[u32; 3]>> = None;
    for cell in cells {
        let mut faces = cell.link.clone();
        faces.extend(
            cell.pieces
                .iter()
                .filter(|f| !f.contains(&v))
                .map(|f| f.map(|x| if x == m { v } else { x })),
        );
        let mut apexes: Vec<u32> = faces.iter().flatten().copied().collect();
        apexes.sort_unstable();
        apexes.dedup();
        if v_only {
            apexes = vec![v];
        }
        let best = apexes
            .into_iter()
            .filter_map(|w| cone(ctx, &faces, w, None))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        match best {
            Some((t, q)) => {
                tets.extend(t);
                worst = worst.min(q);
            }
            None if blocked.is_none() => blocked = Some(faces),
            None => return None,
        }
    }
    let Some(faces) = blocked else {
        return Some(Plan {
            tets,
            at: None,
            apex: v,
            quality: worst,
        });
    };
    let (at, (t, q)) = inside_positions(ctx, m, &faces)
        .into_iter()
        .filter_map(|at| Some((at, cone(ctx, &faces, m, Some((m, at)))?)))
        .max_by(|a, b| a.1 .1.total_cmp(&b.1 .1))?;
    tets.extend(t);
    Some(Plan {
        tets,
        at: Some(at),
        apex: v,
        quality: worst.min(q),
    })
}

/// Places to try for `m` inside a cell bounded by `faces` (floating point: each is then
/// tested exactly): steps from `m` along the mean inward normal of the cell's faces through
/// `m`'s old position (the fan pieces, in whose planes `m` lies), a fraction of the distance
/// to the nearest boundary vertex; and the centroid of the boundary vertices.
fn inside_positions(ctx: &Ctx, m: u32, faces: &[[u32; 3]]) -> Vec<[f64; 3]> {
    let pm = ctx.dt.point(m);
    let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let dot = |u: [f64; 3], w: [f64; 3]| u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    let mut dir = [0.0; 3];
    let mut h = f64::INFINITY;
    let mut centroid = [0.0; 3];
    let mut count = 0.0;
    for f in faces {
        let [a, b, c] = f.map(|x| ctx.dt.point(x));
        // The pieces contain `m` itself: the nearest vertex is another one (with `m` counted,
        // every step would be zero and `m` would "move" to where it was, a rounding off the
        // surface, into tets of no volume).
        for (&x, p) in f.iter().zip([a, b, c]) {
            if x == m {
                continue;
            }
            let d = sub(p, pm);
            h = h.min(dot(d, d).sqrt());
            centroid = [0, 1, 2].map(|i| centroid[i] + p[i]);
            count += 1.0;
        }
        // Faces through m's old place: m is in their plane (to rounding).
        let (u, w) = (sub(b, a), sub(c, a));
        let n = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let len = dot(n, n).sqrt();
        if len == 0.0 || dot(n, sub(pm, a)).abs() > 1e-9 * len * dot(u, u).sqrt() {
            continue;
        }
        // Inward: the side where orient(a, b, c, ·) > 0.
        let probe = [0, 1, 2].map(|i| a[i] + n[i]);
        let s = if orient(&a, &b, &c, &probe) > 0.0 {
            1.0
        } else {
            -1.0
        };
        dir = [0, 1, 2].map(|i| dir[i] + s * n[i] / len);
    }
    let mut out = Vec::new();
    let dl = dot(dir, dir).sqrt();
    if dl > 1e-6 && h.is_finite() {
        for s in [0.5, 0.35, 0.25, 0.15, 0.1, 0.05, 0.02] {
            out.push([0, 1, 2].map(|i| pm[i] + s * h * dir[i] / dl));
        }
    }
    if count > 0.0 {
        out.push(centroid.map(|x| x / count));
    }
    out.retain(|p| *p != pm);
    out
}
