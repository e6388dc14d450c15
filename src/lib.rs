//! tetrafoil: unstructured tetrahedral mesh generation with directional refinement for
//! aerodynamic CFD, after Peraire & Morgan. See `ARCHITECTURE.md` for the map of the code.

pub mod case;
pub mod cli;
pub mod curve;
pub mod geometry;
pub mod io;
pub mod mesh;
pub mod model;
pub mod pipeline;
pub mod prisms;
pub mod progress;
pub mod refine;
pub mod samples;
pub mod service;
pub mod sizing;
pub mod surface;
pub mod volume;
