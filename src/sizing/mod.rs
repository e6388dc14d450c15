//! The spacing function δ(x): the smallest of a uniform background value, a background mesh,
//! point/line/triangle sources, the curvature limit, the proximity limit, a flow domain's body
//! spacing, and the local refinement the pipeline adds where a surface mesh crossed itself. Everything downstream asks
//! only [`SizingField::spacing`].

pub mod background;
pub mod body;
pub mod curvature;
pub mod estimate;
pub mod graded;
pub mod proximity;
pub mod sources;

pub use background::{BackgroundError, BackgroundMesh};
pub use curvature::CurvatureLimit;
pub use graded::{GradedSample, GradedSamples};
pub use proximity::ProximityLimit;
pub use sources::{felisa, Source, SourceShape};

use glam::DVec3;

pub struct SizingField {
    /// Spacing everywhere no other contribution is smaller.
    pub uniform: f64,
    pub background: Option<BackgroundMesh>,
    pub sources: Vec<Source>,
    pub curvature: Option<CurvatureLimit>,
    pub proximity: Option<ProximityLimit>,
    /// Local refinement where a coarser surface mesh of this model crossed itself (added by
    /// the pipeline before it meshes the surface again: [`Self::refine_at_crossings`]).
    crossings: Vec<GradedSample>,
    crossings_index: Option<GradedSamples>,
    /// A flow domain's body spacing, graded out to the far field ([`Self::keep_body_fine`]).
    body: Option<GradedSamples>,
    /// Seconds spent sampling the model for the curvature and proximity limits (reported as
    /// the "sizing" stage: it is meshing work, though done while loading).
    pub limits_seconds: f64,
}

impl SizingField {
    pub fn uniform(size: f64) -> Self {
        SizingField {
            uniform: size,
            background: None,
            sources: Vec::new(),
            curvature: None,
            proximity: None,
            crossings: Vec::new(),
            crossings_index: None,
            body: None,
            limits_seconds: 0.0,
        }
    }

    /// δ at `p`: the spacing curves and surfaces are meshed to.
    pub fn spacing(&self, p: DVec3) -> f64 {
        self.spacing_graded(p, graded::RATE)
    }

    /// δ at `p` inside a region, for the interior points: the curvature and proximity limits
    /// grade away from the surface at [`graded::VOLUME_RATE`], not at the surfaces' gentle
    /// rate, so a small feature refines the volume next to it and not a ball several sizes
    /// wide. Equal to [`Self::spacing`] on the features themselves.
    /// The finest spacing the case's sources ask for at `p` (infinite without sources): the
    /// one part of the field that can be small far from every surface node.
    pub fn source_spacing(&self, p: DVec3) -> f64 {
        self.sources
            .iter()
            .map(|s| s.spacing(p))
            .fold(f64::INFINITY, f64::min)
    }

    pub fn volume_spacing(&self, p: DVec3) -> f64 {
        self.spacing_graded(p, graded::VOLUME_RATE)
    }

    /// δ at `p` (graded at `rate`) as [with every contribution, without the curvature limit,
    /// without the proximity limit]: one search per limit for all three, which is what the
    /// element estimate needs to say how many elements each limit adds.
    pub fn spacing_with_and_without_limits(&self, p: DVec3, rate: f64) -> [f64; 3] {
        let base = self.graded_extras(p, self.given_spacing(p), rate);
        let curvature = self
            .curvature
            .as_ref()
            .and_then(|c| c.spacing_below_at(p, base, rate))
            .unwrap_or(base);
        let proximity = self
            .proximity
            .as_ref()
            .and_then(|c| c.spacing_below_at(p, base, rate))
            .unwrap_or(base);
        [curvature.min(proximity), proximity, curvature]
    }

    /// The spacing the case asks for at `p` itself: uniform, background mesh and sources (the
    /// local limits prune their searches with it).
    fn given_spacing(&self, p: DVec3) -> f64 {
        let mut d = self.uniform;
        if let Some(b) = self.background.as_ref().and_then(|b| b.spacing(p)) {
            d = d.min(b);
        }
        for s in &self.sources {
            d = d.min(s.spacing(p));
        }
        d
    }

    fn spacing_graded(&self, p: DVec3, rate: f64) -> f64 {
        let mut d = self.given_spacing(p);
        if let Some(c) = self
            .curvature
            .as_ref()
            .and_then(|c| c.spacing_below_at(p, d, rate))
        {
            d = d.min(c);
        }
        if let Some(c) = self
            .proximity
            .as_ref()
            .and_then(|c| c.spacing_below_at(p, d, rate))
        {
            d = d.min(c);
        }
        self.graded_extras(p, d, rate)
    }

    /// `d` lowered by the crossings' and the body's samples.
    fn graded_extras(&self, p: DVec3, mut d: f64, rate: f64) -> f64 {
        for samples in [&self.crossings_index, &self.body].into_iter().flatten() {
            if let Some(c) = samples.spacing_below_at(p, d, rate) {
                d = d.min(c);
            }
        }
        d
    }

    /// A flow domain: the far field spaced `far` (the uniform value), the body's `samples`
    /// asking for its own spacing and grading out to it.
    pub fn keep_body_fine(&mut self, far: f64, samples: Vec<GradedSample>) {
        self.uniform = far;
        self.body = Some(GradedSamples::new(samples));
    }

    /// Ask for finer spacing around the places a surface mesh crossed itself (kept with those
    /// of earlier calls), graded at the same rates as the curvature and proximity limits.
    pub fn refine_at_crossings(&mut self, samples: &[GradedSample]) {
        self.crossings.extend_from_slice(samples);
        self.crossings_index = Some(GradedSamples::new(self.crossings.iter().copied()));
    }

    /// How many crossing samples [`Self::refine_at_crossings`] has added.
    pub fn crossing_samples(&self) -> usize {
        self.crossings.len()
    }
}
