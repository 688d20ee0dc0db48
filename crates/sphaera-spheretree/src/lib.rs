//! # sphaera-spheretree
//!
//! Sphere-trees for time-critical collision detection: a hierarchy of spheres around a
//! triangle mesh whose every level covers the whole surface and fits it more tightly
//! than the level above, so that a collision test can stop at any level and still have
//! an answer with a known error. This crate implements G. Bradshaw and C. O'Sullivan,
//! *Adaptive Medial-Axis Approximation for Sphere-Tree Construction* (ACM Transactions on
//! Graphics 23(1), 2004): the adaptive medial-axis approximation of [`sphaera_medial`],
//! refined in each node's part of the surface and reduced to a few children by the
//! paper's **merge**, **burst**, **expand-select** or **combined** reducers, beside the
//! classic octree, grid and Hubbard constructions the paper compares against. Beyond the
//! paper, coverage of the surface itself (not only of its samples) is certified at every
//! level, every sphere's error is certified by branch and bound, and the tree is built
//! in the mesh's canonical pose, so it turns, scales and moves with the mesh.
//!
//! Around the construction: certified fit evaluation ([`evaluate`]), the shallowest level
//! or smallest cut that meets a tolerance ([`select`]), interruptible tree-against-tree
//! traversal under rigid motions ([`collide`](mod@collide)) and exports to JSON, the
//! original toolkit's `.sph`, robot planners' collision-sphere YAML and parry3d
//! ([`export`]).
//!
//! # Quick start
//!
//! One entry point, [`build`], takes the prepared [`Surface`] (its inside test and exact
//! closest points, built once) and the [`SphereTreeOptions`], whose [`Method`] picks a
//! medial reducer or a classic baseline. The same surface then evaluates the tree. (The
//! options below are small so that the example runs fast; the defaults are the paper's
//! depth 3, branch 8 and 10,000 samples.)
//!
//! ```
//! use sphaera_mesh::shapes;
//! use sphaera_spheretree::{
//!     Budget, DVec3, EvaluationOptions, Method, Similarity, SphereTreeOptions, Surface, build,
//!     collide, evaluate_set, level_for_tolerance,
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
//! // Two copies 0.9 apart (the capsule is 1 wide) touch: contacts at the deepest level.
//! let near = Similarity::from_translation(DVec3::new(0.9, 0.0, 0.0))?;
//! let hit = collide(&tree, &Similarity::IDENTITY, &tree, &near, &Budget::Unlimited)?;
//! assert!(hit.completed && hit.level == 2 && !hit.contacts.is_empty());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # How it works
//!
//! The paper's Algorithm 1, for the medial methods ([`Method::is_medial`]):
//!
//! 1. **Samples.** The surface is represented by [`SphereTreeOptions::samples`]
//!    Poisson-disk samples ([`sphaera_mesh::sampling::poisson_disk`]); each stands for
//!    the surface within half the sample spacing of it. A node's *region* is the set of
//!    samples it must cover.
//! 2. **Root.** The minimum enclosing ball of the mesh's vertices
//!    ([`sphaera_mesh::geometry::minimum_enclosing_ball`]), whose region is every sample.
//! 3. **Medial spheres.** An adaptive medial approximation of
//!    [`SphereTreeOptions::initial_spheres`] spheres
//!    ([`build`](sphaera_medial::MedialApproximation::build)):
//!    spheres centred on the inner Voronoi vertices of the samples, covering every
//!    sample. It is shared by the whole construction and refined as it goes.
//! 4. **Each level, each parent.** The medial approximation is refined inside the
//!    parent's region ([`refine_region`](sphaera_medial::MedialApproximation::refine_region))
//!    until it holds [`SphereTreeOptions::min_spheres_per_node`] spheres there whose error
//!    is at most [`SphereTreeOptions::error_fraction`] of the parent's. A reducer then
//!    turns those spheres into at most [`SphereTreeOptions::branch`] spheres covering the
//!    region ([`reduce`]: [`reduce::merge`] combines neighbouring pairs, [`reduce::burst`]
//!    removes spheres and grows their neighbours over the gap, [`reduce::expand_select`]
//!    expands every sphere to a common standoff and selects a covering subset,
//!    [`reduce::combined`] runs merge and expand-select and keeps the tighter set). The
//!    region is divided between the children ([`segment::divide`]): a sample covered by
//!    several goes to the one of smallest power distance, and the dividing planes are
//!    moved (Nelder–Mead over the power weights) to balance the children's regions, as
//!    the paper's section 3.1 asks. A child gets a positive radius and is never looser
//!    than its parent (below).
//! 5. **Coverage.** Each finished level is certified to cover every point of every
//!    triangle ([`cover::certify_coverage`]): triangles are split until each piece lies
//!    in one sphere, and where none holds a piece at the resolution, the sphere needing
//!    the least growth grows by exactly that ([`CoverageCertificate`] records it).
//!
//! A node's error ([`TreeNode::error`]) is the paper's eq. 2: for a centre inside the
//! object, the radius minus the centre's distance to the surface, an upper bound on how
//! far the sphere pokes out of the object. [`evaluate_set`] certifies the true value,
//! the largest distance from a point of the sphere outside the object to the surface, as
//! an interval at most a tolerance wide (branch and bound over the sphere's surface,
//! see [`evaluate`]). The baselines ([`Method::Octree`], [`Method::Grid`],
//! [`Method::Hubbard`]) are the classic constructions as published: same tree structure
//! and samples, coverage measured but not certified.
//!
//! Using a tree: [`level_for_tolerance`] and [`cut_for_tolerance`] pick the coarsest
//! detail whose worst error meets a tolerance ("model no more than the scene needs");
//! [`collide`](fn@collide) descends two placed trees breadth-first, a level at a time, so
//! that it can stop when a [`Budget`] (the paper's cost model, or wall time) runs out and
//! still report contacts with an error bound; [`overlaps`] answers yes or no, depth-first.
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
//! # Errors
//!
//! Every fallible function returns [`SphereTreeError`]; library code does not panic on
//! user input. The variants a caller meets most:
//!
//! - [`SphereTreeError::InvalidParameter`]: an option out of its domain (a zero branch
//!   factor, fewer than 4 samples, an error fraction outside `(0, 1]`, an evaluation
//!   tolerance that is not finite and positive), with the parameter's name, value and
//!   requirement;
//! - [`SphereTreeError::Mesh`]: the mesh cannot be sampled (no area) or a transform is
//!   not a similarity (a mesh without a meaningful inside is refused earlier, by
//!   [`Surface::new`]);
//! - [`SphereTreeError::Medial`]: the medial approximation cannot start (fewer than four
//!   distinct, non-coplanar samples);
//! - [`SphereTreeError::InvalidSphere`] and [`SphereTreeError::EmptySphereSet`]: spheres
//!   given to an evaluation or an export that are not spheres, or none;
//! - [`SphereTreeError::SphSyntax`], [`SphereTreeError::Json`] and
//!   [`SphereTreeError::InvalidTree`]: a file that cannot be read back, with the line and
//!   what is wrong.
//!
//! # Performance
//!
//! The build time follows the number of samples, not the mesh's size: the medial
//! refinement and the reductions work on samples and medial spheres, and the mesh is
//! touched through the [`Surface`]'s trees (closest points and winding numbers, typically
//! logarithmic in the triangle count per query). Measured on the 2-core reference machine
//! (2026-11-25, `cargo run --release -p sphaera-cli -- spheretree MESH --json -q`, the
//! default options: `auto`, depth 3, branch 8, 10,000 samples):
//!
//! | mesh | build | evaluation of every level | certified worst error, L1 / L2 / L3 |
//! |---|---:|---:|---|
//! | low-res bunny (3,674 triangles) | 1.9 s | 1.1 s | 9.10 / 3.79 / 1.45 % of the diagonal |
//! | Stanford bunny (69k triangles) | 3.0 s | 0.7 s | 10.12 / 4.34 / 3.63 % |
//! | Stanford dragon (871k triangles) | 7.3–7.7 s | 2.8 s | 13.12 / 6.67 / 4.29 % |
//!
//! On the low-res bunny the paper's authors' toolkit takes 100–170 s of CPU for
//! 10.26 / 3.73 / 2.09 % at best and leaves 1.3–1.6 % of the surface outside its
//! level-3 spheres; every medial method here leaves none. With the paper's settings
//! (error fraction ½; criterion, `cargo bench -p sphaera-spheretree --bench spheretree`,
//! 2026-11-21) the reducers take 0.73 s (burst) to 1.97 s (combined) on the same mesh,
//! the octree 72 ms and the grid 139 ms. Over 20 random similarity transforms of four
//! meshes, a level's worst error varies by at most 7.3 % (2026-11-25). A collision
//! traversal of two such trees takes microseconds (see the performance section of
//! [`collide`](fn@collide)). Every figure, with the command that made it, the charts of
//! error against level and against time, and what was tried, is in the repository's
//! `docs/benchmarks.md` (sections "Sphere-trees" and "Issue 16").
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! - [`sphaera_medial`]: the Delaunay tetrahedralization and the adaptive medial-axis
//!   approximation the medial methods refine, usable on their own.
//! - [`sphaera_mesh`]: the [`Surface`] (inside test and exact closest points), sampling,
//!   [`Similarity`] transforms and the procedural test shapes.
//! - `sphaera-sweep`: certified closest points and Hausdorff distances on the same meshes;
//!   `sphaera-hal`: HAL trees, another hierarchy of signed balls (Veltkamp).
//! - `sphaera` (the facade, as `sphaera::spheretree`) and the `sphaera spheretree`
//!   command of `sphaera-cli`, which builds, evaluates and writes a tree from a mesh file.

mod baseline;
mod build;
pub mod collide;
pub mod cover;
mod error;
pub mod evaluate;
pub mod export;
pub mod minimax;
mod options;
pub mod reduce;
pub mod segment;
pub mod select;
mod tree;

pub use build::{build, build_with_progress};
pub use collide::{
    Budget, Collision, Contact, CostModel, Similarity, Traversal, TraversalStats, collide, overlaps,
};
pub use cover::CoverageCertificate;
pub use error::SphereTreeError;
pub use evaluate::{
    EvaluationOptions, SetEvaluation, SphereFit, evaluate_set, evaluate_set_bounded,
};
pub use glam::DVec3;
pub use minimax::MAX_TREE_NODES;
pub use options::{
    Effort, MAX_BASELINE_DEPTH, MAX_BASELINE_SAMPLES, MAX_BRANCH, MAX_MEDIAL_DEPTH, Method,
    SphereTreeOptions, SphereTreeProgress,
};
pub use select::{Cut, cut_for_tolerance, level_for_tolerance};
pub use sphaera_mesh::{Sphere, Surface};
pub use tree::{SphereTree, TreeDefect, TreeNode};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
