//! The evaluation of a whole sphere set: error statistics and coverage.

use std::time::{Duration, Instant};

use sphaera_mesh::Length;
use sphaera_query::Surface;

use super::coverage::{Coverage, coverage};
use super::sphere_fit::{SphereFit, check_spheres, sphere_errors};
use super::{EvaluationOptions, SCREENING_FACTOR};
use crate::{Sphere, SphereTreeError};

/// The fit of a sphere set (a sphere-tree level, or any flat set) to an object: the
/// paper's section-6 measures, computed the same way for every method.
///
/// # Examples
///
/// ```
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, evaluate_set};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let mesh = shapes::cube(2.0, 1)?;
/// let surface = Surface::new(&mesh)?;
/// // The circumscribed ball of the cube [-1, 1]³ covers it; its points above the face
/// // centres are farthest from the cube, √3 − 1 away.
/// let ball = [Sphere::new(DVec3::ZERO, 3.0_f64.sqrt())];
/// let options = EvaluationOptions::default().with_coverage_samples(2_000);
/// let set = evaluate_set(&surface, &ball, &options)?;
/// assert_eq!(set.sphere_count, 1);
/// assert_eq!(set.coverage.uncovered, 0);
/// let exact = 3.0_f64.sqrt() - 1.0;
/// assert!(set.worst_lower <= exact + 1e-12 && exact <= set.worst_upper + 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SetEvaluation {
    /// The number of spheres.
    pub sphere_count: usize,
    /// The certified error of each sphere, in input order.
    pub fits: Vec<SphereFit>,
    /// The largest per-sphere lower bound: the worst error is at least this.
    pub worst_lower: f64,
    /// The largest per-sphere upper bound: the worst error is at most this.
    pub worst_upper: f64,
    /// The index of the sphere with the largest upper bound (the first on ties).
    pub worst_index: usize,
    /// The mean of the per-sphere errors' **upper bounds** (each within the tolerance of
    /// the true error when it converged).
    pub mean_error: f64,
    /// The population variance (divided by the count) of the per-sphere errors' upper
    /// bounds.
    pub error_variance: f64,
    /// Whether every sphere's interval converged to the tolerance.
    pub converged: bool,
    /// The absolute tolerance used.
    pub tolerance: f64,
    /// Uncovered surface fraction and largest gap.
    pub coverage: Coverage,
    /// Wall time of the evaluation (errors and coverage).
    pub elapsed: Duration,
}

/// Every sphere to [`SCREENING_FACTOR`] times the tolerance, then again to the tolerance
/// those whose upper bound is above the largest lower bound.
fn screened_errors(
    surface: &Surface,
    spheres: &[Sphere],
    options: &EvaluationOptions,
) -> Result<Vec<SphereFit>, SphereTreeError> {
    let tolerance = options.checked_tolerance(surface.diagonal())?;
    let coarse = options.with_tolerance(Length::Absolute(SCREENING_FACTOR * tolerance));
    let mut fits = sphere_errors(surface, spheres, &coarse)?;
    let floor = fits.iter().map(|f| f.lower).fold(0.0, f64::max);
    let open: Vec<usize> = (0..fits.len())
        .filter(|&i| fits[i].upper - fits[i].lower > tolerance && fits[i].upper > floor)
        .collect();
    let again: Vec<Sphere> = open.iter().map(|&i| spheres[i]).collect();
    for (i, fit) in open
        .into_iter()
        .zip(sphere_errors(surface, &again, options)?)
    {
        fits[i] = fit;
    }
    Ok(fits)
}

