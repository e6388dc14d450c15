//! Intra-face parallelism: a face whose mesh will be large is cut in its parameter plane into
//! parts that the advancing front meshes concurrently, then merged on the shared cut nodes.
//! Faces are meshed in parallel one per task, so a model with one dominant face (a revolved
//! sphere is a single face) otherwise keeps one thread busy while the others wait.
//!
//! A cut is a straight line in (u,v) between two vertices of a region's outer loop, with new
//! nodes at the sizing field's spacing δ along its 3-D image. It is taken only when exact
//! `orient2d` tests say it leaves both ends into the face and crosses no loop, and 3-D tests
//! say it meets the boundary at decent angles and passes no loop closely; otherwise the face
//! is meshed whole, as before. The decision depends on the face alone, never on the thread
//! count, so the mesh is the same on any number of threads.

use super::boundary::{Boundary, FaceVertex};
use super::geometry2d::segments_cross;
use crate::geometry::{orient2d, Surface};
use crate::sizing::graded::RATE;
use crate::sizing::sources::distance_to_segment;
use crate::sizing::SizingField;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// A region is cut in two when it is expected to hold at least this many triangles.
const SPLIT_FROM: f64 = 1200.0;
/// Halvings at most (so at most four parts).
const MAX_DEPTH: usize = 2;
/// Density samples per side of a region's (u,v) box.
const GRID: usize = 16;
/// Samples per side of the first, cheap look: most faces are far too small to cut.
const COARSE_GRID: usize = 6;
/// Regions the cheap look expects below this share of [`SPLIT_FROM`] are not looked at again.
const COARSE_MARGIN: f64 = 0.5;
/// Candidate cut ends taken from a loop (evenly spread).
const MAX_ENDS: usize = 96;
/// Candidate cuts checked exactly, shortest first.
const MAX_TRIED: usize = 24;
/// Smallest 3-D angle between the cut and the boundary at either end (50°).
const MIN_ANGLE: f64 = 50.0 * std::f64::consts::PI / 180.0;
/// Cut and boundary keep this fraction of the local spacing apart.
const CLEARANCE: f64 = 0.5;
/// Largest share of a region's expected triangles one side of a cut may take.
const MAX_SHARE: f64 = 0.65;
/// Shortest cut considered, as a fraction of the square root of the region's area.
const MIN_CUT: f64 = 0.2;
/// Candidate cuts whose balance is computed at once (in parallel).
const BALANCE_CHUNK: usize = 128;
/// Equilateral triangle area per δ².
const TRIANGLE_AREA: f64 = 0.433_012_701_892_219_3;

/// Part of a face: its outer loop (counter-clockwise in (u,v)), then its holes, as ids into
/// the face's vertex pool.
#[derive(Clone, Debug)]
struct Region {
    loops: Vec<Vec<usize>>,
}

/// One part to mesh: its boundary on local vertex ids, and the pool id of each.
pub struct Part {
    pub pool_ids: Vec<usize>,
    pub boundary: Boundary,
    /// Triangles it is expected to hold (to schedule the largest work first).
    pub expected: f64,
}

/// A face cut into parts: the face's boundary vertices, then the cut nodes (the pool), and
/// the parts.
pub struct Plan {
    pub vertices: Vec<FaceVertex>,
    /// Pool ids from here on are cut nodes.
    pub first_cut: usize,
    pub parts: Vec<Part>,
}

