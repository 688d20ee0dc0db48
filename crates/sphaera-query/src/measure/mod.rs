//! Sampled Hausdorff distances between two surfaces: a measured **lower bound** of the
//! true distance, the check that certified upper bounds are held against.
//!
//! # What it is for
//!
//! The simplifier's error spheres and the certified Hausdorff distance of `sphaera-sweep`
//! give *upper bounds*. This module gives the other side: the largest distance from a set
//! of points of one surface to the other surface. A certified bound below it is wrong. The
//! `sphaera simplify --measure` command prints it beside the simplifier's bound, and the
//! test helpers of the workspace (`sphaera-tests`) measure the same samples with parry3d's
//! projection as an independent oracle, refined around the best ones.
//!
//! # Why the result is a lower bound
//!
//! The directed Hausdorff distance `h(A → B) = sup_{p ∈ A} d(p, B)` is a supremum over
//! every point of the surface `A`. Every sample is a point of `A` (a referenced vertex, an
//! edge midpoint or a uniform random point), and `d(p, B)` is measured against the whole
//! of `B`, so each measured value is one term of the supremum:
//! `max_i d(p_i, B) ≤ h(A → B)`, up to floating-point rounding (a few ulps of the
//! coordinates). More samples can only raise the value towards the true distance, never
//! past it. The symmetric distance is the larger of both directions.
//!
//! # The parts
//!
//! - [`SurfaceSamples`]: the sample set of one surface, configured by [`SampleOptions`]:
//!   referenced vertices (optionally every `n`-th), distinct edge midpoints, seeded random
//!   points ([`crate::sampling::random`]), in that order, each with its [`SampleOrigin`].
//! - [`DirectedDistance`]: the largest distance from points to a target over **any
//!   distance oracle** (`Fn(DVec3) -> f64 + Sync`), where it is reached ([`Farthest`]) and
//!   how many points were measured; [`distances`] gives every value.
//! - [`sampled_hausdorff`]: both directions between two meshes with exact distances
//!   through [`TriangleTree`]; [`sampled_hausdorff_by`] with oracles of the caller's
//!   choice. [`MeasureOptions`] holds the sample options, the second surface's seed offset
//!   and the choice of threads.
//!
//! # Determinism
//!
//! Samples are drawn from fixed seeds; distances are computed in parallel with the
//! `parallel` feature but collected in sample order, and every maximum breaks ties by the
//! lowest sample index. The value, the point and the count are the same on every run, for
//! any number of threads, with or without the feature.
//!
//! # Examples
//!
//! ```
//! use sphaera_mesh::{TriMesh, shapes};
//! use sphaera_query::measure;
//!
//! let small = shapes::cube(1.0, 2)?;
//! let (positions, triangles) = small.clone().into_parts();
//! let big = TriMesh::new(positions.iter().map(|&p| 1.1 * p).collect(), triangles)?;
//! let h = measure::sampled_hausdorff(&small, &big, &measure::MeasureOptions::default())?;
//! // Every point of the small cube is 0.05 from the big one; the big cube's corners are
//! // 0.05·√3 from the small one, and vertices are samples.
//! assert!((h.a_to_b.distance - 0.05).abs() < 1e-12);
//! assert!((h.b_to_a.distance - 0.05 * 3f64.sqrt()).abs() < 1e-12);
//! assert_eq!(h.symmetric(), h.b_to_a.distance);
//! let corner = h.b_to_a.farthest.unwrap().point;
//! assert!((corner.abs() - glam::DVec3::splat(0.55)).length() < 1e-12);
//! // 26 vertices, 72 edge midpoints and 10,000 random points on each cube.
//! assert_eq!(h.a_to_b.measured, 26 + 72 + 10_000);
//! # Ok::<(), sphaera_query::QueryError>(())
//! ```
//!
//! # Errors
//!
//! [`QueryError::EmptyMesh`] when a mesh has no triangle (there is no surface to measure
//! to); [`QueryError::InvalidParameter`] for a bad [`SampleOptions`] (see
//! [`SurfaceSamples::new`]).
//!
//! # Performance
//!
//! One oracle call per sample: about `V + 1.5 T + n` samples per mesh. With
//! [`TriangleTree`] each is a nearest-triangle descent, `O(log T)` on well-spread
//! meshes. `sphaera simplify --measure` (100,000 random points per surface) was timed by
//! hand on the embedded bunny against its 10 % simplification; no bench keeps that
//! figure.

