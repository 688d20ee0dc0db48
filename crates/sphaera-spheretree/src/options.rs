//! How a sphere-tree is built: the [`Method`] and the [`SphereTreeOptions`] of
//! [`build`](crate::build).

use sphaera_mesh::Length;
use sphaera_mesh::ParseNameError;

use crate::SphereTreeError;
use crate::reduce::Reducer;

/// The deepest tree a baseline method builds: an octree cell at depth 20 is a millionth of
/// the bounding cube's edge, far below any sample spacing, and deeper trees only repeat
/// one-sample leaves.
pub const MAX_BASELINE_DEPTH: usize = 20;

/// The deepest tree a medial method builds. Every node keeps at least one surface sample,
/// so even two children per node and ten million samples are used up by depth 24; past a
/// few levels more than the samples support, the leaves stop getting tighter and each
/// level only costs time (`--depth 1000` would run for hours).
pub const MAX_MEDIAL_DEPTH: usize = 24;

/// The most children per node (the most spheres of a one-level tree) the minimax method
/// builds: each child is fitted to its own pieces, and the region is split into about 400
/// pieces per child before it is divided.
pub const MAX_BRANCH: usize = 10_000;

/// The most surface samples ([`SphereTreeOptions::samples`]) a medial or baseline
/// method draws: 3,355,443, the most for which the Poisson-disk sampler's five candidates
/// per sample stay within [`sphaera_query::sampling::MAX_SAMPLES`] (2²⁴). More are
/// refused ([`SphereTreeError::InvalidParameter`] named `"samples"`) before anything is
/// sampled. (The minimax method does not sample.)
pub const MAX_SURFACE_SAMPLES: usize = sphaera_query::sampling::MAX_SAMPLES / 5;

/// The most surface samples a baseline method accepts (each costs about 100 bytes per
/// level): [`MAX_SURFACE_SAMPLES`], as for the medial methods. (It was 10,000,000, more
/// than the sampler ever drew.)
pub const MAX_BASELINE_SAMPLES: usize = MAX_SURFACE_SAMPLES;

/// How a sphere-tree is built: the minimax construction (the default), the paper's
/// adaptive medial construction with one of its reducers, or one of the classic methods
/// the paper compares against.
///
/// Every method gives a [`SphereTree`](crate::SphereTree) of the same structure: the
/// root is the minimum enclosing ball of the mesh's vertices, every node's region (its
/// part of the surface) is partitioned between its children, and every node's sphere
/// covers its region. Node errors are the paper's eq. 2
/// ([`TreeNode::error`](crate::TreeNode::error)); the certified error of a level comes
/// from [`evaluate_set`](crate::evaluate_set).
///
/// - [`Method::Minimax`] (and [`Method::Auto`], which chooses it) represents each region
///   exactly by triangle pieces and chooses the children that make the worst child's
///   error least ([`crate::minimax`]); it covers the surface exactly by construction,
///   builds to a depth, a budget (a one-level tree of `branch` spheres) or a tolerance
///   ([`SphereTreeOptions::tolerance`]), and handles shells (sheets without inside).
/// - The paper's medial methods ([`Method::is_medial`]) refine the adaptive medial
///   approximation in each node's region (section 4 of the paper, `sphaera-medial`) and
///   reduce its spheres to at most `branch` children; their coverage of the whole surface
///   is certified at every level ([`SphereTreeOptions::certify_coverage`]). They need a
///   solid.
/// - The baselines are the classic methods as published: their coverage is measured, not
///   certified.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::Method;
///
/// assert_eq!(Method::default(), Method::Auto);
/// assert_eq!(Method::Auto.resolved(), Method::Minimax);
/// assert_eq!(Method::from_name("expand"), Some(Method::Expand));
/// assert!(Method::Expand.is_medial() && !Method::Octree.is_medial());
/// assert!(Method::Minimax.certifies_coverage() && !Method::Octree.certifies_coverage());
/// assert_eq!(Method::ALL.len(), 9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Method {
    /// Medial spheres reduced by pair merges, the tightest result first
    /// ([`reduce::merge`](crate::reduce::merge)).
    Merge,
    /// Medial spheres reduced by bursting one at a time
    /// ([`reduce::burst`](crate::reduce::burst)).
    Burst,
    /// Medial spheres reduced by expand-select with `MaxElim`
    /// ([`reduce::expand_select`](crate::reduce::expand_select)).
    Expand,
    /// Both merge and expand-select per node, keeping the tighter set
    /// ([`reduce::combined`](crate::reduce::combined)); the paper's best method.
    Combined,
    /// The minimax construction ([`crate::minimax`]): each region, represented exactly by
    /// triangle pieces, divided between the children whose worst eq. 2 error is least
    /// (a search over medial candidates, then every centre moved off them on the exact
    /// surface). The tightest and fastest method here; the only one that builds to a
    /// tolerance and the only one for shells.
    Minimax,
    /// The default: the best method for the surface, today always [`Method::Minimax`]
    /// (the paper's methods remain available by name).
    #[default]
    Auto,
    /// The octree (Palmer and Grimsdale, Hubbard, O'Sullivan and Dingliana; section 2 of
    /// the paper): the bounding cube subdivided recursively into 8; every cube holding
    /// surface samples is a node whose sphere is the cube's circumscribed sphere (it
    /// contains the whole cube, so every part of the surface inside it, and makes the
    /// figures comparable with the classic toolkit's). At most 8 children per node
    /// whatever `branch` says; only `depth`, `samples` and `seed` are used.
    Octree,
    /// A regular grid per level: level `l` uses the cubic cells (anchored at the bounding
    /// box's minimum corner) of the smallest edge, found by bisection, for which at most
    /// `branch^l` cells hold a sample; a node is a (parent, cell) pair with the cell's
    /// circumscribed sphere. Consecutive grids are not nested, so a cell straddling two
    /// parents yields a child of each, and [`SphereTree::branch`](crate::SphereTree::branch)
    /// reports the most children any node got.
    Grid,
    /// Hubbard's medial-axis method, the paper's reference: a static medial
    /// approximation of [`SphereTreeOptions::forming_points`] forming points (never
    /// refined; its coverage of the samples completed), whose spheres covering a node's
    /// region are merged in pairs into approximate bounding spheres (the smallest sphere
    /// enclosing both spheres) until at most `branch` remain; pairs start as each
    /// sphere's 8 nearest centres, standing in for Hubbard's Voronoi neighbours.
    Hubbard,
}

