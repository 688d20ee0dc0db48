//! Brute-force point-to-mesh distances, the reference of the closest-point tests: every
//! triangle measured, nothing skipped, no acceleration structure.
//!
//! # Examples
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_tests::brute;
//!
//! let cube = shapes::cube(1.0, 2).unwrap();
//! let p = DVec3::new(0.0, 0.0, 2.0);
//! assert!(brute::close(brute::distance(&cube, p), 1.5));
//! assert_eq!(brute::sorted_distances(&cube, p)[0], brute::distance(&cube, p));
//! ```

use sphaera_mesh::geometry::point_triangle_distance_squared;
use sphaera_mesh::{DVec3, TriMesh};

/// The distance from `p` to the nearest triangle of `mesh` (infinite for a mesh without
/// triangles).
#[must_use]
pub fn distance(mesh: &TriMesh, p: DVec3) -> f64 {
    mesh.triangle_iter()
        .map(|t| point_triangle_distance_squared(p, &t))
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

/// The distance from `p` to every triangle of `mesh`, in increasing order (ties between
/// triangles at nearly the same distance show in the first few).
#[must_use]
pub fn sorted_distances(mesh: &TriMesh, p: DVec3) -> Vec<f64> {
    let mut d: Vec<f64> = mesh
        .triangle_iter()
        .map(|t| point_triangle_distance_squared(p, &t).sqrt())
        .collect();
    d.sort_by(f64::total_cmp);
    d
}

/// Whether two exact distances agree: within `10⁻⁹` relative, or `10⁻¹²` absolute below
/// `10⁻³`.
#[must_use]
pub fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1e-3)
}
