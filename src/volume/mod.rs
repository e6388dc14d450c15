//! Volume meshing: the Delaunay kernel and, later, boundary recovery, interior points,
//! region marking and mesh improvement (DESIGN.md, pipeline step 5).

pub mod delaunay;
pub mod recover;
