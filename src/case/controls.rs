//! The types every part of case loading shares: the mesh controls and their command-line
//! overrides, the loaded [`Case`], and the context errors are made in ([`Ctx`]: the file's
//! text and path). Here so that building a case file (`build.rs`), loading a CAD file
//! (`cad.rs`) and mixing geometry (`mix/`) use them without importing each other.

use super::error::{line_of, CaseError};
use crate::model::Model;
use crate::sizing::{CurvatureLimit, ProximityLimit, SizingField};
use toml::Spanned;

/// Whether a prism side-quad warp tolerance (degrees) can be used: above 0, at most 90.
pub fn prism_warp_ok(w: f64) -> bool {
    w > 0.0 && w <= 90.0
}

/// Whether `n` segments per circle is a curvature limit the mesher takes: 0 (off) or at least
/// 3 (fewer cannot follow a circle). One rule for the case file and the command line.
pub fn curvature_segments_ok(n: f64) -> bool {
    n == 0.0 || (n.is_finite() && n >= 3.0)
}

/// The mesh controls of a case, after defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshControls {
    pub size: f64,
    /// n in δ ≤ 2πR/n; 0 turns the curvature limit off.
    pub curvature_segments: f64,
    /// n in δ ≤ w/n across a face only w wide; 0 turns the proximity limit off.
    pub proximity_cells: f64,
    pub min_size: f64,
    /// Edges must lie within this distance of the faces they bound.
    pub tolerance: f64,
    /// Merge the stretched layers' tets into prisms (`[mesh] prisms`, `--prisms`).
    pub prisms: bool,
    /// A prism side quad warped more than this (degrees) stays two triangles.
    pub prism_warp: f64,
}

/// Mesh controls given on the command line: they replace the case's own before its sizing
/// field is built (building it at the case's values first, then again, cost up to 15% of
/// loading a CAD file).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ControlOverrides {
    pub size: Option<f64>,
    pub curvature_segments: Option<f64>,
    pub proximity_cells: Option<f64>,
    /// `--prisms`: on when given (the case's `[mesh] prisms` otherwise).
    pub prisms: bool,
    /// `--prism-warp`.
    pub prism_warp: Option<f64>,
    /// `--farfield shape:size`: a flow domain around the body, CAD or native (the case's
    /// `[mesh] farfield` otherwise).
    pub farfield: Option<super::farfield::FarfieldSpec>,
    /// `--wakes auto`: wake sheets from the trailing edges found (the case's `[mesh] wakes`
    /// otherwise).
    pub wakes: Option<AutoWakes>,
}

/// Wakes shed from every trailing edge found on the body, along the free stream: angle of
/// attack `alpha` (degrees, about y: the stream tilts towards +z) and sideslip `beta`
/// (degrees, towards +y), each `length` long in the model's unit, or to the far field (less
/// one far-field cell) when tetrafoil built it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AutoWakes {
    pub alpha: f64,
    pub beta: f64,
    pub length: Option<f64>,
}

impl AutoWakes {
    /// The free stream's unit direction: +x at alpha = beta = 0.
    pub fn stream(&self) -> glam::DVec3 {
        let (a, b) = (self.alpha.to_radians(), self.beta.to_radians());
        glam::DVec3::new(a.cos() * b.cos(), b.sin(), a.sin() * b.cos())
    }
}

impl ControlOverrides {
    /// Replace the controls given; a new size scales the size floor with it (the floor is a
    /// fraction of the size a user asks for, whether the case gave it or the default did).
    pub fn apply(&self, c: &mut MeshControls) {
        c.prisms |= self.prisms;
        if let Some(w) = self.prism_warp {
            c.prism_warp = w;
        }
        if let Some(h) = self.size {
            if c.size > 0.0 && h > 0.0 {
                c.min_size *= h / c.size;
            }
            c.size = h;
        }
        if let Some(n) = self.curvature_segments {
            c.curvature_segments = n;
        }
        if let Some(n) = self.proximity_cells {
            c.proximity_cells = n;
        }
    }
}

/// Default n of the proximity limit δ ≤ w/n: a face narrower than δ is spanned by triangles
/// at most twice as long as it is wide. (With n = 1 the strips' fine spacing, graded into the
/// faces around them, cost 1.3–2.8× the tets on CAD parts for the same minimum dihedral.)
pub const PROXIMITY_CELLS: f64 = 0.5;

/// The proximity limit asks for no less than size/PROXIMITY_FLOOR (nor the size floor): a
/// face narrower than that is spanned by a stretched triangle rather than refined towards its
/// width. Floored only at the size floor (size/100), one chamfer strip refined the faces
/// around it over several sizes and gave 30–80× Gmsh's tets on CAD parts at the same size;
/// the curvature limit keeps the lower floor (Gmsh resolves curvature without one).
pub const PROXIMITY_FLOOR: f64 = 10.0;

impl SizingField {
    /// (Re)build the limits that sample the model, the curvature and the proximity limit, from
    /// the controls (after a change of size, curvature or proximity setting).
    pub fn set_local_limits(&mut self, model: &Model, c: &MeshControls) {
        let start = std::time::Instant::now();
        // Side by side: each is parallel over faces, which leaves threads idle on a model
        // of few faces.
        (self.curvature, self.proximity) = rayon::join(
            || {
                (c.curvature_segments > 0.0)
                    .then(|| CurvatureLimit::from_model(model, c.curvature_segments, c.min_size))
            },
            || {
                (c.proximity_cells > 0.0).then(|| {
                    ProximityLimit::from_model(
                        model,
                        c.proximity_cells,
                        c.min_size.max(c.size / PROXIMITY_FLOOR),
                        c.proximity_cells * c.size,
                    )
                })
            },
        );
        self.limits_seconds = start.elapsed().as_secs_f64();
    }
}

/// A loaded case: the oriented model, its controls and spacing function.
pub struct Case {
    pub model: Model,
    pub controls: MeshControls,
    pub sizing: SizingField,
    /// Directional refinement stages (`[[refine]]`), empty for an isotropic mesh.
    pub refinement: crate::refine::Refinement,
}

/// Where a case file's text came from, for errors that name its key and line.
pub(super) struct Ctx<'a> {
    pub(super) text: &'a str,
    pub(super) path: &'a str,
}

impl Ctx<'_> {
    pub(super) fn at<T>(&self, s: &Spanned<T>, key: &str, message: impl Into<String>) -> CaseError {
        CaseError::At {
            path: self.path.to_string(),
            line: line_of(self.text, s.span().start),
            key: key.to_string(),
            message: message.into(),
        }
    }
    pub(super) fn model(&self, message: impl Into<String>) -> CaseError {
        CaseError::Model {
            path: self.path.to_string(),
            message: message.into(),
        }
    }
}
