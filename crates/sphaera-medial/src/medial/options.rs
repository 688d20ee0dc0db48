//! What a medial approximation should reach, and how it completes coverage.

use crate::MedialError;

/// How an uncovered sample chooses its cover sphere among the spheres of its Voronoi
/// cell (the paper's two criteria, section 4.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum CoverCriterion {
    /// The sphere with the smallest error: tighter, possibly more cover spheres.
    #[default]
    SmallestError,
    /// The sphere covering the most uncovered samples: fewer cover spheres.
    LargestCoverage,
}

impl CoverCriterion {
    /// Every criterion, the default first.
    pub const ALL: [Self; 2] = [Self::SmallestError, Self::LargestCoverage];

    /// The name users type and reports show (`"smallest-error"`, `"largest-coverage"`), as
    /// [`Display`](std::fmt::Display) writes it and [`FromStr`](std::str::FromStr) reads
    /// it.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_medial::CoverCriterion;
    ///
    /// assert_eq!("largest-coverage".parse(), Ok(CoverCriterion::LargestCoverage));
    /// assert_eq!(CoverCriterion::SmallestError.to_string(), "smallest-error");
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::SmallestError => "smallest-error",
            Self::LargestCoverage => "largest-coverage",
        }
    }
}

impl std::fmt::Display for CoverCriterion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for CoverCriterion {
    type Err = sphaera_mesh::ParseNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| {
                sphaera_mesh::ParseNameError::new(
                    "cover criterion",
                    s,
                    "smallest-error or largest-coverage",
                )
            })
    }
}

/// Options of [`MedialApproximation::build`](crate::MedialApproximation::build).
///
/// # Examples
///
/// ```
/// use sphaera_medial::MedialOptions;
///
/// let options = MedialOptions::default().with_target_spheres(500);
/// assert_eq!(options.target_spheres, Some(500));
/// assert_eq!(options.max_error, None);
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub struct MedialOptions {
    /// Stop improving once the set has at least this many spheres.
    pub target_spheres: Option<usize>,
    /// Stop improving once the worst sphere error is at most this (absolute, in mesh
    /// units).
    pub max_error: Option<f64>,
    /// Samples the Voronoi diagram starts from (spread by farthest-point selection
    /// among the surface samples); the adaptive algorithm adds more where needed.
    pub initial_points: usize,
    /// How uncovered samples choose their cover sphere.
    pub cover: CoverCriterion,
    /// A cap on improvement steps (each inserts one point).
    pub max_iterations: usize,
}

impl Default for MedialOptions {
    fn default() -> Self {
        Self {
            target_spheres: None,
            max_error: None,
            initial_points: 32,
            cover: CoverCriterion::SmallestError,
            max_iterations: 100_000,
        }
    }
}

impl MedialOptions {
    /// Improve until the set has at least `n` spheres.
    #[must_use]
    pub fn with_target_spheres(mut self, n: usize) -> Self {
        self.target_spheres = Some(n);
        self
    }

    /// Improve until the worst sphere error is at most `e` (mesh units).
    #[must_use]
    pub fn with_max_error(mut self, e: f64) -> Self {
        self.max_error = Some(e);
        self
    }

    /// With the given cover criterion.
    #[must_use]
    pub fn with_cover(mut self, cover: CoverCriterion) -> Self {
        self.cover = cover;
        self
    }

    /// With `n` samples for the Voronoi diagram to start from.
    #[must_use]
    pub fn with_initial_points(mut self, n: usize) -> Self {
        self.initial_points = n;
        self
    }

    /// With at most `n` improvement steps.
    #[must_use]
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }
}

/// What [`MedialApproximation::refine_region`](crate::MedialApproximation::refine_region)
/// must reach for the spheres covering a region: at least `min_spheres` of them, and a
/// worst error of at most `max_error`.
///
/// # Examples
///
/// ```
/// use sphaera_medial::RegionOptions;
///
/// let options = RegionOptions::default().with_min_spheres(100).with_max_error(0.01);
/// assert_eq!((options.min_spheres, options.max_error), (100, Some(0.01)));
/// assert_eq!(options.max_iterations, 20_000);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub struct RegionOptions {
    /// At least this many spheres cover some sample of the region (default 1).
    pub min_spheres: usize,
    /// Worst error of those spheres (mesh units); `None` for no bound (the default).
    pub max_error: Option<f64>,
    /// A cap on improvement steps for this region (default 20,000).
    pub max_iterations: usize,
}

impl Default for RegionOptions {
    fn default() -> Self {
        Self {
            min_spheres: 1,
            max_error: None,
            max_iterations: 20_000,
        }
    }
}

impl RegionOptions {
    /// With at least `n` spheres covering the region.
    #[must_use]
    pub fn with_min_spheres(mut self, n: usize) -> Self {
        self.min_spheres = n;
        self
    }

    /// With a worst error of at most `e` (mesh units).
    #[must_use]
    pub fn with_max_error(mut self, e: f64) -> Self {
        self.max_error = Some(e);
        self
    }

    /// With at most `n` improvement steps.
    #[must_use]
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }
}

/// Checks `options` before a build.
pub(super) fn validate_options(options: &MedialOptions) -> Result<(), MedialError> {
    if let Some(e) = options.max_error
        && (e.is_nan() || e < 0.0)
    {
        return Err(MedialError::InvalidParameter {
            name: "max_error",
            value: e,
            requirement: "a non-negative number",
        });
    }
    if options.initial_points < 4 {
        return Err(MedialError::InvalidParameter {
            name: "initial_points",
            value: options.initial_points as f64,
            requirement: "at least 4",
        });
    }
    Ok(())
}
