//! # sphaera-spheretree
//!
//! Sphere-trees for time-critical collision detection: a hierarchy of spheres around a
//! triangle mesh whose every level covers the whole surface and fits it more tightly
//! than the level above, so that a collision test can stop at any level and still have
//! an answer with a known error. Beside the trees to a depth the paper builds, this crate
//! builds trees **to a tolerance** (refined only where the error is, as deep as needed)
//! and sphere sets **of an exact budget**, on solids and on **sheets** (surfaces without
//! inside).
//!
//! It implements G. Bradshaw and C. O'Sullivan, *Adaptive Medial-Axis Approximation for
//! Sphere-Tree Construction* (ACM Transactions on Graphics 23(1), 2004): the adaptive
//! medial-axis approximation of [`sphaera_medial`], refined in each node's part of the
//! surface and reduced to a few children by the paper's **merge**, **burst**,
//! **expand-select** or **combined** reducers, beside the classic octree, grid and
//! Hubbard constructions the paper compares against. The default is this crate's own
//! construction, [`minimax`]: each node's part of the surface, tiled exactly by triangle
//! pieces, is divided between the children whose worst error is least (medial balls as
//! candidate centres, a set-cover search, then every centre moved on the exact surface),
//! so that every cut covers the surface by construction, and on the meshes charted nearly
//! every level is tighter than the paper's best reducer's (the figures are in the section
//! *Charts* of *Sphere-trees (`sphaera-spheretree`)* in the repository's
//! `docs/benchmarks.md`). Every node's error is a certified bound, every tree is built in
//! the mesh's canonical pose, so it turns, scales and moves with the mesh.
//!
//! Around the construction: certified fit evaluation ([`evaluate`]), the shallowest level
//! or smallest cut that meets a tolerance ([`select`]), interruptible tree-against-tree
//! traversal under rigid motions ([`collide`](mod@collide)) and exports to JSON, the
//! original toolkit's `.sph`, robot planners' collision-sphere YAML and parry3d
//! ([`export`]).
//!
//! # Quick start
//!
//! One entry point, [`build`], takes the prepared [`Surface`] (exact closest points and
//! the inside test, built once; [`Surface::shell`] for a sheet) and the
//! [`SphereTreeOptions`]: a depth, a tolerance or a one-level budget. The same surface then
//! evaluates the tree. (The [`Effort::Quick`] below keeps the example fast.)
//!
//! ```
//! use sphaera_mesh::{Length, shapes};
//! use sphaera_spheretree::{
//!     Budget, DVec3, Effort, EvaluationOptions, Similarity, SphereTreeOptions, Surface,
//!     build, collide, evaluate_set_bounded,
//! };
//!
//! let surface = Surface::new(&shapes::capsule(0.5, 2.0, 12)?)?;
//! let quick = SphereTreeOptions::default().with_effort(Effort::Quick);
//!
//! // A tree to a depth: every level covers the surface, each tighter than the last.
//! let tree = build(&surface, &quick.clone().with_depth(2).with_branch(4))?;
//! let worst = |l: usize| tree.level(l).iter().map(|n| n.error).fold(0.0, f64::max);
//! assert!(worst(2) < worst(1) && worst(1) < worst(0));
//!
//! // A tree to a tolerance: refined where the error is, until every leaf meets it.
//! let tolerance = 0.02 * surface.diagonal();
//! let fine = build(&surface, &quick.clone().with_tolerance(Length::Absolute(tolerance)))?;
//! assert!(fine.leaves().iter().all(|&leaf| fine.nodes()[leaf].error <= tolerance));
//!
//! // A budget: exactly 12 spheres, covering the surface.
//! let twelve = build(&surface, &quick.with_depth(1).with_branch(12))?;
//! assert_eq!(twelve.level(1).len(), 12);
//!
//! // The certified worst error of a level (node errors are certified upper bounds).
//! let spheres = tree.level_spheres(2);
//! let bounds: Vec<f64> = tree.level(2).iter().map(|n| n.error).collect();
//! let fit = evaluate_set_bounded(&surface, &spheres, &bounds, &EvaluationOptions::default())?;
//! assert!(fit.worst_lower <= fit.worst_upper && fit.worst_upper <= worst(2));
//! assert_eq!(fit.coverage.uncovered, 0);
//!
//! // Two copies 0.9 apart (the capsule is 1 wide) touch: contacts at the deepest level.
//! let near = Similarity::from_translation(DVec3::new(0.9, 0.0, 0.0))?;
//! let hit = collide(&tree, &Similarity::IDENTITY, &tree, &near, &Budget::Unlimited)?;
//! assert!(hit.completed && hit.level == 2 && !hit.contacts.is_empty());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # How it works
//!
//! **The minimax construction** ([`Method::Minimax`], which [`Method::Auto`] chooses; the
//! [`minimax`] module has the details). A node must cover its region with at most
//! `branch` children whose largest error is as small as it can be, the error of a sphere
//! being the paper's eq. 2: its radius less the signed distance of its centre to the
//! surface, an upper bound on how far it pokes out of the object.
//!
//! 1. **Pieces.** The region is tiled by triangles (the mesh's, split at their longest
//!    edge until a node has about 8,000): a sphere containing a piece's corners contains
//!    the piece, so children that contain their pieces cover the surface exactly.
//! 2. **Candidates.** Medial balls, found by shrinking a ball tangent at a piece against
//!    the exact surface: where a sphere reaches far along the surface while poking out
//!    least. On a shell, the pieces' centroids.
//! 3. **Search.** Every candidate expanded to a common standoff (the paper's expand
//!    step); a depth-first search on the most constrained piece finds a few that cover
//!    every representative piece, and bisection the least standoff it finds them at.
//! 4. **Refinement.** Lloyd's iteration (each piece to its cheapest sphere, each sphere
//!    to its best candidate), then Nelder–Mead moves every centre off the candidates on
//!    the exact surface; a count asked for is completed by splitting the worst child;
//!    several starts where few nodes are divided (the root's division shapes all below),
//!    swaps at the root, and regions balanced by area without raising the worst.
//! 5. **The tree.** Top down, level by level: to a depth, every node divided into
//!    `branch` children; to a tolerance ([`SphereTreeOptions::tolerance`]), only the
//!    nodes whose certified error exceeds it, each into the fewest children that meet it,
//!    as deep as needed; a budget is a one-level tree of exactly `branch` spheres.
//!
//! **The paper's Algorithm 1**, for the medial methods ([`Method::is_medial`]):
//!
//! 1. **Samples.** The surface is represented by [`SphereTreeOptions::samples`]
//!    Poisson-disk samples ([`sphaera_query::sampling::poisson_disk`]); each stands for
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
//! A node's error ([`TreeNode::error`]) is a certified upper bound on how far its sphere
//! pokes out of the object: the paper's eq. 2 with an exact distance and a certified
//! inside test (or the branch and bound's bound, where a tolerance tree needed it).
//! [`evaluate_set`] certifies the true value, the largest distance from a point of the
//! sphere outside the object to the surface, as an interval at most a tolerance wide
//! (branch and bound over the sphere's surface, see [`evaluate`]);
//! [`evaluate_set_bounded`] does it far faster for a tree's nodes, whose errors it takes as
//! bounds. The baselines ([`Method::Octree`], [`Method::Grid`], [`Method::Hubbard`]) are
//! the classic constructions as published: same tree structure and samples, coverage
//! measured but not certified.
//!
//! Using a tree: [`level_for_tolerance`] and [`cut_for_tolerance`] pick the coarsest
//! detail whose worst error meets a tolerance ("model no more than the scene needs");
//! [`SphereTree::cut_at`] gives what covers the surface at a depth of a tree whose leaves
//! are not all at the bottom (a tolerance tree); [`collide`](fn@collide) descends two
//! placed trees breadth-first, a level at a time (a leaf standing for itself below its
//! level), so that it can stop when a [`Budget`] (the paper's cost model, or wall time)
//! runs out and still report contacts with an error bound; [`overlaps`] answers yes or
//! no, depth-first.
//!
//! # What every tree guarantees
//!
//! - Every level (every cut) covers the whole surface: by construction for minimax (its
//!   spheres contain the pieces tiling their regions), certified piece by piece for the
//!   medial methods ([`cover`]).
//! - A tolerance asked for is met by every leaf, certified, or the build says it cannot
//!   be ([`SphereTreeError::ToleranceUnreachable`]); a budget of `n` spheres gives `n`.
//!   A node budget ([`SphereTreeOptions::max_nodes`]) bounds a tolerance tree.
//! - Errors are certified on closed meshes, on shells, and on open meshes taken as solids
//!   (a scan with holes, whose inside the winding number extends across the holes): there
//!   node errors come from the certified evaluation, which lets a patch inherit its side
//!   only while its margin exceeds the winding number's gradient bound from the holes'
//!   rims (see [`evaluate`]).
//! - Every node has a positive radius, and no child is built looser than its parent: its
//!   error bound never exceeds a lower bound on the parent's certified error (else the
//!   child takes the parent's sphere). On an open mesh taken as a solid, a region whose
//!   children poke out through a hole is divided again around the surface itself, the
//!   tighter division kept.
//! - The same input, options and seed give the same tree, with or without `parallel`.
//! - The tree moves with the mesh: it is built in the mesh's canonical pose
//!   ([`sphaera_mesh::geometry::CanonicalPose`]: a frame taken from the mesh's own
//!   vertices, coordinates snapped to a grid far coarser than rounding), so a mesh
//!   turned, rescaled or moved by any similarity gives the same tree mapped, to rounding
//!   (unless the transform's own rounding crosses the grid: a mesh moved 10⁶ of its sizes
//!   away has lost 20 bits to the move). Scaling by a power of two gives every number
//!   scaled, bit for bit.
//!
//! # Errors
//!
//! Every fallible function returns [`SphereTreeError`]; library code does not panic on
//! user input. The variants a caller meets most:
//!
//! - [`SphereTreeError::InvalidParameter`]: an option out of its domain (a zero branch
//!   factor, a branch above [`MAX_BRANCH`], a tolerance that is not finite and positive or
//!   given to a method other than minimax, fewer than 4 samples, an error fraction
//!   outside `(0, 1]`), with the parameter's name, value and requirement. Parameters that
//!   size memory are checked against their caps before anything is allocated: a depth
//!   above [`MAX_MEDIAL_DEPTH`] or [`MAX_BASELINE_DEPTH`], a branch above [`MAX_BRANCH`],
//!   a node budget above [`MAX_TREE_NODES`], more samples than [`MAX_SURFACE_SAMPLES`],
//!   an evaluation's patch budget above [`MAX_PATCHES`] or more coverage samples than
//!   [`MAX_COVERAGE_SAMPLES`];
//! - [`SphereTreeError::ToleranceUnreachable`]: a tolerance that would need more than
//!   [`MAX_TREE_NODES`] nodes, [`MAX_MEDIAL_DEPTH`] levels or more surface pieces per level
//!   than memory allows, with the worst leaf reached;
//! - [`SphereTreeError::NeedsInside`]: one of the paper's methods asked for a shell;
//! - [`SphereTreeError::Mesh`]: the mesh cannot be sampled (no area) or a transform is
//!   not a similarity (a mesh facing inward is refused earlier, by [`Surface::new`] and
//!   [`Surface::solid_or_shell`]);
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
//! Minimax's work follows the number of nodes divided, not the mesh's size: each node is
//! tiled by about 8,000 pieces (400 per child for a budget), and the mesh is touched
//! through the [`Surface`]'s trees (exact closest points, and the inside test: the
//! pseudo-normal test on certified embedded solids, the winding number elsewhere,
//! logarithmic in the triangle count per query). A tolerance tree costs in proportion to
//! the spheres it needs; a budget in proportion to the count asked. [`Effort`] trades
//! time for accuracy. The figures, generated from the experiments' CSVs by `cargo xtask
//! tables` (the commands are in the repository's `docs/benchmarks.md`, with the charts of
//! error against level, against time and against the sphere count):
//!
#![doc = include_str!("performance.md")]
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
    EvaluationOptions, LevelEvaluation, MAX_COVERAGE_SAMPLES, MAX_PATCHES, SetEvaluation,
    SphereFit, evaluate_level, evaluate_set, evaluate_set_bounded,
};
pub use glam::DVec3;
pub use minimax::MAX_TREE_NODES;
pub use options::{
    Effort, MAX_BASELINE_DEPTH, MAX_BASELINE_SAMPLES, MAX_BRANCH, MAX_MEDIAL_DEPTH,
    MAX_SURFACE_SAMPLES, Method, SphereTreeOptions, SphereTreeProgress,
};
pub use select::{Cut, cut_for_tolerance, level_for_tolerance};
pub use sphaera_mesh::Sphere;
pub use sphaera_query::Surface;
pub use tree::{SphereTree, TreeDefect, TreeNode};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
