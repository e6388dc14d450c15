//! Native Ferguson geometry: piecewise cubic Hermite curves, bicubic
//! Coons–Hermite patches and C¹ patch networks interpolating point grids.
//!
//! Pure math on `glam` vectors with analytic first and second derivatives; no
//! mesher types, so the root crate can wrap these in its own geometry traits.

mod curve;
mod error;
mod hermite;
mod patch;
mod surface;

pub use curve::FergusonCurve;
pub use error::NativeError;
pub use patch::{FergusonPatch, SurfaceDerivatives};
pub use surface::FergusonSurface;
