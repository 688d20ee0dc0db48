//! The parameters of fit evaluation.

use crate::SphereTreeError;

/// Default error tolerance, as a fraction of the mesh's bounding-box diagonal.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-4;

/// Default budget of surface patches per sphere.
pub const DEFAULT_MAX_PATCHES: usize = 50_000;

/// Default number of independent surface samples of the coverage measure.
pub const DEFAULT_COVERAGE_SAMPLES: usize = 100_000;

/// Default seed of the coverage samples.
pub const DEFAULT_COVERAGE_SEED: u64 = 0x5EA1;

/// The 20 faces of the icosahedron the branch and bound starts from.
pub(crate) const INITIAL_PATCHES: usize = 20;

/// Parameters of [`sphere_error`](super::sphere_error), [`sphere_errors`](super::sphere_errors),
/// [`coverage`](super::coverage) and [`evaluate_set`](super::evaluate_set), set
/// builder-style so that options can be added without breaking callers.
///
/// - **tolerance**: the branch and bound stops when the certified interval
///   `[lower, upper]` of a sphere's error is at most this wide. Absolute (scene units) with
///   [`EvaluationOptions::with_tolerance`]; by default
///   [`DEFAULT_RELATIVE_TOLERANCE`] (10⁻⁴) times the mesh's bounding-box diagonal.
/// - **patch budget** ([`DEFAULT_MAX_PATCHES`]): the most surface patches evaluated per
///   sphere; a sphere that reaches it reports `converged: false` (its interval stays
///   valid, only wider).
/// - **coverage samples and seed** ([`DEFAULT_COVERAGE_SAMPLES`],
///   [`DEFAULT_COVERAGE_SEED`]): the independent area-weighted surface samples of the
///   uncovered-surface measure.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::evaluate::EvaluationOptions;
///
/// let options = EvaluationOptions::default()
///     .with_tolerance(1e-3)
///     .with_coverage_samples(10_000)
///     .with_seed(7);
/// assert_eq!(options.tolerance_for(2.0), 1e-3);
/// assert_eq!(EvaluationOptions::default().tolerance_for(2.0), 2e-4);
/// assert_eq!(options.coverage_samples(), 10_000);
/// assert!(options.validate().is_ok());
/// assert!(EvaluationOptions::default().with_tolerance(-1.0).validate().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EvaluationOptions {
    tolerance: Option<f64>,
    relative_tolerance: f64,
    max_patches: usize,
    coverage_samples: usize,
    seed: u64,
}

impl Default for EvaluationOptions {
    /// Tolerance 10⁻⁴ of the diagonal, 50,000 patches per sphere, 100,000 coverage samples.
    fn default() -> Self {
        Self {
            tolerance: None,
            relative_tolerance: DEFAULT_RELATIVE_TOLERANCE,
            max_patches: DEFAULT_MAX_PATCHES,
            coverage_samples: DEFAULT_COVERAGE_SAMPLES,
            seed: DEFAULT_COVERAGE_SEED,
        }
    }
}

impl EvaluationOptions {
    /// Sets an absolute tolerance (scene units) on the width of each sphere's error
    /// interval; it replaces the relative tolerance. Must be finite and positive.
    #[must_use]
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = Some(tolerance);
        self
    }

    /// Sets the tolerance as a fraction of the mesh's bounding-box diagonal (default
    /// 10⁻⁴), and forgets any absolute tolerance. Must be finite and positive.
    #[must_use]
    pub fn with_relative_tolerance(mut self, fraction: f64) -> Self {
        self.tolerance = None;
        self.relative_tolerance = fraction;
        self
    }

    /// Sets the budget of surface patches evaluated per sphere (default 50,000, at
    /// least 20: the icosahedron's faces).
    #[must_use]
    pub fn with_max_patches(mut self, max_patches: usize) -> Self {
        self.max_patches = max_patches;
        self
    }

    /// Sets the number of surface samples of the coverage measure (default 100,000, at
    /// least 1).
    #[must_use]
    pub fn with_coverage_samples(mut self, samples: usize) -> Self {
        self.coverage_samples = samples;
        self
    }

    /// Sets the seed of the coverage samples.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// The absolute tolerance for a mesh of bounding-box diagonal `diagonal`.
    #[must_use]
    pub fn tolerance_for(&self, diagonal: f64) -> f64 {
        self.tolerance.unwrap_or(self.relative_tolerance * diagonal)
    }

    /// The budget of patches per sphere.
    #[must_use]
    pub fn max_patches(&self) -> usize {
        self.max_patches
    }

    /// The number of coverage samples.
    #[must_use]
    pub fn coverage_samples(&self) -> usize {
        self.coverage_samples
    }

    /// The seed of the coverage samples.
    #[must_use]
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Checks every option.
    ///
    /// # Errors
    ///
    /// [`SphereTreeError::InvalidParameter`] for a tolerance that is not finite and
    /// positive, a patch budget below 20 or no coverage samples.
    pub fn validate(&self) -> Result<(), SphereTreeError> {
        if let Some(t) = self.tolerance
            && !(t.is_finite() && t > 0.0)
        {
            return Err(SphereTreeError::InvalidParameter {
                name: "tolerance",
                value: t,
                requirement: "finite and positive",
            });
        }
        let rel = self.relative_tolerance;
        if !(rel.is_finite() && rel > 0.0) {
            return Err(SphereTreeError::InvalidParameter {
                name: "relative_tolerance",
                value: rel,
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
        if self.coverage_samples == 0 {
            return Err(SphereTreeError::InvalidParameter {
                name: "coverage_samples",
                value: 0.0,
                requirement: "at least 1",
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
