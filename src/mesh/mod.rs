//! Output mesh types, validity checks and quality measures.

pub mod quality;
pub mod validity;
pub mod volume;

pub use volume::{CellKind, LayerTag, Marker, VolumeMesh};