impl Method {
    /// Every method: the paper's medial ones, minimax and the default, the baselines.
    pub const ALL: [Self; 9] = [
        Self::Merge,
        Self::Burst,
        Self::Expand,
        Self::Combined,
        Self::Minimax,
        Self::Auto,
        Self::Octree,
        Self::Grid,
        Self::Hubbard,
    ];

    /// The method's name, as the CLI and the reports spell it (`"merge"`, `"minimax"`,
    /// `"octree"`, …); also its [`Display`](std::fmt::Display), and what
    /// [`FromStr`](std::str::FromStr) parses.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Merge => "merge",
            Self::Burst => "burst",
            Self::Expand => "expand",
            Self::Combined => "combined",
            Self::Minimax => "minimax",
            Self::Auto => "auto",
            Self::Octree => "octree",
            Self::Grid => "grid",
            Self::Hubbard => "hubbard",
        }
    }

    /// The method named `name` (as [`Method::name`] spells it).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The method [`Method::Auto`] stands for; any other method itself.
    #[must_use]
    pub fn resolved(self) -> Self {
        match self {
            Self::Auto => Self::Minimax,
            other => other,
        }
    }

    /// Whether the method is one of the paper's, refining the adaptive medial
    /// approximation (merge, burst, expand, combined).
    #[must_use]
    pub fn is_medial(self) -> bool {
        self.reducer().is_some()
    }

    /// Whether the method certifies that every level covers the whole surface (the
    /// medial methods and minimax; not the baselines).
    #[must_use]
    pub fn certifies_coverage(self) -> bool {
        self.is_medial() || self.resolved() == Self::Minimax
    }

    /// The reducer of a medial method.
    pub(crate) fn reducer(self) -> Option<Reducer> {
        match self {
            Self::Merge => Some(Reducer::Merge),
            Self::Burst => Some(Reducer::Burst),
            Self::Expand => Some(Reducer::Expand),
            Self::Combined => Some(Reducer::Combined),
            Self::Minimax | Self::Auto | Self::Octree | Self::Grid | Self::Hubbard => None,
        }
    }
}

