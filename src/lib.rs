//! tetrafoil library.
pub mod volume;
