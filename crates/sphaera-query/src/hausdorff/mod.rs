//! Certified Hausdorff distances between two meshes, from a [`TriangleTree`] of each:
//! [`hausdorff`] brackets the distance between lower bounds (exact distances at samples)
//! and upper bounds (module [`bound`]) until they are within the tolerance, refining in
//! rounds on every core. `sphaera-sweep` adds the paper's engine (Meshsweeper, section 6)
//! on the same types and bounds.
//!
//! [`TriangleTree`]: crate::closest::TriangleTree

pub mod bound;
mod rows;
mod trees;

use glam::DVec3;
use sphaera_mesh::{Length, TriMesh};

use crate::QueryError;
pub use rows::Rows;

/// A direction of a one-sided Hausdorff distance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Direction {
    /// `h(A → B)`: the points of the first mesh, measured against the second.
    AToB,
    /// `h(B → A)`.
    BToA,
}

/// A certified one-sided Hausdorff distance `h(S → T)` from a source mesh `S` to a target
/// `T`, with where it is reached and the distance of every source vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct DirectedHausdorff {
    /// A lower bound of `h(S → T)`: the largest exact distance found at a sample.
    pub lower: f64,
    /// An upper bound of `h(S → T)`.
    pub upper: f64,
    /// The sample of `S` where [`lower`](Self::lower) is reached.
    pub farthest: DVec3,
    /// Its closest point on `T`.
    pub closest: DVec3,
    /// The distance to `T` of every input vertex of `S` (by input vertex index): the
    /// distance to the nearest point found, an upper bound that is almost always exact;
    /// certified exact for every vertex with [`HausdorffOptions::exact_vertex_distances`]. 0 for
    /// a vertex no triangle uses (not a point of the surface).
    pub vertex_distances: Vec<f64>,
    /// Points of `S` sampled: its vertices plus the edge midpoints of refined triangles.
    pub samples: usize,
    /// Samples given a certified distance by a closest-point query (the others only
    /// needed a near point, found by a local walk from their neighbours' answers).
    pub certified_samples: usize,
    /// Triangles split in four.
    pub refined_triangles: usize,
}

/// The result of [`hausdorff`].
#[derive(Clone, Debug, PartialEq)]
pub struct HausdorffDistance {
    /// A lower bound of the distance (`h(A → B)`, or `H(A, B)` when symmetric).
    pub lower: f64,
    /// An upper bound of the distance.
    pub upper: f64,
    /// The direction `A → B`.
    pub a_to_b: DirectedHausdorff,
    /// The direction `B → A` (only when symmetric).
    pub b_to_a: Option<DirectedHausdorff>,
    /// The direction whose lower bound is the larger (where the maximum is reached).
    pub dominating: Direction,
    /// `false` when the sample budget ran out before the tolerance was met (the bounds
    /// are still certified, only wider).
    pub converged: bool,
}

impl HausdorffDistance {
    /// `upper − lower`.
    pub fn gap(&self) -> f64 {
        self.upper - self.lower
    }

    /// The dominating direction's details.
    pub fn dominating_side(&self) -> &DirectedHausdorff {
        match (self.dominating, &self.b_to_a) {
            (Direction::BToA, Some(b)) => b,
            _ => &self.a_to_b,
        }
    }
}

/// Progress of a Hausdorff computation, reported every few thousand samples.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct HausdorffProgress {
    /// Vertices queried so far, of [`vertices`](Self::vertices).
    pub vertices_done: usize,
    /// Vertices of the sampled meshes.
    pub vertices: usize,
    /// Samples queried so far (vertices and midpoints).
    pub samples: usize,
    /// The current lower bound.
    pub lower: f64,
    /// The current upper bound (infinite until the vertices are done).
    pub upper: f64,
}

