//! Spherizing every link: budgets, the minimax sphere-tree of each link's meshes, the
//! analytic sets of its primitives, and the report of each link.

use std::collections::BTreeMap;
use std::time::Instant;

use glam::DVec3;
use serde::Serialize;
use sphaera_mesh::geometry::minimum_enclosing_ball_of_balls;
use sphaera_mesh::{Length, Sphere};
use sphaera_query::Surface;
use sphaera_spheretree::{
    Effort, EvaluationOptions, Method, SphereTree, SphereTreeOptions, evaluate_set_bounded,
};

use crate::RobotError;
use crate::geometry::{GeometrySource, LinkGeometry, MeshResolver};
use crate::primitive::{Primitive, Shape};
use crate::urdf::Urdf;

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
    /// fewer only where the link cannot use them ([`LinkReport::shortfall`] says why:
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

/// How [`spherize`] spherizes a robot.
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
}

impl Default for SpherizeOptions {
    fn default() -> Self {
        Self {
            source: GeometrySource::Collision,
            budget: SphereBudget::PerLink(16),
            per_link: BTreeMap::new(),
            tree: SphereTreeOptions::default(),
            max_spheres_per_link: 1_000,
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

    /// With at most `n` spheres per link under a tolerance.
    #[must_use]
    pub fn with_max_spheres_per_link(mut self, n: usize) -> Self {
        self.max_spheres_per_link = n;
        self
    }
}

/// What one link got, and how well its spheres fit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LinkReport {
    /// The link.
    pub link: String,
    /// Its mesh files.
    pub files: Vec<String>,
    /// Its mesh triangles.
    pub triangles: usize,
    /// Its primitives (box, cylinder, sphere, capsule).
    pub primitives: usize,
    /// Whether its meshes (vertices at identical positions welded) are a closed,
    /// consistently oriented manifold without self-intersections (a certified embedded
    /// solid), whose sphere-tree node errors bound the protrusion; `true` without meshes.
    /// Other meshes are spherized as the solid their winding number encloses (or as a
    /// shell), and their spheres evaluated in full.
    pub closed: bool,
    /// Whether its meshes were taken as a shell (no inside: an open or flat mesh), so
    /// that every point of a sphere counts towards the protrusion; `false` for a solid.
    pub shell: bool,
    /// The diagonal of its geometry's bounding box.
    pub diagonal: f64,
    /// The spheres it was given (`None` under a tolerance).
    pub budget: Option<usize>,
    /// Why it has fewer spheres than its budget (`None` when it has them all, and under
    /// a tolerance): e.g. "a sphere primitive is its own sphere".
    pub shortfall: Option<String>,
    /// The tolerance it was spherized to, in its units (`None` under a count).
    pub tolerance: Option<f64>,
    /// Whether the worst protrusion meets the tolerance (`None` under a count): always
    /// `true`, since a tolerance that cannot be met is an error.
    pub meets_tolerance: Option<bool>,
    /// Its spheres.
    pub spheres: usize,
    /// How far any sphere reaches beyond the link's surface, at most (certified: the
    /// sphere-tree's node errors, tightened by branch and bound, on the meshes; exact on
    /// the primitives).
    pub worst_protrusion: f64,
    /// The 95th percentile of the protrusion over the boundary of the spheres' union
    /// (points spread over it by area, 0 inside the link).
    pub p95_protrusion: f64,
    /// The fraction of surface samples inside a sphere (1: certified for every point of
    /// the surface, not only the samples).
    pub coverage: f64,
    /// Whether coverage of every point of the surface is certified.
    pub coverage_certified: bool,
    /// Seconds to spherize and evaluate the link.
    pub seconds: f64,
}

/// One link's spheres, in the link's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkSpheres {
    /// The link.
    pub link: String,
    /// The spheres: the meshes' sphere-tree spheres, then each primitive's.
    pub spheres: Vec<Sphere>,
    /// A sphere around all of them (the level above the spheres, for planners that
    /// test it first).
    pub bounding_sphere: Sphere,
    /// The report.
    pub report: LinkReport,
}

/// A robot's spheres, link by link (links without geometry have none).
#[derive(Clone, Debug, PartialEq)]
pub struct RobotSpheres {
    /// The robot's name.
    pub robot: String,
    /// The geometry spherized.
    pub source: GeometrySource,
    /// The links with geometry, in URDF order.
    pub links: Vec<LinkSpheres>,
    /// The links without geometry of the chosen kind.
    pub links_without_geometry: Vec<String>,
}

impl RobotSpheres {
    /// All spheres.
    #[must_use]
    pub fn sphere_count(&self) -> usize {
        self.links.iter().map(|l| l.spheres.len()).sum()
    }

    /// The link named `name`.
    #[must_use]
    pub fn link(&self, name: &str) -> Option<&LinkSpheres> {
        self.links.iter().find(|l| l.link == name)
    }
}