/// Cut the face into parts if it is large enough and a safe cut exists; `None` to mesh it
/// whole.
pub fn plan(surface: &dyn Surface, sizing: &SizingField, boundary: &Boundary) -> Option<Plan> {
    // Cheap refusal first: a face with few boundary nodes is small (a sphere's 2000 triangles
    // come with ~100 boundary vertices counting both seam sides and the pole pieces).
    if boundary.vertices.len() < 40 {
        return None;
    }
    let region = region_of(boundary)?;
    let mut pool = boundary.vertices.clone();
    let first_cut = pool.len();
    let mut done = Vec::new();
    // Regions still to look at, with their depth and, for halves, the expected triangles
    // their parent's samples give them (no need to sample a half too small to cut).
    let mut todo = vec![(region, 0, None)];
    while let Some((r, depth, expected)) = todo.pop() {
        let worth_a_look = depth < MAX_DEPTH
            && match expected {
                Some(n) => n >= SPLIT_FROM,
                None => may_be_large(surface, sizing, &pool, &r),
            };
        let halves = if worth_a_look {
            let density = Density::sample(surface, sizing, &pool, &r, GRID, MAX_REFINE);
            (density.total >= SPLIT_FROM)
                .then(|| cut(surface, sizing, &mut pool, &r, &density))
                .flatten()
                .map(|(a, b, share)| (a, b, share * density.total, density.total))
        } else {
            None
        };
        match halves {
            Some((a, b, in_a, total)) => {
                todo.push((b, depth + 1, Some(total - in_a)));
                todo.push((a, depth + 1, Some(in_a)));
            }
            None => done.push((r, expected.unwrap_or(0.0))),
        }
    }
    if done.len() < 2 {
        return None;
    }
    let parts = done
        .iter()
        .map(|(r, expected)| part_of(&pool, r, *expected))
        .collect();
    Some(Plan {
        vertices: pool,
        first_cut,
        parts,
    })
}

/// Triangles a face is expected to hold, to schedule the largest work first: the coarse
/// density look where the boundary is simple, else from its boundary vertices as if it were a
/// square (n²/16 cells of δ², 1/0.433 triangles each).
pub fn expected_triangles(surface: &dyn Surface, sizing: &SizingField, boundary: &Boundary) -> f64 {
    let n = boundary.vertices.len();
    let from_boundary = (n * n) as f64 / (16.0 * TRIANGLE_AREA);
    if n < 40 {
        return from_boundary;
    }
    match region_of(boundary) {
        Some(r) => Density::sample(surface, sizing, &boundary.vertices, &r, COARSE_GRID, 0).total,
        None => from_boundary,
    }
}

/// The face's loops as vertex cycles, outer first, if the boundary is simple enough to cut:
/// every vertex on exactly one segment in and one out (no merged copies, no slits), the first
/// loop counter-clockwise and every other one a clockwise hole inside it.
fn region_of(b: &Boundary) -> Option<Region> {
    let n = b.vertices.len();
    if b.segments.len() != n {
        return None;
    }
    let mut next = vec![usize::MAX; n];
    let mut has_prev = vec![false; n];
    for &[p, q] in &b.segments {
        if next[p] != usize::MAX || has_prev[q] {
            return None;
        }
        next[p] = q;
        has_prev[q] = true;
    }
    let mut seen = vec![false; n];
    let mut loops = Vec::new();
    for start in 0..n {
        if seen[start] {
            continue;
        }
        let mut lp = Vec::new();
        let mut v = start;
        while !seen[v] {
            seen[v] = true;
            lp.push(v);
            v = next[v];
        }
        if v != start || lp.len() < 3 {
            return None;
        }
        loops.push(lp);
    }
    let uv = |l: &Vec<usize>| l.iter().map(|&v| b.vertices[v].uv).collect::<Vec<_>>();
    let area = |l: &Vec<usize>| signed_area(&uv(l));
    let (outer, holes) = loops.split_first()?;
    if area(outer) <= 0.0 {
        return None;
    }
    for h in holes {
        if area(h) >= 0.0 || !inside_loop(&b.vertices, outer, b.vertices[h[0]].uv) {
            return None;
        }
    }
    Some(Region { loops })
}

/// Could region `r` hold [`SPLIT_FROM`] triangles? A coarse density grid with a wide margin.
fn may_be_large(
    surface: &dyn Surface,
    sizing: &SizingField,
    pool: &[FaceVertex],
    r: &Region,
) -> bool {
    let coarse = Density::sample(surface, sizing, pool, r, COARSE_GRID, 0);
    coarse.total >= COARSE_MARGIN * SPLIT_FROM
}

/// Twice the signed area of a polygon (shoelace; positive counter-clockwise).
fn signed_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    (0..n).map(|k| poly[k].perp_dot(poly[(k + 1) % n])).sum()
}