/// Options of [`hausdorff`] and of `sphaera-sweep`'s `meshsweeper_hausdorff`, the certified Hausdorff
/// distance between two meshes.
///
/// The one-sided distance `h(A → B) = max over x ∈ A of d(x, B)` is bracketed:
///
/// - the **lower bound** is the largest exact distance at a sample of `A` (a sample is a
///   point of `A`, so it cannot exceed the maximum);
/// - the **upper bound** is the largest, over triangles covering `A`, of a bound of the
///   distance from every point of the triangle to `B`, from points of `B` known near its
///   corners: the paper's bisector-plane bound (Fig. 9), a bound through one triangle of
///   `B` (the distance to a triangle is convex, so over a triangle of `A` it is largest
///   at a corner), the same split across an edge shared by two triangles of `B`. The
///   smallest applies.
///
/// Triangles whose bound exceeds the lower bound by more than the tolerance are split in
/// four at their edge midpoints (new samples), until every bound is within the
/// tolerance: only triangles whose bound can still exceed the lower bound are ever
/// refined. For the symmetric `H(A, B) = max(h(A → B), h(B → A))` both directions share
/// one lower bound, so once one direction's bounds fall below the other's lower bound it
/// is never refined again (its own lower bound is then only as tight as it needed to be).
///
/// The two engines differ in how samples are answered and what else bounds a triangle:
///
/// - [`hausdorff`] (the default) gives **every** sample an exact closest point from a
///   [`TriangleTree`](crate::closest::TriangleTree) of the other mesh, and when the corners'
///   triangles are not enough asks the tree for the best single triangle
///   ([`TriangleTree::triangle_upper_bound`](crate::closest::TriangleTree::triangle_upper_bound)).
///   It refines in rounds at a fixed lower bound, each round's queries and bounds on
///   every core (identical results on one).
/// - `sphaera-sweep`'s `meshsweeper_hausdorff` (the paper's, on two `Sweeper`s) gives most samples only
///   a local walk from a neighbour's answer (an upper bound needs *a* point of `B`, not
///   the closest), certifies those that could raise the lower bound with a Meshsweeper
///   query, adds a bound through a level of detail of `B` from its hierarchy, and splits
///   the triangle with the largest bound first, on one thread.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_mesh::Length;
/// use sphaera_query::hausdorff::{Direction, HausdorffOptions, hausdorff};
///
/// // A cube with corners at ±1 and a unit sphere inside it.
/// let (cube, sphere) = (shapes::cube(2.0, 8)?, shapes::sphere(1.0, 32)?);
/// let options = HausdorffOptions::default().with_tolerance(Length::Absolute(1e-6));
/// let result = hausdorff(&cube, &sphere, &options)?;
/// assert!(result.lower <= result.upper && result.gap() <= 1e-6);
/// // The cube's corners are farthest: √3 − 1 from the (tessellated) sphere.
/// assert_eq!(result.dominating, Direction::AToB);
/// assert!((result.upper - (3f64.sqrt() - 1.0)).abs() < 1e-2);
/// assert!(result.dominating_side().farthest.abs().min_element() > 0.999);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct HausdorffOptions {
    /// Stop once `upper − lower` is at most this: [`Length::Absolute`] in the meshes'
    /// units, or [`Length::RelativeToDiagonal`] as a fraction of the bounding-box diagonal
    /// of both meshes together (not of the distance). Default
    /// `Length::RelativeToDiagonal(1e-4)`.
    pub tolerance: Length,
    /// Stop refining once this many samples (vertices included) were queried; the result
    /// then says `converged: false`. Default 20 million (about 1.3 GB of samples); at most
    /// [`MAX_HAUSDORFF_SAMPLES`] (2²⁵), checked by both engines before they start.
    pub max_samples: usize,
    /// Certify the distance of every vertex (default `false`) in `sphaera-sweep`'s
    /// `meshsweeper_hausdorff`: the
    /// [`vertex_distances`](DirectedHausdorff::vertex_distances) are then exact, at the
    /// cost of one coherent closest-point query per vertex instead of a local walk.
    /// [`hausdorff`]'s are always exact.
    pub exact_vertex_distances: bool,
    /// The symmetric `H(A, B) = max(h(A → B), h(B → A))` (`true`, the default), or the
    /// one-sided `h(A → B)` only.
    pub symmetric: bool,
}

impl Default for HausdorffOptions {
    fn default() -> Self {
        Self {
            tolerance: Length::RelativeToDiagonal(1e-4),
            max_samples: 20_000_000,
            exact_vertex_distances: false,
            symmetric: true,
        }
    }
}

