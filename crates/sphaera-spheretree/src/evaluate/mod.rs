//! Fit evaluation of sphere sets (the paper's section 6), with **certified** errors.
//!
//! The error of a sphere `S` bounding an object is `E(S) = max f(x)` over the points `x`
//! of its surface, where `f(x)` is the distance from `x` to the object's surface when `x`
//! lies outside the object and 0 inside: how far the sphere pokes out. The sphere-tree
//! literature estimates it from a few dozen fixed points per sphere, which
//! under-estimates it (by a wide margin on the low-res bunny); here every sphere gets an
//! interval `[lower, upper]` that contains `E(S)`, at most a tolerance wide.
//!
//! # Quick start
//!
//! ```
//! use sphaera_query::Surface;
//! use sphaera_mesh::shapes;
//! use sphaera_spheretree::evaluate::{EvaluationOptions, evaluate_set};
//! use sphaera_spheretree::{DVec3, Sphere};
//!
//! let mesh = shapes::capsule(0.5, 2.0, 24)?;
//! let surface = Surface::new(&mesh)?;
//! let spheres = [
//!     Sphere::new(DVec3::new(0.0, 0.0, -0.6), 0.75),
//!     Sphere::new(DVec3::new(0.0, 0.0, 0.6), 0.75),
//! ];
//! let set = evaluate_set(&surface, &spheres, &EvaluationOptions::default())?;
//! assert!(set.converged && set.worst_upper - set.worst_lower <= set.tolerance);
//! // Each sphere pokes out of the tube by 0.75 − 0.5 = 0.25 (a little more from the
//! // polygonal mesh).
//! assert!(set.worst_lower > 0.25 && set.worst_upper < 0.26);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Method: branch and bound over the sphere's surface
//!
//! The sphere's surface is tiled by the 20 faces of the icosahedron, projected to
//! geodesic triangles; a patch splits into four at its edges' geodesic midpoints, and the
//! live patches always tile the whole sphere. Each patch is probed at its representative
//! point `p` (the normalised sum of its corners): the exact closest surface point `q` and
//! distance `d(p)` (`sphaera-mesh`'s triangle tree, through
//! [`Surface::closest`](sphaera_query::Surface::closest)) and the inside test
//! ([`Surface::is_inside_certified`](sphaera_query::Surface::is_inside_certified)). With `ρ` the largest
//! distance from `p` to the patch (the chord of the cap through its corners: a cap of at
//! most 90° is spherically convex, so it contains the geodesic triangle), `f` is bounded
//! on the patch by the smallest of:
//!
//! - `d(p) + ρ` (the distance to a surface is 1-Lipschitz);
//! - `max(0, ρ − d(p))` when `p` is inside: a point of the patch outside the object is
//!   separated from `p` by the surface, which the segment between them crosses at least
//!   `d(p)` from `p`;
//! - `max |x − q|` over the patch (any surface point bounds the distance), computed in
//!   closed form over the cap. This bound is tight to second order in the patch size where
//!   the error is largest, which makes convergence fast: the error's maximiser is where
//!   `x − q` is normal to the sphere.
//!
//! `lower` is `f(p)` at the best probe. The patches wait in a max-heap by upper bound; the
//! search stops when the largest upper bound is within the tolerance of `lower`
//! ([`EvaluationOptions::tolerance`], default 10⁻⁴ of the mesh's diagonal), or at
//! the patch budget ([`EvaluationOptions::with_max_patches`]; then
//! [`SphereFit::converged`] is `false` and the interval, still valid, is wider). Patches
//! whose bound is already within the tolerance of `lower` are never split.
//!
//! # What the certificate assumes
//!
//! - **The inside test.**
//!   [`Surface::is_inside_certified`](sphaera_query::Surface::is_inside_certified) gives
//!   the exact generalized winding number's answer (it refines the fast approximation
//!   until its error bound decides, exactly as a last resort), except within rounding of
//!   the surface itself. A probe closer to the surface than a **guard band** (a quarter of
//!   the tolerance) is not classified at all: its patch gets the bound valid on both sides
//!   (`d(p) + ρ`, or the closest-point bound) and it never raises `lower`. So on a closed
//!   mesh the interval is rigorous up to floating-point rounding.
//! - **Open meshes** (the Stanford bunny's holes). "Inside" is then the winding number's
//!   region `w > ½`, whose boundary spans the holes where the mesh has none: a path from
//!   inside to outside through a hole crosses no triangle, so neither the inside bound
//!   `ρ − d(p)` nor a side inherited along a clear segment follows from the segment
//!   alone. What holds instead: off the mesh, `w` varies only as fast as the rims of the
//!   holes let it (`|∇w|` is bounded by the Biot–Savart field of the mesh's boundary
//!   chain, [`WindingBoundary`](sphaera_query::winding::WindingBoundary)). Each probe's
//!   side comes with a certified margin `m ≤ |w(p) − ½|`
//!   ([`Surface::side_with_margin`](sphaera_query::Surface::side_with_margin)); the inside
//!   bound is used only where `m` exceeds `ρ` times the gradient bound over the patch's
//!   ball, and a side is inherited only while the margin, less the step times the
//!   gradient bound, stays positive (the proof is on the search's `evaluate`). Elsewhere
//!   the patch keeps the bounds valid on both sides and is split. The bounds are thus
//!   certified for the winding number's solid, holes included, which is what the
//!   independent check (`tests/checks`) measures. A closed mesh has no boundary chain:
//!   nothing changes and nothing is paid for it.
//! - **Floating point.** Every bound carries a relative slack of 10⁻¹², far above the
//!   rounding of its few operations.
//!
//! # Coverage
//!
//! [`coverage`] draws independent, area-weighted random samples of the surface
//! ([`sampling::random`](sphaera_query::sampling::random)), tests each against the union of
//! the balls with a bounding-volume hierarchy over the spheres, and reports the uncovered
//! fraction and the largest gap (the largest distance from an uncovered sample to the
//! nearest sphere's surface). Both are estimates from samples, not certificates (the
//! sphere-tree construction certifies coverage itself).
//!
//! # Performance
//!
//! Each patch costs one closest-point query and, away from the surface, one winding-number
//! inside test (on a mesh with holes, also a descent of the tree over the holes' rims).
//! The time and the patches per sphere for 512 spheres poking out of `bunny_lowres.obj`,
//! at the default tolerance and at 10⁻³ of the diagonal, and the time of the coverage of
//! 100,000 samples, are printed by `cargo test --release -p sphaera-spheretree --test
//! evaluate bunny_512 -- --ignored --nocapture` (not kept in `docs/benchmarks.md`). Flat
//! maxima cost the most: a sphere concentric with a sphere mesh needs many patches.
//!
//! # Determinism
//!
//! Results depend only on the inputs: the heap breaks ties by creation order, the
//! coverage samples come from the seed, and the `parallel` feature (one sphere, or one
//! sample, per task) gives identical results. Only [`SetEvaluation::elapsed`] varies.

mod coverage;
mod level;
mod options;
mod patch;
mod set;
mod sphere_bvh;
mod sphere_fit;

pub use coverage::{Coverage, coverage};
pub use level::{LevelEvaluation, evaluate_level};
pub use options::{
    DEFAULT_COVERAGE_SAMPLES, DEFAULT_COVERAGE_SEED, DEFAULT_MAX_PATCHES,
    DEFAULT_RELATIVE_TOLERANCE, EvaluationOptions, LEVEL_REPORT_TOLERANCE, MAX_COVERAGE_SAMPLES,
    MAX_PATCHES, SCREENING_FACTOR,
};
pub use set::{SetEvaluation, evaluate_set, evaluate_set_bounded};
pub use sphere_fit::{SphereFit, sphere_error, sphere_errors};
