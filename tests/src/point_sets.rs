//! Reproducible point sets for tests and benchmarks, including the degenerate ones a
//! Delaunay code must survive (grids, exactly cospherical and cocircular points).
//!
//! They were `sphaera_medial::point_sets`, public API that only tests, benches and
//! examples used. They return plain [`DVec3`]s (glam's), so unit tests of any crate may
//! use them (see the [crate documentation](crate)).

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sphaera_mesh::DVec3;

/// `n` nearly uniform unit vectors: the Fibonacci lattice on the sphere (`z` in equal
/// steps from near 1 to near −1, the azimuth turned by the golden angle each step).
///
/// # Examples
///
/// ```
/// let directions = sphaera_tests::point_sets::fibonacci_sphere(300);
/// assert_eq!(directions.len(), 300);
/// assert!(directions.iter().all(|d| (d.length() - 1.0).abs() < 1e-12));
/// ```
#[must_use]
pub fn fibonacci_sphere(n: usize) -> Vec<DVec3> {
    let golden_angle = std::f64::consts::PI * (3.0 - 5.0_f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = golden_angle * i as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// `n` points uniform in the unit cube, from `seed`.
///
/// # Examples
///
/// ```
/// let points = sphaera_tests::point_sets::random_in_cube(100, 7);
/// assert_eq!(points, sphaera_tests::point_sets::random_in_cube(100, 7));
/// assert!(points.iter().all(|p| p.min_element() >= 0.0 && p.max_element() < 1.0));
/// ```
#[must_use]
pub fn random_in_cube(n: usize, seed: u64) -> Vec<DVec3> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| DVec3::new(rng.random(), rng.random(), rng.random()))
        .collect()
}

/// About `n` points on the surface of the cube `[0, k]³` at the integer grid points, with
/// `k` chosen so that the count is closest to `n`: every face is a plane of cocircular
/// squares, the worst case for ties.
///
/// # Examples
///
/// ```
/// let points = sphaera_tests::point_sets::cube_surface_grid(100_000);
/// assert!(points.len().abs_diff(100_000) < 1_000);
/// ```
#[must_use]
pub fn cube_surface_grid(n: usize) -> Vec<DVec3> {
    // A k-cube has (k+1)³ − (k−1)³ = 6k² + 2 surface grid points.
    let k = ((n as f64 - 2.0).max(6.0) / 6.0).sqrt().round().max(1.0) as i32;
    let mut points = Vec::with_capacity(6 * (k as usize).pow(2) + 2);
    for x in 0..=k {
        for y in 0..=k {
            for z in 0..=k {
                let on_surface = [x, y, z].iter().any(|&c| c == 0 || c == k);
                if on_surface {
                    points.push(DVec3::new(f64::from(x), f64::from(y), f64::from(z)));
                }
            }
        }
    }
    points
}

/// The integer points with `x² + y² + z² = r²`: exactly cospherical.
///
/// # Examples
///
/// ```
/// let points = sphaera_tests::point_sets::integer_sphere(5);
/// assert!(points.iter().all(|p| p.length_squared() == 25.0));
/// ```
#[must_use]
pub fn integer_sphere(r: i32) -> Vec<DVec3> {
    let mut points = Vec::new();
    for x in -r..=r {
        for y in -r..=r {
            for z in -r..=r {
                if x * x + y * y + z * z == r * r {
                    points.push(DVec3::new(f64::from(x), f64::from(y), f64::from(z)));
                }
            }
        }
    }
    points
}
