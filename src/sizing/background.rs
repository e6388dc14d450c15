//! The background mesh: a coarse tetrahedral mesh with a spacing at each node, interpolated
//! linearly inside each tet. Point location goes through an R*-tree of tet bounding boxes and an
//! exact containment test.

use glam::DVec3;
use rstar::{primitives::GeomWithData, primitives::Rectangle, RTree};

type TetBox = GeomWithData<Rectangle<[f64; 3]>, usize>;

/// Why a background mesh is unusable.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum BackgroundError {
    #[error("background tet {tet} refers to node {node}, but there are only {nodes} nodes")]
    BadNode {
        tet: usize,
        node: usize,
        nodes: usize,
    },
    #[error("background node {node} has spacing {spacing}; spacings must be positive and finite")]
    BadSpacing { node: usize, spacing: f64 },
    #[error("background tet {tet} is flat (zero volume)")]
    FlatTet { tet: usize },
}

pub struct BackgroundMesh {
    nodes: Vec<DVec3>,
    spacing: Vec<f64>,
    tets: Vec<[usize; 4]>,
    tree: RTree<TetBox>,
}

impl BackgroundMesh {
    pub fn new(
        nodes: Vec<DVec3>,
        spacing: Vec<f64>,
        tets: Vec<[usize; 4]>,
    ) -> Result<Self, BackgroundError> {
        for (node, &s) in spacing.iter().enumerate() {
            if !(s.is_finite() && s > 0.0) {
                return Err(BackgroundError::BadSpacing { node, spacing: s });
            }
        }
        for (tet, t) in tets.iter().enumerate() {
            if let Some(&node) = t.iter().find(|&&n| n >= nodes.len() || n >= spacing.len()) {
                return Err(BackgroundError::BadNode {
                    tet,
                    node,
                    nodes: nodes.len().min(spacing.len()),
                });
            }
            if orient(&nodes, t) == 0.0 {
                return Err(BackgroundError::FlatTet { tet });
            }
        }
        let boxes = tets
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let lo = t.iter().fold(DVec3::INFINITY, |m, &n| m.min(nodes[n]));
                let hi = t.iter().fold(DVec3::NEG_INFINITY, |m, &n| m.max(nodes[n]));
                GeomWithData::new(Rectangle::from_corners(lo.to_array(), hi.to_array()), i)
            })
            .collect();
        Ok(BackgroundMesh {
            nodes,
            spacing,
            tets,
            tree: RTree::bulk_load(boxes),
        })
    }

    /// Interpolated spacing at `p`, or `None` outside the background mesh.
    pub fn spacing(&self, p: DVec3) -> Option<f64> {
        let q = p.to_array();
        for cand in self.tree.locate_all_at_point(&q) {
            let t = &self.tets[cand.data];
            if let Some(w) = self.barycentric_if_inside(t, p) {
                return Some((0..4).map(|i| w[i] * self.spacing[t[i]]).sum());
            }
        }
        None
    }

    /// Barycentric weights of `p` in tet `t` when `p` is inside or on it (exact test).
    fn barycentric_if_inside(&self, t: &[usize; 4], p: DVec3) -> Option<[f64; 4]> {
        let v = t.map(|n| self.nodes[n]);
        let total = orient(&self.nodes, t);
        let mut w = [0.0; 4];
        for (i, wi) in w.iter_mut().enumerate() {
            let mut sub = v;
            sub[i] = p;
            let part = orient3d(sub);
            // Inside when every sub-volume has the sign of the whole (or is zero).
            if part != 0.0 && part.signum() != total.signum() {
                return None;
            }
            *wi = part / total;
        }
        Some(w)
    }
}

fn orient(nodes: &[DVec3], t: &[usize; 4]) -> f64 {
    orient3d(t.map(|n| nodes[n]))
}

/// Exact sign, approximate magnitude, of the volume of a tet (robust's adaptive orient3d).
fn orient3d(v: [DVec3; 4]) -> f64 {
    let c = |p: DVec3| robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    };
    robust::orient3d(c(v[0]), c(v[1]), c(v[2]), c(v[3]))
}
