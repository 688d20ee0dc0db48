//! The parameters of fit evaluation.

use sphaera_mesh::Length;

use crate::SphereTreeError;

/// Default error tolerance, as a fraction of the mesh's bounding-box diagonal.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-4;

/// Default budget of surface patches per sphere.
pub const DEFAULT_MAX_PATCHES: usize = 50_000;

/// Default number of independent surface samples of the coverage measure.
pub const DEFAULT_COVERAGE_SAMPLES: usize = 100_000;

/// The largest patch budget per sphere ([`EvaluationOptions::max_patches`]): 2²⁰
/// (1,048,576, twenty times the default), about 200 MB of queued patches for one sphere
/// on each worker thread. A larger budget is refused by [`EvaluationOptions::validate`]
/// (named `"max_patches"`) before any sphere is evaluated.
pub const MAX_PATCHES: usize = 1 << 20;

/// The most coverage samples ([`EvaluationOptions::coverage_samples`]): the sampler's cap,
/// [`sphaera_query::sampling::MAX_SAMPLES`] (2²⁴, about 1.3 GB of samples). More are
/// refused by [`EvaluationOptions::validate`] (named `"coverage_samples"`) before any is
/// drawn.
pub const MAX_COVERAGE_SAMPLES: usize = sphaera_query::sampling::MAX_SAMPLES;

/// The tolerance of [`EvaluationOptions::level_report`], as a fraction of the diagonal:
/// what the CLI, the Python bindings and the experiments evaluate each level's cut to.
pub const LEVEL_REPORT_TOLERANCE: f64 = 1e-3;

/// Default seed of the coverage samples.
pub const DEFAULT_COVERAGE_SEED: u64 = 0x5EA1;

/// The 20 faces of the icosahedron the branch and bound starts from.
pub(crate) const INITIAL_PATCHES: usize = 20;

/// Options of [`sphere_error`](super::sphere_error), [`sphere_errors`](super::sphere_errors),
/// [`coverage`](super::coverage) and [`evaluate_set`](super::evaluate_set).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::Length;
/// use sphaera_spheretree::evaluate::EvaluationOptions;
///
/// let options = EvaluationOptions::default()
///     .with_tolerance(Length::Absolute(1e-3))
///     .with_coverage_samples(10_000)
///     .with_seed(7);
/// assert_eq!(options.tolerance_for(2.0), 1e-3);
/// assert_eq!(EvaluationOptions::default().tolerance_for(2.0), 2e-4);
/// assert_eq!(options.coverage_samples, 10_000);
/// assert!(options.validate().is_ok());
/// let negative = EvaluationOptions::default().with_tolerance(Length::Absolute(-1.0));
/// assert!(negative.validate().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct EvaluationOptions {
    /// The branch and bound stops when the certified interval `[lower, upper]` of a
    /// sphere's error is at most this wide (default [`DEFAULT_RELATIVE_TOLERANCE`], 10⁻⁴,
    /// of the mesh's bounding-box diagonal). Finite and positive.
    pub tolerance: Length,
    /// The most surface patches evaluated per sphere (default [`DEFAULT_MAX_PATCHES`], at
    /// least 20: the icosahedron's faces, and at most [`MAX_PATCHES`]); a sphere that
    /// reaches it reports `converged: false` (its interval stays valid, only wider).
    pub max_patches: usize,
    /// Independent area-weighted surface samples of the uncovered-surface measure
    /// (default [`DEFAULT_COVERAGE_SAMPLES`], at least 1 and at most
    /// [`MAX_COVERAGE_SAMPLES`]).
    pub coverage_samples: usize,
    /// Their seed (default [`DEFAULT_COVERAGE_SEED`]).
    pub seed: u64,
    /// [`evaluate_set`](super::evaluate_set): evaluate every sphere to
    /// [`SCREENING_FACTOR`] times the tolerance first, then to the tolerance only those
    /// whose interval reaches above the largest lower bound (the ones that may be the
    /// worst). The worst error's interval is as narrow as without; the other spheres'
    /// intervals, and so the mean and variance of their upper ends, are coarser (still
    /// valid bounds). Default off: every sphere to the tolerance.
    pub screening: bool,
}

/// How much coarser [`EvaluationOptions::screening`]'s first pass is.
pub const SCREENING_FACTOR: f64 = 10.0;

