//! The spacing function δ(x): the smallest of a uniform background value, a background mesh,
//! point/line/triangle sources and the curvature limit. Everything downstream asks only
//! [`SizingField::spacing`].

pub mod background;
pub mod curvature;
pub mod sources;

pub use background::{BackgroundError, BackgroundMesh};
pub use curvature::CurvatureLimit;
pub use sources::{felisa, Source, SourceShape};

use glam::DVec3;

pub struct SizingField {
    /// Spacing everywhere no other contribution is smaller.
    pub uniform: f64,
    pub background: Option<BackgroundMesh>,
    pub sources: Vec<Source>,
    pub curvature: Option<CurvatureLimit>,
}

impl SizingField {
    pub fn uniform(size: f64) -> Self {
        SizingField {
            uniform: size,
            background: None,
            sources: Vec::new(),
            curvature: None,
        }
    }

    /// δ at `p`.
    pub fn spacing(&self, p: DVec3) -> f64 {
        let mut d = self.uniform;
        if let Some(b) = self.background.as_ref().and_then(|b| b.spacing(p)) {
            d = d.min(b);
        }
        for s in &self.sources {
            d = d.min(s.spacing(p));
        }
        if let Some(c) = self.curvature.as_ref().and_then(|c| c.spacing_below(p, d)) {
            d = d.min(c);
        }
        d
    }
}
