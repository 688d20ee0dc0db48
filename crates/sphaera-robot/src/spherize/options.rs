//! How a robot is spherized: the sphere budget and the options of
//! [`spherize`](crate::spherize), and their validation.

use std::collections::BTreeMap;

use sphaera_mesh::Length;
use sphaera_spheretree::{Effort, Method, SphereTreeOptions};

use crate::RobotError;
use crate::geometry::GeometrySource;
use crate::self_collision::SelfCollisionOptions;
/// How many spheres the links get.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SphereBudget {
    /// This many spheres in all, summing to exactly this: the links with their own count
    /// ([`SpherizeOptions::per_link`]) keep it, and the rest is divided among the other
    /// links in proportion to what each needs, estimated by its surface area times
    /// `1 + ¼·log₂(triangles / 12)` (largest remainders, at least one each). Each link
    /// then gets its share as [`SphereBudget::PerLink`] gives a count; spheres a link
    /// cannot use (a sphere primitive is its own sphere) are passed on to the links that
    /// use all theirs, so the robot has exactly the total unless no link can use them
    /// (the reports say why). A total that cannot give every link a sphere is refused
    /// ([`RobotError::Budget`]).
    Total(usize),
    /// Exactly this many spheres for every link with geometry: its meshes (joined) get a
    /// one-level minimax sphere-tree of this many spheres, its primitives analytic sets;
    /// fewer only where the link cannot use them
    /// ([`LinkReport::shortfall`](crate::LinkReport::shortfall) says why:
    /// a sphere primitive is its own sphere), never more.
    PerLink(usize),
    /// Every link's spheres within this of its surface (certified worst protrusion), with
    /// as few spheres as the tolerance needs: its meshes get the leaves of a minimax
    /// tolerance tree (refined only where a sphere reaches farther, each node into the
    /// fewest children that meet it), its primitives the fewest analytic spheres. A
    /// relative length is a fraction of each link's bounding-box diagonal. A link that
    /// would need more than [`SpherizeOptions::max_spheres_per_link`] spheres is refused
    /// ([`RobotError::ToleranceUnreachable`]).
    Tolerance(Length),
}

/// How [`spherize`](crate::spherize) spherizes a robot.
///
/// # Examples
///
/// ```
/// use sphaera_robot::{Effort, SphereBudget, SpherizeOptions};
///
/// let options = SpherizeOptions::default()
///     .with_budget(SphereBudget::PerLink(40))
///     .with_link("panda_hand", 60)
///     .with_effort(Effort::Quick);
/// assert_eq!(options.per_link["panda_hand"], 60);
/// assert_eq!(options.tree.effort, Effort::Quick);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SpherizeOptions {
    /// Collision (default) or visual geometry.
    pub source: GeometrySource,
    /// The budget (default: 16 spheres per link).
    pub budget: SphereBudget,
    /// Sphere counts for named links, overriding the budget (a total budget is divided
    /// among the other links).
    pub per_link: BTreeMap<String, usize>,
    /// The minimax sphere-tree of each link's meshes (default: the library's defaults).
    /// Its [`effort`](SphereTreeOptions::effort) trades time for tighter spheres, and its
    /// [`branch`](SphereTreeOptions::branch) is the most children per node of a
    /// tolerance tree; the depth, the count and the tolerance come from the budget. The
    /// method must be minimax ([`Method::Auto`] or [`Method::Minimax`]): the paper's
    /// reducers give neither exact counts nor tolerance trees.
    pub tree: SphereTreeOptions,
    /// The most spheres a tolerance may give a link (default 1,000; at most
    /// [`MAX_SPHERES_PER_LINK`]).
    pub max_spheres_per_link: usize,
    /// The self-collision matrix to compute after spherizing ([`crate::spherize`] only: it
    /// needs the URDF's joints), or `None` (the default) to leave
    /// [`RobotSpheres::self_collision`](crate::RobotSpheres::self_collision) empty; the
    /// planner formats that need one then compute it with the default options.
    pub self_collision: Option<SelfCollisionOptions>,
}

