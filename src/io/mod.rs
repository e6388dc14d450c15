//! Writers and readers. Every file is written to a temporary file beside the target and then
//! renamed, so an interrupted run never leaves a half-written mesh where a good one was.

mod atomic;
pub mod vtk;

pub use atomic::write_atomic;
