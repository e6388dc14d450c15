//! Output mesh types, validity checks and quality measures.

pub mod quality;
