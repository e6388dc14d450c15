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
/// Round a curve source, the arc (radians times the distance) that spaces points of one layer.
pub const CLEAR_AROUND: f64 = 1.0;

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
    /// Unit tangent of a curve source at the line's foot; zero for a face source.
    pub along: DVec3,
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
    /// of a vertex lying on the source. In the volume (`square`), a line from a curve's node
    /// runs square to the curve; on a face, the face stage projects its points onto the
    /// surface and keeps the line to the triangle's centre.
    pub fn candidates(
        &self,
        s: usize,
        sites: &[f64],
        pos: &[DVec3],
        near: &[&[Near]],
        centre: DVec3,
        square: bool,
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
            let dir = line_direction(&n, pos[i], centre, square);
            if dir == DVec3::ZERO {
                continue;
            }
            let k = d.layer_of(site * (1.0 - 1e-12)).min(d.sites().len());
            out.push(Candidate {
                point: n.foot + dir * site,
                site,
                dir,
                along: n.along,
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
/// direction to `centre` (an edge), made `square` to the curve in the volume (a line slanted
/// along the curve puts its sites nearer the curve than they say, between the curve's nodes).
fn line_direction(n: &Near, vertex: DVec3, centre: DVec3, square: bool) -> DVec3 {
    let towards = centre - vertex;
    if n.phi > 1e-9 * towards.length() {
        return n.dir;
    }
    if n.dir == DVec3::ZERO {
        let across = if square {
            towards - n.along * towards.dot(n.along)
        } else {
            towards
        };
        return across.normalize_or_zero();
    }
    if n.dir.dot(towards) >= 0.0 {
        n.dir
    } else {
        -n.dir
    }
}

/// True when `q` lies inside the metric ball of candidate `c` (half a layer along its line,
/// `CLEAR_TANGENT · delta` across it).
///
/// Around a curve source the layers are tubes, and across the line there are two directions:
/// along the curve, where δ is the spacing, and round it, where points at the same distance
/// `site` sit an arc apart. Measured with δ round the curve too, a point at the first layers
/// would crowd everything on its ring: where the curve runs along a concave corner of the
/// domain (a box's edge, a wing/body junction), the face points on the two walls then refused
/// every volume point and the tets between them and the isotropic interior stayed slivers.
/// Round a curve the ball is [`CLEAR_AROUND`] radians of arc wide instead (never more than δ
/// across, never less than a layer).
pub fn crowds(c: &Candidate, q: DVec3, delta: f64) -> bool {
    let r = q - c.point;
    let a = r.dot(c.dir);
    let an = a / (CLEAR_NORMAL * c.spacing);
    let across = if c.along == DVec3::ZERO {
        let t2 = (r.length_squared() - a * a).max(0.0);
        t2 / (CLEAR_TANGENT * delta).powi(2)
    } else {
        let b = r.dot(c.along);
        let round2 = (r.length_squared() - a * a - b * b).max(0.0);
        let arc = (CLEAR_AROUND * c.site).clamp(c.spacing, delta.max(c.spacing));
        (b / (CLEAR_TANGENT * delta)).powi(2) + round2 / (CLEAR_TANGENT * arc).powi(2)
    };
    an * an + across < 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A candidate a first layer (0.001) out from the x axis, in direction `dir`.
    fn around_x_axis(dir: DVec3, along: DVec3) -> Candidate {
        Candidate {
            point: dir * 0.001,
            site: 0.001,
            dir,
            along,
            spacing: 0.001,
            source: 0,
            from: 0,
        }
    }

    #[test]
    fn round_a_curve_points_of_one_layer_crowd_within_an_arc_not_within_delta() {
        let delta = 0.1;
        let c = around_x_axis(DVec3::Y, DVec3::X);
        let at = |degrees: f64| {
            let (s, co) = degrees.to_radians().sin_cos();
            DVec3::new(0.0, co, s) * 0.001
        };
        // 45° round the axis at the same distance (a corner's bisector beside its wall): clear.
        assert!(!crowds(&c, at(45.0), delta));
        // Ten degrees round: within half a radian of arc, crowded.
        assert!(crowds(&c, at(10.0), delta));
        // Along the curve δ still spaces them: 0.04 along crowds, 0.06 does not.
        assert!(crowds(&c, c.point + DVec3::X * 0.04, delta));
        assert!(!crowds(&c, c.point + DVec3::X * 0.06, delta));
        // From a face source the same 45° lies within δ across: crowded.
        let face = around_x_axis(DVec3::Y, DVec3::ZERO);
        assert!(crowds(&face, at(45.0), delta));
    }

    #[test]
    fn a_line_from_a_curve_node_runs_square_to_the_curve() {
        let on_curve = Near {
            phi: 0.0,
            foot: DVec3::ZERO,
            dir: DVec3::ZERO,
            along: DVec3::X,
        };
        let centre = DVec3::new(0.05, 0.01, 0.01);
        let slanted = line_direction(&on_curve, DVec3::ZERO, centre, false);
        assert!((slanted - centre.normalize()).length() < 1e-12, "{slanted}");
        let d = line_direction(&on_curve, DVec3::ZERO, centre, true);
        assert!(d.dot(DVec3::X).abs() < 1e-12, "{d}");
        assert!(
            (d - DVec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-12,
            "{d}"
        );
    }
}
