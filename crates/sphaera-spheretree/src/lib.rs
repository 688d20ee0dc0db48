//! # sphaera-spheretree
//!
//! Sphere-trees for time-critical collision detection, after Bradshaw and O'Sullivan
//! (*Adaptive Medial-Axis Approximation for Sphere-Tree Construction*, 2004): the
//! adaptive medial approximation of `sphaera-medial` reduced to a few spheres per node by
//! merge, burst, expand-select or their combination, with coverage of the surface itself
//! certified at every level, fit evaluation, and interruptible traversal.
//!
//! # Example
//!
//! One entry point, [`build`], takes the prepared [`Surface`] (its inside test and exact
//! closest points, built once) and the [`SphereTreeOptions`], whose [`Method`] picks a
//! medial reducer or a classic baseline. The same surface then evaluates the tree.
//!
//! ```
//! use sphaera_mesh::shapes;
//! use sphaera_spheretree::{
//!     EvaluationOptions, Method, SphereTreeOptions, Surface, build, evaluate_set,
//!     level_for_tolerance,
//! };
//!
//! let surface = Surface::new(&shapes::capsule(0.5, 2.0, 12)?)?;
//! let options = SphereTreeOptions::default()
//!     .with_method(Method::Expand)
//!     .with_depth(2)
//!     .with_branch(4)
//!     .with_samples(1_500)
//!     .with_initial_spheres(100)
//!     .with_min_spheres_per_node(30);
//! let tree = build(&surface, &options)?;
//! assert_eq!(tree.level_count(), 3);
//! // Every level covers the whole surface, certified piece by piece.
//! assert_eq!(tree.coverage().len(), 3);
//! // Errors shrink level by level; pick the shallowest level tight enough.
//! let worst = |l: usize| tree.level(l).iter().map(|n| n.error).fold(0.0, f64::max);
//! assert!(worst(2) < worst(0));
//! assert_eq!(level_for_tolerance(&tree, worst(1)), Some(1));
//! // The certified worst error of a level, from the same surface.
//! let fit = evaluate_set(&surface, &tree.level_spheres(2), &EvaluationOptions::default())?;
//! assert!(fit.worst_lower <= fit.worst_upper);
//! assert_eq!(fit.coverage.uncovered, 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # What every medial tree guarantees
//!
//! - Every level covers the whole surface, certified piece by piece ([`cover`]).
//! - Every node has a positive radius covering its samples: a one-sample region gets
//!   the ball of half the sample spacing around its sample, not a point.
//! - No child is built looser than its parent: its eq. 2 error, an upper bound on its
//!   certified error, never exceeds a lower bound on the parent's certified error. The
//!   coverage certificate may then grow spheres: by about the resolution where spheres
//!   barely overlap, by a gap's size where there was a gap (with few samples per node, a
//!   level can end up looser than its parent; at the default 10,000 samples every
//!   shared mesh is monotone).
//! - The same input, options and seed give the same tree, with or without `parallel`.
//! - The tree moves with the mesh: it is built in the mesh's canonical pose
//!   ([`sphaera_mesh::geometry::CanonicalPose`]: a frame taken from the mesh's own
//!   vertices, coordinates snapped to a grid far coarser than rounding), so a mesh
//!   turned, rescaled or moved by any similarity gives the same tree mapped, to rounding
//!   (unless the transform's own rounding crosses the grid: a mesh moved 10⁶ of its sizes
//!   away has lost 20 bits to the move). Scaling by a power of two gives every number
//!   scaled, bit for bit.
//!
//! The default [`Method::Auto`] runs expand-select per node and merge only where
//! expand-select's children are looser than their parent, at an error fraction of ⅛
//! ([`SphereTreeOptions::error_fraction`]); the paper's reducers stay available by name.
//!
//! # Feature flags
#![doc = document_features::document_features!()]

mod baseline;
mod build;
pub mod collide;
pub mod cover;
mod error;
pub mod evaluate;
pub mod export;
mod options;
pub mod reduce;
pub mod segment;
pub mod select;
mod tree;

pub use build::{build, build_with_progress};
pub use collide::{Budget, Collision, Contact, CostModel, Similarity, collide, overlaps};
pub use cover::CoverageCertificate;
pub use error::SphereTreeError;
pub use evaluate::{EvaluationOptions, SetEvaluation, SphereFit, evaluate_set};
pub use glam::DVec3;
pub use options::{
    MAX_BASELINE_DEPTH, MAX_BASELINE_SAMPLES, Method, SphereTreeOptions, SphereTreeProgress,
};
pub use select::{Cut, cut_for_tolerance, level_for_tolerance};
pub use sphaera_mesh::{Sphere, Surface};
pub use tree::{SphereTree, TreeDefect, TreeNode};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