/// Is `p` inside the closed polygon `lp` (winding number, exact orientation tests)?
fn inside_loop(pool: &[FaceVertex], lp: &[usize], p: DVec2) -> bool {
    let mut winding = 0i32;
    for k in 0..lp.len() {
        let (a, b) = (pool[lp[k]].uv, pool[lp[(k + 1) % lp.len()]].uv);
        if a.y <= p.y {
            if b.y > p.y && orient2d(a, b, p) > 0.0 {
                winding += 1;
            }
        } else if b.y <= p.y && orient2d(a, b, p) < 0.0 {
            winding -= 1;
        }
    }
    winding != 0
}

fn inside_region(pool: &[FaceVertex], r: &Region, p: DVec2) -> bool {
    inside_loop(pool, &r.loops[0], p) && !r.loops[1..].iter().any(|h| inside_loop(pool, h, p))
}

/// A density cell's centre, expected triangles (0 outside) and first fundamental form there.
type Sample = (DVec2, f64, [f64; 3]);

/// Expected triangles over a grid of (u,v) cells of a region: |Su × Sv| / (equilateral area
/// at δ) per unit of (u,v) area, over the parts of cells inside (see [`CellCtx::triangles`]
/// for how δ varies across a cell). δ is also capped by what the loops impose: a loop segment
/// of length h grows at the sizing's own rate beyond it (small holes make many more triangles
/// around them than the field alone says). Also keeps the first fundamental form at every
/// cell's centre, to estimate the 3-D length of candidate cuts.
struct Density {
    grid: usize,
    lo: DVec2,
    step: DVec2,
    /// Position, expected triangles (0 outside), first fundamental form.
    samples: Vec<Sample>,
    total: f64,
    /// 3-D area of the inside samples' cells.
    area: f64,
}

impl Density {
    fn sample(
        surface: &dyn Surface,
        sizing: &SizingField,
        pool: &[FaceVertex],
        r: &Region,
        grid: usize,
        refine: usize,
    ) -> Self {
        let uvs = r.loops[0].iter().map(|&v| pool[v].uv);
        let lo = uvs.clone().fold(DVec2::INFINITY, DVec2::min);
        let hi = uvs.fold(DVec2::NEG_INFINITY, DVec2::max);
        let step = (hi - lo) / grid as f64;
        let imposed = loop_spacings(pool, r);
        let spacing_at = |p: DVec3| {
            imposed
                .iter()
                .map(|&(q, h)| h + RATE * q.distance(p))
                .fold(sizing.spacing(p), f64::min)
        };
        let ctx = CellCtx {
            refine,
            surface,
            spacing_at: &spacing_at,
            inside: &|uv| inside_region(pool, r, uv),
        };
        // Across the threads: a face that is cut waits for this before any part starts.
        let corner: Vec<f64> = (0..(grid + 1) * (grid + 1))
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k % (grid + 1), k / (grid + 1));
                spacing_at(surface.point(lo + step * DVec2::new(i as f64, j as f64)))
            })
            .collect();
        let cells: Vec<(Sample, f64)> = (0..grid * grid)
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k % grid, k / grid);
                let a = lo + step * DVec2::new(i as f64, j as f64);
                let uv = a + 0.5 * step;
                let d = surface.derivs(uv);
                let (e, f, g) = d.first_form();
                let at = |di: usize, dj: usize| corner[(j + dj) * (grid + 1) + i + di];
                let corners = [at(0, 0), at(1, 0), at(0, 1), at(1, 1)];
                let (weight, inside_area) = ctx.triangles(a, a + step, corners, Some(d), 0);
                ((uv, weight, [e, f, g]), inside_area)
            })
            .collect();
        let area = cells.iter().map(|c| c.1).sum();
        let samples: Vec<Sample> = cells.into_iter().map(|c| c.0).collect();
        let total = samples.iter().map(|s| s.1).sum();
        Density {
            grid,
            lo,
            step,
            samples,
            total,
            area,
        }
    }

    /// First fundamental form at the sample nearest `uv`.
    fn form_near(&self, uv: DVec2) -> [f64; 3] {
        let at = ((uv - self.lo) / self.step).floor();
        let i = (at.x.max(0.0) as usize).min(self.grid - 1);
        let j = (at.y.max(0.0) as usize).min(self.grid - 1);
        self.samples[j * self.grid + i].2
    }

    /// Rough 3-D length of the (u,v) segment a–b: the metric at four points along it.
    fn length(&self, a: DVec2, b: DVec2) -> f64 {
        let d = (b - a) / 4.0;
        (0..4)
            .map(|k| {
                let [e, f, g] = self.form_near(a + d * (k as f64 + 0.5));
                (e * d.x * d.x + 2.0 * f * d.x * d.y + g * d.y * d.y)
                    .max(0.0)
                    .sqrt()
            })
            .sum()
    }

    /// Share of the expected triangles left of the line a→b (a score only: exact for convex
    /// regions, checked on the real parts afterwards).
    fn share_left(&self, a: DVec2, b: DVec2) -> f64 {
        let ab = b - a;
        let left: f64 = self
            .samples
            .iter()
            .filter(|s| s.1 > 0.0 && ab.perp_dot(s.0 - a) > 0.0)
            .map(|s| s.1)
            .sum();
        left / self.total
    }

    /// Share of the expected triangles inside region `r`.
    fn share_in(&self, pool: &[FaceVertex], r: &Region) -> f64 {
        let inside: f64 = self
            .samples
            .iter()
            .filter(|s| s.1 > 0.0 && inside_region(pool, r, s.0))
            .map(|s| s.1)
            .sum();
        inside / self.total
    }
}

