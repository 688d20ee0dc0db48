//! `--measure`: a sampled symmetric Hausdorff distance between two meshes, by
//! [`sphaera::mesh::measure`].
//!
//! Each direction is the largest distance from a point of one surface to the other
//! surface, over every referenced vertex, every edge midpoint and [`RANDOM_SAMPLES`]
//! area-weighted random points (fixed seed) of the first, with exact distances
//! (nearest triangle through `TriangleTree`). Each value is one term of the supremum that
//! defines the Hausdorff distance: the result is a **lower bound** of the true distance,
//! and the simplifier's certified bound can never be below it.

use sphaera::mesh::{
    QueryError, TriMesh,
    measure::{self, MeasureOptions, SampleOptions},
};

/// Random points per surface, on top of its vertices and edge midpoints.
pub const RANDOM_SAMPLES: usize = 100_000;

/// Fixed seed of the first surface: the same meshes give the same value on every run.
const SEED: u64 = 0x5EED;

/// The second surface draws its random points with `SEED + 1`.
const SECOND_SEED_OFFSET: u64 = 1;

/// The options of `--measure`.
fn options() -> MeasureOptions {
    MeasureOptions::default()
        .with_samples(
            SampleOptions::default()
                .with_random_points(RANDOM_SAMPLES)
                .with_seed(SEED),
        )
        .with_second_seed_offset(SECOND_SEED_OFFSET)
}

/// The sampled symmetric Hausdorff distance between the surfaces of `a` and `b` (0 when
/// either has no triangle); a lower bound of the true distance (see the module docs).
///
/// # Errors
///
/// As [`measure::sampled_hausdorff`], except for a mesh without triangles.
///
/// # Performance
///
/// One nearest-triangle query (`O(log T)` on well-spread meshes) per sample, in parallel;
/// about `V + 1.5 T + 100,000` samples per mesh.
pub fn sampled_hausdorff(a: &TriMesh, b: &TriMesh) -> Result<f64, QueryError> {
    if a.is_empty() || b.is_empty() {
        return Ok(0.0);
    }
    Ok(measure::sampled_hausdorff(a, b, &options())?.symmetric())
}

#[cfg(test)]
mod tests {
    use sphaera::mesh::shapes;

    use super::*;

    #[test]
    fn identical_meshes_are_at_distance_zero() {
        let sphere = shapes::sphere(1.0, 8).expect("a sphere");
        assert!(sampled_hausdorff(&sphere, &sphere).expect("measured") < 1e-12);
    }

    #[test]
    fn scaled_cube_distance_is_the_corner_offset() {
        // Every point of the small cube is 0.05 from the big one; the big cube's corners
        // are 0.05·√3 from the small one, and corners are sampled.
        let small = shapes::cube(1.0, 2).expect("a cube");
        let (positions, triangles) = small.clone().into_parts();
        let big =
            TriMesh::new(positions.iter().map(|&p| 1.1 * p).collect(), triangles).expect("a cube");
        let h = sampled_hausdorff(&small, &big).expect("measured");
        assert!((h - 0.05 * 3f64.sqrt()).abs() < 1e-12, "{h}");
        assert!((sampled_hausdorff(&big, &small).expect("measured") - h).abs() < 1e-15);
    }

    #[test]
    fn samples_cover_vertices_midpoints_and_random_points() {
        let cube = shapes::cube(1.0, 1).expect("a cube"); // 8 vertices, 18 edges
        let options = options();
        let first = measure::SurfaceSamples::new(&cube, &options.samples).expect("samples");
        assert_eq!(first.len(), 8 + 18 + RANDOM_SAMPLES);
        assert_eq!(options.second_samples().seed, SEED + 1);
    }
}