/// How hard the minimax method works for its accuracy ([`SphereTreeOptions::effort`]):
/// the time–accuracy trade-off of [`Method::Minimax`], charted in the repository's
/// `docs/benchmarks.md`.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::{Effort, SphereTreeOptions};
///
/// assert_eq!(SphereTreeOptions::default().effort, Effort::Default);
/// assert_eq!("quick".parse::<Effort>().ok(), Some(Effort::Quick));
/// assert!("fast".parse::<Effort>().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Effort {
    /// One start per division, one round of refinement, a coarse tiling of each region
    /// (about 1,500 pieces a node): for previews and for trees built while a user waits.
    Quick,
    /// The default: several starts where few nodes are divided (the root gets eight),
    /// four rounds of refinement, swaps at the root, regions balanced, about 8,000 pieces
    /// a node.
    #[default]
    Default,
    /// Twice the starts, six rounds, about 16,000 pieces a node: for trees built once and
    /// used for long. The default's tree is built as well and kept when it is the tighter
    /// (a division that is best for its own level can shape worse regions below it), so
    /// a thorough tree is never looser than the default's: by the product of its levels'
    /// worst errors when built to a depth, by its count of spheres with a tolerance.
    Thorough,
}

impl Effort {
    /// Every level, quickest first.
    pub const ALL: [Self; 3] = [Self::Quick, Self::Default, Self::Thorough];

    /// Its name, as the CLI spells it (`"quick"`, `"default"`, `"thorough"`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Quick => "quick",
            Self::Default => "default",
            Self::Thorough => "thorough",
        }
    }
}

impl std::str::FromStr for Effort {
    type Err = ParseNameError;

    /// Parses [`Effort::name`].
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|e| e.name() == s)
            .ok_or_else(|| ParseNameError::new("effort", s, "quick, default or thorough"))
    }
}

impl std::fmt::Display for Effort {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Method {
    type Err = ParseNameError;

