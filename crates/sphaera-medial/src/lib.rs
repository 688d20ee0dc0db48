//! # sphaera-medial
//!
//! A robust incremental 3D Delaunay tetrahedralization with its Voronoi dual, and the
//! adaptive medial-axis approximation of Bradshaw and O'Sullivan (*Adaptive Medial-Axis
//! Approximation for Sphere-Tree Construction*, 2004, section 4) built on it.
//!
//! ```
//! use sphaera_medial::{DVec3, Delaunay};
//!
//! // A 5×5×5 grid: every cell's corners are cospherical, yet the result is valid.
//! let grid: Vec<DVec3> = (0..125)
//!     .map(|i| DVec3::new(f64::from(i % 5), f64::from(i / 5 % 5), f64::from(i / 25)))
//!     .collect();
//! let delaunay = Delaunay::new(&grid)?;
//! delaunay.validate()?;
//! // Every tetrahedron has positive volume and they fill the 4×4×4 box.
//! let volume: f64 = delaunay
//!     .tetrahedra()
//!     .map(|(_, t)| {
//!         let [a, b, c, d] = t.map(|v| delaunay.point(v));
//!         (b - a).cross(c - a).dot(d - a) / 6.0
//!     })
//!     .sum();
//! assert!((volume.abs() - 64.0).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Feature flags
#![doc = document_features::document_features!()]

pub mod delaunay;
mod error;
pub mod medial;

pub use delaunay::{Delaunay, INFINITE, Insertion, TetId, VoronoiCell};
pub use error::{DelaunayError, MedialError, Violation};
pub use glam::DVec3;
pub use medial::{
    CoverCriterion, MedialApproximation, MedialOptions, MedialProgress, MedialSphere, MedialStats,
    RegionOptions, RegionOutcome, SphereKind,
};
/// The mesh a medial approximation describes (defined in `sphaera-mesh`): its inside test
/// and exact closest points.
pub use sphaera_mesh::Surface;

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
