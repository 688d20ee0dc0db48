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

use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};
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

/// The distance between two triangles: 0 when they cross or touch, otherwise the
/// smallest of the vertex–triangle and edge–edge distances.
#[must_use]
pub fn triangle_distance(a: &Triangle, b: &Triangle) -> f64 {
    let edges = |t: &Triangle| [(t.a, t.b), (t.b, t.c), (t.c, t.a)];
    let crosses = |edge: (DVec3, DVec3), t: &Triangle| {
        sphaera_mesh::geometry::ray_triangle_intersection(edge.0, edge.1 - edge.0, t)
            .is_some_and(|hit| hit.t <= 1.0)
    };
    if edges(a).into_iter().any(|e| crosses(e, b)) || edges(b).into_iter().any(|e| crosses(e, a)) {
        return 0.0;
    }
    let mut d2 = f64::INFINITY;
    for p in [a.a, a.b, a.c] {
        d2 = d2.min(point_triangle_distance_squared(p, b));
    }
    for p in [b.a, b.b, b.c] {
        d2 = d2.min(point_triangle_distance_squared(p, a));
    }
    for (p0, p1) in edges(a) {
        for (q0, q1) in edges(b) {
            d2 = d2.min(
                sphaera_mesh::geometry::closest_points_between_segments(p0, p1, q0, q1)
                    .distance_squared,
            );
        }
    }
    d2.sqrt()
}

/// The distance between two closed meshes as solids, by brute force over every pair of
/// triangles: 0 when their surfaces cross or one holds a vertex of the other (by
/// winding number), otherwise the smallest triangle–triangle distance.
///
/// # Panics
///
/// When a mesh is not valid for a [`sphaera_query::Surface`].
#[must_use]
pub fn solid_distance(a: &TriMesh, b: &TriMesh) -> f64 {
    let inside = |outer: &TriMesh, inner: &TriMesh| {
        let surface = sphaera_query::Surface::new(outer).expect("a closed mesh");
        inner
            .positions()
            .first()
            .is_some_and(|&p| surface.is_inside(p))
    };
    if inside(a, b) || inside(b, a) {
        return 0.0;
    }
    let mut best = f64::INFINITY;
    for ta in a.triangle_iter() {
        for tb in b.triangle_iter() {
            best = best.min(triangle_distance(&ta, &tb));
            if best == 0.0 {
                return 0.0;
            }
        }
    }
    best
}
