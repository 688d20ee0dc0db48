//! Uniform random points on a surface.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{AreaTable, SurfaceSample, check_count};
use crate::QueryError;
use sphaera_mesh::TriMesh;

/// `n` independent points uniformly distributed over the surface of `mesh`, reproducible
/// from `seed`.
///
/// Each point picks a triangle with probability proportional to its area (cumulative areas
/// and a binary search), then a uniform point in it: for uniform `r₁`, `r₂ ∈ [0, 1)` and
/// `s = √r₁`, the barycentric coordinates `(1 − s, s (1 − r₂), s r₂)`. The random numbers
/// come from `ChaCha8Rng::seed_from_u64(seed)`, three per point, so the result is the
/// same on every platform and run. Degenerate (zero-area) triangles never receive points;
/// unreferenced vertices do not matter. `n = 0` gives an empty vector.
///
/// # Examples
///
/// ```
/// use sphaera_query::sampling;
/// use sphaera_mesh::shapes;
///
/// let mesh = shapes::cylinder(1.0, 2.0, 24)?;
/// let samples = sampling::random(&mesh, 500, 42)?;
/// assert_eq!(samples.len(), 500);
/// // Each point lies on the surface of the cylinder: on a cap or on the side.
/// assert!(samples.iter().all(|s| s.position.z.abs() <= 1.0 + 1e-12));
/// assert_ne!(samples, sampling::random(&mesh, 500, 43)?);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Errors
///
/// - [`QueryError::EmptyMesh`] if the mesh has no triangles;
/// - [`QueryError::ZeroSurfaceArea`] if all its triangles are degenerate;
/// - [`QueryError::InvalidParameter`] if `n` exceeds [`super::MAX_SAMPLES`], the memory for
///   `n` samples cannot be reserved, or the surface area overflows `f64`.
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// `O(T + n log T)` for `T` triangles, single-threaded (a single random stream keeps it
/// reproducible). No bench times it yet (see the section *Other primitives (no bench
/// yet)* of `docs/benchmarks.md` in the repository).
pub fn random(mesh: &TriMesh, n: usize, seed: u64) -> Result<Vec<SurfaceSample>, QueryError> {
    check_count("n", n)?;
    let table = AreaTable::new(mesh)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut samples = super::try_with_capacity("n", n)?;
    for _ in 0..n {
        let triangle = table.pick(rng.random::<f64>());
        let (r1, r2) = (rng.random::<f64>(), rng.random::<f64>());
        let s = r1.sqrt();
        let barycentric = [1.0 - s, s * (1.0 - r2), s * r2];
        // `pick` returns an index below the triangle count (it is clamped to the last
        // triangle with positive area), so this lookup always succeeds (invariant).
        let Some(tri) = mesh.triangle(triangle) else {
            continue;
        };
        let [u, v, w] = barycentric;
        samples.push(SurfaceSample {
            position: u * tri.a + v * tri.b + w * tri.c,
            triangle,
            barycentric,
            normal: tri.unit_normal().unwrap_or_default(),
        });
    }
    Ok(samples)
}