mod directed;
mod samples;
#[cfg(test)]
mod tests;

use glam::DVec3;

pub use directed::{DirectedDistance, Farthest, distances};
pub use samples::{SampleOptions, SampleOrigin, SurfaceSamples};

use crate::QueryError;
use crate::closest::TriangleTree;
use sphaera_mesh::TriMesh;

/// The default offset of the second surface's seed: `seed + 0x9E37_79B9_7F4A_7C15`
/// (2⁶⁴ over the golden ratio), so the two surfaces never draw the same random stream.
pub const DEFAULT_SECOND_SEED_OFFSET: u64 = 0x9E37_79B9_7F4A_7C15;

/// Options of [`sampled_hausdorff`] and [`sampled_hausdorff_by`].
///
/// # Examples
///
/// ```
/// use sphaera_query::measure::{MeasureOptions, SampleOptions};
///
/// let options = MeasureOptions::default()
///     .with_samples(SampleOptions::default().with_random_points(100_000).with_seed(7))
///     .with_second_seed_offset(1);
/// assert_eq!(options.samples.seed, 7);
/// assert_eq!(options.second_samples().seed, 8);
/// assert_eq!(options.second_samples().random_points, 100_000);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct MeasureOptions {
    /// The samples of both surfaces; the second surface draws its random points with the
    /// seed offset by [`MeasureOptions::second_seed_offset`].
    pub samples: SampleOptions,
    /// Added (wrapping) to the seed for the second surface (default
    /// [`DEFAULT_SECOND_SEED_OFFSET`]), so the two never draw the same random stream.
    pub second_seed_offset: u64,
    /// Measure on every core with the `parallel` feature (default `true`); `false`
    /// measures on the calling thread, for single-threaded timings. The result is the
    /// same either way.
    pub parallel: bool,
}

impl Default for MeasureOptions {
    /// The default [`SampleOptions`] on both surfaces, the second's seed offset by
    /// [`DEFAULT_SECOND_SEED_OFFSET`], on every core.
    fn default() -> Self {
        Self {
            samples: SampleOptions::default(),
            second_seed_offset: DEFAULT_SECOND_SEED_OFFSET,
            parallel: true,
        }
    }
}

impl MeasureOptions {
    /// With the given samples of both surfaces.
    #[must_use]
    pub fn with_samples(mut self, samples: SampleOptions) -> Self {
        self.samples = samples;
        self
    }

    /// With the given offset of the second surface's seed.
    #[must_use]
    pub fn with_second_seed_offset(mut self, second_seed_offset: u64) -> Self {
        self.second_seed_offset = second_seed_offset;
        self
    }

    /// Measured on every core (`true`) or on the calling thread.
    #[must_use]
    pub fn with_parallel(mut self, parallel: bool) -> Self {
        self.parallel = parallel;
        self
    }

    /// The samples of the second surface: the first's, with the seed offset.
    #[must_use]
    pub fn second_samples(&self) -> SampleOptions {
        self.samples
            .with_seed(self.samples.seed.wrapping_add(self.second_seed_offset))
    }
}

/// A sampled Hausdorff distance between meshes `A` and `B`: both directions.
///
/// Each direction is a **lower bound** of the true directed Hausdorff distance (see the
/// [module documentation](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledHausdorff {
    /// From the samples of `A` to the surface `B`.
    pub a_to_b: DirectedDistance,
    /// From the samples of `B` to the surface `A`.
    pub b_to_a: DirectedDistance,
}

impl SampledHausdorff {
    /// `max(a_to_b, b_to_a)`: a lower bound of the symmetric Hausdorff distance.
    ///
    /// # Examples
    ///
    /// See the [module documentation](self).
    pub fn symmetric(&self) -> f64 {
        self.a_to_b.distance.max(self.b_to_a.distance)
    }
}

