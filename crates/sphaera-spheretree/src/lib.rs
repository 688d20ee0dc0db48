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
//! ```
//! use sphaera_mesh::shapes;
//! use sphaera_spheretree::{Params, Reducer, build, level_for_tolerance};
//!
//! let capsule = shapes::capsule(0.5, 2.0, 12)?;
//! let params = Params::default()
//!     .reducer(Reducer::Expand)
//!     .depth(2)
//!     .branch(4)
//!     .samples(1_500)
//!     .initial_spheres(100)
//!     .min_spheres_per_node(30);
//! let tree = build(&capsule, &params)?;
//! assert_eq!(tree.level_count(), 3);
//! // Every level covers the whole surface, certified piece by piece.
//! assert_eq!(tree.coverage().len(), 3);
//! // Errors shrink level by level; pick the shallowest level tight enough.
//! let worst = |l: usize| tree.level(l).iter().map(|n| n.error).fold(0.0, f64::max);
//! assert!(worst(2) < worst(0));
//! assert_eq!(level_for_tolerance(&tree, worst(1)), Some(1));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod baseline;
mod build;
pub mod collide;
pub mod cover;
mod error;
pub mod evaluate;
pub mod export;
pub mod reduce;
pub mod segment;
pub mod select;
pub mod sph;
mod tree;

pub use build::{BuildProgress, Params, build, build_with_progress};
pub use collide::{Budget, Collision, Contact, CostModel, Similarity, collide, overlaps};
pub use cover::CoverageCertificate;
pub use error::SphereTreeError;
pub use evaluate::{EvaluationOptions, SetEvaluation, SphereFit, evaluate_set};
pub use glam::DVec3;
pub use reduce::Reducer;
pub use select::{Cut, cut_for_tolerance, level_for_tolerance};
pub use sph::{SphFile, read_sph, write_sph};
pub use sphaera_mesh::Sphere;
pub use tree::{SphereTree, TreeNode};
