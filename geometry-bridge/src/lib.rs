//! tetrafoil-occt: safe Rust over OpenCASCADE for tetrafoil, knowing nothing about meshing.
//!
//! - [`CadModel`] reads STEP (with XDE names), IGES and BREP, sews and heals, and extracts a
//!   plain-data [`CadTopology`] with stable 0-based ids.
//! - [`OccSurface`], [`OccCurve`], [`OccPcurve`] are `Send + Sync` geometry handles: each owns
//!   a deep copy of its OCCT geometry behind its own lock.
//!
//! OCCT classes covered by `opencascade-sys` (IGES and BREP reading, BRepGProp, bounding box)
//! are used through it; the rest goes through this crate's small cxx shim (`cpp/`).
mod curve;
mod error;
mod ffi;
mod model;
mod repair;
mod surface;
mod topology;

pub use curve::{CurveDerivs, OccCurve, OccPcurve, PcurveDerivs};
pub use error::{CadError, CadWarning};
pub use model::{BoundingBox, CadModel};
pub use repair::{HealReport, SewReport};
pub use surface::{CircleHit, OccSurface, SurfaceDerivs};
pub use topology::{CadTopology, Counts, Edge, EdgeUse, Face, Shell, Solid, Vertex};