/// Spherizes every link of `urdf` with geometry of `options.source`: the meshes of a
/// link by a minimax sphere-tree (every point of the surface covered by construction,
/// protrusion certified), on the solid they enclose or, for open and flat meshes, on
/// the shell they are; its primitives analytically (exact). Links are spherized in
/// parallel with the `parallel` feature; the result is the same either way.
///
/// # Examples
///
/// ```
/// use sphaera_robot::{MeshResolver, SphereBudget, SpherizeOptions, Urdf, spherize};
///
/// let urdf = Urdf::parse(r#"
///   <robot name="cart">
///     <link name="body"><collision><geometry><box size="0.6 0.4 0.2"/></geometry></collision></link>
///     <link name="mast"><collision><origin xyz="0 0 0.4"/><geometry><cylinder radius="0.03" length="0.6"/></geometry></collision></link>
///     <joint name="fix" type="fixed"><parent link="body"/><child link="mast"/></joint>
///   </robot>"#, "cart.urdf")?;
/// let resolver = MeshResolver::new(urdf.folder());
/// let robot = spherize(&urdf, &resolver, &SpherizeOptions::default().with_budget(SphereBudget::PerLink(8)))?;
/// let mast = robot.link("mast").unwrap();
/// assert_eq!(mast.spheres.len(), 8);
/// assert!(mast.report.coverage == 1.0 && mast.report.worst_protrusion < 0.03);
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
///
/// # Errors
///
/// As [`LinkGeometry::load`] for the geometry (a missing mesh file is
/// [`RobotError::MeshNotFound`], with every path tried); [`RobotError::NoGeometry`]
/// when no link has geometry of the kind asked for; [`RobotError::UnknownLink`] for a
/// per-link count naming no link with geometry; [`RobotError::InvalidParameter`] for a
/// zero count, a count above [`MAX_SPHERES_PER_LINK`], a tolerance that is not positive
/// and finite, or a sphere-tree method other than minimax; [`RobotError::Budget`] for a
/// total that cannot give every link a sphere; [`RobotError::ToleranceUnreachable`] for
/// a link whose tolerance needs more than [`SpherizeOptions::max_spheres_per_link`]
/// spheres; [`RobotError::Spherize`] for a link whose mesh cannot be spherized (a closed
/// mesh facing inward, no area), with the sphere-tree's reason.
pub fn spherize(
    urdf: &Urdf,
    resolver: &MeshResolver,
    options: &SpherizeOptions,
) -> Result<RobotSpheres, RobotError> {
    spherize_with_progress(urdf, resolver, options, &|_| {})
}

/// How far [`spherize_with_progress`] has got.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SpherizeProgress {
    /// Links finished.
    pub done: usize,
    /// Links with geometry.
    pub total: usize,
    /// The link just finished.
    pub link: String,
}

/// [`spherize`], calling `progress` as each link finishes (from the thread that
/// spherized it, hence `Sync`).
///
/// # Errors
///
/// As [`spherize`].
pub fn spherize_with_progress(
    urdf: &Urdf,
    resolver: &MeshResolver,
    options: &SpherizeOptions,
    progress: &(dyn Fn(&SpherizeProgress) + Sync),
) -> Result<RobotSpheres, RobotError> {
    validate(options)?;
    let geometry = LinkGeometry::load_all(urdf, options.source, resolver)?;
    spherize_geometry(&urdf.name, geometry, options, progress)
}

/// [`spherize_with_progress`] on geometry already loaded (one entry per link).
///
/// # Errors
///
/// As [`spherize`].
pub fn spherize_geometry(
    robot: &str,
    geometry: Vec<LinkGeometry>,
    options: &SpherizeOptions,
    progress: &(dyn Fn(&SpherizeProgress) + Sync),
) -> Result<RobotSpheres, RobotError> {
    validate(options)?;
    let (with, without): (Vec<LinkGeometry>, Vec<LinkGeometry>) =
        geometry.into_iter().partition(|g| !g.is_empty());
    if with.is_empty() {
        return Err(RobotError::NoGeometry {
            robot: robot.to_owned(),
            kind: options.source,
        });
    }
    if let SphereBudget::Total(n) = options.budget
        && n / with.len() > MAX_SPHERES_PER_LINK
    {
        return Err(RobotError::InvalidParameter {
            name: "total sphere count",
            value: n as f64,
            requirement: "at most 10,000 per link with geometry",
        });
    }
    for name in options.per_link.keys() {
        if !with.iter().any(|g| &g.link == name) {
            return Err(RobotError::UnknownLink {
                name: name.clone(),
                without_geometry: without.iter().any(|g| &g.link == name),
            });
        }
    }
    let mut targets = allocate(&with, options)?;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let mut links = spherize_links(&with, &targets, options, &|link| {
        progress(&SpherizeProgress {
            done: done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1,
            total: with.len(),
            link: link.to_owned(),
        });
    })?;
    if matches!(options.budget, SphereBudget::Total(_)) {
        pass_on_unused(&with, &mut targets, &mut links, options)?;
    }
    Ok(RobotSpheres {
        robot: robot.to_owned(),
        source: options.source,
        links,
        links_without_geometry: without.into_iter().map(|g| g.link).collect(),
    })
}

/// Every link spherized to its target, in parallel with the `parallel` feature, calling
/// `finished` with each link's name as it finishes.
fn spherize_links(
    links: &[LinkGeometry],
    targets: &[Target],
    options: &SpherizeOptions,
    finished: &(dyn Fn(&str) + Sync),
) -> Result<Vec<LinkSpheres>, RobotError> {
    let work = |(link, target): (&LinkGeometry, &Target)| {
        let result = spherize_link(link, *target, options);
        finished(&link.link);
        result
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        links.par_iter().zip(targets.par_iter()).map(work).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        links.iter().zip(targets.iter()).map(work).collect()
    }
}

