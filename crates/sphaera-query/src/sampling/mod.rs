//! Seeded, deterministic sampling of points on a mesh's surface.
//!
//! Two samplers, both returning [`SurfaceSample`]s (position, triangle, barycentric
//! coordinates, normal) and both reproducible from a `u64` seed — on every run, every
//! platform, and with or without the `parallel` feature:
//!
//! - [`random`]: independent, uniformly distributed points (area-weighted triangle choice,
//!   then uniform in the triangle). Fast; clumps and gaps as random points do.
//! - [`poisson_disk`]: evenly spread points with a large minimum distance (a Poisson-disk
//!   set), by **sample elimination** (Cem Yuksel, "Sample Elimination for Generating
//!   Poisson Disk Sample Sets", Computer Graphics Forum 34(2), 2015): draw `k·n` random
//!   points, then greedily remove the point most crowded by its neighbours until exactly
//!   `n` remain. It reports the minimum distance it achieved relative to the ideal spacing
//!   of `n` points on that area.
//!
//! The medial-axis approximation and the sphere-trees use these points to test coverage
//! (every sample must lie inside some sphere), so even spacing means fewer points for the
//! same confidence.
//!
//! Distances are Euclidean (in space, not along the surface). Asking for `n = 0` points
//! returns an empty set, not an error.
//!
//! # Examples
//!
//! ```
//! use sphaera_query::sampling;
//! use sphaera_mesh::shapes;
//!
//! let mesh = shapes::sphere(1.0, 32)?;
//! let points = sampling::random(&mesh, 1000, 7)?;
//! assert_eq!(points.len(), 1000);
//! assert_eq!(points, sampling::random(&mesh, 1000, 7)?); // same seed, same points
//!
//! let even = sampling::poisson_disk(&mesh, 1000, 7)?;
//! assert_eq!(even.samples.len(), 1000);
//! // Random points come much closer to each other than Poisson-disk points.
//! assert!(even.relative_min_distance() > 0.5);
//! # Ok::<(), sphaera_query::QueryError>(())
//! ```
//!
//! # Errors
//!
//! [`QueryError::EmptyMesh`] for a mesh without triangles, [`QueryError::ZeroSurfaceArea`]
//! when every triangle is degenerate, [`QueryError::InvalidParameter`] for more than
//! [`MAX_SAMPLES`] points, a bad option, or a surface area too large for `f64`.
//!
//! # Performance
//!
//! [`random`] is `O(T + n log T)` for `T` triangles; [`poisson_disk`] is about
//! `O(T + k n log n)`, dominated by the neighbour search (parallel with the `parallel`
//! feature) and the elimination heap (an indexed max-heap with decrease-key). Only
//! [`poisson_disk`] is benched, as the medial approximation's first step (section
//! *Adaptive medial approximation* of `docs/benchmarks.md` in the repository).

mod grid;
mod poisson;
mod random;
#[cfg(test)]
mod tests;

pub use poisson::{PoissonDiskOptions, PoissonDiskSamples, poisson_disk, poisson_disk_with};
pub use random::random;

use glam::DVec3;

use crate::QueryError;
use sphaera_mesh::TriMesh;

/// The most points a sampler draws (2²⁴ ≈ 16.8 million, counting [`poisson_disk`]'s
/// oversampled candidates): a guard against a typo exhausting memory.
///
/// A [`SurfaceSample`] takes 80 bytes, so the cap bounds [`random`]'s output at about
/// 1.3 GB and [`poisson_disk`]'s candidates at the same (plus their neighbour lists, a few
/// times more). Within the cap, a failed allocation of the output is reported as
/// [`QueryError::InvalidParameter`] rather than aborting the process.
pub const MAX_SAMPLES: usize = 1 << 24;

/// A point on a mesh's surface.
///
/// # Examples
///
/// ```
/// use sphaera_query::sampling;
/// use sphaera_mesh::shapes;
///
/// let mesh = shapes::cube(1.0, 2)?;
/// for s in sampling::random(&mesh, 10, 1)? {
///     let [a, b, c] = mesh.triangles()[s.triangle].map(|v| mesh.positions()[v as usize]);
///     let [u, v, w] = s.barycentric;
///     assert!((u + v + w - 1.0).abs() < 1e-12);
///     assert!((s.position - (u * a + v * b + w * c)).length() < 1e-12);
/// }
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceSample {
    /// The point.
    pub position: DVec3,
    /// Index of the triangle it lies on.
    pub triangle: usize,
    /// Barycentric coordinates: weights of the triangle's first, second and third corner
    /// (non-negative, sum 1).
    pub barycentric: [f64; 3],
    /// The triangle's unit normal (outward for an outward-oriented mesh); zero only if the
    /// triangle is too small to normalise its normal.
    pub normal: DVec3,
}

/// Cumulative triangle areas for area-weighted triangle choice.
#[derive(Debug)]
struct AreaTable {
    /// `cumulative[t]` = total area of triangles `0..=t`.
    cumulative: Vec<f64>,
    /// The last triangle with positive area (where a draw that rounds up to the total
    /// lands).
    last_positive: usize,
}

impl AreaTable {
    /// The table for `mesh`.
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`], [`QueryError::ZeroSurfaceArea`], or
    /// [`QueryError::InvalidParameter`] if the area overflows.
    fn new(mesh: &TriMesh) -> Result<Self, QueryError> {
        if mesh.is_empty() {
            return Err(QueryError::EmptyMesh);
        }
        let mut total = 0.0;
        let mut last_positive = None;
        let cumulative = mesh
            .triangle_iter()
            .enumerate()
            .map(|(t, tri)| {
                let area = tri.area();
                if area > 0.0 {
                    last_positive = Some(t);
                }
                total += area;
                total
            })
            .collect();
        if !total.is_finite() {
            return Err(QueryError::InvalidParameter {
                name: "surface area",
                value: total,
                requirement: "finite (scale the mesh down)",
            });
        }
        match last_positive {
            Some(last_positive) if total > 0.0 => Ok(Self {
                cumulative,
                last_positive,
            }),
            _ => Err(QueryError::ZeroSurfaceArea {
                triangle_count: mesh.triangle_count(),
            }),
        }
    }

    /// Total area.
    fn total(&self) -> f64 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }

    /// The triangle whose cumulative-area interval holds `fraction · total`, for
    /// `fraction ∈ [0, 1)`: each triangle with probability proportional to its area,
    /// zero-area triangles never.
    fn pick(&self, fraction: f64) -> usize {
        let x = fraction * self.total();
        self.cumulative
            .partition_point(|&c| c <= x)
            .min(self.last_positive)
    }
}

/// An empty vector with room for `n` samples.
///
/// # Errors
///
/// [`QueryError::InvalidParameter`] (named `name`) if the memory cannot be reserved.
fn try_with_capacity<T>(name: &'static str, n: usize) -> Result<Vec<T>, QueryError> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| QueryError::InvalidParameter {
            name,
            value: n as f64,
            requirement: "small enough for the memory available",
        })?;
    Ok(v)
}

/// `Ok` if `n` is at most [`MAX_SAMPLES`].
fn check_count(name: &'static str, n: usize) -> Result<(), QueryError> {
    if n <= MAX_SAMPLES {
        Ok(())
    } else {
        Err(QueryError::InvalidParameter {
            name,
            value: n as f64,
            requirement: "at most `sampling::MAX_SAMPLES` (2^24)",
        })
    }
}
