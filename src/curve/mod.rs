//! Curve meshing: every edge is discretised once by integrating 1/δ along its arc length and
//! placing nodes at equal increments of that integral (Peiró et al., as the seed paper cites).
//! Nodes are numbered globally, model vertices first, so every face that uses an edge sees the
//! very same nodes.

mod integral;

pub use integral::SpacingIntegral;

use crate::model::{EdgeId, Model};
use crate::sizing::SizingField;
use glam::DVec3;
use rayon::prelude::*;

/// The discretisation of one edge.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeMesh {
    /// Edge parameters of the nodes, from `range.0` to `range.1`.
    pub params: Vec<f64>,
    /// Global node ids, same length as `params`; the first and last are the edge's vertices.
    pub nodes: Vec<usize>,
    /// ∫ ds/δ over the edge: the ideal number of segments.
    pub integral: f64,
}

/// All edges' discretisations and the node coordinates they share.
#[derive(Clone, Debug, Default)]
pub struct CurveMesh {
    pub points: Vec<DVec3>,
    pub edges: Vec<EdgeMesh>,
}

impl CurveMesh {
    /// Segments of all edges as node pairs.
    pub fn segments(&self) -> impl Iterator<Item = (EdgeId, [usize; 2])> + '_ {
        self.edges
            .iter()
            .enumerate()
            .flat_map(|(e, m)| m.nodes.windows(2).map(move |w| (e, [w[0], w[1]])))
    }
}

#[derive(Debug, thiserror::Error)]
pub enum CurveError {
    #[error(
        "{edge}: the spacing integral along it is not finite (δ is zero or the curve is broken)"
    )]
    BadIntegral { edge: String },
}

/// Discretise every edge of `model` with the spacing `sizing` (edges in parallel).
pub fn mesh_curves(model: &Model, sizing: &SizingField) -> Result<CurveMesh, CurveError> {
    let per_edge: Vec<Result<(Vec<f64>, f64), CurveError>> = (0..model.edges.len())
        .into_par_iter()
        .map(|e| {
            let edge = &model.edges[e];
            let Some(curve) = &edge.curve else {
                return Ok((vec![edge.range.0, edge.range.1], 0.0));
            };
            let integral = SpacingIntegral::new(curve.as_ref(), edge.range, |p| sizing.spacing(p));
            let total = integral.total();
            if !total.is_finite() {
                return Err(CurveError::BadIntegral {
                    edge: model.edge_ref(e).to_string(),
                });
            }
            // A closed edge needs three segments to stay a loop; others at least one.
            let min = if edge.is_closed() { 3 } else { 1 };
            let n = (total.round() as usize).max(min);
            Ok((integral.equal_increments(n), total))
        })
        .collect();
    let mut mesh = CurveMesh {
        points: model.vertices.iter().map(|v| v.point).collect(),
        edges: Vec::with_capacity(model.edges.len()),
    };
    for (e, res) in per_edge.into_iter().enumerate() {
        let (params, integral) = res?;
        let edge = &model.edges[e];
        let mut nodes = Vec::with_capacity(params.len());
        nodes.push(edge.start);
        if !edge.is_degenerate() {
            for &t in &params[1..params.len() - 1] {
                nodes.push(mesh.points.len());
                mesh.points.push(model.edge_point(e, t));
            }
        }
        nodes.push(edge.end);
        let params = if edge.is_degenerate() {
            vec![edge.range.0, edge.range.1]
        } else {
            params
        };
        mesh.edges.push(EdgeMesh {
            params,
            nodes,
            integral,
        });
    }
    Ok(mesh)
}
