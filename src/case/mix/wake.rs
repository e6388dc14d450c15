//! `[[wake]]`: a native sheet swept from a chain of CAD edges (a trailing edge) along a
//! direction, added as an embedded face of the region whose boundary holds the chain. The
//! sheet shares the CAD edges; its two side edges and its far edge are native.
//!
//! The sheet is a Ferguson network through samples of the chain and the same samples moved by
//! the offset, so its far edge is exactly the Ferguson curve through the moved samples. The
//! chain is sampled more densely until the CAD edges lie on the sheet to the tolerance (exact
//! at once for a straight chain).

use super::chain::{order_chain, Chain};
use crate::geometry::{Curve, Surface};
use crate::model::{project_pcurve, Edge, EdgeId, EdgeUse, Face, Loop, Model, Vertex};
use glam::DVec3;
use std::sync::Arc;
use tetrafoil_native::{FergusonCurve, FergusonSurface};

/// The most segments per chain edge tried.
const MAX_SEGMENTS: usize = 256;

pub(super) struct WakeSpec {
    pub name: String,
    pub edges: Vec<EdgeId>,
    pub offset: DVec3,
}

pub(super) fn add_wake(model: &mut Model, spec: &WakeSpec, tol: f64) -> Result<(), String> {
    let chain = order_chain(model, &spec.edges)?;
    let region = (0..model.regions.len())
        .find(|&r| {
            model.region_faces(r).any(|fu| {
                model.faces[fu.face]
                    .loops
                    .iter()
                    .flat_map(|l| &l.uses)
                    .any(|u| u.edge == chain.uses[0].0)
            })
        })
        .ok_or_else(|| {
            format!(
                "{} bounds no region: a wake must start on a region's boundary",
                model.edge_ref(chain.uses[0].0)
            )
        })?;
    let (sheet, samples, deviation) = fit_sheet(model, &chain, spec.offset, tol)?;
    let ptol = 10.0 * tol + 4.0 * deviation;

    let (a, b) = (chain.first, chain.last);
    let far: Vec<DVec3> = samples.iter().map(|&p| p + spec.offset).collect();
    let a2 = push_vertex(model, model.vertices[a].point + spec.offset);
    let b2 = push_vertex(model, model.vertices[b].point + spec.offset);
    let line = |p: DVec3, q: DVec3| -> Result<Arc<dyn Curve>, String> {
        Ok(Arc::new(
            FergusonCurve::interpolate(&[p, q]).map_err(|e| e.to_string())?,
        ))
    };
    let side_a = push_edge(model, &spec.name, "side_start", a, a2, {
        let (p, q) = (model.vertices[a].point, model.vertices[a2].point);
        line(p, q)?
    });
    let side_b = push_edge(model, &spec.name, "side_end", b, b2, {
        let (p, q) = (model.vertices[b].point, model.vertices[b2].point);
        line(p, q)?
    });
    let far_curve: Arc<dyn Curve> =
        Arc::new(FergusonCurve::interpolate(&far).map_err(|e| e.to_string())?);
    let far_edge = push_edge(model, &spec.name, "far", a2, b2, far_curve);

    let mut order: Vec<(EdgeId, bool)> = chain.uses.clone();
    order.extend([(side_b, false), (far_edge, true), (side_a, true)]);
    let mut uses = Vec::with_capacity(order.len());
    for (edge, reversed) in order {
        let e = &model.edges[edge];
        let curve = e.curve.as_ref().expect("chain edges are not degenerate");
        let pc = project_pcurve(&sheet, curve.as_ref(), e.range, ptol).map_err(|off| {
            format!(
                "{} is {:.3e} from the wake sheet at parameter {}",
                model.edge_ref(edge),
                off.distance,
                off.t
            )
        })?;
        uses.push(EdgeUse {
            edge,
            reversed,
            pcurve: Some(Arc::new(pc)),
        });
    }
    let face = model.faces.len();
    model.faces.push(Face {
        name: Some(spec.name.clone()),
        surface: Arc::new(sheet),
        loops: vec![Loop { uses, vertex: None }],
    });
    model.regions[region].embedded_faces.push(face);
    for (side, root) in [(side_a, a), (side_b, b)] {
        if let Some(f) = boundary_face_holding(model, region, side, tol) {
            imprint_slit(model, f, side, root, ptol)?;
        }
    }
    Ok(())
}

