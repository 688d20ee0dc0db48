//! # sphaera-medial
//!
//! Spheres that fill a solid from the inside and touch its surface: the **adaptive
//! medial-axis approximation** of G. Bradshaw and C. O'Sullivan, *Adaptive Medial-Axis
//! Approximation for Sphere-Tree Construction* (ACM Transactions on Graphics 23(1),
//! 2004, section 4), and what it stands on: a robust incremental **3D Delaunay
//! tetrahedralization** with its **Voronoi dual**. The medial spheres are centred on the
//! Voronoi vertices of surface samples that lie inside the mesh; every sample is covered,
//! and the set is improved where it fits worst, for the whole object or for one region of
//! samples at a time. `sphaera-spheretree` builds its sphere-trees from them; the
//! Delaunay is usable on its own, on any points, degenerate ones included.
//!
//! # Quick start
//!
//! The tetrahedralization stays valid on cospherical input, where plain floating point
//! breaks:
//!
//! ```
//! use sphaera_medial::{DVec3, Delaunay};
//!
//! // A 5×5×5 grid: every cell's corners are cospherical, yet the result is valid.
//! let grid: Vec<DVec3> = (0..125)
//!     .map(|i| DVec3::new(f64::from(i % 5), f64::from(i / 5 % 5), f64::from(i / 25)))
//!     .collect();
//! let delaunay = Delaunay::new(&grid)?;
//! delaunay.validate()?;
//! // Every tetrahedron has positive volume and they fill the 4×4×4 box.
//! let volume: f64 = delaunay
//!     .tetrahedra()
//!     .map(|(_, t)| {
//!         let [a, b, c, d] = t.map(|v| delaunay.point(v));
//!         (b - a).cross(c - a).dot(d - a) / 6.0
//!     })
//!     .sum();
//! assert!((volume.abs() - 64.0).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The medial approximation of a mesh, from its prepared [`Surface`] and surface samples:
//!
//! ```
//! use sphaera_medial::{MedialApproximation, MedialOptions, SphereKind, Surface};
//! use sphaera_query::sampling;
//! use sphaera_mesh::shapes;
//!
//! let mesh = shapes::capsule(0.5, 2.0, 8)?;
//! let surface = Surface::new(&mesh)?;
//! let samples: Vec<_> = sampling::poisson_disk(&mesh, 500, 1)?
//!     .samples
//!     .iter()
//!     .map(|s| s.position)
//!     .collect();
//! let options = MedialOptions::default().with_target_spheres(60);
//! let medial = MedialApproximation::build(&surface, &samples, &options)?;
//! assert!(medial.sphere_count() >= 60);
//! // Every sample is covered, by a medial sphere or a cover sphere.
//! assert!(medial.uncovered_samples().is_empty());
//! let spheres = medial.spheres();
//! assert!(spheres.iter().any(|s| s.kind == SphereKind::Internal));
//! // Each sphere's error bounds how far it pokes out of the capsule (radius 0.5).
//! assert!(spheres.iter().all(|s| s.error >= 0.0 && s.error <= medial.worst_error()));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # How it works
//!
//! **The tetrahedralization** ([`delaunay`], [`Delaunay`]) is Bowyer–Watson: each point
//! is located by a walk from the last created tetrahedron, the tetrahedra whose
//! circumsphere contains it are removed, and the hole is filled by joining the point to
//! its boundary ([`Delaunay::insert`], which reports the [`Insertion`]). Orientation and
//! in-sphere signs are exact (Shewchuk's adaptive predicates, the `robust` crate), and
//! in-sphere ties are broken by a symbolic perturbation that depends on the points only,
//! so grids, spheres and cylinders of points give a valid, unique tetrahedralization with
//! no flat tetrahedra, whatever the insertion order. Ghost tetrahedra sharing the vertex
//! [`INFINITE`] close the convex hull, so points outside it are inserted like any other.
//! [`Delaunay::new`] inserts a batch in a biased randomized order sorted along a Hilbert
//! curve (fixed seed: the order is a function of the points). [`Delaunay::validate`]
//! checks every invariant and names the first broken one ([`Violation`]). The Voronoi
//! dual is read off the same arrays: [`Delaunay::circumsphere`] of a tetrahedron is a
//! Voronoi vertex, [`Delaunay::voronoi_cell`] a point's cell ([`VoronoiCell`]).
//!
//! **The medial approximation** ([`medial`], [`MedialApproximation`]) follows the paper:
//! the surface samples are the forming points of a Voronoi diagram, and the sphere
//! around each Voronoi vertex inside the object, through its four forming points,
//! touches the surface there ([`SphereKind::Internal`]).
//!
//! 1. **Start** from [`MedialOptions::initial_points`] samples spread by farthest-point
//!    selection.
//! 2. **Complete coverage** (section 4.1): a sample no sphere covers lies in the Voronoi
//!    cell of its nearest forming point, and the spheres around that cell's vertices
//!    cover the cell; one of them joins the set as a [`SphereKind::Cover`] sphere, chosen
//!    by [`CoverCriterion`]. If the cell is unbounded and none of them contains the
//!    sample, the sample itself becomes a forming point.
//! 3. **Improve** (section 4.2): the worst sphere is replaced by inserting the surface
//!    point closest to its centre as a new forming point: the spheres of its new cell
//!    pass through that point, so the error there drops to zero. Repeat from 2 until
//!    [`MedialOptions::target_spheres`] or [`MedialOptions::max_error`] is reached
//!    ([`MedialApproximation::build`]), or, for one region of samples,
//!    [`RegionOptions`]' goal ([`MedialApproximation::refine_region`], what a sphere-tree
//!    node asks).
//!
//! A sphere's error ([`MedialSphere::error`]) is the paper's eq. 2: for a centre `v`
//! inside, `r − ‖q − v‖` with `q` the closest surface point (exact, from the
//! [`Surface`]), which bounds how far any point of the sphere lies outside the surface;
//! for a centre outside (a cover sphere), `r + ‖q − v‖`. Hubbard's static approximation,
//! the paper's baseline, is [`MedialApproximation::build_static`].
//!
//! # Guarantees
//!
//! - Every tetrahedralization [`Delaunay::new`] and [`Delaunay::insert`] return is valid
//!   (positive tetrahedra, symmetric neighbours, every face locally Delaunay under the
//!   perturbation; property-tested and fuzzed against exact brute force); a repeated
//!   point is kept as a vertex id but not inserted ([`Delaunay::duplicate_of`]).
//! - Every sample given to [`MedialApproximation::build`] is covered by a sphere of the
//!   set, and every sphere's error is an upper bound of how far it reaches beyond the
//!   surface. Covering the samples is not covering the surface: between samples a sliver
//!   of surface can lie outside every sphere (measured: see Performance below).
//!   `sphaera-spheretree` certifies coverage of the surface itself.
//! - The same points, samples and options give the same result, with or without the
//!   `parallel` feature.
//!
//! # Errors
//!
//! Two error enums, both without panics on user input:
//!
//! - [`DelaunayError`] from the tetrahedralization: a NaN or infinite coordinate
//!   ([`DelaunayError::NonFinite`], with the point's index), fewer than four distinct
//!   points ([`DelaunayError::TooFewPoints`]), points all on a plane, line or point
//!   ([`DelaunayError::Flat`]), more points than 32-bit ids name
//!   ([`DelaunayError::TooManyPoints`]), and [`DelaunayError::Invalid`] when
//!   [`Delaunay::validate`] finds a broken invariant (a bug: please report it).
//! - [`MedialError`] from the medial approximation: the mesh refused
//!   ([`MedialError::Mesh`]), a NaN sample ([`MedialError::NonFiniteSample`]), too few
//!   distinct, non-coplanar samples ([`MedialError::TooFewSamples`]), an option out of
//!   its domain ([`MedialError::InvalidParameter`]), a region naming a sample that does
//!   not exist ([`MedialError::RegionOutOfRange`]).
//!
//! # Performance
//!
//! The figures are in the repository's `docs/benchmarks.md`; each bullet names its
//! section and the command that measures it.
//!
//! - **Delaunay** (`cargo bench -p sphaera-medial --bench delaunay`, one thread):
//!   insertions per second for 100,000 random points and for 100,000 points of a cube's
//!   surface grid, where every square is cocircular; one point at a time into an
//!   existing tetrahedralization is several times slower (the walk dominates). The
//!   `delaunay` crate, timed in the same run as Sphaera (`cargo bench -p sphaera-eval
//!   --bench delaunay_vs_peer`), is orders of magnitude slower. Section *Delaunay
//!   tetrahedralization (`sphaera-medial`)*.
//! - **Medial approximation** (`cargo bench -p sphaera-medial --bench medial`): 500 and
//!   1,000 spheres of the 69k-triangle Stanford bunny from 10,000 samples, the
//!   preparation of the [`Surface`] and of the samples, and 200 spheres of each Franka
//!   Panda collision link; most of the time is exact closest points. Section *Adaptive
//!   medial approximation (`sphaera-medial`)*.
//! - **Fit**: against Hubbard's static approximation on the same samples, the adaptive
//!   set leaves far less of the surface uncovered between samples, and is tighter from
//!   several hundred spheres on (`cargo run --release -p sphaera-eval -- --only
//!   medial_static_vs_adaptive`, part of `cargo xtask charts`). Section *Static against
//!   adaptive (the paper's Figs. 10–13)*.
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! - `sphaera-spheretree`: sphere-trees for collision detection built from this
//!   approximation, with coverage of the surface certified at every level.
//! - [`sphaera_mesh`]: the [`Surface`] (inside test and exact closest points) and the
//!   surface samples ([`sphaera_query::sampling::poisson_disk`]).
//! - `sphaera` (the facade, as `sphaera::medial`) and the `sphaera medial` command of
//!   `sphaera-cli`, which approximates a mesh file and certifies surface coverage.

pub mod delaunay;
mod error;
pub mod medial;

pub use delaunay::{Delaunay, INFINITE, Insertion, TetId, VoronoiCell};
pub use error::{DelaunayError, MedialError, Violation};
pub use glam::DVec3;
pub use medial::{
    CoverCriterion, MedialApproximation, MedialOptions, MedialProgress, MedialSphere, MedialStats,
    RegionOptions, RegionOutcome, SphereKind, eq2_error, surface_eq2_error,
};
/// The mesh a medial approximation describes (defined in `sphaera-query`): its inside test
/// and exact closest points.
pub use sphaera_query::Surface;

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