/// Rounds of [`pass_on_unused`] at most.
const PASSES: usize = 3;

/// A total honoured where links cannot use their share: the spheres a link leaves
/// unused (a sphere primitive, a box whose tightest layout is smaller) go to the links
/// that use all theirs, have no count of their own and are not spheres alone, in
/// proportion to their weights, and those links are spherized again; the giving links'
/// budgets become what they use (their shortfall says where the rest went).
fn pass_on_unused(
    with: &[LinkGeometry],
    targets: &mut [Target],
    links: &mut [LinkSpheres],
    options: &SpherizeOptions,
) -> Result<(), RobotError> {
    for _ in 0..PASSES {
        let unused: usize = links
            .iter()
            .map(|l| l.report.budget.unwrap_or(0).saturating_sub(l.spheres.len()))
            .sum();
        // A link of spheres alone never uses more than one sphere each.
        let may_use_more = |g: &LinkGeometry| {
            g.mesh.is_some()
                || g.primitives
                    .iter()
                    .any(|p| !matches!(p.shape, Shape::Sphere { .. }))
        };
        let takers: Vec<usize> = (0..links.len())
            .filter(|&i| {
                links[i].report.shortfall.is_none()
                    && !options.per_link.contains_key(&with[i].link)
                    && may_use_more(&with[i])
            })
            .collect();
        if unused == 0 || takers.is_empty() {
            return Ok(());
        }
        let weights: Vec<f64> = takers.iter().map(|&i| weight(&with[i])).collect();
        let extra = proportional(unused, &weights, 0);
        for link in links.iter_mut() {
            let r = &mut link.report;
            let given = r.budget.unwrap_or(0);
            if given > link.spheres.len() {
                let passed = given - link.spheres.len();
                r.budget = Some(link.spheres.len());
                if let Some(why) = &mut r.shortfall {
                    why.push_str(&format!(
                        " ({} passed to other links)",
                        spheres_text(passed)
                    ));
                }
            }
        }
        let again: Vec<usize> = takers
            .iter()
            .zip(&extra)
            .filter(|&(_, &e)| e > 0)
            .map(|(&i, _)| i)
            .collect();
        for (&i, &e) in takers.iter().zip(&extra) {
            if let Target::Count(n) = targets[i] {
                targets[i] = Target::Count((n + e).min(MAX_SPHERES_PER_LINK));
            }
        }
        let geometry: Vec<LinkGeometry> = again.iter().map(|&i| with[i].clone()).collect();
        let goals: Vec<Target> = again.iter().map(|&i| targets[i]).collect();
        let redone = spherize_links(&geometry, &goals, options, &|_| {})?;
        for (&i, link) in again.iter().zip(redone) {
            links[i] = link;
        }
    }
    Ok(())
}

/// The most spheres [`spherize`] gives one link: planners use tens; ten thousand is far
/// past any use, and far less than would exhaust memory or time.
pub const MAX_SPHERES_PER_LINK: usize = 10_000;

fn validate(options: &SpherizeOptions) -> Result<(), RobotError> {
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

/// What one link is spherized to.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    Count(usize),
    Tolerance(f64),
}

/// The budget of every link with geometry, in order.
fn allocate(links: &[LinkGeometry], options: &SpherizeOptions) -> Result<Vec<Target>, RobotError> {
    let fixed = |g: &LinkGeometry| options.per_link.get(&g.link).copied();
    Ok(match options.budget {
        SphereBudget::PerLink(n) => links
            .iter()
            .map(|g| Target::Count(fixed(g).unwrap_or(n)))
            .collect(),
        SphereBudget::Tolerance(length) => links
            .iter()
            .map(|g| match fixed(g) {
                Some(n) => Target::Count(n),
                None => Target::Tolerance(length.resolve(g.diagonal())),
            })
            .collect(),
        SphereBudget::Total(total) => {
            let taken: usize = links.iter().filter_map(fixed).sum();
            let free: Vec<usize> = (0..links.len())
                .filter(|&i| fixed(&links[i]).is_none())
                .collect();
            if free.is_empty() && taken != total {
                return Err(RobotError::Budget {
                    message: format!(
                        "every link has its own count, and they sum to {taken}, not the total of {total}"
                    ),
                });
            }
            if total < taken + free.len() {
                return Err(RobotError::Budget {
                    message: format!(
                        "a total of {total} spheres cannot give each of the {} links with geometry one{}",
                        links.len(),
                        if taken > 0 {
                            format!(" (the per-link counts take {taken})")
                        } else {
                            String::new()
                        }
                    ),
                });
            }
            let weights: Vec<f64> = free.iter().map(|&i| weight(&links[i])).collect();
            let shares = divide(total - taken, &weights);
            let mut targets: Vec<Target> = links
                .iter()
                .map(|g| Target::Count(fixed(g).unwrap_or(1)))
                .collect();
            for (&i, share) in free.iter().zip(shares) {
                if share > MAX_SPHERES_PER_LINK {
                    return Err(RobotError::Budget {
                        message: format!(
                            "a total of {total} spheres would give link \"{}\" {share}, more than the 10,000 allowed per link",
                            links[i].link
                        ),
                    });
                }
                targets[i] = Target::Count(share);
            }
            targets
        }
    })
}

