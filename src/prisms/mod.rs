//! Prisms from the stretched layers (`--prisms`, `[mesh] prisms = true`): the seed paper's
//! closing remark made real. The directional refinement stacks its points in columns, one
//! point per site; three columns at two consecutive levels span a triangular prism, which the
//! layers fill with three tets. Those triples are merged into prisms where the result stays a
//! conforming hybrid mesh: a merged prism's side quad is met by another prism, by a pyramid
//! (two tets beyond it sharing their fourth point) or lies on the boundary. Every split of a
//! prism or pyramid must be positive, and a side quad warped more than the tolerance stays
//! two triangles.
//!
//! Entry point: [`group`]. The candidates are found in `find.rs`, the conforming choice made in
//! `conform.rs`, the shapes measured in `shape.rs`.

mod conform;
mod find;
pub mod shape;

use crate::mesh::VolumeMesh;
use find::sorted;
use std::collections::HashMap;

/// A side quad warped more than this (degrees between its two triangles, either diagonal)
/// stays two triangles: its prism stays three tets.
pub const DEFAULT_MAX_WARP_DEGREES: f64 = 20.0;

/// Why there is nothing to group.
#[derive(Debug, thiserror::Error)]
pub enum PrismError {
    #[error(
        "--prisms: the mesh has no stretched layers to group (prisms come from the directional \
         refinement: add a [[refine]] stage or --refine-faces)"
    )]
    NoLayers,
}

/// What the grouping did, for the report.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct PrismReport {
    pub tets_before: usize,
    pub tets: usize,
    pub prisms: usize,
    pub pyramids: usize,
    pub cells_before: usize,
    pub cells: usize,
    /// Cells whose points all lie in one stage's layers, before and after.
    pub layer_cells_before: usize,
    pub layer_cells: usize,
    /// 1 − layer_cells / layer_cells_before.
    pub layer_reduction: f64,
    /// The same per refinement stage (a curve stage's layers wrap a line: no triangles stack
    /// there, so its cells stay tets).
    pub stages: Vec<StageCells>,
    /// Triples of tets filling a prism.
    pub candidates: usize,
    pub refused_shape: usize,
    pub refused_not_filling: usize,
    pub refused_warp: usize,
    pub refused_unmatched: usize,
    pub boundary_quads: usize,
    /// The tolerance and the worst side-quad warp of the merged prisms and pyramids, degrees.
    pub max_warp_allowed: f64,
    pub max_warp: f64,
    /// Prism skew (largest angle of a column edge to the bottom's normal), degrees.
    pub skew_p50: f64,
    pub skew_max: f64,
    /// Prism aspect ratio (longest triangle edge over mean column height).
    pub aspect_p50: f64,
    pub aspect_max: f64,
    /// Layers holding prisms (the highest level + 1).
    pub layers: u32,
    /// Set when the hybrid mesh failed the validity check and the tets were kept: the first
    /// defect.
    pub reverted: Option<String>,
}

/// Layer cells of one refinement stage before and after the grouping.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct StageCells {
    pub stage: u16,
    pub layer_cells_before: usize,
    pub layer_cells: usize,
    pub layer_reduction: f64,
}

/// Layer cells per stage, indexed by stage (cells of every kind: a mesh may be grouped twice).
fn cells_per_stage(mesh: &VolumeMesh) -> Vec<usize> {
    let mut count = Vec::new();
    for (_, c, _) in mesh.cells() {
        if let Some(s) = find::layer_stage(mesh, c) {
            let s = s as usize;
            if count.len() <= s {
                count.resize(s + 1, 0);
            }
            count[s] += 1;
        }
    }
    count
}