/// Spacing at least this ratio apart across a density cell has it cut in four.
const GRADED: f64 = 2.0;
/// Quarterings of a density cell at most.
const MAX_REFINE: usize = 4;

/// What a density cell needs to count its triangles.
struct CellCtx<'a> {
    /// Quarterings allowed.
    refine: usize,
    surface: &'a dyn Surface,
    /// δ at a 3-D point, loop spacings included.
    spacing_at: &'a (dyn Fn(DVec3) -> f64 + Sync),
    inside: &'a (dyn Fn(DVec2) -> bool + Sync),
}

impl CellCtx<'_> {
    /// Expected triangles and inside 3-D area of the (u,v) box `a`–`b`, whose corners have
    /// spacings `c` (a; b.x, a.y; a.x, b.y; b). 1/δ² over a cell is the geometric mean of its
    /// corners' values, exact where δ grows linearly across it; a cell whose corners differ by
    /// [`GRADED`] or more is quartered (a graded band beside a small fine feature is much
    /// narrower than a cell: the centre's value alone counted half of hemisphere_cylinder's
    /// plane face, 929 of 1862 triangles). `centre`: the derivatives there, if known.
    fn triangles(
        &self,
        a: DVec2,
        b: DVec2,
        c: [f64; 4],
        centre: Option<crate::geometry::SurfaceDerivs>,
        depth: usize,
    ) -> (f64, f64) {
        let mid = 0.5 * (a + b);
        let (lo, hi) = c.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        if depth < self.refine && lo > 0.0 && hi >= GRADED * lo {
            let at = |u: f64, v: f64| (self.spacing_at)(self.surface.point(DVec2::new(u, v)));
            let (bottom, top) = (at(mid.x, a.y), at(mid.x, b.y));
            let (left, right) = (at(a.x, mid.y), at(b.x, mid.y));
            let centre = at(mid.x, mid.y);
            let quarters = [
                (a, mid, [c[0], bottom, left, centre]),
                (
                    DVec2::new(mid.x, a.y),
                    DVec2::new(b.x, mid.y),
                    [bottom, c[1], centre, right],
                ),
                (
                    DVec2::new(a.x, mid.y),
                    DVec2::new(mid.x, b.y),
                    [left, centre, c[2], top],
                ),
                (mid, b, [centre, right, top, c[3]]),
            ];
            return quarters.iter().fold((0.0, 0.0), |(n, s), &(qa, qb, qc)| {
                let (dn, ds) = self.triangles(qa, qb, qc, None, depth + 1);
                (n + dn, s + ds)
            });
        }
        if !(self.inside)(mid) {
            return (0.0, 0.0);
        }
        let d = centre.unwrap_or_else(|| self.surface.derivs(mid));
        let area = d.normal_raw().length() * (b.x - a.x) * (b.y - a.y);
        let corners = (c[0] * c[1] * c[2] * c[3]).sqrt();
        let n = area / (TRIANGLE_AREA * corners);
        (if n.is_finite() { n } else { 0.0 }, area)
    }
}