impl HausdorffOptions {
    /// With the given tolerance.
    #[must_use]
    pub fn with_tolerance(mut self, tolerance: Length) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// With a sample budget (at most [`MAX_HAUSDORFF_SAMPLES`]).
    #[must_use]
    pub fn with_max_samples(mut self, max_samples: usize) -> Self {
        self.max_samples = max_samples;
        self
    }

    /// With every vertex distance certified exact, or not.
    #[must_use]
    pub fn with_exact_vertex_distances(mut self, exact: bool) -> Self {
        self.exact_vertex_distances = exact;
        self
    }

    /// With the symmetric distance (`true`) or the one-sided `h(A → B)` (`false`).
    #[must_use]
    pub fn with_symmetric(mut self, symmetric: bool) -> Self {
        self.symmetric = symmetric;
        self
    }
}

impl HausdorffProgress {
    /// A report: `vertices_done` of `vertices` queried, `samples` in all, the current
    /// bounds (for engines outside this crate).
    #[must_use]
    pub fn new(
        vertices_done: usize,
        vertices: usize,
        samples: usize,
        lower: f64,
        upper: f64,
    ) -> Self {
        Self {
            vertices_done,
            vertices,
            samples,
            lower,
            upper,
        }
    }
}

impl HausdorffDistance {
    /// The distance from its directions `A → B` and (when symmetric) `B → A`, in that
    /// order: the bounds of the one-sided distance, or the larger of both; `converged`
    /// says whether every direction met its tolerance. What each engine returns.
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`] without any direction.
    pub fn from_directions(
        mut directed: impl Iterator<Item = DirectedHausdorff>,
        converged: bool,
    ) -> Result<Self, QueryError> {
        let a_to_b = directed.next().ok_or(QueryError::EmptyMesh)?;
        let b_to_a = directed.next();
        let (lower, upper, dominating) = match &b_to_a {
            Some(b) if b.lower > a_to_b.lower => {
                (b.lower, a_to_b.upper.max(b.upper), Direction::BToA)
            }
            Some(b) => (a_to_b.lower, a_to_b.upper.max(b.upper), Direction::AToB),
            None => (a_to_b.lower, a_to_b.upper, Direction::AToB),
        };
        Ok(Self {
            lower,
            upper,
            a_to_b,
            b_to_a,
            dominating,
            converged,
        })
    }
}

impl HausdorffOptions {
    /// The tolerance in the meshes' units, for meshes of positions `a` and `b` (a relative
    /// tolerance is a fraction of their joint bounding-box diagonal).
    ///
    /// Both engines call it first: it checks the options.
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidParameter`] for a negative or non-finite tolerance, or a
    /// sample budget above [`MAX_HAUSDORFF_SAMPLES`].
    pub fn allowed_gap(&self, a: &[DVec3], b: &[DVec3]) -> Result<f64, QueryError> {
        if self.max_samples > MAX_HAUSDORFF_SAMPLES {
            return Err(QueryError::InvalidParameter {
                name: "max_samples",
                value: self.max_samples as f64,
                requirement: "at most `hausdorff::MAX_HAUSDORFF_SAMPLES` (2^25, about 33.5 \
                              million samples)",
            });
        }
        let value = self.tolerance.value();
        if !(value.is_finite() && value >= 0.0) {
            return Err(QueryError::InvalidParameter {
                name: "tolerance",
                value,
                requirement: "finite and non-negative",
            });
        }
        Ok(match self.tolerance {
            Length::Absolute(t) => t,
            Length::RelativeToDiagonal(f) => f * joint_diagonal(a, b),
        })
    }
}

/// The largest sample budget ([`HausdorffOptions::max_samples`]) either engine accepts:
/// 2²⁵ (33.5 million) samples, about 2 to 3.4 GB at 64 to 100 bytes a sample. A larger
/// budget is refused ([`QueryError::InvalidParameter`] named `"max_samples"`) before
/// anything is computed, so that a typo cannot exhaust memory; the default, 20 million,
/// is within it.
pub const MAX_HAUSDORFF_SAMPLES: usize = 1 << 25;