/// The sampled Hausdorff distance between the surfaces of `a` and `b`, with exact
/// point-to-surface distances through a [`TriangleTree`] of each mesh.
///
/// # Examples
///
/// See the [module documentation](self).
///
/// # Errors
///
/// [`QueryError::EmptyMesh`] if a mesh has no triangle; [`QueryError::TooManyTriangles`]
/// beyond what the tree addresses; as [`SurfaceSamples::new`] for bad sample options.
///
/// # Performance
///
/// Builds both trees (`O(T log T)`), then one nearest-triangle query per sample; see the
/// [module documentation](self).
pub fn sampled_hausdorff(
    a: &TriMesh,
    b: &TriMesh,
    options: &MeasureOptions,
) -> Result<SampledHausdorff, QueryError> {
    let to_a = TriangleTree::new(a)?;
    let to_b = TriangleTree::new(b)?;
    // Samples lie on a finite mesh, so `distance` fails only for a point that overflowed
    // (an edge midpoint of coordinates near `f64::MAX`): NaN keeps it out of the maximum.
    sampled_hausdorff_by(
        a,
        b,
        options,
        |p: DVec3| to_a.distance(p).unwrap_or(f64::NAN),
        |p: DVec3| to_b.distance(p).unwrap_or(f64::NAN),
    )
}

/// The sampled Hausdorff distance between the surfaces of `a` and `b`, measured by the
/// caller's oracles: `distance_to_a(p)` is the distance from `p` to the surface of `a`,
/// `distance_to_b(p)` to that of `b`.
///
/// The samples of `a` ([`MeasureOptions::samples`]) are measured with `distance_to_b`,
/// then those of `b` ([`MeasureOptions::second_samples`]) with `distance_to_a`. The
/// result is a lower bound of the Hausdorff distance as long as the oracles are exact (or
/// never overestimate).
///
/// # Examples
///
/// A brute-force oracle over every triangle gives the same value as the default one:
///
/// ```
/// use sphaera_mesh::{DVec3, TriMesh, geometry, shapes};
/// use sphaera_query::measure;
///
/// let brute = |mesh: &TriMesh, p: DVec3| {
///     mesh.triangle_iter()
///         .map(|t| geometry::point_triangle_distance_squared(p, &t))
///         .fold(f64::INFINITY, f64::min)
///         .sqrt()
/// };
/// let a = shapes::sphere(1.0, 8)?;
/// let b = shapes::cube(1.5, 2)?;
/// let options = measure::MeasureOptions::default()
///     .with_samples(measure::SampleOptions::default().with_random_points(200));
/// let by_brute = measure::sampled_hausdorff_by(
///     &a,
///     &b,
///     &options,
///     |p| brute(&a, p),
///     |p| brute(&b, p),
/// )?;
/// let by_tree = measure::sampled_hausdorff(&a, &b, &options)?;
/// assert!((by_brute.symmetric() - by_tree.symmetric()).abs() < 1e-12);
/// assert_eq!(by_brute.b_to_a.measured, by_tree.b_to_a.measured);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Errors
///
/// [`QueryError::EmptyMesh`] if a mesh has no triangle; as [`SurfaceSamples::new`] for bad
/// sample options.
///
/// # Performance
///
/// One oracle call per sample, in parallel with the `parallel` feature unless
/// [`MeasureOptions::with_parallel`] says otherwise.
pub fn sampled_hausdorff_by<DA, DB>(
    a: &TriMesh,
    b: &TriMesh,
    options: &MeasureOptions,
    distance_to_a: DA,
    distance_to_b: DB,
) -> Result<SampledHausdorff, QueryError>
where
    DA: Fn(DVec3) -> f64 + Sync,
    DB: Fn(DVec3) -> f64 + Sync,
{
    if a.is_empty() || b.is_empty() {
        return Err(QueryError::EmptyMesh);
    }
    let a_to_b = directed(a, &options.samples, distance_to_b, options.parallel)?;
    let b_to_a = directed(
        b,
        &options.second_samples(),
        distance_to_a,
        options.parallel,
    )?;
    Ok(SampledHausdorff { a_to_b, b_to_a })
}

/// One direction: the samples of `source` measured by `distance_to_target`.
fn directed<D>(
    source: &TriMesh,
    samples: &SampleOptions,
    distance_to_target: D,
    parallel: bool,
) -> Result<DirectedDistance, QueryError>
where
    D: Fn(DVec3) -> f64 + Sync,
{
    let samples = SurfaceSamples::new(source, samples)?;
    Ok(if parallel {
        DirectedDistance::measure(samples.points(), distance_to_target)
    } else {
        DirectedDistance::measure_on_this_thread(samples.points(), distance_to_target)
    })
}
