//! # sphaera-spheretree
//!
//! Sphere-trees for time-critical collision detection, after Bradshaw and O'Sullivan
//! (*Adaptive Medial-Axis Approximation for Sphere-Tree Construction*, 2004): the
//! adaptive medial approximation of `sphaera-medial` reduced to a few spheres per node by
//! merge, burst, expand-select or their combination, with coverage of the surface itself
//! certified at every level, fit evaluation, and interruptible traversal.

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
pub use collide::{Budget, Collision, Contact, CostModel, Placement, collide, overlaps};
pub use cover::CoverageCertificate;
pub use error::SphereTreeError;
pub use evaluate::{EvaluationOptions, SetEvaluation, SphereFit, evaluate_set};
pub use glam::DVec3;
pub use reduce::Reducer;
pub use select::{Cut, cut_for_tolerance, level_for_tolerance};
pub use sph::{SphFile, read_sph, write_sph};
pub use sphaera_mesh::Sphere;
pub use tree::{SphereTree, TreeNode};