    /// Parses [`Method::name`].
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_name(s).ok_or_else(|| {
            ParseNameError::new(
                "sphere-tree method",
                s,
                "auto, minimax, merge, burst, expand, combined, octree, grid or hubbard",
            )
        })
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Options of [`build`](crate::build), with the paper's defaults.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::{Method, SphereTreeOptions};
///
/// let options = SphereTreeOptions::default()
///     .with_method(Method::Expand)
///     .with_depth(2)
///     .with_branch(4);
/// assert_eq!((options.depth, options.branch, options.samples), (2, 4, 10_000));
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SphereTreeOptions {
    /// How the tree is built (default [`Method::Auto`]).
    pub method: Method,
    /// Children per node at most (default 8; at most [`MAX_BRANCH`] for the minimax
    /// method, which divides each region into pieces per child). For [`Method::Grid`],
    /// the growth of the occupied cell count per level; [`Method::Octree`] always splits a
    /// cell in 8. (The medial methods and the baselines never get more children than
    /// samples, so their `branch` sizes nothing.)
    pub branch: usize,
    /// Levels below the root (default 3; at most [`MAX_MEDIAL_DEPTH`] for the medial
    /// methods and [`MAX_BASELINE_DEPTH`] for the baselines).
    pub depth: usize,
    /// Surface samples standing for the surface (default 10,000; the paper used
    /// 5,000–10,000; at most [`MAX_SURFACE_SAMPLES`], 3,355,443, for the medial methods
    /// and the baselines; the minimax method does not sample).
    pub samples: usize,
    /// Seed of the surface sampling (default 1).
    pub seed: u64,
    /// Medial methods: spheres of the initial medial approximation (default 500; the
    /// paper: 500–1,000).
    pub initial_spheres: usize,
    /// Medial methods: medial spheres a node's region is refined to before reduction
    /// (default 100; the paper: 100–200).
    pub min_spheres_per_node: usize,
    /// Medial methods: the region's medial spheres must have at most this fraction of the
    /// parent's error (default ⅛, tighter at levels 2 and 3 than the paper's ½ to ¼ — use
    /// `0.5` for the paper's settings).
    pub error_fraction: f64,
    /// Medial methods: balance the division of a region between children by moving the
    /// dividing planes (default on).
    pub balance_regions: bool,
    /// Medial methods: certify that every level covers the whole surface, not only the
    /// samples, growing spheres where needed ([`crate::cover`]; default on).
    pub certify_coverage: bool,
    /// Medial methods: the certification's resolution (default 10⁻³ of the mesh's
    /// bounding-box diagonal, taken in the mesh's canonical pose so that it does not
    /// change when the mesh is turned; see [`crate::build`]): triangle pieces are split down to this size before a
    /// sphere is grown to contain one, so a sphere grows by about this much at most where
    /// two spheres barely overlap, and by the gap's size where a gap was.
    pub coverage_resolution: Length,
    /// [`Method::Hubbard`]: forming points of the static Voronoi diagram (default 600,
    /// which gives about 2,500 medial spheres on the low-res bunny, the size the paper
    /// used for Hubbard's method there).
    pub forming_points: usize,
    /// [`Method::Minimax`] (and [`Method::Auto`]): build until every leaf's certified
    /// error is at most this (absolute, or a fraction of the bounding-box diagonal),
    /// refining only the nodes that exceed it, each into the fewest children (at most
    /// `branch`) that meet it, as deep as needed; `depth` is then not used (default
    /// `None`: every node divided to `depth`). A tolerance that would need more than
    /// [`MAX_TREE_NODES`](crate::MAX_TREE_NODES) nodes or
    /// [`MAX_MEDIAL_DEPTH`] levels is refused
    /// ([`SphereTreeError::ToleranceUnreachable`]).
    pub tolerance: Option<Length>,
    /// [`Method::Minimax`] with a tolerance: the most nodes the tree may have (default and
    /// at most [`MAX_TREE_NODES`](crate::MAX_TREE_NODES)). A tolerance that would need more
    /// is refused ([`SphereTreeError::ToleranceUnreachable`]) as soon as the next level
    /// could exceed it, so a sphere budget and a tolerance can be asked for together: the
    /// tolerance is met within the budget, or the answer says it cannot be.
    pub max_nodes: usize,
    /// [`Method::Minimax`]: how hard each division works for its accuracy (default
    /// [`Effort::Default`]).
    pub effort: Effort,
}

impl Default for SphereTreeOptions {
    fn default() -> Self {
        Self {
            method: Method::Auto,
            branch: 8,
            depth: 3,
            samples: 10_000,
            seed: 1,
            initial_spheres: 500,
            min_spheres_per_node: 100,
            error_fraction: 0.125,
            balance_regions: true,
            certify_coverage: true,
            coverage_resolution: Length::RelativeToDiagonal(1e-3),
            forming_points: 600,
            tolerance: None,
            max_nodes: crate::MAX_TREE_NODES,
            effort: Effort::Default,
        }
    }
}

impl SphereTreeOptions {
    /// With the given construction method.
    #[must_use]
    pub fn with_method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// With `branch` children per node at most.
    #[must_use]
    pub fn with_branch(mut self, branch: usize) -> Self {
        self.branch = branch;
        self
    }

    /// With `depth` levels below the root.
    #[must_use]
    pub fn with_depth(mut self, depth: usize) -> Self {
        self.depth = depth;
        self
    }

    /// With `samples` surface samples.
    #[must_use]
    pub fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// With the given sampling seed.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// With `n` spheres in the initial medial approximation.
    #[must_use]
    pub fn with_initial_spheres(mut self, n: usize) -> Self {
        self.initial_spheres = n;
        self
    }

    /// With at least `n` medial spheres per node's region before reduction.
    #[must_use]
    pub fn with_min_spheres_per_node(mut self, n: usize) -> Self {
        self.min_spheres_per_node = n;
        self
    }

    /// With a node's medial spheres refined to at most `fraction` of the parent's error
    /// (in (0, 1]; checked by [`build`](crate::build)).
    #[must_use]
    pub fn with_error_fraction(mut self, fraction: f64) -> Self {
        self.error_fraction = fraction;
        self
    }

    /// With region balancing on or off.
    #[must_use]
    pub fn with_balance_regions(mut self, on: bool) -> Self {
        self.balance_regions = on;
        self
    }

    /// With surface-coverage certification on or off.
    #[must_use]
    pub fn with_certify_coverage(mut self, on: bool) -> Self {
        self.certify_coverage = on;
        self
    }

    /// With the given certification resolution.
    #[must_use]
    pub fn with_coverage_resolution(mut self, resolution: Length) -> Self {
        self.coverage_resolution = resolution;
        self
    }

