//! The classic `.sph` sphere-tree text format (work in progress).