/// Make `edge`, which starts at `root` on a loop of boundary face `face` and runs inside it
/// (a wake's side edge on a symmetry plane), a slit of the face: its loop goes out along the
/// edge and back at `root`, so the face's mesh has the edge's nodes from both sides and the
/// wake's triangles meet it there.
fn imprint_slit(
    model: &mut Model,
    face: usize,
    edge: EdgeId,
    root: usize,
    tol: f64,
) -> Result<(), String> {
    let at = model.faces[face]
        .loops
        .iter()
        .enumerate()
        .find_map(|(l, lp)| {
            (lp.uses.iter())
                .position(|u| model.use_vertices(u).1 == root)
                .map(|k| (l, k))
        });
    let Some((l, k)) = at else {
        return Err(format!(
            "{} lies on {} but starts at none of its vertices: the wake cannot be joined to \
             that face",
            model.edge_ref(edge),
            model.face_ref(face)
        ));
    };
    // The edge onto the face, both ends projected: its nodes then lie in the face (a plane's
    // nodes in the plane to rounding: they are on the Delaunay hull there, and a row of them
    // a CAD vertex's tolerance beside it, as a line from that vertex would be, leaves thin
    // hull facets that boundary recovery cannot match). The edge still starts at `root`,
    // within that vertex's tolerance; the sheet's corner at the far end moves as far.
    let far = model.edges[edge].end;
    let surface = model.faces[face].surface.clone();
    let onto = |p: DVec3| surface.closest_uv(p, None).map(|uv| surface.point(uv));
    if let (Some(p), Some(q)) = (
        onto(model.vertices[root].point),
        onto(model.vertices[far].point),
    ) {
        model.vertices[far].point = q;
        let line = FergusonCurve::interpolate(&[p, q]).map_err(|e| e.to_string())?;
        model.edges[edge].range = Curve::range(&line);
        model.edges[edge].curve = Some(Arc::new(line));
    }
    let e = &model.edges[edge];
    let curve = e.curve.as_ref().expect("a wake's side edge has a curve");
    let surface = surface.as_ref();
    let pcurve: Arc<dyn crate::geometry::Curve2d> = Arc::new(
        project_pcurve(surface, curve.as_ref(), e.range, tol).map_err(|off| {
            format!(
                "{} is {:.3e} off {} at parameter {}",
                model.edge_ref(edge),
                off.distance,
                model.face_ref(face),
                off.t
            )
        })?,
    );
    let slit = [false, true].map(|reversed| EdgeUse {
        edge,
        reversed,
        pcurve: Some(pcurve.clone()),
    });
    log::info!(
        "{}: {} imprinted as a slit from {}",
        model.face_ref(face),
        model.edge_ref(edge),
        model.vertex_ref(root)
    );
    let uses = &mut model.faces[face].loops[l].uses;
    uses.splice(k + 1..k + 1, slit);
    Ok(())
}

/// A boundary face of `region` whose surface holds all of edge `edge` (three samples within
/// 10 `tol`): a wake edge lying in a symmetry plane, which the CAD face does not know about.
fn boundary_face_holding(model: &Model, region: usize, edge: EdgeId, tol: f64) -> Option<usize> {
    let e = &model.edges[edge];
    let points: Vec<DVec3> = [0.0, 0.5, 1.0]
        .map(|s| model.edge_point(edge, e.range.0 + (e.range.1 - e.range.0) * s))
        .to_vec();
    model.region_faces(region).map(|fu| fu.face).find(|&f| {
        let surface = model.faces[f].surface.as_ref();
        points.iter().all(|&p| {
            surface
                .closest_uv(p, None)
                .is_some_and(|uv| surface.point(uv).distance(p) <= 10.0 * tol)
        })
    })
}

/// The sheet through `n` samples per chain edge, doubling `n` until the chain's midpoints lie
/// on it within `tol`: the sheet, the chain samples and the worst distance left.
fn fit_sheet(
    model: &Model,
    chain: &Chain,
    offset: DVec3,
    tol: f64,
) -> Result<(FergusonSurface, Vec<DVec3>, f64), String> {
    let mut segments = 1;
    loop {
        let samples = sample_chain(model, chain, segments, 0.0);
        let grid: Vec<Vec<DVec3>> = samples.iter().map(|&p| vec![p, p + offset]).collect();
        let sheet = FergusonSurface::interpolate(&grid).map_err(|e| e.to_string())?;
        let deviation = sample_chain(model, chain, segments, 0.5)
            .into_iter()
            .map(|p| sheet_distance(&sheet, p).unwrap_or(f64::INFINITY))
            .fold(0.0, f64::max);
        if deviation <= tol || segments >= MAX_SEGMENTS {
            return Ok((sheet, samples, deviation));
        }
        segments *= 2;
    }
}

fn sheet_distance(sheet: &FergusonSurface, p: DVec3) -> Option<f64> {
    let uv = Surface::closest_uv(sheet, p, None)?;
    Some(Surface::point(sheet, uv).distance(p))
}

/// The chain's points at its edges' ends and midpoints.
pub(super) fn chain_points(model: &Model, chain: &Chain) -> Vec<DVec3> {
    let mut points = sample_chain(model, chain, 1, 0.0);
    points.extend(sample_chain(model, chain, 1, 0.5));
    points
}

/// Points along the chain, `segments` per edge: at fractions (k + shift)/segments of each
/// edge's range in chain direction; with `shift = 0` the ends are included once each.
fn sample_chain(model: &Model, chain: &Chain, segments: usize, shift: f64) -> Vec<DVec3> {
    let mut points = Vec::new();
    for (i, &(e, reversed)) in chain.uses.iter().enumerate() {
        let edge = &model.edges[e];
        let (t0, t1) = if reversed {
            (edge.range.1, edge.range.0)
        } else {
            edge.range
        };
        let first = if shift == 0.0 && i > 0 { 1 } else { 0 };
        let last = if shift == 0.0 { segments } else { segments - 1 };
        for k in first..=last {
            let s = (k as f64 + shift) / segments as f64;
            points.push(model.edge_point(e, t0 + (t1 - t0) * s));
        }
    }
    points
}

fn push_vertex(model: &mut Model, point: DVec3) -> usize {
    model.vertices.push(Vertex { name: None, point });
    model.vertices.len() - 1
}

fn push_edge(
    model: &mut Model,
    wake: &str,
    what: &str,
    start: usize,
    end: usize,
    curve: Arc<dyn Curve>,
) -> EdgeId {
    let range = curve.range();
    model.edges.push(Edge {
        name: Some(format!("{wake}_{what}")),
        curve: Some(curve),
        range,
        start,
        end,
    });
    model.edges.len() - 1
}