    /// With `n` forming points for [`Method::Hubbard`]'s static diagram.
    #[must_use]
    pub fn with_forming_points(mut self, n: usize) -> Self {
        self.forming_points = n;
        self
    }

    /// With the given [`Effort`] (minimax only).
    #[must_use]
    pub fn with_effort(mut self, effort: Effort) -> Self {
        self.effort = effort;
        self
    }

    /// Built until every leaf's certified error meets `tolerance`
    /// ([`SphereTreeOptions::tolerance`]; minimax only).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{Length, shapes};
    /// use sphaera_query::Surface;
    /// use sphaera_spheretree::{SphereTreeOptions, build};
    ///
    /// let surface = Surface::new(&shapes::capsule(0.5, 2.0, 12)?)?;
    /// let options = SphereTreeOptions::default().with_tolerance(Length::RelativeToDiagonal(0.02));
    /// let tree = build(&surface, &options)?;
    /// let tolerance = 0.02 * surface.diagonal();
    /// assert!(tree.leaves().iter().all(|&leaf| tree.nodes()[leaf].error <= tolerance));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn with_tolerance(mut self, tolerance: Length) -> Self {
        self.tolerance = Some(tolerance);
        self
    }

    /// With at most `max_nodes` nodes in a tolerance tree
    /// ([`SphereTreeOptions::max_nodes`]).
    #[must_use]
    pub fn with_max_nodes(mut self, max_nodes: usize) -> Self {
        self.max_nodes = max_nodes;
        self
    }

