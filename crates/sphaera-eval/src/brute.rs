//! Brute force: the distance from a point to a mesh as the minimum over every triangle,
//! single thread, no acceleration structure. Shared by the `sweep_throughput` and
//! `hausdorff_gap_vs_time` experiments and the `hausdorff` bench.
//!
//! The distance to each triangle is [`point_triangle_distance_squared`] (exact, with its
//! own fallback for degenerate triangles), so the minimum is the exact distance to the
//! surface up to rounding.
//!
//! The naive Hausdorff estimate is `sphaera_mesh`'s sampled Hausdorff distance
//! ([`measure::sampled_hausdorff_by`]) on the vertex samples only, with this brute force as
//! its distance oracle, on one thread.

use sphaera::mesh::{
    DVec3, QueryError, TriMesh,
    geometry::{Triangle, point_triangle_distance_squared},
    measure::{self, MeasureOptions, SampleOptions, SurfaceSamples},
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
/// `stride`-th of them (`stride` 1 or 0: all; a larger stride measures a subset whose time
/// is scaled by `evaluations` to extrapolate).
///
/// The samples are [`SurfaceSamples`] of [`vertex_samples`], measured by
/// [`measure::sampled_hausdorff_by`] with [`BruteForce`] distances on the calling thread:
/// first every sample of `a` against `b`, then those of `b` against `a`.
///
/// # Errors
///
/// [`QueryError::EmptyMesh`] if a mesh has no triangle.
pub fn naive_hausdorff(
    a: &TriMesh,
    b: &TriMesh,
    stride: usize,
) -> Result<NaiveHausdorff, QueryError> {
    let (to_a, to_b) = (BruteForce::new(a), BruteForce::new(b));
    let options = MeasureOptions::default()
        .with_samples(vertex_samples(stride))
        .with_parallel(false);
    let h =
        measure::sampled_hausdorff_by(a, b, &options, |p| to_a.distance(p), |p| to_b.distance(p))?;
    Ok(NaiveHausdorff {
        value: h.symmetric(),
        samples: h.a_to_b.measured + h.b_to_a.measured,
        evaluations: h.a_to_b.measured * to_b.triangle_count()
            + h.b_to_a.measured * to_a.triangle_count(),
    })
}

/// The naive estimate's samples: every `stride`-th referenced vertex (all for 0 or 1), no
/// edge midpoint, no random point.
pub fn vertex_samples(stride: usize) -> SampleOptions {
    SampleOptions::default()
        .with_edge_midpoints(false)
        .with_random_points(0)
        .with_vertex_stride(stride.max(1))
}

/// The vertices of `mesh` that some triangle uses, in index order (the samples of
/// [`naive_hausdorff`] with stride 1).
pub fn referenced_vertices(mesh: &TriMesh) -> Vec<DVec3> {
    // Vertex samples without random points cannot fail (no parameter is out of range).
    SurfaceSamples::new(mesh, &vertex_samples(1))
        .map(SurfaceSamples::into_points)
        .unwrap_or_default()
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
        let naive = naive_hausdorff(&small, &big, 1).unwrap();
        // The big cube's corners are √3 × 0.5 from the small one's.
        assert!((naive.value - 0.5 * 3f64.sqrt()).abs() < 1e-12);
        assert_eq!(naive.samples, 2 * small.vertex_count());
        assert_eq!(naive.evaluations, naive.samples * small.triangle_count());
    }
}
