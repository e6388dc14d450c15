//! A flow domain around a body: the far-field solid (box, sphere, or their half on a symmetry
//! plane) with the body's solids cut out (OCCT's Boolean cut).

use crate::error::CadError;
use crate::ffi::bridge as ffi;
use crate::model::{occt, CadModel};

/// The far-field solid's shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OuterShape {
    Box,
    Sphere,
}

/// The far-field solid: its shape about `centre` with half extents `half` (a sphere's radius is
/// `half[0]`), and, for a half model, the symmetry plane kept.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Farfield {
    pub shape: OuterShape,
    pub centre: [f64; 3],
    pub half: [f64; 3],
    pub symmetry: Option<SymmetryPlane>,
    /// Gaps up to this are contact (the body's face on the symmetry plane meets the plane).
    pub fuzzy: f64,
}

/// The plane coord[`axis`] = `at`; the domain keeps the side `positive` says.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetryPlane {
    pub axis: usize,
    pub at: f64,
    pub positive: bool,
}

impl CadModel {
    /// The domain between the far-field solid and this model's solids. Its faces are named
    /// `farfield` (the outer solid's), `symmetry` (on the plane) or as the body's faces were
    /// (`body` for a face without a name).
    pub fn farfield_domain(&self, f: &Farfield) -> Result<CadModel, CadError> {
        let _guard = crate::model::translator_lock();
        let (axis, at, side) = match f.symmetry {
            Some(s) => (s.axis as i32, s.at, if s.positive { 1 } else { -1 }),
            None => (-1, 0.0, 0),
        };
        let kind = match f.shape {
            OuterShape::Box => 0,
            OuterShape::Sphere => 1,
        };
        let idx = ffi::farfield_domain(
            &self.index,
            kind,
            &f.centre,
            &f.half,
            axis,
            at,
            side,
            f.fuzzy,
        )
        .map_err(|e| occt(self.file(), "building the far field", e))?;
        CadModel::new(self.file().to_string(), idx)
    }
}
