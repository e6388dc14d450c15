//! tetrafoil library.
