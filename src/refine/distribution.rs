//! The 1-D point distribution of a refinement source (seed paper, figure 1): the sites φₖ at
//! which points should stand along the normal of the source, from `first` spacing at the
//! source, `constant` equally spaced layers, then geometric growth, until the layer spacing
//! reaches the local isotropic δ (or the distance reaches `thickness`).

/// Why a distribution cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DistributionError {
    #[error("first must be a positive number, got {0}")]
    First(f64),
    #[error("growth must be at least 1, got {0}")]
    Growth(f64),
    #[error("growth = 1 never reaches the isotropic spacing: give a thickness to end the layers")]
    NeverEnds,
    #[error("thickness must be a positive number, got {0}")]
    Thickness(f64),
    #[error("first = {first} is not smaller than the isotropic spacing δ = {delta}")]
    NotFiner { first: f64, delta: f64 },
}

/// Layers stop after this many sites even if δ is not reached (growth barely above 1).
const MAX_SITES: usize = 4000;

/// A 1-D spacing distribution away from a source.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution {
    /// Spacing of the layer next to the source.
    pub first: f64,
    /// Ratio of one layer's spacing to the one below it, once the constant layers end.
    pub growth: f64,
    /// Number of layers of spacing `first` next to the source (at least 1).
    pub constant: usize,
    /// Distance beyond which nothing is refined.
    pub thickness: Option<f64>,
    /// Sites φ₀ = 0 < φ₁ < …, up to the largest spacing asked for (`with_cap`).
    sites: Vec<f64>,
}

impl Distribution {
    /// A checked distribution whose sites run until the layer spacing reaches `max_delta`
    /// (the largest isotropic spacing of the model) or the distance reaches `thickness`.
    pub fn new(
        first: f64,
        growth: f64,
        constant: usize,
        thickness: Option<f64>,
        max_delta: f64,
    ) -> Result<Self, DistributionError> {
        if !(first.is_finite() && first > 0.0) {
            return Err(DistributionError::First(first));
        }
        if !(growth.is_finite() && growth >= 1.0) {
            return Err(DistributionError::Growth(growth));
        }
        if let Some(t) = thickness {
            if !(t.is_finite() && t > 0.0) {
                return Err(DistributionError::Thickness(t));
            }
        } else if growth == 1.0 {
            return Err(DistributionError::NeverEnds);
        }
        if first >= max_delta {
            return Err(DistributionError::NotFiner {
                first,
                delta: max_delta,
            });
        }
        let mut d = Distribution {
            first,
            growth,
            constant: constant.max(1),
            thickness,
            sites: vec![0.0],
        };
        let cap = thickness.unwrap_or(f64::INFINITY);
        let mut phi = 0.0;
        for k in 0..MAX_SITES {
            let s = d.layer_spacing(k);
            if s >= max_delta || phi + s > cap * (1.0 + 1e-12) {
                break;
            }
            phi += s;
            d.sites.push(phi);
        }
        Ok(d)
    }

    /// Spacing of layer `k` (between sites k and k+1).
    pub fn layer_spacing(&self, k: usize) -> f64 {
        let grown = (k + 1).saturating_sub(self.constant);
        self.first * self.growth.powi(grown as i32)
    }

    /// All sites, from φ₀ = 0.
    pub fn sites(&self) -> &[f64] {
        &self.sites
    }

    /// Index of the layer holding distance `phi` (sites[k] ≤ phi < sites[k+1]); past the last
    /// site, the index of the last layer.
    pub fn layer_of(&self, phi: f64) -> usize {
        let k = self.sites.partition_point(|&s| s <= phi);
        k.saturating_sub(1)
    }

    /// Spacing asked for at distance `phi`: the spacing of the layer holding it.
    pub fn spacing_at(&self, phi: f64) -> f64 {
        self.layer_spacing(self.layer_of(phi))
    }

    /// The distance up to which layers of spacing below `delta` reach: the last site whose
    /// layer below it is finer than `delta`.
    pub fn reach(&self, delta: f64) -> f64 {
        let mut r = 0.0;
        for (k, w) in self.sites.windows(2).enumerate() {
            if self.layer_spacing(k) >= delta {
                break;
            }
            r = w[1];
        }
        r
    }

    /// Sites strictly inside `(lo, hi)`, each kept `margin` × its layer spacing away from both
    /// ends, and no farther than `reach`.
    pub fn sites_between(&self, lo: f64, hi: f64, reach: f64, margin: f64) -> Vec<f64> {
        let start = self.sites.partition_point(|&s| s <= lo);
        let mut out = Vec::new();
        for (k, &s) in self.sites.iter().enumerate().skip(start) {
            if s > hi || s > reach * (1.0 + 1e-12) {
                break;
            }
            let h = self.layer_spacing(k.saturating_sub(1)) * margin;
            if s > lo + h && s < hi - h {
                out.push(s);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_layers_then_growth_until_delta() {
        let d = Distribution::new(0.01, 1.5, 3, None, 0.1).unwrap();
        let s = d.sites();
        assert!((s[1] - 0.01).abs() < 1e-15);
        assert!((s[3] - 0.03).abs() < 1e-15);
        assert!((s[4] - s[3] - 0.015).abs() < 1e-15);
        // Spacings 0.01 ×3, 0.015, 0.0225, 0.03375, 0.050625, 0.0759375: the next is 0.1139.
        assert_eq!(s.len(), 9);
        assert!((d.spacing_at(0.005) - 0.01).abs() < 1e-15);
        assert!((d.spacing_at(0.031) - 0.015).abs() < 1e-15);
        // With δ = 0.04 locally, layers stop below the first spacing ≥ 0.04.
        let r = d.reach(0.04);
        assert!((r - (0.03 + 0.015 + 0.0225 + 0.03375)).abs() < 1e-12, "{r}");
    }

    #[test]
    fn sites_between_keep_a_margin_from_the_ends() {
        let d = Distribution::new(0.01, 1.2, 5, None, 1.0).unwrap();
        let got = d.sites_between(0.0, 0.0405, 1.0, 0.25);
        assert_eq!(
            got.len(),
            3,
            "0.04 is within a quarter spacing of 0.0405: {got:?}"
        );
        assert!((got[0] - 0.01).abs() < 1e-15);
        let got = d.sites_between(0.0, 0.043, 1.0, 0.25);
        assert_eq!(got.len(), 4);
        let got = d.sites_between(0.0, 0.0426, 0.02, 0.25);
        assert_eq!(got, vec![0.01, 0.02]);
    }

    #[test]
    fn bad_values_are_refused() {
        assert_eq!(
            Distribution::new(0.0, 1.2, 1, None, 1.0),
            Err(DistributionError::First(0.0))
        );
        assert_eq!(
            Distribution::new(0.1, 0.9, 1, None, 1.0),
            Err(DistributionError::Growth(0.9))
        );
        assert_eq!(
            Distribution::new(0.1, 1.0, 1, None, 1.0),
            Err(DistributionError::NeverEnds)
        );
        assert!(Distribution::new(0.1, 1.0, 1, Some(0.5), 1.0).is_ok());
        assert_eq!(
            Distribution::new(2.0, 1.2, 1, None, 1.0),
            Err(DistributionError::NotFiner {
                first: 2.0,
                delta: 1.0
            })
        );
    }

    #[test]
    fn thickness_caps_the_sites() {
        let d = Distribution::new(0.1, 1.0, 1, Some(0.55), 1.0).unwrap();
        assert_eq!(d.sites().len(), 6);
        assert!((d.sites()[5] - 0.5).abs() < 1e-12);
    }
}
