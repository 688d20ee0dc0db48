//! # sphaera-query
//!
//! Spatial queries on triangle meshes for Sphaera: the box tree, exact closest points
//! ([`closest::TriangleTree`] and its cursor), inside/outside by the generalized winding
//! number, the [`Surface`] (a mesh as the boundary of a solid: its inside test, closest
//! points and signed closest points), seeded surface sampling and sampled Hausdorff
//! distances. It stands on `sphaera-mesh`'s [`TriMesh`](sphaera_mesh::TriMesh) and reads
//! no files.
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_query::{Surface, closest::TriangleTree, sampling, winding::WindingNumber};
//!
//! let torus = shapes::torus(1.0, 0.3, 48)?;
//!
//! // Inside/outside by the generalized winding number: the tube is inside, the hole is not.
//! let inside = WindingNumber::new(&torus)?;
//! assert!(inside.is_inside(DVec3::new(1.0, 0.0, 0.0)));
//! assert!(!inside.is_inside(DVec3::ZERO));
//!
//! // The exact closest point on the surface, and the same through a `Surface`.
//! let tree = TriangleTree::new(&torus)?;
//! let hit = tree.closest(DVec3::new(2.0, 0.0, 0.0))?;
//! assert!((hit.distance - 0.7).abs() < 1e-2);
//! let surface = Surface::new(&torus)?;
//! assert!(surface.is_inside(DVec3::new(1.0, 0.0, 0.0)));
//!
//! // 2,000 evenly spread surface samples, the same for the same seed.
//! let samples = sampling::poisson_disk(&torus, 2_000, 7)?;
//! assert_eq!(samples.samples.len(), 2_000);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # What is where
//!
//! | module | what it holds |
//! |---|---|
//! | [`bvh`] | the workspace's one bounding-volume hierarchy: a box tree over items, built by median splits, with a nearest-first search |
//! | [`closest`] | exact closest points on a mesh: [`closest::TriangleTree`] and its [`closest::ClosestPoint`] with the mesh [`closest::Feature`] hit |
//! | [`grid`] | the workspace's one uniform grid: items (points, spheres, boxes) listed in the cells their boxes meet, for "what can be near here" queries |
//! | [`winding`] | generalized winding number, brute force and hierarchically accelerated (Barill et al. 2018), ray-parity reference, a solidity check |
//! | [`surface`] | [`Surface`]: a mesh as the boundary of a solid, its inside test, closest points and signed closest points ([`Surface::signed_closest`]: exact pseudo-normal test on a certified embedded solid, certified winding number otherwise), the embedded-solid certificate and its [`surface::EmbeddingDefect`] |
//! | [`sampling`] | seeded area-weighted random and Poisson-disk (sample elimination, Yuksel 2015) surface samples |
//! | [`hausdorff`] | certified Hausdorff distances between two meshes from a triangle tree of each, on every core; the types and upper bounds `sphaera-sweep`'s paper engine shares |
//! | [`measure`] | sampled Hausdorff distance between two surfaces, a lower bound of the true one: the sample set of a surface (referenced vertices, edge midpoints, seeded random points), directed and symmetric maxima over any distance oracle, exact by default through [`closest::TriangleTree`] |
//!
//! # Algorithm notes
//!
//! - **Winding numbers** use Van Oosterom–Strackee solid angles and a box tree with
//!   far-field dipole expansions; a certified mode bounds the approximation error.
//! - **Closest points** descend the box tree nearest-first with exact point–triangle
//!   distances; a cursor keeps its answer for a point that moves a little.
//!
//! # Errors
//!
//! Every fallible function returns [`QueryError`]; invalid meshes surface as
//! [`QueryError::Mesh`]. Library code does not panic on user input.
//!
//! Parameters that size memory are checked against documented caps before anything is
//! allocated, and refused with [`QueryError::InvalidParameter`] naming the parameter and
//! the cap: sample counts ([`MAX_SAMPLES`]), a Hausdorff sample budget
//! ([`MAX_HAUSDORFF_SAMPLES`]), a uniform grid's cells ([`MAX_GRID_CELLS`]).
//!
//! # Feature flags
#![doc = document_features::document_features!()]

pub mod bvh;
pub mod closest;
mod error;
pub mod grid;
pub mod hausdorff;
pub mod measure;
pub mod sampling;
pub mod surface;
pub mod winding;

pub use error::QueryError;
pub use grid::MAX_GRID_CELLS;
pub use hausdorff::MAX_HAUSDORFF_SAMPLES;
pub use sampling::MAX_SAMPLES;
pub use surface::Surface;

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
