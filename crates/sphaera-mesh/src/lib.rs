//! # sphaera-mesh
//!
//! The kernel of Sphaera: the indexed triangle mesh every crate works on, validation, an
//! editable half-edge topology, explicit repair, geometric primitives, priority queues and
//! procedural test shapes. Files are read and written by `sphaera-io`; spatial queries
//! (box tree, closest points, winding numbers, the `Surface`, sampling, sampled Hausdorff
//! distances) live in `sphaera-query`.
//!
//! It implements no single paper; it is the ground that the implementations of Meshsweeper
//! (Guéziec 2000), the medial-axis sphere-trees of Bradshaw & O'Sullivan (2004), HAL trees
//! (Veltkamp) and silhouette labels (Mata, Pastor & Rodríguez) stand on. Where a method is
//! from the literature, its module cites it.
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{TriMesh, geometry, shapes, topology};
//!
//! // A closed torus: genus 1, one component, no boundary.
//! let torus: TriMesh = shapes::torus(1.0, 0.3, 48)?;
//! let report = topology::analyze(&torus);
//! assert!(report.is_closed && report.is_manifold);
//! assert_eq!(report.genus, Some(1));
//! assert_eq!(report.euler_characteristic, 0);
//!
//! // The minimum enclosing ball of the vertices contains every vertex.
//! let ball = geometry::minimum_enclosing_ball(torus.positions())?;
//! assert!(torus.positions().iter().all(|&p| ball.contains_point(p, 0.0)));
//! # Ok::<(), sphaera_mesh::MeshError>(())
//! ```
//!
//! # What is where
//!
//! | module | what it holds |
//! |---|---|
//! | crate root | [`TriMesh`] (finite `f64` positions, in-range `[u32; 3]` triangles), [`Sphere`] (the one sphere type of the workspace), [`Aabb`], [`Length`] (absolute or relative to the diagonal), [`MeshError`] |
//! | [`topology`] | [`topology::analyze`]: closed, manifold, oriented, genus, components, boundary loops, Euler characteristic, degenerate and duplicate triangles, for any mesh; [`topology::HalfEdgeMesh`]: editable half-edges with edge collapse and its exact inverse, vertex split; repair helpers (weld, drop degenerate / duplicate triangles, drop unreferenced vertices) that report what they changed |
//! | [`geometry`] | closest point on a triangle (with the feature hit) and on a segment, segment–segment closest points, minimum enclosing ball of points and of balls, circumspheres, ray–triangle intersection, similarity transforms (placing a mesh or spheres in a scene; rigid motions) |
//! | [`heap`] | priority queues with one convention (the highest [`heap::Priority`] first): a binary max-heap and an indexed heap of one item per id |
//! | [`shapes`] | closed procedural shapes with a resolution: cube, sphere, ellipsoid, capsule, cylinder, cone, torus, thick-walled tube, S tube, L block; small fixed meshes for tests (`shapes::fixtures`, feature `fixtures`) |
//!
//! # Algorithm notes
//!
//! - **Topology** is computed after merging bit-identical positions (OBJ exporters split
//!   vertices at texture seams), edges are matched by sorting, components are
//!   edge-connected; the numbers agree with trimesh/pymeshlab on all 39 meshes of the
//!   project's test data (a test checks it).
//! - **Half-edges**: face `f` owns half-edges `3f..3f+2`; non-manifold input is accepted by
//!   leaving extra faces on an edge unpaired and splitting non-manifold vertices into one
//!   copy per fan, flagged so editors lock them.
//! - **Minimum enclosing balls** are exact (every input inside, radius optimal to 1e-12
//!   relative): a pivoting loop over support sets of at most four, solved exhaustively.
//!
//! # Errors
//!
//! Every fallible function returns [`MeshError`]. Variants are structured and say what
//! was wrong and where: the vertex and axis of a NaN coordinate, the triangle of an
//! out-of-range index, the half-edge of a refused collapse. Library code does not panic on
//! user input.
//!
//! # Performance
//!
//! Topology and the half-edge mesh are linear in the size of the mesh; the measured times on
//! the 871k-triangle dragon are in the repository's `docs/benchmarks.md` (section
//! "Loading and topology", `cargo bench -p sphaera-io --bench load_topology`).
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! The facade crate `sphaera` re-exports this crate as `sphaera::mesh` (with `sphaera-io`
//! and `sphaera-query` beside it, and under their old paths `sphaera::mesh::io`,
//! `sphaera::mesh::winding`...). Later crates of the workspace (`sphaera-simplify`,
//! `sphaera-sweep`, `sphaera-medial`, `sphaera-spheretree`, `sphaera-hal`,
//! `sphaera-silhouette`) all take a [`TriMesh`].

mod aabb;
mod error;
pub mod geometry;
pub mod heap;
mod length;
mod mesh;
mod name;
pub mod shapes;
mod sphere;
pub mod topology;

pub use aabb::Aabb;
pub use error::MeshError;
pub use glam;
pub use glam::DVec3;
pub use length::{Length, ParseLengthError};
pub use mesh::TriMesh;
pub use name::ParseNameError;
pub use sphere::Sphere;

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