/// A link's share of a total: its area times a complexity factor.
fn weight(link: &LinkGeometry) -> f64 {
    let complexity = 1.0 + 0.25 * (link.triangles().max(12) as f64 / 12.0).log2();
    link.area().max(f64::MIN_POSITIVE) * complexity
}

/// `total` split in proportion to `weights`, at least 1 each, by largest remainders
/// (`total` at least the number of weights: then the shares sum to it exactly).
fn divide(total: usize, weights: &[f64]) -> Vec<usize> {
    proportional(total, weights, 1)
}

/// `total` split in proportion to `weights`, at least `least` each, by largest
/// remainders: the shares sum to `total` when it is at least `least` per weight.
fn proportional(total: usize, weights: &[f64], least: usize) -> Vec<usize> {
    let n = weights.len();
    if n == 0 {
        return Vec::new();
    }
    if total <= least * n {
        return vec![least; n];
    }
    let spare = (total - least * n) as f64;
    let sum: f64 = weights.iter().sum();
    let exact: Vec<f64> = weights
        .iter()
        .map(|w| {
            if sum > 0.0 {
                spare * w / sum
            } else {
                spare / n as f64
            }
        })
        .collect();
    let mut shares: Vec<usize> = exact.iter().map(|e| least + e.floor() as usize).collect();
    // Rounding may give a floor one too many; take back from the smallest remainders.
    while shares.iter().sum::<usize>() > total {
        if let Some(i) = (0..n).filter(|&i| shares[i] > least).min_by(|&a, &b| {
            (exact[a] - exact[a].floor()).total_cmp(&(exact[b] - exact[b].floor()))
        }) {
            shares[i] -= 1;
        } else {
            break;
        }
    }
    let mut left = total.saturating_sub(shares.iter().sum::<usize>());
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        (exact[b] - exact[b].floor())
            .total_cmp(&(exact[a] - exact[a].floor()))
            .then(a.cmp(&b))
    });
    for &i in order.iter().cycle() {
        if left == 0 {
            break;
        }
        shares[i] += 1;
        left -= 1;
    }
    shares
}

/// The spheres of one part of a link (its meshes, or one primitive) and their fit.
struct PartFit {
    spheres: Vec<Sphere>,
    /// Certified worst protrusion beyond the part.
    protrusion: f64,
    /// Surface samples inside a sphere, of `samples`.
    covered: usize,
    samples: usize,
    /// Whether every point of the part's surface is certified covered.
    certified: bool,
}

impl PartFit {
    /// A primitive's spheres, checked against points spread over its surface.
    fn of_primitive(primitive: &Primitive, spheres: Vec<Sphere>, protrusion: f64) -> Self {
        let points = primitive.surface_points(500);
        // The points lie on the surface the spheres are fitted to (a sphere link's sphere
        // is the link itself): a relative slack of 10⁻⁹ keeps rounding from counting them
        // out.
        let covered = points
            .iter()
            .filter(|&&q| {
                spheres
                    .iter()
                    .any(|s| s.center.distance(q) <= s.radius * (1.0 + 1e-9))
            })
            .count();
        Self {
            spheres,
            protrusion,
            covered,
            samples: points.len(),
            // Analytic layouts and grown inscribed trees cover by construction.
            certified: true,
        }
    }
}

/// A link's spheres and their fit, all parts together.
struct LinkFit {
    spheres: Vec<Sphere>,
    protrusion: f64,
    covered: usize,
    samples: usize,
    certified: bool,
    shortfall: Option<String>,
}

impl LinkFit {
    fn new() -> Self {
        Self {
            spheres: Vec::new(),
            protrusion: 0.0,
            covered: 0,
            samples: 0,
            certified: true,
            shortfall: None,
        }
    }

    fn add(&mut self, part: PartFit) {
        self.spheres.extend(part.spheres);
        self.protrusion = self.protrusion.max(part.protrusion);
        self.covered += part.covered;
        self.samples += part.samples;
        self.certified &= part.certified;
    }
}