/// Each loop vertex with the spacing its segments impose (their mean 3-D length; a pole's
/// zero-length pieces impose nothing).
fn loop_spacings(pool: &[FaceVertex], r: &Region) -> Vec<(DVec3, f64)> {
    let mut out = Vec::new();
    for lp in &r.loops {
        let m = lp.len();
        for k in 0..m {
            let p = pool[lp[k]].xyz;
            let before = p.distance(pool[lp[(k + m - 1) % m]].xyz);
            let after = p.distance(pool[lp[(k + 1) % m]].xyz);
            let h = if before > 0.0 && after > 0.0 {
                0.5 * (before + after)
            } else {
                before.max(after)
            };
            if h > 0.0 {
                out.push((p, h));
            }
        }
    }
    out
}

/// Cut region `r` in two: the shortest balanced candidate that passes every check. The cut
/// nodes are appended to `pool`; also returns the first half's share of the samples.
fn cut(
    surface: &dyn Surface,
    sizing: &SizingField,
    pool: &mut Vec<FaceVertex>,
    r: &Region,
    density: &Density,
) -> Option<(Region, Region, f64)> {
    let outer = &r.loops[0];
    let m = outer.len();
    let stride = m.div_ceil(MAX_ENDS);
    let ends: Vec<usize> = (0..m).step_by(stride).collect();
    // Every pair of ends by estimated length; the balance (a sum over the samples) only for
    // the shortest, until enough balanced ones are found.
    let uv = |k: usize| pool[outer[k]].uv;
    // A chord much shorter than the region is wide cuts off a corner or a notch, however
    // its line divides the samples (the balance estimate is the line's, not the chord's).
    let shortest = MIN_CUT * density.area.sqrt();
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (k, &i) in ends.iter().enumerate() {
        for &j in &ends[k + 1..] {
            if j - i >= 2 && m - (j - i) >= 2 {
                let length = density.length(uv(i), uv(j));
                // Cheap necessary conditions first, so that candidates bound to fail them
                // (short chords along a boundary, seen by the balance as splitting a fine
                // zone) do not take up the exact checks' budget.
                if length >= shortest
                    && enters(pool, outer, i, uv(j))
                    && enters(pool, outer, j, uv(i))
                    && roughly_meets_well(pool, outer, i, uv(j), density)
                    && roughly_meets_well(pool, outer, j, uv(i), density)
                {
                    pairs.push((length, i, j));
                }
            }
        }
    }
    pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    // Shortest first, a chunk at a time across the threads (each balance sums over every
    // sample, and the face waits for its plan before any part starts).
    let mut candidates: Vec<(f64, usize, usize)> = Vec::new();
    for chunk in pairs.chunks(BALANCE_CHUNK) {
        let balanced: Vec<(f64, usize, usize)> = chunk
            .par_iter()
            .filter_map(|&(length, i, j)| {
                let off = (density.share_left(uv(i), uv(j)) - 0.5).abs();
                // Among cuts of about the same length, the better balanced.
                (off <= MAX_SHARE - 0.5).then_some((length * (1.0 + 2.0 * off), i, j))
            })
            .collect();
        candidates.extend(balanced);
        if candidates.len() >= MAX_TRIED {
            break;
        }
    }
    candidates.truncate(MAX_TRIED);
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    for &(_, i, j) in candidates.iter().take(MAX_TRIED) {
        let Some(nodes) = cut_nodes(surface, sizing, pool, r, i, j) else {
            continue;
        };
        let first = pool.len();
        let ids: Vec<usize> = (first..first + nodes.len()).collect();
        pool.extend(nodes);
        let (a, b) = halves(pool, r, i, j, &ids);
        let share = density.share_in(pool, &a);
        if (share - 0.5).abs() <= MAX_SHARE - 0.5 {
            return Some((a, b, share));
        }
        pool.truncate(first);
    }
    None
}