/// [`evaluate_set`] for spheres each known to reach at most `bounds[i]` beyond the surface
/// (certified upper bounds, such as a sphere-tree node's [`error`](crate::TreeNode::error)):
/// the worst error's interval is as narrow as [`evaluate_set`]'s, at a fraction of the
/// cost.
///
/// The spheres are evaluated in decreasing order of their bounds, in batches (in parallel
/// with the `parallel` feature; the result does not depend on it): a sphere whose bound is
/// within the tolerance of the largest lower bound found so far cannot be the worst by more
/// than the tolerance and is not evaluated (its interval is `[0, bound]`), and a sphere's
/// search stops once its upper bound falls to that lower bound. Every sphere's upper end is
/// the smaller of its search's and its bound. So the worst error's interval meets the
/// tolerance, and the other spheres' intervals are valid but may be wide (the mean and
/// variance of their upper ends are conservative).
///
/// # Examples
///
/// ```
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, evaluate_set, evaluate_set_bounded};
/// use sphaera_spheretree::{SphereTreeOptions, build};
///
/// let surface = Surface::new(&shapes::capsule(0.5, 2.0, 12)?)?;
/// let tree = build(&surface, &SphereTreeOptions::default().with_depth(2).with_branch(4))?;
/// let level = tree.level(2);
/// let spheres: Vec<_> = level.iter().map(|n| n.sphere).collect();
/// let bounds: Vec<f64> = level.iter().map(|n| n.error).collect();
/// let options = EvaluationOptions::default().with_coverage_samples(2_000);
/// let quick = evaluate_set_bounded(&surface, &spheres, &bounds, &options)?;
/// let full = evaluate_set(&surface, &spheres, &options)?;
/// assert!(quick.worst_lower <= full.worst_upper && full.worst_lower <= quick.worst_upper);
/// assert!(quick.worst_upper - quick.worst_lower <= quick.tolerance);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// As [`evaluate_set`], and [`SphereTreeError::InvalidParameter`] when `bounds` does not
/// have one finite bound per sphere.
///
/// # Panics
///
/// Never.
pub fn evaluate_set_bounded(
    surface: &Surface,
    spheres: &[Sphere],
    bounds: &[f64],
    options: &EvaluationOptions,
) -> Result<SetEvaluation, SphereTreeError> {
    let start = Instant::now();
    let tolerance = options.checked_tolerance(surface.diagonal())?;
    if spheres.is_empty() {
        return Err(SphereTreeError::EmptySphereSet);
    }
    check_spheres(spheres)?;
    if bounds.len() != spheres.len() || bounds.iter().any(|b| b.is_nan()) {
        return Err(SphereTreeError::InvalidParameter {
            name: "bounds",
            value: bounds.len() as f64,
            requirement: "one bound (not NaN) per sphere",
        });
    }
    let mut order: Vec<usize> = (0..spheres.len()).collect();
    order.sort_by(|&a, &b| bounds[b].total_cmp(&bounds[a]).then(a.cmp(&b)));
    let mut fits: Vec<Option<SphereFit>> = vec![None; spheres.len()];
    let mut floor = 0.0_f64;
    let batch = BOUNDED_BATCH;
    let mut next = 0;
    while next < order.len() {
        let chunk: Vec<usize> = order[next..]
            .iter()
            .copied()
            .take(batch)
            .take_while(|&i| bounds[i] > floor + tolerance)
            .collect();
        if chunk.is_empty() {
            break;
        }
        next += chunk.len();
        let settle = floor;
        let one = |&i: &usize| {
            super::sphere_fit::fit(surface, &spheres[i], tolerance, options.max_patches, settle)
        };
        #[cfg(feature = "parallel")]
        let found: Result<Vec<SphereFit>, SphereTreeError> = {
            use rayon::prelude::*;
            chunk.par_iter().map(one).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let found: Result<Vec<SphereFit>, SphereTreeError> = chunk.iter().map(one).collect();
        for (&i, fit) in chunk.iter().zip(found?) {
            floor = floor.max(fit.lower);
            fits[i] = Some(fit);
        }
    }
    let fits: Vec<SphereFit> = fits
        .into_iter()
        .zip(bounds)
        .map(|(fit, &bound)| match fit {
            Some(f) => SphereFit {
                upper: f.upper.min(bound.max(f.lower)),
                ..f
            },
            None => SphereFit {
                lower: 0.0,
                upper: bound.max(0.0),
                converged: true,
                patches: 0,
                witness: None,
            },
        })
        .collect();
    summarize(surface, spheres, fits, tolerance, options, start)
}

/// Spheres evaluated together by [`evaluate_set_bounded`] before the floor is raised.
const BOUNDED_BATCH: usize = 8;

/// Evaluates `spheres` against the object of `surface`: per-sphere
/// certified errors ([`sphere_errors`](super::sphere_errors)), their worst, mean and
/// variance, and the surface coverage ([`coverage`](super::coverage)).
///
/// # Examples
///
/// ```
/// use sphaera_query::Surface;
/// use sphaera_mesh::shapes;
/// use sphaera_spheretree::evaluate::{EvaluationOptions, evaluate_set};
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let mesh = shapes::sphere(1.0, 16)?;
/// let surface = Surface::new(&mesh)?;
/// let spheres = [Sphere::new(DVec3::new(0.0, 0.0, 0.9), 0.3), Sphere::new(DVec3::ZERO, 0.2)];
/// let options = EvaluationOptions::default().with_coverage_samples(5_000);
/// let set = evaluate_set(&surface, &spheres, &options)?;
/// assert_eq!(set.worst_index, 0);
/// assert!(set.worst_lower > 0.15 && set.worst_upper < 0.21);
/// assert!(set.coverage.uncovered_fraction > 0.9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::EmptySphereSet`] for no spheres (a defined "error 0, nothing
/// covered" would hide a bug upstream); [`SphereTreeError::InvalidSphere`] with the index
/// of the first invalid sphere; [`SphereTreeError::InvalidParameter`] for bad options;
/// [`SphereTreeError::Mesh`] when the mesh cannot be sampled.
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Dominated by the per-sphere branch and bound (see the [module
/// documentation](super)); the coverage costs `O(n log S)` for `n` samples.
pub fn evaluate_set(
    surface: &Surface,
    spheres: &[Sphere],
    options: &EvaluationOptions,
) -> Result<SetEvaluation, SphereTreeError> {
    let start = Instant::now();
    let tolerance = options.checked_tolerance(surface.diagonal())?;
    if spheres.is_empty() {
        return Err(SphereTreeError::EmptySphereSet);
    }
    check_spheres(spheres)?;
    let fits = if options.screening {
        screened_errors(surface, spheres, options)?
    } else {
        sphere_errors(surface, spheres, options)?
    };
    summarize(surface, spheres, fits, tolerance, options, start)
}

/// The set's statistics and coverage from its spheres' fits.
fn summarize(
    surface: &Surface,
    spheres: &[Sphere],
    fits: Vec<SphereFit>,
    tolerance: f64,
    options: &EvaluationOptions,
    start: Instant,
) -> Result<SetEvaluation, SphereTreeError> {
    let coverage = coverage(surface.mesh(), spheres, options)?;
    let n = fits.len() as f64;
    let mut worst_index = 0;
    for (i, f) in fits.iter().enumerate() {
        if f.upper > fits[worst_index].upper {
            worst_index = i;
        }
    }
    let worst_upper = fits[worst_index].upper;
    let worst_lower = fits.iter().map(|f| f.lower).fold(0.0, f64::max);
    let mean_error = fits.iter().map(|f| f.upper).sum::<f64>() / n;
    let error_variance = fits
        .iter()
        .map(|f| (f.upper - mean_error).powi(2))
        .sum::<f64>()
        / n;
    Ok(SetEvaluation {
        sphere_count: spheres.len(),
        converged: fits.iter().all(|f| f.converged),
        fits,
        worst_lower,
        worst_upper,
        worst_index,
        mean_error,
        error_variance,
        tolerance,
        coverage,
        elapsed: start.elapsed(),
    })
}