fn spherize_link(
    link: &LinkGeometry,
    target: Target,
    options: &SpherizeOptions,
) -> Result<LinkSpheres, RobotError> {
    let started = Instant::now();
    let fail = |message: String| RobotError::Spherize {
        link: link.link.clone(),
        message,
    };
    let surface = link
        .mesh
        .as_ref()
        .map(prepare_surface)
        .transpose()
        .map_err(|e| fail(e.to_string()))?;
    let fit = match target {
        Target::Count(n) => fit_count(link, surface.as_ref(), n, options).map_err(fail)?,
        Target::Tolerance(t) => fit_tolerance(link, surface.as_ref(), t, options)?,
    };
    let bounding_sphere =
        minimum_enclosing_ball_of_balls(&fit.spheres).map_err(|e| fail(e.to_string()))?;
    let worst = fit.protrusion;
    // A quantile never exceeds the maximum; rounding in the sampled distances could make
    // it (1e-17 above an exact 0 on a sphere link).
    let p95 =
        percentile_protrusion(&fit.spheres, surface.as_ref(), &link.primitives, 0.95).min(worst);
    let report = LinkReport {
        link: link.link.clone(),
        files: link.files.iter().map(|p| p.display().to_string()).collect(),
        triangles: link
            .mesh
            .as_ref()
            .map_or(0, sphaera_mesh::TriMesh::triangle_count),
        primitives: link.primitives.len(),
        closed: surface.as_ref().is_none_or(Surface::is_embedded_solid),
        shell: surface.as_ref().is_some_and(|s| !s.has_inside()),
        diagonal: link.diagonal(),
        budget: match target {
            Target::Count(n) => Some(n),
            Target::Tolerance(_) => None,
        },
        shortfall: fit.shortfall,
        tolerance: match target {
            Target::Count(_) => None,
            Target::Tolerance(t) => Some(t),
        },
        meets_tolerance: match target {
            Target::Count(_) => None,
            Target::Tolerance(t) => Some(worst <= t),
        },
        spheres: fit.spheres.len(),
        worst_protrusion: worst,
        p95_protrusion: p95,
        coverage: if fit.samples == 0 {
            1.0
        } else {
            fit.covered as f64 / fit.samples as f64
        },
        coverage_certified: fit.certified,
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok(LinkSpheres {
        link: link.link.clone(),
        spheres: fit.spheres,
        bounding_sphere,
        report,
    })
}

/// The surface of a link's meshes: its vertices at identical positions welded first
/// (meshes exported per triangle, as OBJ and STL files often are, become the closed
/// manifolds they are, certified embedded solids), then a solid when it has an inside,
/// else a shell. The geometry is unchanged.
fn prepare_surface(mesh: &sphaera_mesh::TriMesh) -> Result<Surface, sphaera_query::QueryError> {
    let (welded, _) = sphaera_mesh::topology::weld_vertices(mesh, 0.0)?;
    Surface::solid_or_shell(&welded)
}

/// Whether the sphere-tree's node errors (the paper's eq. 2 on the certified side of
/// the centre) bound the spheres' protrusion: on a certified embedded solid (a closed
/// manifold) and on a shell. On a mesh that encloses a solid only loosely (holes,
/// non-manifold edges: the winding number does not jump from 0 to 1 across every
/// triangle) a point can leave the inside without crossing the surface, so the spheres
/// are evaluated in full instead.
fn bounds_hold(surface: &Surface) -> bool {
    surface.is_embedded_solid() || !surface.has_inside()
}

/// How far `ball` reaches beyond the solid (or shell) of `surface`, at most: eq. 2 where
/// it holds, else the branch and bound's certified upper end.
fn ball_bound(surface: &Surface, ball: Sphere) -> Result<f64, String> {
    if bounds_hold(surface) {
        let side = surface
            .signed_closest(ball.center)
            .map_err(|e| e.to_string())?;
        return Ok((ball.radius + side.signed_distance()).max(0.0));
    }
    let options = EvaluationOptions::default().with_coverage_samples(1);
    sphaera_spheretree::evaluate_set(surface, &[ball], &options)
        .map(|fit| fit.worst_upper)
        .map_err(|e| e.to_string())
}

/// Exactly `n` spheres for the link (fewer only where a part cannot use them): the
/// count divided among its parts by area, a primitive's unused share handed to the
/// meshes; more parts than spheres share them (one sphere each, the closest merged).
fn fit_count(
    link: &LinkGeometry,
    surface: Option<&Surface>,
    n: usize,
    options: &SpherizeOptions,
) -> Result<LinkFit, String> {
    let parts = usize::from(surface.is_some()) + link.primitives.len();
    if parts > n {
        return merged(link, surface, n, options);
    }
    let mut areas: Vec<f64> = Vec::with_capacity(parts);
    if let Some(surface) = surface {
        areas.push(surface.mesh().surface_area());
    }
    areas.extend(link.primitives.iter().map(Primitive::area));
    let shares = divide(n, &areas);
    let (mesh_share, primitive_shares) = match surface {
        Some(_) => (shares[0], &shares[1..]),
        None => (0, &shares[..]),
    };
    let mut primitives: Vec<PartFit> = Vec::with_capacity(link.primitives.len());
    let mut unused = 0;
    let mut reasons: Vec<String> = Vec::new();
    for (primitive, &share) in link.primitives.iter().zip(primitive_shares) {
        let part = primitive_count(primitive, share, options);
        if part.spheres.len() < share {
            unused += share - part.spheres.len();
            reasons.push(match primitive.shape {
                Shape::Sphere { .. } => "a sphere primitive is its own sphere".to_owned(),
                _ => format!(
                    "the {}'s tightest layout has {} (no set of {share} found is tighter)",
                    primitive.kind(),
                    spheres_text(part.spheres.len())
                ),
            });
        }
        primitives.push(part);
    }
    let mut fit = LinkFit::new();
    if let Some(surface) = surface {
        // The meshes take what the primitives could not use.
        let count = mesh_share + unused;
        let part = mesh_count(surface, count, options)?;
        reasons.clear();
        unused = count - part.spheres.len().min(count);
        if unused > 0 {
            reasons.push(format!(
                "the meshes' surface was divided into only {} regions",
                part.spheres.len()
            ));
        }
        fit.add(part);
    }
    for part in primitives {
        fit.add(part);
    }
    if unused > 0 {
        fit.shortfall = Some(reasons.join("; "));
    }
    Ok(fit)
}

/// `1 sphere`, `6 spheres`.
fn spheres_text(n: usize) -> String {
    if n == 1 {
        "1 sphere".to_owned()
    } else {
        format!("{n} spheres")
    }
}

/// Fewer spheres than parts: one sphere per part (the meshes' one-sphere tree, each
/// primitive's own), then the two whose enclosing ball is smallest replaced by it until
/// `n` remain. A merged ball holds the balls it replaces, so the surface stays covered;
/// its protrusion beyond the link is at most its protrusion beyond any one part (eq. 2
/// on the meshes, exact on a primitive).
fn merged(
    link: &LinkGeometry,
    surface: Option<&Surface>,
    n: usize,
    options: &SpherizeOptions,
) -> Result<LinkFit, String> {
    let mut fit = LinkFit::new();
    let mut balls: Vec<Sphere> = Vec::new();
    if let Some(surface) = surface {
        let part = mesh_count(surface, 1, options)?;
        fit.covered += part.covered;
        fit.samples += part.samples;
        fit.certified &= part.certified;
        balls.extend(part.spheres);
    }
    for primitive in &link.primitives {
        let (set, _) = primitive.spherize(1);
        balls.extend(set);
    }
    while balls.len() > n.max(1) {
        let mut best: Option<(f64, usize, usize, Sphere)> = None;
        for i in 0..balls.len() {
            for j in i + 1..balls.len() {
                let ball = minimum_enclosing_ball_of_balls(&[balls[i], balls[j]])
                    .map_err(|e| e.to_string())?;
                if best.is_none_or(|(r, ..)| ball.radius < r) {
                    best = Some((ball.radius, i, j, ball));
                }
            }
        }
        let Some((_, i, j, ball)) = best else {
            break;
        };
        balls.swap_remove(j);
        balls[i] = ball;
    }
    for ball in &balls {
        let mut bound = f64::INFINITY;
        if let Some(surface) = surface {
            bound = ball_bound(surface, *ball)?;
        }
        for primitive in &link.primitives {
            bound = bound.min(primitive.protrusion(ball));
        }
        fit.protrusion = fit.protrusion.max(bound);
    }
    for primitive in &link.primitives {
        let part = PartFit::of_primitive(primitive, balls.clone(), 0.0);
        fit.covered += part.covered;
        fit.samples += part.samples;
    }
    fit.spheres = balls;
    Ok(fit)
}

/// Every link's spheres within `tolerance`: its meshes' tolerance tree, its
/// primitives' fewest analytic spheres.
fn fit_tolerance(
    link: &LinkGeometry,
    surface: Option<&Surface>,
    tolerance: f64,
    options: &SpherizeOptions,
) -> Result<LinkFit, RobotError> {
    let max = options.max_spheres_per_link;
    let unreachable = |message: String| RobotError::ToleranceUnreachable {
        link: link.link.clone(),
        tolerance,
        max,
        message,
    };
    let mut fit = LinkFit::new();
    if let Some(surface) = surface {
        let part = mesh_tolerance(surface, tolerance, options).map_err(|message| {
            RobotError::Spherize {
                link: link.link.clone(),
                message,
            }
        })?;
        if part.spheres.len() > max {
            return Err(unreachable(format!(
                "its meshes need {} spheres",
                part.spheres.len()
            )));
        }
        fit.add(part);
    }
    for primitive in &link.primitives {
        let part = primitive_tolerance(primitive, tolerance, options);
        if part.protrusion > tolerance {
            return Err(unreachable(format!(
                "{} spheres of its {} reach {} beyond it",
                part.spheres.len(),
                primitive.kind(),
                part.protrusion
            )));
        }
        fit.add(part);
    }
    if fit.spheres.len() > max {
        return Err(unreachable(format!(
            "its parts need {} spheres together",
            fit.spheres.len()
        )));
    }
    if fit.protrusion > tolerance {
        // The tolerance trees' leaves meet it by construction; this is a last guard.
        return Err(unreachable(format!(
            "its spheres reach {} beyond it",
            fit.protrusion
        )));
    }
    Ok(fit)
}

/// Exactly `count` spheres of a one-level minimax tree on `surface`.
fn mesh_count(
    surface: &Surface,
    count: usize,
    options: &SpherizeOptions,
) -> Result<PartFit, String> {
    let mut tree_options = options.tree.clone().with_depth(1).with_branch(count);
    tree_options.tolerance = None;
    let tree = sphaera_spheretree::build(surface, &tree_options).map_err(|e| e.to_string())?;
    let (spheres, bounds) = cut(&tree, 1);
    let upper = certified_uppers(surface, &spheres, &bounds, None)?;
    finish(surface, spheres, &upper, tree.coverage().get(1).is_some())
}

/// The spheres within `tolerance` of `surface`: the leaves of a minimax tolerance tree,
/// each within it by construction where the node errors hold ([`bounds_hold`]).
/// Elsewhere every leaf is evaluated in full, and a leaf that reaches farther (near a
/// hole, a point can be outside without crossing the surface) is replaced by a tolerance
/// tree of the surface that meets it, taken as a shell: those spheres reach no farther
/// from that part of the surface, hence from the object, than the tolerance, and they
/// cover every point of the surface the leaf covered.
fn mesh_tolerance(
    surface: &Surface,
    tolerance: f64,
    options: &SpherizeOptions,
) -> Result<PartFit, String> {
    let tree_options = options
        .tree
        .clone()
        .with_tolerance(Length::Absolute(tolerance));
    let tree = sphaera_spheretree::build(surface, &tree_options).map_err(|e| e.to_string())?;
    let deepest = tree.level_count().saturating_sub(1);
    let (leaves, bounds) = cut(&tree, deepest);
    let leaf_upper = certified_uppers(surface, &leaves, &bounds, Some(tolerance))?;
    let mut certified = tree.coverage().get(deepest).is_some();
    let mut spheres = Vec::with_capacity(leaves.len());
    let mut upper = Vec::with_capacity(leaves.len());
    for (leaf, u) in leaves.into_iter().zip(leaf_upper) {
        if u <= tolerance {
            spheres.push(leaf);
            upper.push(u);
            continue;
        }
        let Some(patch) = clip_to_sphere(surface.mesh(), leaf) else {
            // No surface meets the leaf: it covers nothing.
            continue;
        };
        let shell = Surface::shell(&patch).map_err(|e| e.to_string())?;
        let patch_tree =
            sphaera_spheretree::build(&shell, &tree_options).map_err(|e| e.to_string())?;
        let (patch_spheres, patch_bounds) = cut(&patch_tree, patch_tree.level_count() - 1);
        certified &= !patch_tree.coverage().is_empty();
        spheres.extend(patch_spheres);
        upper.extend(patch_bounds);
    }
    finish(surface, spheres, &upper, certified)
}

/// The spheres of the cut of `tree` at `level` (the level itself for a one-level tree,
/// the leaves at the deepest level of a tolerance tree) and their node errors.
fn cut(tree: &SphereTree, level: usize) -> (Vec<Sphere>, Vec<f64>) {
    tree.cut_at(level)
        .into_iter()
        .map(|i| (tree.nodes()[i].sphere, tree.nodes()[i].error))
        .unzip()
}

/// A certified upper bound on each sphere's protrusion: its node error where those
/// hold ([`bounds_hold`]), else the upper end of a full branch and bound (to a finer
/// interval for the spheres whose interval holds `tolerance`, so that a sphere within it
/// is found to be).
fn certified_uppers(
    surface: &Surface,
    spheres: &[Sphere],
    bounds: &[f64],
    tolerance: Option<f64>,
) -> Result<Vec<f64>, String> {
    if bounds_hold(surface) {
        return Ok(bounds.to_vec());
    }
    let options = EvaluationOptions::default().with_coverage_samples(1);
    let fit =
        sphaera_spheretree::evaluate_set(surface, spheres, &options).map_err(|e| e.to_string())?;
    let mut upper: Vec<f64> = fit.fits.iter().map(|f| f.upper).collect();
    if let Some(t) = tolerance {
        let open: Vec<usize> = (0..spheres.len())
            .filter(|&i| fit.fits[i].lower <= t && upper[i] > t)
            .collect();
        if !open.is_empty() {
            let again: Vec<Sphere> = open.iter().map(|&i| spheres[i]).collect();
            let fine = options.with_tolerance(Length::Absolute(1e-3 * t));
            let refit = sphaera_spheretree::evaluate_set(surface, &again, &fine)
                .map_err(|e| e.to_string())?;
            for (&i, f) in open.iter().zip(&refit.fits) {
                upper[i] = upper[i].min(f.upper);
            }
        }
    }
    Ok(upper)
}

/// The fit of `spheres` given certified per-sphere upper bounds: the worst protrusion
/// tightened by branch and bound, and the coverage of independent surface samples.
fn finish(
    surface: &Surface,
    spheres: Vec<Sphere>,
    upper: &[f64],
    certified: bool,
) -> Result<PartFit, String> {
    let fit = evaluate_set_bounded(surface, &spheres, upper, &EvaluationOptions::default())
        .map_err(|e| e.to_string())?;
    Ok(PartFit {
        spheres,
        protrusion: fit.worst_upper,
        covered: fit.coverage.samples - fit.coverage.uncovered,
        samples: fit.coverage.samples,
        certified,
    })
}

/// The part of `mesh` that meets `sphere` (grown by a relative 10⁻⁹ so that rounding
/// loses nothing inside it), in pieces: every triangle that meets it split at its
/// longest edge until its pieces are under a quarter of the radius long, the pieces
/// that meet the sphere kept. They hold every point of the surface inside the sphere.
/// `None` when nothing meets it.
fn clip_to_sphere(mesh: &sphaera_mesh::TriMesh, sphere: Sphere) -> Option<sphaera_mesh::TriMesh> {
    use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};
    let reach = sphere.radius * (1.0 + 1e-9);
    let small = 0.25 * sphere.radius;
    let meets = |t: &Triangle| point_triangle_distance_squared(sphere.center, t) <= reach * reach;
    let mut positions: Vec<DVec3> = Vec::new();
    let mut stack: Vec<Triangle> = mesh.triangle_iter().filter(|t| meets(t)).collect();
    while let Some(t) = stack.pop() {
        let [a, b, c] = [t.a, t.b, t.c];
        let edges = [(a, b, c), (b, c, a), (c, a, b)];
        let (p, q, r) = edges.into_iter().max_by(|x, y| {
            x.0.distance_squared(x.1)
                .total_cmp(&y.0.distance_squared(y.1))
        })?;
        if p.distance(q) <= small {
            positions.extend([a, b, c]);
            continue;
        }
        let m = 0.5 * (p + q);
        for half in [Triangle::new(p, m, r), Triangle::new(m, q, r)] {
            if meets(&half) {
                stack.push(half);
            }
        }
    }
    let triangles: Vec<[u32; 3]> = (0..u32::try_from(positions.len() / 3).ok()?)
        .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
        .collect();
    if triangles.is_empty() {
        return None;
    }
    sphaera_mesh::TriMesh::new(positions, triangles).ok()
}