/// The two regions either side of the cut from outer-loop position `i` to `j` through the
/// cut nodes `ids` (in order from i to j); each hole goes with the side that holds it.
fn halves(pool: &[FaceVertex], r: &Region, i: usize, j: usize, ids: &[usize]) -> (Region, Region) {
    let outer = &r.loops[0];
    let m = outer.len();
    // Along the loop from i to j, then back along the cut.
    let mut a: Vec<usize> = outer[i..=j].to_vec();
    a.extend(ids.iter().rev());
    // Along the loop from j round to i, then along the cut.
    let mut b: Vec<usize> = (j..m + i + 1).map(|k| outer[k % m]).collect();
    b.extend(ids);
    let mut ra = Region { loops: vec![a] };
    let mut rb = Region { loops: vec![b] };
    for h in &r.loops[1..] {
        if inside_loop(pool, &ra.loops[0], pool[h[0]].uv) {
            ra.loops.push(h.clone());
        } else {
            rb.loops.push(h.clone());
        }
    }
    (ra, rb)
}

/// The nodes inside the cut from outer-loop position `i` to `j`, or `None` when the cut is not
/// safe: it must leave both ends into the face and cross no loop (exact), meet the boundary
/// at no less than [`MIN_ANGLE`] and keep [`CLEARANCE`] from every loop (3-D).
fn cut_nodes(
    surface: &dyn Surface,
    sizing: &SizingField,
    pool: &[FaceVertex],
    r: &Region,
    i: usize,
    j: usize,
) -> Option<Vec<FaceVertex>> {
    let outer = &r.loops[0];
    let (va, vb) = (outer[i], outer[j]);
    let (a, b) = (pool[va].uv, pool[vb].uv);
    if !enters(pool, outer, i, b) || !enters(pool, outer, j, a) {
        return None;
    }
    if crosses_a_loop(pool, r, (va, a), (vb, b)) {
        return None;
    }
    let nodes = place_nodes(surface, sizing, pool[va], pool[vb])?;
    let ends = (pool[va].node, pool[vb].node);
    let mut chain = vec![pool[va].xyz];
    chain.extend(nodes.iter().map(|n| n.xyz));
    chain.push(pool[vb].xyz);
    let first = chain[1];
    let last = chain[chain.len() - 2];
    if !meets_well(pool, outer, i, first) || !meets_well(pool, outer, j, last) {
        return None;
    }
    if !clear(sizing, pool, r, &chain, [va, vb], ends) {
        return None;
    }
    Some(nodes)
}

/// Does the cut from the vertex at outer-loop position `i` towards `to` leave into the face,
/// i.e. strictly inside the corner between the loop's segments in and out of it?
fn enters(pool: &[FaceVertex], lp: &[usize], i: usize, to: DVec2) -> bool {
    let m = lp.len();
    let (p, o, n) = (
        pool[lp[(i + m - 1) % m]].uv,
        pool[lp[i]].uv,
        pool[lp[(i + 1) % m]].uv,
    );
    let left_of_out = orient2d(o, n, to) > 0.0;
    let left_of_in = orient2d(p, o, to) > 0.0;
    if orient2d(p, o, n) > 0.0 {
        left_of_out && left_of_in
    } else {
        left_of_out || left_of_in
    }
}

/// Does the (u,v) segment a–b cross or touch any loop segment? A segment at a or b blocks it
/// only by running along it.
fn crosses_a_loop(pool: &[FaceVertex], r: &Region, a: (usize, DVec2), b: (usize, DVec2)) -> bool {
    let along = |o: DVec2, x: DVec2, y: DVec2| orient2d(o, x, y) == 0.0 && (x - o).dot(y - o) > 0.0;
    r.loops.iter().any(|lp| {
        (0..lp.len()).any(|k| {
            let (p, q) = (lp[k], lp[(k + 1) % lp.len()]);
            let (pp, pq) = (pool[p].uv, pool[q].uv);
            let shared = |v: usize| v == a.0 || v == b.0;
            match (shared(p), shared(q)) {
                (true, true) => true,
                (true, false) => along(pp, if p == a.0 { b.1 } else { a.1 }, pq),
                (false, true) => along(pq, if q == a.0 { b.1 } else { a.1 }, pp),
                (false, false) => segments_cross(a.1, b.1, pp, pq),
            }
        })
    })
}

