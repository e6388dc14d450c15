//! Ordering a set of edges into one open chain (a trailing edge made of several CAD edges).

use crate::model::{EdgeId, Model, VertexId};
use std::collections::HashMap;

/// The edges in chain order, each with `reversed` set when the chain runs from its end to
/// its start, and the chain's first and last vertex.
pub(super) struct Chain {
    pub uses: Vec<(EdgeId, bool)>,
    pub first: VertexId,
    pub last: VertexId,
}

pub(super) fn order_chain(model: &Model, edges: &[EdgeId]) -> Result<Chain, String> {
    if edges.is_empty() {
        return Err("no edges given".into());
    }
    let mut degree: HashMap<VertexId, usize> = HashMap::new();
    for (k, &e) in edges.iter().enumerate() {
        if edges[..k].contains(&e) {
            return Err(format!("{} is listed twice", model.edge_ref(e)));
        }
        let edge = &model.edges[e];
        if edge.is_degenerate() || edge.is_closed() {
            return Err(format!(
                "{} is degenerate or closed: a chain needs open edges",
                model.edge_ref(e)
            ));
        }
        *degree.entry(edge.start).or_default() += 1;
        *degree.entry(edge.end).or_default() += 1;
    }
    if let Some((&v, _)) = degree.iter().find(|(_, &d)| d > 2) {
        return Err(format!("the edges branch at {}", model.vertex_ref(v)));
    }
    let mut ends: Vec<VertexId> = degree
        .iter()
        .filter(|(_, &d)| d == 1)
        .map(|(&v, _)| v)
        .collect();
    ends.sort_unstable();
    let Some(&first) = ends.first() else {
        return Err("the edges form a closed loop: a wake needs an open chain".into());
    };
    let mut uses = Vec::with_capacity(edges.len());
    let mut at = first;
    while let Some(&e) = edges.iter().find(|&&e| {
        let edge = &model.edges[e];
        !uses.iter().any(|&(u, _)| u == e) && (edge.start == at || edge.end == at)
    }) {
        let reversed = model.edges[e].start != at;
        at = if reversed {
            model.edges[e].start
        } else {
            model.edges[e].end
        };
        uses.push((e, reversed));
    }
    if uses.len() != edges.len() {
        return Err("the edges do not form one connected chain".into());
    }
    Ok(Chain {
        uses,
        first,
        last: at,
    })
}
