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
//! | [`mesh`] | `sphaera-mesh` | indexed triangle meshes, half-edge topology, validation and repair, file I/O, geometric primitives, the box tree and exact closest points, the `Surface` (inside test and closest points), winding numbers, surface sampling, sampled Hausdorff distances, procedural test shapes |
//! | `simplify` (feature `simplify`) | `sphaera-simplify` | edge-collapse simplification whose reported error bound holds in both directions (error spheres) |
//! | `sweep` (feature `sweep`) | `sphaera-sweep` | Meshsweeper: exact and anytime closest-point queries on the simplification hierarchy, with coherent sessions, motion, polylines and certified Hausdorff distances |
//! | `medial` (feature `medial`) | `sphaera-medial` | robust incremental 3D Delaunay tetrahedralization, its Voronoi dual, and the adaptive medial-axis approximation with guaranteed sample coverage |
//! | `spheretree` (feature `spheretree`) | `sphaera-spheretree` | sphere-trees for collision detection through one entry point (merge, burst, expand-select and combined reducers; octree, grid and Hubbard baselines), with coverage of the whole surface certified at every level, certified fit evaluation, traversal and exports |
//! | `hal` (feature `hal`) | `sphaera-hal` | HAL trees: hierarchical approximation and localization of polygons and polylines by signed discs, adaptive approximation by widths, hierarchical point inclusion and intersection detection, for polygons, polylines and closed genus-0 meshes |
//! | `silhouette` (feature `silhouette`) | `sphaera-silhouette` | view-dependent distance-transform silhouette labels: camera sets with constant-time nearest views, conservative mesh mapping, exact Euclidean and chamfer distance transforms, labels for new views, and the silhouette-preserving level of detail they guide, with a certified bound per region |
//!
//! Each module's documentation is its crate's: what it does and which paper it implements
//! (Guéziec's Meshsweeper, Bradshaw and O'Sullivan's adaptive medial-axis sphere-trees,
//! Veltkamp's HAL trees, Mata, Pastor and Rodríguez's distance labels), a quick start,
//! the algorithm, errors and measured performance. See `docs/architecture.md` in the
//! repository for how the crates fit together.
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
//! # Errors
//!
//! Each module returns its own crate's error enum (`mesh::MeshError`,
//! `simplify::SimplifyError`, `sweep::SweepError`, `medial::MedialError` and
//! `medial::DelaunayError`, `spheretree::SphereTreeError`, `hal::HalError`,
//! `silhouette::SilhouetteError`); each is `#[non_exhaustive]`, says what was wrong and
//! where, and none of the crates panics on user input.
//!
//! # Performance
//!
//! The facade adds nothing at run time. Each crate's documentation gives its measured
//! figures, and the repository's `docs/benchmarks.md` has them all, with the machine, the
//! date and the command that made each number, beside the peer libraries measured in the
//! same run.
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! The `sphaera` command-line tool (`sphaera-cli`), one subcommand per capability, and
//! the single crates above for users who need only one of them.

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

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