/// Merge the layer tets of `mesh` into prisms and pyramids, in place.
pub fn group(mesh: &mut VolumeMesh, max_warp: f64) -> Result<PrismReport, PrismError> {
    if mesh.point_layer.iter().all(Option::is_none) {
        return Err(PrismError::NoLayers);
    }
    let per_stage_before = cells_per_stage(mesh);
    let (cands, found) = find::candidates(mesh);
    let chosen = conform::conform(mesh, &cands, max_warp);
    let mut report = PrismReport {
        tets_before: mesh.tets.len(),
        cells_before: mesh.cell_count(),
        layer_cells_before: per_stage_before.iter().sum(),
        candidates: cands.len() + found.bad_shape,
        refused_shape: found.bad_shape,
        refused_not_filling: found.not_filling,
        refused_warp: chosen.refused_warp,
        refused_unmatched: chosen.refused_unmatched,
        max_warp_allowed: max_warp,
        ..Default::default()
    };
    let mut gone = vec![false; mesh.tets.len()];
    let mut quads: Vec<[u32; 4]> = Vec::new();
    let mut skews = Vec::new();
    let mut aspects = Vec::new();
    for (c, cand) in cands.iter().enumerate() {
        if !chosen.accepted[c] {
            continue;
        }
        for &t in &cand.tets {
            gone[t as usize] = true;
        }
        mesh.prisms.push(cand.nodes);
        mesh.prism_region.push(cand.region);
        let p = cand.nodes.map(|v| mesh.points[v as usize]);
        skews.push(shape::prism_skew_degrees(&p));
        aspects.push(shape::prism_aspect(&p));
        report.layers = report.layers.max(cand.level + 1);
        let n = cand.nodes;
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            quads.push([n[i], n[j], n[j + 3], n[i + 3]]);
        }
    }
    for p in &chosen.pyramids {
        for &t in &p.tets {
            gone[t as usize] = true;
        }
        mesh.pyramids.push(p.nodes);
        mesh.pyramid_region.push(p.region);
        quads.push([p.nodes[0], p.nodes[1], p.nodes[2], p.nodes[3]]);
    }
    report.max_warp = quads
        .iter()
        .map(|q| shape::warp_degrees(q.map(|v| mesh.points[v as usize])))
        .fold(0.0, f64::max);
    keep_tets(mesh, &gone);
    report.boundary_quads = boundary_quads(mesh, &quads);
    report.tets = mesh.tets.len();
    report.prisms = mesh.prisms.len();
    report.pyramids = mesh.pyramids.len();
    report.cells = mesh.cell_count();
    let per_stage = cells_per_stage(mesh);
    report.layer_cells = per_stage.iter().sum();
    report.layer_reduction =
        1.0 - report.layer_cells as f64 / report.layer_cells_before.max(1) as f64;
    report.stages = (per_stage_before.iter().enumerate())
        .filter(|&(_, &before)| before > 0)
        .map(|(s, &before)| {
            let after = per_stage.get(s).copied().unwrap_or(0);
            StageCells {
                stage: s as u16,
                layer_cells_before: before,
                layer_cells: after,
                layer_reduction: 1.0 - after as f64 / before as f64,
            }
        })
        .collect();
    (report.skew_p50, report.skew_max) = median_and_max(&mut skews);
    (report.aspect_p50, report.aspect_max) = median_and_max(&mut aspects);
    Ok(report)
}

fn keep_tets(mesh: &mut VolumeMesh, gone: &[bool]) {
    drop_marked(&mut mesh.tets, gone);
    drop_marked(&mut mesh.tet_region, gone);
}

/// Remove the elements of `v` whose place is marked in `marked`, keeping the order.
fn drop_marked<T>(v: &mut Vec<T>, marked: &[bool]) {
    let mut k = 0;
    v.retain(|_| {
        k += 1;
        !marked[k - 1]
    });
}

/// Boundary triangle pairs that are the halves of a merged cell's quad become one boundary
/// quad, facing the way its triangles faced. Returns how many.
fn boundary_quads(mesh: &mut VolumeMesh, quads: &[[u32; 4]]) -> usize {
    let index: HashMap<[u32; 3], usize> = (mesh.boundary.iter().enumerate())
        .map(|(k, &t)| (sorted(t), k))
        .collect();
    let mut drop = vec![false; mesh.boundary.len()];
    let mut made = 0;
    for q in quads {
        // The two triangles of either diagonal.
        let halves = [
            [[q[0], q[1], q[2]], [q[0], q[2], q[3]]],
            [[q[0], q[1], q[3]], [q[1], q[2], q[3]]],
        ];
        for [x, y] in halves {
            let (Some(&a), Some(&b)) = (index.get(&sorted(x)), index.get(&sorted(y))) else {
                continue;
            };
            if drop[a] || drop[b] {
                continue; // the quad of two cells (an embedded face): listed once
            }
            drop[a] = true;
            drop[b] = true;
            let listed = mesh.boundary[a];
            let quad = if runs_along(listed, *q) {
                *q
            } else {
                [q[0], q[3], q[2], q[1]]
            };
            mesh.boundary_quads.push(quad);
            mesh.quad_marker.push(mesh.boundary_marker[a]);
            made += 1;
        }
    }
    drop_marked(&mut mesh.boundary, &drop);
    drop_marked(&mut mesh.boundary_marker, &drop);
    made
}

/// Whether triangle `t` turns the way quad cycle `q` does: some edge of `t` that is a side of
/// `q` is run in the same direction.
fn runs_along(t: [u32; 3], q: [u32; 4]) -> bool {
    (0..3).any(|i| {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        (0..4).any(|j| q[j] == a && q[(j + 1) % 4] == b)
    })
}

fn median_and_max(x: &mut [f64]) -> (f64, f64) {
    if x.is_empty() {
        return (0.0, 0.0);
    }
    x.sort_unstable_by(f64::total_cmp);
    (x[x.len() / 2], x[x.len() - 1])
}
