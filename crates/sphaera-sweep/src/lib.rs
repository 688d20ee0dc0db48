//! # sphaera-sweep
//!
//! Closest points and Hausdorff distances on triangle meshes, with two engines in one
//! design:
//!
//! - **Exact answers, and intervals to a tolerance,** come from the triangle tree
//!   ([`TriangleTree`], from `sphaera-mesh`, re-exported here): a box tree over the input
//!   triangles with surface-area splits, quick to build (see Performance). It offers
//!   [`TriangleTree::closest`], [`TriangleTree::closest_many`] (every core, the same
//!   answers), [`TriangleTree::cursor`] (a stream of points that move a little: the
//!   previous answer seeds the next), [`TriangleTree::closest_approx`] (a certified
//!   interval at most a given gap wide) and [`TriangleTree::refit`] (a deforming mesh,
//!   frame by frame). This is the engine `sphaera distance` uses, and the engine of
//!   certified Hausdorff distances between whole meshes ([`hausdorff`], on every core).
//! - **The rest** comes from Meshsweeper (Guéziec, *"Meshsweeper": From Closest Point to
//!   Hausdorff Distances Between Meshes*, 2000) on the progressive hierarchy of error
//!   spheres that [`sphaera_simplify`] records: meshes that deform through inflated
//!   radii ([`Session::deform`], [`Session::move_vertices`]), intervals after a budget of
//!   refinement steps ([`Session::closest_with_budget`]), the `k` nearest triangles, and
//!   the paper's Hausdorff distance ([`meshsweeper_hausdorff`]). A [`Session`]'s
//!   exact and tolerance queries ([`Session::closest`], [`Session::closest_within`]) come
//!   from the tree by default while the mesh keeps its shape (rigid poses included,
//!   [`Session::move_mesh`]); [`SessionOptions::with_exact_by_tree`]`(false)` answers
//!   them the paper's way, which is how the paper's claims are tested.
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_sweep::{Feature, Sweeper, Tolerance, TriangleTree, build_hierarchy};
//!
//! let cube = shapes::cube(2.0, 4)?; // corners at ±1
//!
//! // Exact answers: the triangle tree.
//! let tree = TriangleTree::new(&cube)?;
//! let answer = tree.closest(DVec3::new(3.0, 0.2, 0.1))?;
//! assert!((answer.distance - 2.0).abs() < 1e-12);
//! assert!((answer.point - DVec3::new(1.0, 0.2, 0.1)).length() < 1e-12);
//! // Beyond a corner, the answer is that vertex of the input mesh.
//! let corner = tree.closest(DVec3::splat(2.0))?;
//! assert!(matches!(corner.feature, Feature::Vertex(_)));
//! assert!((corner.distance - 3f64.sqrt()).abs() < 1e-12);
//!
//! // Certified intervals, motion, k nearest: a Meshsweeper session.
//! let hierarchy = build_hierarchy(&cube)?;
//! let sweeper = Sweeper::new(&hierarchy)?;
//! let mut session = sweeper.session();
//! let bounds = session.closest_within(DVec3::new(0.0, 0.0, 1.5), Tolerance::Absolute(0.1))?;
//! assert!(bounds.lower <= 0.5 && 0.5 <= bounds.upper && bounds.gap() <= 0.1);
//! // The 5 nearest input triangles, nearest first.
//! let near = session.k_closest(DVec3::new(0.0, 0.0, 1.5), 5)?;
//! assert_eq!(near.len(), 5);
//! assert!(near.windows(2).all(|w| w[0].distance <= w[1].distance));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Performance
//!
//! Measured against parry3d-f64 in the same criterion run (`cargo bench -p sphaera-eval
//! --bench sweep_vs_parry`): the triangle tree builds faster than parry's BVH and answers
//! uniform and near-surface queries on the 69k bunny about as fast as parry per query or
//! faster, and [`TriangleTree::closest_many`] uses every core. The paper's exact queries
//! are much slower than the tree's; the hierarchy's place is the rest of the list above.
//! The figures are in the section *Closest-point queries (`sphaera-sweep`)* of
//! `docs/benchmarks.md` in the repository. [`hausdorff`] certifies the symmetric distance
//! between the 69k bunny and a 10k simplification of it to 1e-5 of the diagonal faster
//! than cascading-upper-bounds in the same run (`cargo bench -p sphaera-eval --bench
//! hausdorff`); its times, and the 871k dragon's against its 2 % simplification, are in
//! the section *Hausdorff distance (`sphaera-sweep`)* of `docs/benchmarks.md`.
//!
//! # How it works
//!
//! Every vertex of a simplified mesh carries an error radius; the triangle swept by those
//! spheres bounds the part of the input surface it stands for, in both directions
//! (`sphaera_simplify`'s invariants (A) and (B)). So for a query point `p` and a
//! simplified triangle at distance `d` with largest corner radius `ε`, the input surface
//! it covers lies at a distance in `[d − ε, d + r]` (`r` ≤ `ε`: the radius interpolated at
//! the closest point). A [`Session`] keeps the triangles of a selectively refined mesh in
//! a priority queue keyed by `d − ε`; it pops the front, splits one of its vertices (and
//! whatever must be split before, from the hierarchy's fixed tables), re-queues what
//! changed, and stops when the front is a triangle of the input mesh: its interval is a
//! single value below every other lower bound, the exact distance.
//!
//! The fixed tables live in the [`Hierarchy`](sphaera_simplify::Hierarchy) and are shared
//! by every thread through a [`Sweeper`]; a session owns only the changing state: one word
//! per vertex and per collapse, and the queue (16 bytes per queued triangle plus a 4-byte
//! slot per triangle).
//!
//! # Coherence
//!
//! A session keeps the refined mesh and the queue between queries. Moving the query point
//! by `δ` widens every interval by `δ` without reordering (the keys are stored shifted by
//! the total motion), and marks them stale; stale intervals are re-evaluated only when they
//! reach the front. A query within the *safe radius* of the previous exact answer —
//! half the gap between its distance and the next lower bound — is answered from the same
//! triangle without touching the queue. [`SessionOptions`] says when a session resets to
//! the base mesh.
//!
//! # Motion
//!
//! [`Session::move_mesh`] moves the mesh rigidly (queries stay in world coordinates);
//! [`Session::deform`] and [`Session::move_vertices`] deform it with the paper's two
//! methods, key-frames ([`DeformedShape::keyframe`], [`DeformedShape::between`]) and radii inflated from
//! displacement bounds ([`DeformedShape::inflated`]). Every interval is widened by how far the
//! tolerance volumes can have moved, so coherence survives motion.
//!
//! # Hausdorff distance
//!
//! [`hausdorff`] brackets the one-sided or symmetric Hausdorff distance between two
//! meshes with certified bounds at a chosen tolerance: samples answered exactly by each
//! other's [`TriangleTree`], triangles bounded from their corners' answers (the paper's
//! bounds of section 6 and convexity bounds through single triangles), refined in rounds
//! on every core: `sphaera-query`'s engine ([`sphaera_query::hausdorff`]), re-exported
//! here with this crate's errors. [`meshsweeper_hausdorff`] is the paper's engine on two
//! [`Sweeper`]s, on the same types and upper bounds.
//!
//! ```
//! use sphaera_mesh::{Length, shapes};
//! use sphaera_sweep::{HausdorffOptions, hausdorff};
//!
//! let (cube, sphere) = (shapes::cube(2.0, 8)?, shapes::sphere(1.0, 32)?);
//! let options = HausdorffOptions::default().with_tolerance(Length::Absolute(1e-6));
//! let h = hausdorff(&cube, &sphere, &options)?;
//! // The cube's corners are √3 − 1 from the (tessellated) sphere.
//! assert!(h.gap() <= 1e-6 && (h.upper - (3f64.sqrt() - 1.0)).abs() < 1e-2);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Polylines
//!
//! The [`polyline`] module answers the same queries on 2D and 3D polylines with the same
//! design: exact and tolerance queries from a box tree of segments, budgets and the
//! paper's way (section 3) over a Douglas–Peucker hierarchy of capsules; its module docs
//! have a runnable example.
//!
//! # Errors
//!
//! Queries, sessions and Hausdorff distances return [`SweepError`]; nothing panics on user
//! input. The variants met most: [`SweepError::NonFiniteQuery`] (a NaN or infinite query
//! point, with its coordinates), [`SweepError::EmptyMesh`], [`SweepError::InvalidParameter`]
//! (a tolerance, budget or interpolation parameter out of its domain, with its name and
//! requirement), [`SweepError::NotRigid`] and [`SweepError::NonFinitePose`] (a mesh pose
//! that is not a rotation and translation), [`SweepError::LengthMismatch`] and
//! [`SweepError::InvalidVertexValue`] (per-vertex positions or displacements that do not
//! fit the mesh), [`SweepError::InvalidPolyline`] (why a list of points is not a
//! polyline). Building the hierarchy reports
//! [`SimplifyError`](sphaera_simplify::SimplifyError) and building the triangle tree
//! [`MeshError`](sphaera_mesh::MeshError), from the crates that own them.
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! - [`sphaera_simplify`]: the error-sphere simplification and the progressive
//!   [`Hierarchy`](sphaera_simplify::Hierarchy) the sessions refine.
//! - [`sphaera_mesh`]: the [`TriangleTree`] and its closest points, and the sampled
//!   Hausdorff distance ([`sphaera_query::measure`]), a cheaper lower bound.
//! - `sphaera-spheretree` and `sphaera-medial`, which use the same exact closest points
//!   through [`sphaera_query::Surface`]; the facade `sphaera` (as `sphaera::sweep`) and the
//!   `sphaera distance` and `sphaera hausdorff` commands of `sphaera-cli`.

mod answer;
mod deformed_shape;
mod error;
mod hausdorff;
pub mod polyline;
mod pose;
mod queue;
mod session;
mod shifted_keys;
mod sweeper;

pub use answer::{DistanceBounds, SessionStats, Tolerance};
pub use deformed_shape::DeformedShape;
pub use error::SweepError;
pub use hausdorff::{
    DirectedHausdorff, Direction, HausdorffDistance, HausdorffOptions, HausdorffProgress,
    MAX_HAUSDORFF_SAMPLES, hausdorff, hausdorff_with_progress, meshsweeper_hausdorff,
    meshsweeper_hausdorff_with_progress,
};
pub use polyline::{Polyline, PolylineSession};
pub use session::{Session, SessionOptions};
/// The exact closest point a query returns, and the mesh feature it lies on; the
/// triangle tree that answers exact queries without a hierarchy, and its cursor for
/// coherent streams (all defined in `sphaera-mesh`).
pub use sphaera_query::closest::{ApproxClosest, ClosestPoint, Feature, TreeCursor, TriangleTree};
pub use sweeper::{Sweeper, build_hierarchy};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
