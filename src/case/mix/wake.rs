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
    for side in [side_a, side_b] {
        if let Some(f) = boundary_face_holding(model, region, side, tol) {
            log::warn!(
                "wake '{}': {} lies on the surface of {}, which does not have it as an edge: the volume mesh cannot conform there (imprint the edge on the CAD face first)",
                spec.name,
                model.edge_ref(side),
                model.face_ref(f)
            );
        }
    }
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
