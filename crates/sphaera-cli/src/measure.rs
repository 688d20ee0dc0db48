//! `--measure`: a sampled symmetric Hausdorff distance between two meshes.
//!
//! Each direction is the largest distance from a point of one surface to the other
//! surface, over every referenced vertex, every edge midpoint and [`RANDOM_SAMPLES`]
//! area-weighted random points (fixed seed) of the first. Every sample lies on its surface
//! and its distance to the other surface is exact (nearest triangle through
//! [`TriangleTree`]), so each value is one term of the supremum that defines the
//! Hausdorff distance: the result is a **lower bound** of the true distance, and the
//! simplifier's certified bound can never be below it.

use rayon::prelude::*;
use sphaera::mesh::{DVec3, TriMesh, closest::TriangleTree, sampling};

/// Random points per surface, on top of its vertices and edge midpoints.
pub const RANDOM_SAMPLES: usize = 100_000;

/// Fixed seed: the same meshes give the same value on every run.
const SEED: u64 = 0x5EED;

/// The sampled symmetric Hausdorff distance between the surfaces of `a` and `b` (0 when
/// either has no triangle); a lower bound of the true distance (see the module docs).
///
/// # Performance
///
/// One nearest-triangle query (`O(log T)` on well-spread meshes) per sample, in parallel;
/// about `V + 1.5 T + 100,000` samples per mesh.
pub fn sampled_hausdorff(a: &TriMesh, b: &TriMesh) -> f64 {
    if a.triangle_count() == 0 || b.triangle_count() == 0 {
        return 0.0;
    }
    let (Ok(to_a), Ok(to_b)) = (TriangleTree::new(a), TriangleTree::new(b)) else {
        return 0.0;
    };
    let a_to_b = directed(&samples(a, SEED), &to_b);
    let b_to_a = directed(&samples(b, SEED.wrapping_add(1)), &to_a);
    a_to_b.max(b_to_a)
}

/// The largest distance from `points` to `target` (0 for no points).
fn directed(points: &[DVec3], target: &TriangleTree) -> f64 {
    points
        .par_iter()
        .filter_map(|&p| target.distance(p).ok())
        .reduce(|| 0.0, f64::max)
}

/// The referenced vertices, the distinct edge midpoints and the random points of `mesh`.
fn samples(mesh: &TriMesh, seed: u64) -> Vec<DVec3> {
    let positions = mesh.positions();
    let mut referenced = vec![false; positions.len()];
    let mut edges = Vec::with_capacity(3 * mesh.triangle_count());
    for triangle in mesh.triangles() {
        for k in 0..3 {
            let (u, w) = (triangle[k], triangle[(k + 1) % 3]);
            referenced[u as usize] = true;
            edges.push((u.min(w), u.max(w)));
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let mut points: Vec<DVec3> = positions
        .iter()
        .zip(&referenced)
        .filter(|(_, used)| **used)
        .map(|(&p, _)| p)
        .collect();
    points.extend(
        edges
            .iter()
            .map(|&(u, w)| 0.5 * (positions[u as usize] + positions[w as usize])),
    );
    // Random sampling fails only when no triangle has positive area: then the vertices and
    // midpoints are all there is to sample.
    if let Ok(random) = sampling::random(mesh, RANDOM_SAMPLES, seed) {
        points.extend(random.into_iter().map(|s| s.position));
    }
    points
}

#[cfg(test)]
mod tests {
    use sphaera::mesh::shapes;

    use super::*;

    #[test]
    fn identical_meshes_are_at_distance_zero() {
        let sphere = shapes::sphere(1.0, 8).expect("a sphere");
        assert!(sampled_hausdorff(&sphere, &sphere) < 1e-12);
    }

    #[test]
    fn scaled_cube_distance_is_the_corner_offset() {
        // Every point of the small cube is 0.05 from the big one; the big cube's corners
        // are 0.05·√3 from the small one, and corners are sampled.
        let small = shapes::cube(1.0, 2).expect("a cube");
        let (positions, triangles) = small.clone().into_parts();
        let big =
            TriMesh::new(positions.iter().map(|&p| 1.1 * p).collect(), triangles).expect("a cube");
        let h = sampled_hausdorff(&small, &big);
        assert!((h - 0.05 * 3f64.sqrt()).abs() < 1e-12, "{h}");
        assert!((sampled_hausdorff(&big, &small) - h).abs() < 1e-15);
    }

    #[test]
    fn samples_cover_vertices_midpoints_and_random_points() {
        let cube = shapes::cube(1.0, 1).expect("a cube"); // 8 vertices, 18 edges
        assert_eq!(samples(&cube, 1).len(), 8 + 18 + RANDOM_SAMPLES);
    }
}
