//! Geometric primitives every Sphaera crate needs.

mod triangle;

pub use triangle::Triangle;