/// At most `count` spheres for a primitive: its analytic layout, or exactly `count`
/// from a one-level tree of a mesh inside it grown by the mesh's gap (a box or a
/// cylinder) when that is no looser. The protrusion is exact either way (the primitive
/// is convex).
fn primitive_count(primitive: &Primitive, count: usize, options: &SpherizeOptions) -> PartFit {
    let (layout, reach) = primitive.spherize(count);
    let mut best = (layout, reach);
    if let Some((spheres, reach)) = inscribed(primitive, |surface, _| {
        mesh_count(surface, count, options).ok()
    }) && reach <= best.1
    {
        best = (spheres, reach);
    }
    PartFit::of_primitive(primitive, best.0, best.1)
}

/// The fewest spheres within `tolerance` of a primitive (at most
/// [`SpherizeOptions::max_spheres_per_link`]; the protrusion says whether they are
/// within it): its analytic layout, or the leaves of a tolerance tree of a mesh inside
/// it grown by the mesh's gap when they are fewer.
fn primitive_tolerance(
    primitive: &Primitive,
    tolerance: f64,
    options: &SpherizeOptions,
) -> PartFit {
    let (layout, reach) = primitive.spherize_within(tolerance, options.max_spheres_per_link);
    let mut best = (layout, reach);
    // Only where the analytic layout meets the tolerance: the tree is then no larger
    // than a few of its sizes, and is taken only when it needs fewer spheres.
    if reach <= tolerance
        && best.0.len() > 1
        && let Some((spheres, reach)) = inscribed(primitive, |surface, gap| {
            (tolerance - gap > 0.0)
                .then(|| mesh_tolerance(surface, tolerance - gap, options).ok())
                .flatten()
        })
        && reach <= tolerance
        && spheres.len() < best.0.len()
    {
        best = (spheres, reach);
    }
    PartFit::of_primitive(primitive, best.0, best.1)
}

