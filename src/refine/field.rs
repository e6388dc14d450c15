//! One refinement stage's demand on an element: its sources' distance functions and
//! distributions, the test "is this element larger, measured with the distance metric
//! (max φ − min φ), than the distribution asks for", and the candidate points on the lines from
//! its vertices to their nearest source points (seed paper, figure 1).

use super::distribution::Distribution;
use super::source::{Near, SourceDistance};
use glam::DVec3;

/// A site closer than this fraction of its layer spacing to the element's lowest or highest
/// vertex distance does not count: the element already spans that site.
pub const SITE_MARGIN: f64 = 0.3;
/// Normal and tangential fractions of the metric ball a candidate must keep free of other
/// points: half a layer along the source's normal, half the isotropic δ across it.
pub const CLEAR_NORMAL: f64 = 0.5;
pub const CLEAR_TANGENT: f64 = 0.5;

/// A source of a stage: where the distance is measured from and the spacing asked for.
pub struct StageSource<'m> {
    pub distance: SourceDistance<'m>,
    pub distribution: Distribution,
}

/// The sources of one stage; they combine by the minimum of their distributions.
pub struct StageField<'m> {
    pub sources: Vec<StageSource<'m>>,
    /// Surface nodes lying on an embedded source face (a wake) and on no boundary face: the
    /// fluid is on both sides there, so their columns grow both ways.
    pub two_sided: std::collections::HashSet<u32>,
}

/// A candidate point: where, at which site of which source, and its line's direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    pub point: DVec3,
    pub site: f64,
    /// Unit direction of the line it lies on (away from the source).
    pub dir: DVec3,
    /// Spacing of the layer the site starts.
    pub spacing: f64,
    pub source: usize,
    /// Which of the element's vertices the line starts from (an index into its vertices).
    pub from: usize,
}

impl StageField<'_> {
    /// Distance to every source of the stage, in source order.
    pub fn near(&self, p: DVec3) -> Vec<Near> {
        self.sources.iter().map(|s| s.distance.near(p)).collect()
    }

    /// The farthest any layer of the stage reaches where the isotropic spacing is `delta`.
    pub fn reach(&self, delta: f64) -> f64 {
        self.sources
            .iter()
            .map(|s| s.distribution.reach(delta))
            .fold(0.0, f64::max)
    }

    /// The source whose demand on an element with vertex distances `near[i][s]` is finest,
    /// with the sites the element spans and should not: `None` when the element meets every
    /// distribution (or lies beyond their reach at spacing `delta`).
    pub fn demand(&self, near: &[&[Near]], delta: f64) -> Option<(usize, Vec<f64>)> {
        let mut best: Option<(f64, usize, Vec<f64>)> = None;
        for (s, src) in self.sources.iter().enumerate() {
            let (lo, hi) = near.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), n| {
                (lo.min(n[s].phi), hi.max(n[s].phi))
            });
            let d = &src.distribution;
            let reach = d.reach(delta);
            if lo >= reach {
                continue;
            }
            let sites = d.sites_between(lo, hi, reach, SITE_MARGIN);
            if sites.is_empty() {
                continue;
            }
            let spacing = d.spacing_at(lo);
            if best.as_ref().is_none_or(|b| spacing < b.0) {
                best = Some((spacing, s, sites));
            }
        }
        best.map(|(_, s, sites)| (s, sites))
    }

    /// The candidates of an element for source `s` and its spanned `sites`, in the paper's
    /// order: the site just above the lowest vertex on that vertex's line, the site just below
    /// the highest on its line, then two for each other vertex (the sites next to its own
    /// distance, below and above). `pos` are the vertex positions, `centre` picks the side
    /// of a vertex lying on the source.
    pub fn candidates(
        &self,
        s: usize,
        sites: &[f64],
        pos: &[DVec3],
        near: &[&[Near]],
        centre: DVec3,
    ) -> Vec<Candidate> {
        let d = &self.sources[s].distribution;
        let phi: Vec<f64> = near.iter().map(|n| n[s].phi).collect();
        let lowest = (0..pos.len())
            .min_by(|&a, &b| phi[a].total_cmp(&phi[b]))
            .unwrap_or(0);
        let highest = (0..pos.len())
            .max_by(|&a, &b| phi[a].total_cmp(&phi[b]))
            .unwrap_or(0);
        let mut wanted: Vec<(usize, f64)> = Vec::with_capacity(2 + 2 * pos.len());
        wanted.push((lowest, sites[0]));
        if highest != lowest {
            wanted.push((highest, sites[sites.len() - 1]));
        }
        for (i, &phi_i) in phi.iter().enumerate() {
            if i == lowest || i == highest {
                continue;
            }
            let k = sites.partition_point(|&x| x <= phi_i);
            if k > 0 {
                wanted.push((i, sites[k - 1]));
            }
            if k < sites.len() {
                wanted.push((i, sites[k]));
            }
        }
        let mut out = Vec::with_capacity(wanted.len());
        for (i, site) in wanted {
            let n = near[i][s];
            let dir = line_direction(&n, pos[i], centre);
            if dir == DVec3::ZERO {
                continue;
            }
            let k = d.layer_of(site * (1.0 - 1e-12)).min(d.sites().len());
            out.push(Candidate {
                point: n.foot + dir * site,
                site,
                dir,
                spacing: d.layer_spacing(k),
                source: s,
                from: i,
            });
        }
        out
    }
}

/// The direction of a vertex's line to its nearest source point, away from the source; for a
/// vertex on the source, the source's normal on the side of `centre` (a face), or the
/// direction to `centre` (an edge).
fn line_direction(n: &Near, vertex: DVec3, centre: DVec3) -> DVec3 {
    let towards = centre - vertex;
    if n.phi > 1e-9 * towards.length() {
        return n.dir;
    }
    if n.dir == DVec3::ZERO {
        return towards.normalize_or_zero();
    }
    if n.dir.dot(towards) >= 0.0 {
        n.dir
    } else {
        -n.dir
    }
}

/// True when `q` lies inside the metric ball of candidate `c` (half a layer along its line,
/// `CLEAR_TANGENT · delta` across it).
pub fn crowds(c: &Candidate, q: DVec3, delta: f64) -> bool {
    let r = q - c.point;
    let a = r.dot(c.dir);
    let t2 = (r.length_squared() - a * a).max(0.0);
    let an = a / (CLEAR_NORMAL * c.spacing);
    let at2 = t2 / (CLEAR_TANGENT * delta).powi(2);
    an * an + at2 < 1.0
}