/// The Hausdorff distance between meshes `a` and `b`, bracketed by certified bounds as
/// `options` say (see [`HausdorffOptions`] for the method): the fastest engine, on every
/// core with the `parallel` feature (the same result on one).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{Length, shapes};
/// use sphaera_query::hausdorff::{HausdorffOptions, hausdorff};
///
/// let cube = shapes::cube(2.0, 4)?;
/// let same = hausdorff(&cube, &cube, &HausdorffOptions::default())?;
/// assert_eq!((same.lower, same.upper), (0.0, 0.0));
///
/// // A sphere of radius 1 against one of radius 1.1: about 0.1 apart.
/// let (small, large) = (shapes::sphere(1.0, 32)?, shapes::sphere(1.1, 32)?);
/// let options = HausdorffOptions::default().with_tolerance(Length::Absolute(1e-9));
/// let h = hausdorff(&small, &large, &options)?;
/// assert!(h.lower <= h.upper && h.gap() <= 1e-9);
/// assert!((h.upper - 0.1).abs() < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`QueryError::InvalidParameter`] for a negative or non-finite tolerance or a sample
/// budget above [`MAX_HAUSDORFF_SAMPLES`]; [`QueryError::EmptyMesh`] if a mesh has no
/// triangle.
///
/// # Performance
///
/// A triangle tree per mesh, an exact query per used vertex and per midpoint, a bound per
/// triangle of samples. The 69k-triangle bunny against its 10k-triangle simplification to
/// 1e-5 of the diagonal: see the section *Hausdorff distance (`sphaera-sweep`)* of
/// `docs/benchmarks.md` in the repository.
pub fn hausdorff(
    a: &TriMesh,
    b: &TriMesh,
    options: &HausdorffOptions,
) -> Result<HausdorffDistance, QueryError> {
    hausdorff_with_progress(a, b, options, &|_| {})
}

/// [`hausdorff`], calling `progress` after the vertices and after every round of
/// refinement (from the calling thread).
///
/// # Examples
///
/// ```
/// use std::sync::atomic::{AtomicUsize, Ordering};
/// use sphaera_mesh::shapes;
/// use sphaera_query::hausdorff::{HausdorffOptions, HausdorffProgress, hausdorff_with_progress};
///
/// let (cube, sphere) = (shapes::cube(2.0, 24)?, shapes::sphere(1.0, 48)?);
/// let reports = AtomicUsize::new(0);
/// let report = |p: &HausdorffProgress| {
///     assert!(p.lower <= p.upper);
///     reports.fetch_add(1, Ordering::Relaxed);
/// };
/// let h = hausdorff_with_progress(&cube, &sphere, &HausdorffOptions::default(), &report)?;
/// assert!(h.lower <= h.upper);
/// assert!(reports.into_inner() > 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// As [`hausdorff`].
pub fn hausdorff_with_progress(
    a: &TriMesh,
    b: &TriMesh,
    options: &HausdorffOptions,
    progress: &(dyn Fn(&HausdorffProgress) + Sync),
) -> Result<HausdorffDistance, QueryError> {
    let allowed = options.allowed_gap(a.positions(), b.positions())?;
    let (target_b, target_a) = if options.symmetric {
        let (b, a) = join(|| trees::TreeTarget::new(b), || trees::TreeTarget::new(a));
        (b?, Some(a?))
    } else {
        (trees::TreeTarget::new(b)?, None)
    };
    let mut sides = vec![trees::TreeSide::new(a, &target_b)];
    if let Some(target_a) = &target_a {
        sides.push(trees::TreeSide::new(b, target_a));
    }
    let (unsettled, converged) = trees::refine(&mut sides, allowed, options.max_samples, progress)?;
    let directed = sides
        .into_iter()
        .zip(unsettled)
        .map(|(side, upper)| side.finish(upper));
    HausdorffDistance::from_directions(directed, converged)
}

/// Both closures' results, side by side with the `parallel` feature.
fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    #[cfg(feature = "parallel")]
    {
        rayon::join(a, b)
    }
    #[cfg(not(feature = "parallel"))]
    {
        (a(), b())
    }
}

/// The bounding-box diagonal of both meshes' vertices together.
fn joint_diagonal(a: &[DVec3], b: &[DVec3]) -> f64 {
    let (lo, hi) = a.iter().chain(b).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let d = (hi - lo).length();
    if d.is_finite() { d } else { 0.0 }
}
