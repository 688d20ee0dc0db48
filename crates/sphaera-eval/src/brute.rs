//! Brute force: the distance from a point to a mesh as the minimum over every triangle,
//! single thread, no acceleration structure. Shared by the `sweep_throughput` and
//! `hausdorff_gap_vs_time` experiments and the `hausdorff` bench.
//!
//! The distance to each triangle is [`point_triangle_distance_squared`] (exact, with its
//! own fallback for degenerate triangles), so the minimum is the exact distance to the
//! surface up to rounding.

use sphaera::mesh::{
    DVec3, TriMesh,
    geometry::{Triangle, point_triangle_distance_squared},
};

/// Every triangle of a mesh, ready for brute-force distances.
pub struct BruteForce {
    triangles: Vec<Triangle>,
}

impl BruteForce {
    /// The triangles of `mesh`.
    pub fn new(mesh: &TriMesh) -> Self {
        Self {
            triangles: mesh.triangle_iter().collect(),
        }
    }

    /// Triangles tested per query.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The distance from `p` to the surface (infinite for a mesh without triangles).
    pub fn distance(&self, p: DVec3) -> f64 {
        self.triangles
            .iter()
            .map(|t| point_triangle_distance_squared(p, t))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }
}

/// The paper's naive Hausdorff estimate (section 6): every sample of each mesh against
/// every triangle of the other, by brute force.
pub struct NaiveHausdorff {
    /// The largest distance found: `max(h(A → B), h(B → A))` over the samples, a *lower
    /// bound* of the symmetric Hausdorff distance (it certifies nothing above it).
    pub value: f64,
    /// Samples measured (both directions).
    pub samples: usize,
    /// Point–triangle distances evaluated (both directions).
    pub evaluations: usize,
}

/// The naive estimate of [`NaiveHausdorff`] with the referenced vertices of each mesh as
/// samples (an unreferenced vertex is not a point of the surface), taking every
/// `stride`-th of them (`stride` 1: all; a larger stride measures a subset whose time is
/// scaled by `evaluations` to extrapolate).
pub fn naive_hausdorff(a: &TriMesh, b: &TriMesh, stride: usize) -> NaiveHausdorff {
    let mut result = NaiveHausdorff {
        value: 0.0,
        samples: 0,
        evaluations: 0,
    };
    for (source, target) in [(a, b), (b, a)] {
        let target = BruteForce::new(target);
        for p in referenced_vertices(source)
            .into_iter()
            .step_by(stride.max(1))
        {
            result.value = result.value.max(target.distance(p));
            result.samples += 1;
            result.evaluations += target.triangle_count();
        }
    }
    result
}

/// The vertices of `mesh` that some triangle uses, in index order.
pub fn referenced_vertices(mesh: &TriMesh) -> Vec<DVec3> {
    let mut used = vec![false; mesh.vertex_count()];
    for &[i, j, k] in mesh.triangles() {
        for v in [i, j, k] {
            // A valid TriMesh's indices are in range (invariant); `get_mut` avoids a panic.
            if let Some(flag) = used.get_mut(v as usize) {
                *flag = true;
            }
        }
    }
    mesh.positions()
        .iter()
        .zip(&used)
        .filter_map(|(&p, &u)| u.then_some(p))
        .collect()
}

#[cfg(test)]
mod tests {
    use sphaera::mesh::shapes;

    use super::*;

    #[test]
    fn brute_force_matches_a_cube() {
        let cube = shapes::cube(2.0, 2).unwrap();
        let brute = BruteForce::new(&cube);
        assert!((brute.distance(DVec3::new(3.0, 0.0, 0.0)) - 2.0).abs() < 1e-12);
        assert!((brute.distance(DVec3::ZERO) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn naive_hausdorff_of_nested_cubes() {
        let small = shapes::cube(2.0, 2).unwrap();
        let (positions, triangles) = small.clone().into_parts();
        let big = TriMesh::new(positions.iter().map(|&p| 1.5 * p).collect(), triangles).unwrap();
        let naive = naive_hausdorff(&small, &big, 1);
        // The big cube's corners are √3 × 0.5 from the small one's.
        assert!((naive.value - 0.5 * 3f64.sqrt()).abs() < 1e-12);
        assert_eq!(naive.samples, 2 * small.vertex_count());
        assert_eq!(naive.evaluations, naive.samples * small.triangle_count());
    }
}