impl Default for SpherizeOptions {
    fn default() -> Self {
        Self {
            source: GeometrySource::Collision,
            budget: SphereBudget::PerLink(16),
            per_link: BTreeMap::new(),
            tree: SphereTreeOptions::default(),
            max_spheres_per_link: 1_000,
            self_collision: None,
        }
    }
}

impl SpherizeOptions {
    /// With the given budget.
    #[must_use]
    pub fn with_budget(mut self, budget: SphereBudget) -> Self {
        self.budget = budget;
        self
    }

    /// With `count` spheres for the link `name`.
    #[must_use]
    pub fn with_link(mut self, name: impl Into<String>, count: usize) -> Self {
        self.per_link.insert(name.into(), count);
        self
    }

    /// With the given geometry source.
    #[must_use]
    pub fn with_source(mut self, source: GeometrySource) -> Self {
        self.source = source;
        self
    }

    /// With the given sphere-tree options for the links' meshes.
    #[must_use]
    pub fn with_tree(mut self, tree: SphereTreeOptions) -> Self {
        self.tree = tree;
        self
    }

    /// With the given minimax [`Effort`] (quicker, or tighter spheres).
    #[must_use]
    pub fn with_effort(mut self, effort: Effort) -> Self {
        self.tree = self.tree.with_effort(effort);
        self
    }

    /// With the self-collision matrix computed by `options` after spherizing.
    #[must_use]
    pub fn with_self_collision(mut self, options: SelfCollisionOptions) -> Self {
        self.self_collision = Some(options);
        self
    }

    /// With at most `n` spheres per link under a tolerance.
    #[must_use]
    pub fn with_max_spheres_per_link(mut self, n: usize) -> Self {
        self.max_spheres_per_link = n;
        self
    }
}

/// The most spheres [`spherize`](crate::spherize) gives one link: planners use tens; ten
/// thousand is far past any use, and far less than would exhaust memory or time.
pub const MAX_SPHERES_PER_LINK: usize = 10_000;

pub(super) fn validate(options: &SpherizeOptions) -> Result<(), RobotError> {
    if let Some(self_collision) = &options.self_collision {
        crate::self_collision::check_options(self_collision)?;
    }
    let counts = [
        match options.budget {
            SphereBudget::PerLink(n) | SphereBudget::Total(n) => Some(n),
            SphereBudget::Tolerance(_) => None,
        },
        Some(options.max_spheres_per_link),
    ];
    let counts = counts
        .into_iter()
        .flatten()
        .chain(options.per_link.values().copied());
    for n in counts {
        if n == 0 {
            return Err(RobotError::InvalidParameter {
                name: "sphere count",
                value: 0.0,
                requirement: "at least 1",
            });
        }
    }
    let too_many = [
        match options.budget {
            SphereBudget::PerLink(n) => n,
            _ => 0,
        },
        options.max_spheres_per_link,
    ]
    .into_iter()
    .chain(options.per_link.values().copied())
    .find(|&n| n > MAX_SPHERES_PER_LINK);
    if let Some(n) = too_many {
        return Err(RobotError::InvalidParameter {
            name: "sphere count",
            value: n as f64,
            requirement: "at most 10,000 per link",
        });
    }
    if let SphereBudget::Tolerance(length) = options.budget
        && !(length.value() > 0.0 && length.value().is_finite())
    {
        return Err(RobotError::InvalidParameter {
            name: "tolerance",
            value: length.value(),
            requirement: "positive and finite",
        });
    }
    if options.tree.method.resolved() != Method::Minimax {
        return Err(RobotError::InvalidParameter {
            name: "sphere-tree method",
            value: f64::NAN,
            requirement: "minimax (or auto): only it gives exact counts and tolerance trees",
        });
    }
    Ok(())
}
