//! Writers and readers. Every file is written to a temporary file beside the target and then
//! renamed, so an interrupted run never leaves a half-written mesh where a good one was.
//!
//! Solver formats: [`write_volume`] (SU2, Gmsh MSH 4.1/2.2, MEDIT, VTU/VTK, UGRID with its
//! `.mapbc`, CGNS through the CGNS library, STL of the boundary) and [`write_surface`] for a surface mesh alone.

mod atomic;
mod bc_guess;
mod cells;
mod cgns;
mod cgns_lib;
mod format;
mod gmsh;
mod medit;
mod names;
mod stl;
mod su2;
mod ugrid;
pub mod vtk;
mod vtu_binary;
mod zlib_block;

pub use atomic::write_atomic;
pub use format::{mapbc_path, write_surface, write_volume, MeshFormat};
pub use names::clean_name;