/// The spheres `fit` gives for the mesh inside `primitive` (a box or a cylinder), grown
/// by the mesh's gap so that they cover the primitive, with their exact protrusion.
fn inscribed(
    primitive: &Primitive,
    fit: impl FnOnce(&Surface, f64) -> Option<PartFit>,
) -> Option<(Vec<Sphere>, f64)> {
    let (mesh, gap) = primitive.inscribed_mesh()?;
    let surface = Surface::new(&mesh).ok()?;
    let part = fit(&surface, gap)?;
    let grown: Vec<Sphere> = part
        .spheres
        .iter()
        .map(|s| Sphere::new(s.center, s.radius + gap))
        .collect();
    let reach = grown
        .iter()
        .map(|s| primitive.protrusion(s))
        .fold(0.0, f64::max);
    Some((grown, reach))
}

/// The `q` quantile of the distance to the link's solid over points spread by area on
/// the boundary of the union of `spheres` (points inside another sphere are not on it).
fn percentile_protrusion(
    spheres: &[Sphere],
    surface: Option<&Surface>,
    primitives: &[Primitive],
    q: f64,
) -> f64 {
    const POINTS: f64 = 6_000.0;
    let total: f64 = spheres.iter().map(|s| s.radius * s.radius).sum();
    if total <= 0.0 {
        return 0.0;
    }
    let unit = Primitive::new(Shape::Sphere { radius: 1.0 }, glam::DAffine3::IDENTITY);
    let mut distances: Vec<f64> = Vec::new();
    for (i, s) in spheres.iter().enumerate() {
        let n = ((POINTS * s.radius * s.radius / total).ceil() as usize).max(4);
        for u in unit.surface_points(n) {
            let p = s.center + u * s.radius;
            let inside_another = spheres
                .iter()
                .enumerate()
                .any(|(j, o)| j != i && o.center.distance(p) < o.radius);
            if inside_another {
                continue;
            }
            distances.push(solid_distance(p, surface, primitives));
        }
    }
    if distances.is_empty() {
        return 0.0;
    }
    distances.sort_by(f64::total_cmp);
    let index = ((q * distances.len() as f64).ceil() as usize).clamp(1, distances.len()) - 1;
    distances[index]
}

/// The distance from `p` to the link's solid (0 inside any part).
fn solid_distance(p: DVec3, surface: Option<&Surface>, primitives: &[Primitive]) -> f64 {
    let mut best = f64::INFINITY;
    if let Some(surface) = surface {
        if surface.is_inside(p) {
            return 0.0;
        }
        if let Ok(c) = surface.closest(p) {
            best = c.distance;
        }
    }
    for primitive in primitives {
        best = best.min(primitive.signed_distance(p).max(0.0));
    }
    if best.is_finite() { best } else { 0.0 }
}
