//! What a medial approximation should reach, and how it completes coverage.

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

/// Parameters of [`MedialApproximation::build`](crate::MedialApproximation::build).
///
/// # Examples
///
/// ```
/// use sphaera_medial::MedialParams;
///
/// let params = MedialParams::default().spheres(500);
/// assert_eq!(params.target_spheres, Some(500));
/// assert_eq!(params.max_error, None);
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MedialParams {
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

impl Default for MedialParams {
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

impl MedialParams {
    /// Improve until the set has at least `n` spheres.
    #[must_use]
    pub fn spheres(mut self, n: usize) -> Self {
        self.target_spheres = Some(n);
        self
    }

    /// Improve until the worst sphere error is at most `e` (mesh units).
    #[must_use]
    pub fn max_error(mut self, e: f64) -> Self {
        self.max_error = Some(e);
        self
    }

    /// The cover criterion.
    #[must_use]
    pub fn cover(mut self, cover: CoverCriterion) -> Self {
        self.cover = cover;
        self
    }

    /// The number of samples the Voronoi diagram starts from.
    #[must_use]
    pub fn initial_points(mut self, n: usize) -> Self {
        self.initial_points = n;
        self
    }
}

/// What [`MedialApproximation::refine_region`](crate::MedialApproximation::refine_region)
/// must reach for the spheres covering a region: at least `min_spheres` of them, and a
/// worst error of at most `max_error`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RegionGoal {
    /// At least this many spheres cover some sample of the region.
    pub min_spheres: usize,
    /// Worst error of those spheres (mesh units); `f64::INFINITY` for no bound.
    pub max_error: f64,
    /// A cap on improvement steps for this region.
    pub max_iterations: usize,
}

impl RegionGoal {
    /// At least `min_spheres` spheres with worst error at most `max_error`.
    #[must_use]
    pub fn new(min_spheres: usize, max_error: f64) -> Self {
        Self {
            min_spheres,
            max_error,
            max_iterations: 20_000,
        }
    }
}
