//! # sphaera-mesh
//!
//! The indexed triangle mesh every Sphaera crate works on, and everything around it that
//! the hierarchical sphere-based methods need: validation, an editable half-edge topology,
//! explicit repair, file I/O, geometric primitives, inside/outside by the generalized
//! winding number, seeded surface sampling and procedural test shapes.
//!
//! It implements no single paper; it is the ground that the implementations of Meshsweeper
//! (Guéziec 2000), the medial-axis sphere-trees of Bradshaw & O'Sullivan (2004), HAL trees
//! (Veltkamp) and silhouette labels (Mata, Pastor & Rodríguez) stand on. Where a method is
//! from the literature, its module cites it.
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{DVec3, TriMesh, geometry, sampling, shapes, topology, winding};
//!
//! // A closed torus: genus 1, one component, no boundary.
//! let torus: TriMesh = shapes::torus(1.0, 0.3, 48)?;
//! let report = topology::analyze(&torus);
//! assert!(report.is_closed && report.is_manifold);
//! assert_eq!(report.genus, Some(1));
//! assert_eq!(report.euler_characteristic, 0);
//!
//! // Inside/outside by the generalized winding number: the tube is inside, the hole is not.
//! let inside = winding::WindingNumber::new(&torus)?;
//! assert!(inside.is_inside(DVec3::new(1.0, 0.0, 0.0)));
//! assert!(!inside.is_inside(DVec3::ZERO));
//!
//! // 2,000 evenly spread surface samples, the same for the same seed.
//! let samples = sampling::poisson_disk(&torus, 2_000, 7)?;
//! assert_eq!(samples.samples.len(), 2_000);
//!
//! // The minimum enclosing ball of the vertices contains every vertex.
//! let ball = geometry::minimum_enclosing_ball(torus.positions())?;
//! assert!(torus.positions().iter().all(|&p| ball.contains_point(p, 0.0)));
//! # Ok::<(), sphaera_mesh::MeshError>(())
//! ```
//!
//! Reading a file is one call; malformed files give an error with the line or byte offset:
//!
//! ```
//! use sphaera_mesh::io::{self, Format};
//!
//! let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
//! let loaded = io::read_from_bytes(obj, Format::Obj)?;
//! assert_eq!(loaded.mesh.triangle_count(), 4);
//!
//! let err = io::read_from_bytes(b"v 0 0 0\nv 1 0 0\nf 1 2\n", Format::Obj).unwrap_err();
//! assert!(err.to_string().contains("line 3"), "{err}");
//! # Ok::<(), sphaera_mesh::MeshError>(())
//! ```
//!
//! # What is where
//!
//! | module | what it holds |
//! |---|---|
//! | crate root | [`TriMesh`] (finite `f64` positions, in-range `[u32; 3]` triangles), [`Sphere`] (the one sphere type of the workspace), [`Aabb`], [`Length`] (absolute or relative to the diagonal), [`Surface`] (a mesh with its inside test and closest points, checked for a meaningful inside), [`MeshError`] |
//! | [`topology`] | [`topology::analyze`]: closed, manifold, oriented, genus, components, boundary loops, Euler characteristic, degenerate and duplicate triangles, for any mesh; [`topology::HalfEdgeMesh`]: editable half-edges with edge collapse and its exact inverse, vertex split; repair helpers (weld, drop degenerate / duplicate triangles, drop unreferenced vertices) that report what they changed |
//! | [`io`] | read OBJ, PLY (ASCII, binary), STL (ASCII, binary), OFF, glTF 2.0 (`.gltf`, `.glb`: the default scene's triangle meshes placed by their nodes, behind the default `gltf` feature); write OBJ and PLY (with per-vertex colours); polygons triangulated; atomic writes |
//! | [`geometry`] | closest point on a triangle (with the feature hit) and on a segment, segment–segment closest points, minimum enclosing ball of points and of balls, circumspheres, ray–triangle intersection, similarity transforms (placing a mesh or spheres in a scene; rigid motions) |
//! | [`bvh`] | the workspace's one bounding-volume hierarchy: a box tree over items, built by median splits, with a nearest-first search |
//! | [`closest`] | exact closest points on a mesh: [`closest::TriangleTree`] and its [`closest::ClosestPoint`] with the mesh [`closest::Feature`] hit |
//! | [`surface`] | [`Surface`]: a mesh as the boundary of a solid, its inside test, closest points and signed closest points ([`Surface::signed_closest`]: exact pseudo-normal test on a certified embedded solid, certified winding number otherwise), the embedded-solid certificate and its [`surface::EmbeddingDefect`] |
//! | [`heap`] | priority queues with one convention (the highest [`heap::Priority`] first): a binary max-heap and an indexed heap of one item per id |
//! | [`winding`] | generalized winding number, brute force and hierarchically accelerated (Barill et al. 2018), ray-parity reference, a solidity check |
//! | [`sampling`] | seeded area-weighted random and Poisson-disk (sample elimination, Yuksel 2015) surface samples |
//! | [`measure`] | sampled Hausdorff distance between two surfaces, a lower bound of the true one: the sample set of a surface (referenced vertices, edge midpoints, seeded random points), directed and symmetric maxima over any distance oracle, exact by default through [`closest::TriangleTree`] |
//! | [`shapes`] | closed procedural shapes with a resolution: cube, sphere, ellipsoid, capsule, cylinder, cone, torus, thick-walled tube, S tube, L block |
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
//! - **Winding numbers** use Van Oosterom–Strackee solid angles and a BVH with far-field
//!   dipole expansions; a certified mode bounds the approximation error.
//!
//! # Errors
//!
//! Every fallible function returns [`MeshError`]. Variants are structured and say what
//! was wrong and where: the vertex and axis of a NaN coordinate, the triangle of an
//! out-of-range index, the file, line (text formats) or byte offset (binary formats) and
//! reason of a malformed file. Library code does not panic on user input.
//!
//! # Performance
//!
//! Reading and topology are linear in the size of the mesh. Measured on the 2-core
//! reference machine with criterion (2026-11-21,
//! `cargo bench -p sphaera-mesh --bench load_topology`; see `docs/benchmarks.md` in the
//! repository): the 871,414-triangle Stanford dragon (33 MB ASCII PLY) reads in about
//! 0.14 s, its topology report takes about 0.16 s, and its half-edge mesh builds in about
//! 0.11 s.
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! The facade crate `sphaera` re-exports this crate as `sphaera::mesh`. Later crates of
//! the workspace (`sphaera-simplify`, `sphaera-sweep`, `sphaera-medial`,
//! `sphaera-spheretree`, `sphaera-hal`, `sphaera-silhouette`) all take a [`TriMesh`].

mod aabb;
pub mod bvh;
pub mod closest;
mod error;
pub mod geometry;
pub mod heap;
pub mod io;
mod length;
pub mod measure;
mod mesh;
pub mod sampling;
pub mod shapes;
mod sphere;
pub mod surface;
#[cfg(test)]
mod test_meshes;
pub mod topology;
pub mod winding;

pub use aabb::Aabb;
pub use error::MeshError;
pub use glam;
pub use glam::DVec3;
pub use length::{Length, ParseLengthError};
pub use mesh::TriMesh;
pub use sphere::Sphere;
pub use surface::Surface;

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
