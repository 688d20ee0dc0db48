//! How much of the surface a sphere set leaves uncovered, on independent samples.

use glam::DVec3;
use sphaera_mesh::TriMesh;
use sphaera_query::sampling;

use super::EvaluationOptions;
use super::sphere_bvh::SphereBvh;
use super::sphere_fit::check_spheres;
use crate::{Sphere, SphereTreeError};

/// The surface coverage of a sphere set, measured on independent, uniformly
/// area-weighted random surface samples ([`sampling::random`]).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, coverage};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let mesh = shapes::cube(2.0, 1)?; // [-1, 1]³, surface 24
/// // A huge ball bounded by (nearly) the plane x = 0 covers the half x ≥ 0 of the cube: the face x = 1 and half of four faces, 12 of 24.
/// let half = [Sphere::new(DVec3::new(1e6, 0.0, 0.0), 1e6)];
/// let options = EvaluationOptions::default().with_coverage_samples(20_000);
/// let cover = coverage(&mesh, &half, &options)?;
/// assert!((cover.uncovered_fraction - 0.5).abs() < 0.02);
/// // The farthest uncovered points are on the face x = −1, at the edges (1 from the ball).
/// assert!(cover.largest_gap > 0.98 && cover.largest_gap < 1.001);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage {
    /// The number of surface samples.
    pub samples: usize,
    /// How many of them lie outside every sphere.
    pub uncovered: usize,
    /// `uncovered / samples`: an estimate of the uncovered fraction of the surface area
    /// (standard error `√(q(1 − q)/samples)`).
    pub uncovered_fraction: f64,
    /// The largest distance from an uncovered sample to the nearest sphere's surface
    /// (`‖p − c‖ − r`), 0 when every sample is covered. A lower bound of the true largest
    /// gap of the surface.
    pub largest_gap: f64,
    /// The sample where `largest_gap` was found (`None` when every sample is covered).
    pub worst_sample: Option<DVec3>,
}

/// The uncovered surface fraction and largest gap of `spheres` on `mesh`, from
/// [`EvaluationOptions::coverage_samples`] independent samples drawn with
/// [`EvaluationOptions::seed`]. A sample on a sphere's surface counts as covered.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, coverage};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let mesh = shapes::sphere(1.0, 16)?;
/// let options = EvaluationOptions::default().with_coverage_samples(5_000);
/// let full = coverage(&mesh, &[Sphere::new(DVec3::ZERO, 1.0)], &options)?;
/// assert_eq!((full.uncovered, full.largest_gap), (0, 0.0));
/// let none = coverage(&mesh, &[Sphere::new(DVec3::ZERO, 0.5)], &options)?;
/// assert_eq!(none.uncovered_fraction, 1.0);
/// assert!(none.largest_gap > 0.49 && none.largest_gap <= 0.5 + 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::EmptySphereSet`] for no spheres;
/// [`SphereTreeError::InvalidSphere`] for the first invalid sphere;
/// [`SphereTreeError::InvalidParameter`] for bad options; [`SphereTreeError::Mesh`] when
/// the mesh cannot be sampled (no triangles, zero area, too many samples).
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// `O(n log S)` for `n` samples and `S` spheres (a bounding-volume hierarchy over the
/// spheres), in parallel with the `parallel` feature (identical results either way).
pub fn coverage(
    mesh: &TriMesh,
    spheres: &[Sphere],
    options: &EvaluationOptions,
) -> Result<Coverage, SphereTreeError> {
    options.validate()?;
    if spheres.is_empty() {
        return Err(SphereTreeError::EmptySphereSet);
    }
    check_spheres(spheres)?;
    let samples = sampling::random(mesh, options.coverage_samples, options.seed)?;
    let points: Vec<DVec3> = samples.iter().map(|s| s.position).collect();
    let bvh = SphereBvh::new(spheres)?;
    let gap = |p: &DVec3| bvh.distance_to_union(*p);
    #[cfg(feature = "parallel")]
    let gaps: Vec<f64> = {
        use rayon::prelude::*;
        points.par_iter().map(gap).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let gaps: Vec<f64> = points.iter().map(gap).collect();
    let mut uncovered = 0_usize;
    let mut largest_gap = 0.0_f64;
    let mut worst_sample = None;
    for (p, &g) in points.iter().zip(&gaps) {
        if g > 0.0 {
            uncovered += 1;
            if g > largest_gap {
                largest_gap = g;
                worst_sample = Some(*p);
            }
        }
    }
    Ok(Coverage {
        samples: points.len(),
        uncovered,
        uncovered_fraction: uncovered as f64 / points.len().max(1) as f64,
        largest_gap,
        worst_sample,
    })
}