/// Nodes along the (u,v) segment from `a` to `b` (ends excluded) at equal steps of ∫ds/δ of
/// its 3-D image; `None` if the cut would have fewer than two segments.
fn place_nodes(
    surface: &dyn Surface,
    sizing: &SizingField,
    a: FaceVertex,
    b: FaceVertex,
) -> Option<Vec<FaceVertex>> {
    // Fine enough a polyline to follow the image: four samples per δ, at least 32.
    let chord = a.xyz.distance(b.xyz).max(1e-300);
    let rough = {
        let mid = surface.point(a.uv.lerp(b.uv, 0.5));
        a.xyz.distance(mid) + mid.distance(b.xyz)
    };
    let delta = sizing.spacing(a.xyz).min(sizing.spacing(b.xyz));
    let steps = ((4.0 * rough.max(chord) / delta).ceil() as usize).clamp(32, 1024);
    let mut pts = Vec::with_capacity(steps + 1);
    let mut spacing = Vec::with_capacity(steps + 1);
    for k in 0..=steps {
        let p = match k {
            0 => a.xyz,
            _ if k == steps => b.xyz,
            _ => surface.point(a.uv.lerp(b.uv, k as f64 / steps as f64)),
        };
        if !p.is_finite() {
            return None;
        }
        spacing.push(sizing.spacing(p));
        pts.push(p);
    }
    // Cumulative ∫ds/δ by the trapezoid rule on 1/δ.
    let mut cumulative = vec![0.0];
    for k in 0..steps {
        let ds = pts[k].distance(pts[k + 1]);
        let inc = 0.5 * ds * (1.0 / spacing[k] + 1.0 / spacing[k + 1]);
        cumulative.push(cumulative[k] + inc);
    }
    let total = cumulative[steps];
    let segments = total.round() as usize;
    if !total.is_finite() || segments < 2 {
        return None;
    }
    let mut nodes = Vec::with_capacity(segments - 1);
    let mut k = 0;
    for s in 1..segments {
        let target = total * s as f64 / segments as f64;
        while cumulative[k + 1] < target {
            k += 1;
        }
        let span = cumulative[k + 1] - cumulative[k];
        let frac = if span > 0.0 {
            (target - cumulative[k]) / span
        } else {
            0.0
        };
        let t = (k as f64 + frac) / steps as f64;
        let uv = a.uv.lerp(b.uv, t);
        nodes.push(FaceVertex {
            uv,
            xyz: surface.point(uv),
            node: None,
        });
    }
    Some(nodes)
}

/// Angle allowance of [`roughly_meets_well`] below [`MIN_ANGLE`] (10°).
const ROUGH_SLACK: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// [`meets_well`] before any cut node exists: the angles between the straight (u,v) cut
/// towards `to` and the loop's segments at outer-loop position `i`, measured in the first
/// fundamental form near the vertex, with [`ROUGH_SLACK`] to spare. True where the form is
/// degenerate (a pole): the exact test decides there.
fn roughly_meets_well(
    pool: &[FaceVertex],
    lp: &[usize],
    i: usize,
    to: DVec2,
    density: &Density,
) -> bool {
    let m = lp.len();
    let o = pool[lp[i]];
    let distinct = |step: usize| {
        (1..m)
            .map(|k| pool[lp[(i + k * step) % m]])
            .find(|p| p.xyz != o.xyz)
            .map(|p| p.uv - o.uv)
    };
    let (Some(before), Some(after)) = (distinct(m - 1), distinct(1)) else {
        return true;
    };
    let [e, f, g] = density.form_near(o.uv);
    let dot = |x: DVec2, y: DVec2| e * x.x * y.x + f * (x.x * y.y + x.y * y.x) + g * x.y * y.y;
    let angle = |x: DVec2, y: DVec2| {
        let c = dot(x, y) / (dot(x, x) * dot(y, y)).sqrt();
        c.is_finite().then(|| c.clamp(-1.0, 1.0).acos())
    };
    let dir = to - o.uv;
    match (angle(dir, before), angle(dir, after)) {
        (Some(a), Some(b)) => a.min(b) >= MIN_ANGLE - ROUGH_SLACK,
        _ => true,
    }
}