    /// Checks the options the method uses.
    pub(crate) fn validate(&self) -> Result<(), SphereTreeError> {
        let bad = |name: &'static str, value: f64, requirement: &'static str| {
            Err(SphereTreeError::InvalidParameter {
                name,
                value,
                requirement,
            })
        };
        if let Some(tolerance) = self.tolerance {
            let value = tolerance.value();
            if !(value > 0.0 && value.is_finite()) {
                return bad("tolerance", value, "positive and finite");
            }
            if self.method.resolved() != Method::Minimax {
                return bad(
                    "tolerance",
                    value,
                    "used only by the minimax method (auto): the others build to a depth",
                );
            }
        }
        if self.method.resolved() == Method::Minimax {
            if self.depth > MAX_MEDIAL_DEPTH {
                return bad(
                    "depth",
                    self.depth as f64,
                    "at most 24 (`MAX_MEDIAL_DEPTH`)",
                );
            }
            if self.branch == 0 {
                return bad("branch", 0.0, "at least 1");
            }
            if self.max_nodes == 0 || self.max_nodes > crate::MAX_TREE_NODES {
                return bad(
                    "max_nodes",
                    self.max_nodes as f64,
                    "at least 1 and at most MAX_TREE_NODES (2^21)",
                );
            }
            if self.branch > MAX_BRANCH {
                return bad(
                    "branch",
                    self.branch as f64,
                    "at most 10,000 (`MAX_BRANCH`)",
                );
            }
            let resolution = self.coverage_resolution.value();
            if !(resolution > 0.0 && resolution.is_finite()) {
                return bad("coverage_resolution", resolution, "positive and finite");
            }
            return Ok(());
        }
        if self.method.is_medial() {
            if self.depth > MAX_MEDIAL_DEPTH {
                return bad(
                    "depth",
                    self.depth as f64,
                    "at most 24 (`MAX_MEDIAL_DEPTH`) for the medial methods",
                );
            }
            if self.branch == 0 {
                return bad("branch", 0.0, "at least 1");
            }
            if !(4..=MAX_SURFACE_SAMPLES).contains(&self.samples) {
                return bad(
                    "samples",
                    self.samples as f64,
                    "between 4 and 3,355,443 (`MAX_SURFACE_SAMPLES`)",
                );
            }
            let resolution = self.coverage_resolution.value();
            if !(resolution > 0.0 && resolution.is_finite()) {
                return bad("coverage_resolution", resolution, "positive and finite");
            }
            if !(self.error_fraction > 0.0 && self.error_fraction <= 1.0) {
                return bad("error_fraction", self.error_fraction, "in (0, 1]");
            }
            return Ok(());
        }
        if self.depth > MAX_BASELINE_DEPTH {
            return bad(
                "depth",
                self.depth as f64,
                "at most 20 (`MAX_BASELINE_DEPTH`) for the baseline methods",
            );
        }
        if self.branch == 0 {
            return bad("branch", 0.0, "at least 1");
        }
        if !(4..=MAX_BASELINE_SAMPLES).contains(&self.samples) {
            return bad(
                "samples",
                self.samples as f64,
                "between 4 and 3,355,443 (`MAX_BASELINE_SAMPLES`) for the baseline methods",
            );
        }
        if self.forming_points < 4 {
            return bad("forming_points", self.forming_points as f64, "at least 4");
        }
        Ok(())
    }
}

/// Progress of [`build_with_progress`](crate::build_with_progress).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct SphereTreeProgress {
    /// The level being built (1 for the root's children).
    pub level: usize,
    /// Nodes of that level's parents done.
    pub done: usize,
    /// Parents of that level.
    pub total: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for method in Method::ALL {
            assert_eq!(Method::from_name(method.name()), Some(method));
        }
        assert_eq!(Method::from_name("nope"), None);
        assert_eq!(
            Method::ALL.iter().filter(|m| m.is_medial()).count(),
            4,
            "the paper's four reducers"
        );
        assert_eq!(
            Method::ALL
                .iter()
                .filter(|m| m.certifies_coverage())
                .count(),
            6,
            "the reducers, minimax and the default"
        );
    }

    #[test]
    fn each_cap_itself_is_accepted() {
        let minimax = SphereTreeOptions::default()
            .with_depth(MAX_MEDIAL_DEPTH)
            .with_branch(MAX_BRANCH)
            .with_max_nodes(crate::MAX_TREE_NODES);
        assert!(minimax.validate().is_ok());
        let medial = SphereTreeOptions::default()
            .with_method(Method::Expand)
            .with_depth(MAX_MEDIAL_DEPTH)
            .with_samples(MAX_SURFACE_SAMPLES);
        assert!(medial.validate().is_ok());
        assert!(
            medial
                .with_samples(MAX_SURFACE_SAMPLES + 1)
                .validate()
                .is_err()
        );
        let baseline = SphereTreeOptions::default()
            .with_method(Method::Octree)
            .with_depth(MAX_BASELINE_DEPTH)
            .with_samples(MAX_BASELINE_SAMPLES);
        assert!(baseline.validate().is_ok());
    }

    #[test]
    fn each_method_checks_what_it_uses() {
        // Minimax (the default) ignores the medial options, checks its own.
        let bad_fraction = SphereTreeOptions::default().with_error_fraction(2.0);
        assert!(bad_fraction.validate().is_ok());
        assert!(matches!(
            SphereTreeOptions::default()
                .with_branch(MAX_BRANCH + 1)
                .validate(),
            Err(SphereTreeError::InvalidParameter { name: "branch", .. })
        ));
        assert!(matches!(
            SphereTreeOptions::default()
                .with_tolerance(Length::RelativeToDiagonal(f64::NAN))
                .validate(),
            Err(SphereTreeError::InvalidParameter {
                name: "tolerance",
                ..
            })
        ));
        // A tolerance is minimax's alone.
        assert!(matches!(
            SphereTreeOptions::default()
                .with_method(Method::Merge)
                .with_tolerance(Length::RelativeToDiagonal(0.01))
                .validate(),
            Err(SphereTreeError::InvalidParameter {
                name: "tolerance",
                ..
            })
        ));
        let medial = bad_fraction.with_method(Method::Expand);
        assert!(matches!(
            medial.validate(),
            Err(SphereTreeError::InvalidParameter {
                name: "error_fraction",
                ..
            })
        ));
        // The medial methods bound their depth too.
        assert!(matches!(
            medial.clone().with_depth(MAX_MEDIAL_DEPTH + 1).validate(),
            Err(SphereTreeError::InvalidParameter { name: "depth", .. })
        ));
        // A baseline ignores the medial options, and bounds its depth.
        assert!(
            medial
                .clone()
                .with_method(Method::Octree)
                .validate()
                .is_ok()
        );
        assert!(matches!(
            medial.with_method(Method::Grid).with_depth(21).validate(),
            Err(SphereTreeError::InvalidParameter { name: "depth", .. })
        ));
    }
}
