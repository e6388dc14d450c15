//! Graded point samples: each sample (p, δ, r₁) asks for δ within r₁ of p and for
//! δ + RATE·(d − r₁) at distance d beyond, so neighbouring elements differ by a bounded ratio
//! however coarse the surrounding mesh (an exponential law in units of the sample's own small
//! δ jumped from the fine to the coarse size within one element, which the advancing front
//! cannot close). The curvature and proximity limits are both made of such samples.

use glam::DVec3;
use rayon::prelude::*;
use rstar::{primitives::GeomWithData, ParentNode, RTree, RTreeNode};

/// Growth of a sample's spacing per unit distance beyond r₁ on the surfaces: about the size
/// ratio of neighbouring elements minus one. At 0.25 a fillet or a strip refined the faces
/// around it over several sizes (the shared corpus made 1.3 times the triangles it makes at
/// 0.5, for no better dihedral); 0.5 lets two faces of the 27 meshed need the Delaunay
/// fallback (`surface/fallback.rs`) where the front met a steep grading.
pub const RATE: f64 = 0.5;

/// One sample: where, the spacing it asks for, and the radius it asks for it in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GradedSample {
    pub point: DVec3,
    pub delta: f64,
    pub r1: f64,
}

/// Growth per unit distance of the volume's spacing away from a sample: the interior of a
/// region grades out of a fine feature faster than the surfaces do (a surface's advancing
/// front needs the gentler [`RATE`]; the Delaunay interior points do not). At 0.5 (with the
/// surfaces at 0.25) a fillet's fine spacing still filled a ball around it; at 1.0 the mean
/// radius ratio fell by 0.03 over the corpus (0.759 -> 0.730); 0.75 keeps it within 0.012
/// (0.747) with a median 0.75x the tets of (0.25, 0.5) on the 27 corpus files meshed.
pub const VOLUME_RATE: f64 = 0.75;

/// The spacing a sample (δ, r₁) asks for at distance `d` when it grows by `rate`.
fn graded(d: f64, delta: f64, r1: f64, rate: f64) -> f64 {
    delta + rate * (d - r1).max(0.0)
}

type Entry = GeomWithData<[f64; 3], (f64, f64)>; // (delta, r1)

/// Samples of similar δ and r₁ (within a factor of two), so the stopping bound of a nearest-
/// neighbour search is tight for each group.
struct Level {
    tree: RTree<Entry>,
    min_delta: f64,
    max_r1: f64,
}

impl Level {
    /// No sample at distance ≥ `d` asks for less than this (δ ≥ `min_delta`, r₁ ≤ `max_r1`).
    fn lower_bound(&self, d: f64, rate: f64) -> f64 {
        graded(d, self.min_delta, self.max_r1, rate)
    }
}

/// A set of graded samples, searchable for the smallest spacing any of them asks for.
pub struct GradedSamples {
    /// Smallest δ first, so the running minimum drops early.
    levels: Vec<Level>,
}

impl GradedSamples {
    pub fn new(samples: impl IntoIterator<Item = GradedSample>) -> Self {
        let mut groups: std::collections::BTreeMap<(i32, i32), Vec<Entry>> = Default::default();
        for s in samples {
            if !(s.delta.is_finite() && s.delta > 0.0 && s.r1.is_finite()) {
                continue;
            }
            let key = (
                s.delta.log2().floor() as i32,
                s.r1.max(1e-300).log2().floor() as i32,
            );
            groups
                .entry(key)
                .or_default()
                .push(GeomWithData::new(s.point.to_array(), (s.delta, s.r1)));
        }
        // One R*-tree per group, built across the threads (the sizing stage waits for them).
        let levels = groups
            .into_values()
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|entries| Level {
                min_delta: entries
                    .iter()
                    .map(|s| s.data.0)
                    .fold(f64::INFINITY, f64::min),
                max_r1: entries.iter().map(|s| s.data.1).fold(0.0, f64::max),
                tree: RTree::bulk_load(entries),
            })
            .collect();
        GradedSamples { levels }
    }

    pub fn len(&self) -> usize {
        self.levels.iter().map(|l| l.tree.size()).sum()
    }

    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }

    /// The smallest spacing the samples ask for at `p` when it is below `cap`, else `None`.
    /// The cap (the spacing already known from other contributions) prunes the search: only
    /// samples that could beat it are visited, which is most of the cost of a spacing query.
    pub fn spacing_below(&self, p: DVec3, cap: f64) -> Option<f64> {
        self.spacing_below_at(p, cap, RATE)
    }

    /// [`Self::spacing_below`] with the samples' spacing growing by `rate` per unit distance
    /// ([`VOLUME_RATE`] for the interior of a region).
    pub fn spacing_below_at(&self, p: DVec3, cap: f64, rate: f64) -> Option<f64> {
        let mut best = cap;
        for level in &self.levels {
            if level.lower_bound(0.0, rate) >= best {
                continue;
            }
            // The whole level's box first: most levels lie too far to matter, and this costs
            // no allocation (the nearest-neighbour iterator below does).
            let to_box = level
                .tree
                .root()
                .envelope()
                .distance_2(&p.to_array())
                .sqrt();
            if level.lower_bound(to_box, rate) >= best {
                continue;
            }
            level.descend(level.tree.root(), &p.to_array(), rate, &mut best);
        }
        (best < cap).then_some(best)
    }
}

/// Children of one node visited nearest box first: rstar's nodes hold at most 6.
const MAX_CHILDREN: usize = 16;

impl Level {
    /// Branch and bound over the tree: a subtree is entered only if its box is near enough
    /// for some sample in it to beat `best`. (rstar's nearest-neighbour iterator did the same
    /// with a heap, whose upkeep was most of the cost of a spacing query.)
    fn descend(&self, node: &ParentNode<Entry>, p: &[f64; 3], rate: f64, best: &mut f64) {
        let mut near: [(f64, usize); MAX_CHILDREN] = [(0.0, 0); MAX_CHILDREN];
        let mut count = 0;
        for (i, child) in node.children().iter().enumerate() {
            match child {
                RTreeNode::Leaf(s) => {
                    let q = s.geom();
                    let d2 = (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2);
                    let (delta, r1) = s.data;
                    *best = best.min(graded(d2.sqrt(), delta, r1, rate));
                }
                RTreeNode::Parent(c) => {
                    let d = c.envelope().distance_2(p).sqrt();
                    if count < MAX_CHILDREN {
                        near[count] = (d, i);
                        count += 1;
                    } else if self.lower_bound(d, rate) < *best {
                        self.descend(c, p, rate, best);
                    }
                }
            }
        }
        let near = &mut near[..count];
        near.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        for &(d, i) in near.iter() {
            if self.lower_bound(d, rate) >= *best {
                break;
            }
            if let RTreeNode::Parent(c) = &node.children()[i] {
                self.descend(c, p, rate, best);
            }
        }
    }
}