/// Does the cut, whose first node away from the vertex at outer-loop position `i` is `next`,
/// make at least [`MIN_ANGLE`] with the boundary on both sides in 3-D? The boundary
/// directions are taken to the nearest vertex at another 3-D point (a pole's pieces are one).
fn meets_well(pool: &[FaceVertex], lp: &[usize], i: usize, next: DVec3) -> bool {
    let m = lp.len();
    let o = pool[lp[i]].xyz;
    let distinct = |step: usize| {
        (1..m)
            .map(|k| pool[lp[(i + k * step) % m]].xyz)
            .find(|p| *p != o)
    };
    let (Some(before), Some(after)) = (distinct(m - 1), distinct(1)) else {
        return false;
    };
    let dir = next - o;
    dir.angle_between(before - o) >= MIN_ANGLE && dir.angle_between(after - o) >= MIN_ANGLE
}

/// Does the cut polyline `chain` keep [`CLEARANCE`] × the local spacing from every loop in
/// 3-D, both ways (loop vertices from cut segments, cut nodes from loop segments)? The cut's
/// own ends and other copies of their nodes (seam, pole) are exempt, as are loop segments at
/// the ends (the angle test covers those).
fn clear(
    sizing: &SizingField,
    pool: &[FaceVertex],
    r: &Region,
    chain: &[DVec3],
    ends: [usize; 2],
    end_nodes: (Option<usize>, Option<usize>),
) -> bool {
    let exempt = |v: usize| {
        ends.contains(&v)
            || (pool[v].node.is_some()
                && (pool[v].node == end_nodes.0 || pool[v].node == end_nodes.1))
    };
    let cut_spacing: Vec<f64> = chain.iter().map(|&p| sizing.spacing(p)).collect();
    let lo = chain.iter().fold(DVec3::INFINITY, |m, p| m.min(*p));
    let hi = chain.iter().fold(DVec3::NEG_INFINITY, |m, p| m.max(*p));
    let reach = CLEARANCE * cut_spacing.iter().fold(0.0f64, |m, d| m.max(*d));
    let far = |p: DVec3| p.cmplt(lo - reach).any() || p.cmpgt(hi + reach).any();
    for lp in &r.loops {
        for k in 0..lp.len() {
            let (v, w) = (lp[k], lp[(k + 1) % lp.len()]);
            let (pv, pw) = (pool[v].xyz, pool[w].xyz);
            // Loop vertex v against the cut's segments.
            if !exempt(v) && !far(pv) {
                let local = CLEARANCE * sizing.spacing(pv).min(pv.distance(pw).max(0.0));
                let local = if local > 0.0 {
                    local
                } else {
                    CLEARANCE * sizing.spacing(pv)
                };
                if chain
                    .windows(2)
                    .any(|s| distance_to_segment(pv, s[0], s[1]) < local)
                {
                    return false;
                }
            }
            // Cut nodes against loop segment v–w.
            if exempt(v) || exempt(w) {
                continue;
            }
            for (n, &p) in chain.iter().enumerate().take(chain.len() - 1).skip(1) {
                if distance_to_segment(p, pv, pw) < CLEARANCE * cut_spacing[n] {
                    return false;
                }
            }
        }
    }
    true
}

/// A region as a front boundary on local vertex ids (pool ids kept beside them).
fn part_of(pool: &[FaceVertex], r: &Region, expected: f64) -> Part {
    let mut pool_ids = Vec::new();
    let mut segments = Vec::new();
    for lp in &r.loops {
        let first = pool_ids.len();
        pool_ids.extend(lp);
        let n = lp.len();
        segments.extend((0..n).map(|k| [first + k, first + (k + 1) % n]));
    }
    let vertices = pool_ids.iter().map(|&v| pool[v]).collect();
    Part {
        pool_ids,
        boundary: Boundary {
            vertices,
            segments,
            slits: Vec::new(),
        },
        expected,
    }
}
