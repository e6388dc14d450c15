//! Native Ferguson geometry.
