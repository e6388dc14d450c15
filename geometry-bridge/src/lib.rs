//! tetrafoil-occt: safe Rust over OpenCASCADE for tetrafoil, knowing nothing about meshing.
//!
//! - [`CadModel`] reads STEP (with XDE names), IGES and BREP, sews and heals, and extracts a
//!   plain-data [`CadTopology`] with stable 0-based ids.
//! - [`OccSurface`], [`OccCurve`], [`OccPcurve`] are `Send + Sync` geometry handles: each owns
//!   deep copies of its OCCT geometry, each behind its own lock, made as threads call at once.
//!
//! - [`CadModel::farfield_domain`] builds a flow domain around a body (box or sphere, whole or
//!   half on a symmetry plane, the body cut out).
//! - `plugin`: the crate's cdylib is OpenCASCADE as a tetrafoil geometry plugin
//!   (`libtetrafoil_occt.so`, exporting `tetrafoil_geometry_plugin`).
//! - [`build`] constructs the project's own CAD samples (a lofted wing cut from a box) and
//!   writes them as STEP.
//!
//! OCCT classes covered by `opencascade-sys` (IGES and BREP reading, BRepGProp, bounding box)
//! are used through it; the rest goes through this crate's small cxx shim (`cpp/`).
//!
//! # Building
//!
//! OCCT >= 7.8 is needed. From the workspace root:
//!
//! ```text
//! scripts/install-occt.sh          # once: OCCT 7.8.1 + cmake into .occt/ (seconds)
//! cargo build -p tetrafoil-occt    # .cargo/config.toml points the build at .occt/
//! ```
//!
//! Another OCCT: export `DEP_OCCT_ROOT` and `CMAKE` (see `.cargo/config.toml`), or build OCCT
//! from source with `--features tetrafoil-occt/builtin` (slow). Binaries of other packages that
//! link this crate need the OCCT library directory in their RPATH: their build script reads
//! `DEP_TETRAFOIL_OCCT_LIBDIR` and emits
//! `cargo:rustc-link-arg=-Wl,--disable-new-dtags,-rpath,<dir>`.
//!
//! # Ids
//!
//! Entity ids are 0-based indices in TopExp::MapShapes order, stable for one `CadModel`.
//! Sewing and healing return a new model with its own ids; names are carried over.
pub mod build;
mod curve;
mod error;
mod farfield;
mod ffi;
mod model;
mod nudge;
mod plugin;
mod pool;
mod repair;
mod surface;
mod topology;

pub use curve::{CurveDerivs, OccCurve, OccPcurve, PcurveDerivs};
pub use error::{CadError, CadWarning};
pub use farfield::{Farfield, OuterShape, SymmetryPlane};
pub use model::{BoundingBox, CadModel};
pub use repair::{FuseReport, HealReport, SewReport};
pub use surface::{CircleHit, OccSurface, SurfaceDerivs};
pub use topology::{CadTopology, Counts, Edge, EdgeUse, Face, Shell, Solid, Vertex};
