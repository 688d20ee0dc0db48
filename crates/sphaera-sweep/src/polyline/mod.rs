//! Closest points on polygonal curves: exact and anytime closest-point queries on 2D and
//! 3D polylines, open or closed. Exact answers and intervals to a tolerance come from a
//! box tree over the segments (the default); the paper's Meshsweeper on a Douglas–Peucker
//! hierarchy of capsules (section 3) answers queries after a budget of refinement steps,
//! and every query with [`PolylineSessionOptions::with_exact_by_tree`]`(false)`.
//!
//! ```
//! use glam::{DVec2, DVec3};
//! use sphaera_sweep::Tolerance;
//! use sphaera_sweep::polyline::{Polyline, PolylineFeature};
//!
//! // A polygonal circle of radius 1 in the plane (closed).
//! let circle: Vec<DVec2> = (0..360)
//!     .map(|i| DVec2::from_angle(f64::from(i).to_radians()))
//!     .collect();
//! let polyline = Polyline::closed(circle)?;
//! let mut session = polyline.session();
//!
//! let answer = session.closest(DVec2::new(2.0, 0.0))?;
//! assert_eq!(answer.feature, PolylineFeature::Vertex(0));
//! assert!((answer.distance - 1.0).abs() < 1e-15);
//!
//! // The paper's linear worst case: at the centre every capsule is split, and the answer
//! // is still exact (every vertex is at distance 1; the segments are nearer).
//! let centre = session.closest(DVec2::ZERO)?;
//! assert!((centre.distance - (0.5f64.to_radians()).cos()).abs() < 1e-12);
//!
//! // An anytime query on a 3D curve: a certified interval, 1 % wide.
//! let wave: Vec<DVec3> = (0..=1000)
//!     .map(|i| {
//!         let x = f64::from(i) * 0.01;
//!         DVec3::new(x, x.sin(), 0.0)
//!     })
//!     .collect();
//! let polyline = Polyline::open(wave)?;
//! let mut session = polyline.session();
//! let bounds = session.closest_within(DVec3::new(5.0, 0.0, 3.0), Tolerance::RelativeToUpper(0.01))?;
//! let exact = session.closest(DVec3::new(5.0, 0.0, 3.0))?.distance;
//! assert!(bounds.lower <= exact && exact <= bounds.upper);
//! assert!(bounds.gap() <= 0.01 * bounds.upper);
//! # Ok::<(), sphaera_sweep::SweepError>(())
//! ```
//!
//! # How it works
//!
//! [`Polyline::new`] builds a box tree over the segments (binned surface-area splits, 8
//! segments per leaf; 2D points at `z = 0`). A session's [`PolylineSession::closest`]
//! descends it nearest box first, starting from the previous answer's segment as a
//! bound, and keeps a safe ball (half the gap to the nearest other segment or pruned
//! box) for the next query; [`PolylineSession::closest_within`] skips every box that
//! cannot bring the distance down by more than the tolerance, which certifies the
//! interval between the nearest box skipped and the best segment found.
//!
//! It also builds a binary hierarchy by the Douglas–Peucker recursion, without
//! recursion: the root is the chord from the first vertex to the last (to the first
//! again, for a closed polyline), split at the vertex farthest from it, and so on down to
//! single segments. Each node is a *capsule*: its chord `[A, B]` (two polyline vertices)
//! and its error `ε`, the largest distance from the sub-polyline it covers to the chord.
//! The sub-polyline and the chord are then within `ε` of each other *both ways* (the
//! chord's side needs a short argument: the sub-polyline runs from `A` to `B`, so its
//! projection on the chord covers the chord), so for a query at distance `d` from the
//! chord, the sub-polyline is at a distance in `[d − ε, d + ε]`, and at most `|p − A|`
//! and `|p − B|` too. The full argument and the treatment of rounding are in the docs of
//! the hierarchy's source file (`hierarchy.rs`).
//!
//! The paper's [`PolylineSession`] queues a *front* of capsules that covers the polyline, keyed by
//! `d − ε`: it replaces the front capsule by its two children until the front is a single
//! segment, whose interval `[d, d]` lies below every other — the exact answer, with its
//! segment, parameter and feature ([`PolylineClosest`]). Stopped earlier, the front's key
//! and the smallest upper bound seen are a certified interval ([`PolylineBounds`]).
//!
//! # Coherence
//!
//! The front stays between queries: a query moved by `δ` widens every interval by `δ`
//! (shifted keys, paper section 5.1), stale intervals are recomputed when they reach the
//! front, and a query inside the safe ball of the previous answer (section 3.3) costs one
//! point–segment distance. [`PolylineSessionOptions`] is the reset policy;
//! [`SessionStats`](crate::SessionStats) counts queries, constant-time answers, splits,
//! distance evaluations and resets.
//!
//! # Performance
//!
//! On the noisy 100k-point helix of the `polyline_vs_parry` bench of `sphaera-eval`
//! (`cargo bench -p sphaera-eval --bench polyline_vs_parry`, same run as parry3d-f64's
//! BVH), the build, exact uniform and smooth-path queries and anytime queries at 1 % of
//! the diagonal are timed against parry; the figures are in the section *Polylines* of
//! `docs/benchmarks.md` in the repository.
//!
//! Building: `O(n log n)` for most curves, `O(n²)` worst case, 24 bytes per capsule and
//! `2n` capsules, and about 90 bytes per segment for the tree. A session holds 4 bytes per capsule plus 16 per queued one. A query
//! splits the capsules whose intervals reach below the answer: few near a curve, all of
//! them at the centre of a polygonal circle (the linear worst case of paper section 7).
//! The `polyline_vs_parry` bench of `sphaera-eval` compares with parry3d-f64's BVH.

mod answer;
mod curve;
mod hierarchy;
mod point;
mod session;
mod tree;

pub use crate::error::PolylineDefect;
pub use answer::{PolylineBounds, PolylineClosest, PolylineFeature};
pub use curve::Polyline;
pub use point::PolylinePoint;
pub use session::{PolylineSession, PolylineSessionOptions};