impl Default for EvaluationOptions {
    /// Tolerance 10⁻⁴ of the diagonal, 50,000 patches per sphere, 100,000 coverage samples.
    fn default() -> Self {
        Self {
            tolerance: Length::RelativeToDiagonal(DEFAULT_RELATIVE_TOLERANCE),
            max_patches: DEFAULT_MAX_PATCHES,
            coverage_samples: DEFAULT_COVERAGE_SAMPLES,
            seed: DEFAULT_COVERAGE_SEED,
            screening: false,
        }
    }
}

impl EvaluationOptions {
    /// With the given tolerance on the width of each sphere's error interval.
    #[must_use]
    pub fn with_tolerance(mut self, tolerance: Length) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// With a budget of surface patches per sphere.
    #[must_use]
    pub fn with_max_patches(mut self, max_patches: usize) -> Self {
        self.max_patches = max_patches;
        self
    }

    /// With `samples` surface samples for the coverage measure.
    #[must_use]
    pub fn with_coverage_samples(mut self, samples: usize) -> Self {
        self.coverage_samples = samples;
        self
    }

    /// The options every front end reports a tree's levels with ([`evaluate_level`]): the
    /// worst error to [`LEVEL_REPORT_TOLERANCE`] of the diagonal, the other spheres (the
    /// mean) more coarsely (screening on).
    ///
    /// [`evaluate_level`]: crate::evaluate::evaluate_level
    #[must_use]
    pub fn level_report() -> Self {
        Self::default()
            .with_tolerance(Length::RelativeToDiagonal(LEVEL_REPORT_TOLERANCE))
            .with_screening(true)
    }

    /// With screening on or off ([`EvaluationOptions::screening`]).
    #[must_use]
    pub fn with_screening(mut self, on: bool) -> Self {
        self.screening = on;
        self
    }

    /// With the given seed of the coverage samples.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// The absolute tolerance for a mesh of bounding-box diagonal `diagonal`.
    #[must_use]
    pub fn tolerance_for(&self, diagonal: f64) -> f64 {
        self.tolerance.resolve(diagonal)
    }

    /// Checks every option.
    ///
    /// # Errors
    ///
    /// [`SphereTreeError::InvalidParameter`] for a tolerance that is not finite and
    /// positive, a patch budget below 20 or above [`MAX_PATCHES`], no coverage samples or
    /// more than [`MAX_COVERAGE_SAMPLES`].
    pub fn validate(&self) -> Result<(), SphereTreeError> {
        let t = self.tolerance.value();
        if !(t.is_finite() && t > 0.0) {
            return Err(SphereTreeError::InvalidParameter {
                name: "tolerance",
                value: t,
                requirement: "finite and positive",
            });
        }
        if self.max_patches < INITIAL_PATCHES {
            return Err(SphereTreeError::InvalidParameter {
                name: "max_patches",
                value: self.max_patches as f64,
                requirement: "at least 20 (the icosahedron's faces)",
            });
        }
        if self.max_patches > MAX_PATCHES {
            return Err(SphereTreeError::InvalidParameter {
                name: "max_patches",
                value: self.max_patches as f64,
                requirement: "at most 1,048,576 (`evaluate::MAX_PATCHES`, 2^20)",
            });
        }
        if self.coverage_samples == 0 {
            return Err(SphereTreeError::InvalidParameter {
                name: "coverage_samples",
                value: 0.0,
                requirement: "at least 1",
            });
        }
        if self.coverage_samples > MAX_COVERAGE_SAMPLES {
            return Err(SphereTreeError::InvalidParameter {
                name: "coverage_samples",
                value: self.coverage_samples as f64,
                requirement: "at most 16,777,216 (`evaluate::MAX_COVERAGE_SAMPLES`, 2^24)",
            });
        }
        Ok(())
    }

    /// The tolerance for `diagonal`, checked.
    pub(crate) fn checked_tolerance(&self, diagonal: f64) -> Result<f64, SphereTreeError> {
        self.validate()?;
        let t = self.tolerance_for(diagonal);
        if t.is_finite() && t > 0.0 {
            Ok(t)
        } else {
            Err(SphereTreeError::InvalidParameter {
                name: "tolerance",
                value: t,
                requirement: "finite and positive (is the mesh degenerate?)",
            })
        }
    }
}
