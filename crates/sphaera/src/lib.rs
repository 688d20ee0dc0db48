//! # Sphaera
//!
//! Hierarchical, sphere-based approximation of triangle meshes: fast and certified distance
//! queries, bounding sphere-trees for collision detection, tolerance-bounded and
//! silhouette-aware simplification, and HAL trees.
//!
//! This crate is the facade: it re-exports the focused Sphaera crates under short module
//! names, and offers a [`prelude`] with the types almost every user needs. Depend on a
//! single crate (for example `sphaera-mesh`) if that is all you use.
//!
//! | module | crate | what it does |
//! |---|---|---|
//! | [`mesh`] | `sphaera-mesh` | indexed triangle meshes, half-edge topology, validation and repair, file I/O (OBJ, PLY, STL, OFF; glTF 2.0 with the default feature `gltf`), geometric primitives, the box tree and exact closest points, the `Surface` (inside test and closest points), winding numbers, surface sampling, sampled Hausdorff distances, procedural test shapes |
//! | `simplify` (feature `simplify`) | `sphaera-simplify` | edge-collapse simplification whose reported error bound holds in both directions (error spheres) |
//! | `sweep` (feature `sweep`) | `sphaera-sweep` | Meshsweeper: exact and anytime closest-point queries on the simplification hierarchy, with coherent sessions, motion, polylines and certified Hausdorff distances |
//! | `medial` (feature `medial`) | `sphaera-medial` | robust incremental 3D Delaunay tetrahedralization, its Voronoi dual, and the adaptive medial-axis approximation with guaranteed sample coverage |
//! | `spheretree` (feature `spheretree`) | `sphaera-spheretree` | sphere-trees for collision detection through one entry point (merge, burst, expand-select and combined reducers; octree, grid and Hubbard baselines), with coverage of the whole surface certified at every level, certified fit evaluation, traversal and exports |
//! | `hal` (feature `hal`) | `sphaera-hal` | HAL trees: hierarchical approximation and localization of polygons and polylines by signed discs, adaptive approximation by widths, hierarchical point inclusion and intersection detection, for polygons, polylines and closed genus-0 meshes |
//!
//! | `silhouette` (feature `silhouette`) | `sphaera-silhouette` | view-dependent distance-transform silhouette labels: camera sets with constant-time nearest views, conservative mesh mapping, exact Euclidean and chamfer distance transforms, labels for new views (the level of detail they guide is in progress) |
//!
//! See `docs/architecture.md` in the repository for how the crates fit together.
//!
//! # Quick start
//!
//! ```
//! use sphaera::prelude::*;
//!
//! let torus: TriMesh = sphaera::mesh::shapes::torus(1.0, 0.25, 32)?;
//! let report = sphaera::mesh::topology::analyze(&torus);
//! assert!(report.is_closed);
//! assert_eq!(report.genus, Some(1));
//! assert!(torus.bounding_box_diagonal() > 2.0);
//! # Ok::<(), MeshError>(())
//! ```
//!
//! # Feature flags
#![doc = document_features::document_features!()]

#[cfg(feature = "hal")]
pub use sphaera_hal as hal;
#[cfg(feature = "medial")]
pub use sphaera_medial as medial;
pub use sphaera_mesh as mesh;
#[cfg(feature = "silhouette")]
pub use sphaera_silhouette as silhouette;
#[cfg(feature = "simplify")]
pub use sphaera_simplify as simplify;
#[cfg(feature = "spheretree")]
pub use sphaera_spheretree as spheretree;
#[cfg(feature = "sweep")]
pub use sphaera_sweep as sweep;

/// The types almost every Sphaera user needs.
pub mod prelude {
    pub use sphaera_mesh::{Aabb, DVec3, Length, MeshError, Sphere, Surface, TriMesh};
}
