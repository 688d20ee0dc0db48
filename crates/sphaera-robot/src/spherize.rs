//! Spherizing every link: budgets, the sphere-tree of each link's meshes, the analytic
//! sets of its primitives, and the report of each link.

use std::collections::BTreeMap;
use std::time::Instant;

use glam::DVec3;
use serde::Serialize;
use sphaera_mesh::geometry::minimum_enclosing_ball_of_balls;
use sphaera_mesh::{Length, Sphere, Surface};
use sphaera_spheretree::{EvaluationOptions, SphereTreeOptions, evaluate_set};

use crate::RobotError;
use crate::geometry::{GeometrySource, LinkGeometry, MeshResolver};
use crate::urdf::Urdf;

/// How many spheres the links get.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SphereBudget {
    /// This many spheres in all, divided across the links with geometry by size and
    /// complexity (surface area, times `1 + ¼·log₂(triangles / 12)`), at least one each.
    /// Within a link the count is divided among its meshes (joined) and its primitives
    /// by area, at least one each, so a link with more parts than spheres gets one per
    /// part.
    Total(usize),
    /// This many spheres for every link with geometry.
    PerLink(usize),
    /// As few spheres per link as keep every sphere within this of the link's surface
    /// (certified), up to [`SpherizeOptions::max_spheres_per_link`]; a relative length
    /// is a fraction of each link's bounding-box diagonal.
    Tolerance(Length),
}

/// How [`spherize`] spherizes a robot.
///
/// # Examples
///
/// ```
/// use sphaera_robot::{SphereBudget, SpherizeOptions};
///
/// let options = SpherizeOptions::default()
///     .with_budget(SphereBudget::PerLink(40))
///     .with_link("panda_hand", 60);
/// assert_eq!(options.per_link["panda_hand"], 60);
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
    /// The sphere-tree of each link's meshes (default: depth 1, 3,000 samples, 200
    /// initial medial spheres); its branch factor is the link's sphere count.
    pub tree: SphereTreeOptions,
    /// The most spheres a tolerance may give a link (default 256).
    pub max_spheres_per_link: usize,
}

impl Default for SpherizeOptions {
    fn default() -> Self {
        Self {
            source: GeometrySource::Collision,
            budget: SphereBudget::PerLink(16),
            per_link: BTreeMap::new(),
            tree: SphereTreeOptions::default()
                .with_depth(1)
                .with_samples(3_000)
                .with_initial_spheres(200),
            max_spheres_per_link: 256,
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
    /// The diagonal of its geometry's bounding box.
    pub diagonal: f64,
    /// The spheres it was given (`None` under a tolerance).
    pub budget: Option<usize>,
    /// The tolerance it was spherized to, in its units (`None` under a count).
    pub tolerance: Option<f64>,
    /// Whether the worst protrusion meets the tolerance (`None` under a count). `false`
    /// when even [`SpherizeOptions::max_spheres_per_link`] spheres do not: the tree's
    /// samples and error fraction set a floor (more samples lower it).
    pub meets_tolerance: Option<bool>,
    /// Its spheres.
    pub spheres: usize,
    /// How far any sphere reaches beyond the link's surface, at most (certified: branch
    /// and bound on the meshes, exact on the primitives).
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
    /// The spheres: the mesh's sphere-tree leaves, then each primitive's.
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
/// link by a sphere-tree (certified coverage of every point of the surface, certified
/// protrusion), its primitives analytically (exact). Links are spherized in parallel
/// with the `parallel` feature; the result is the same either way.
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
/// assert!(mast.spheres.len() <= 8 && mast.report.coverage == 1.0);
/// assert!(mast.report.worst_protrusion < 0.03);
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
///
/// # Errors
///
/// As [`LinkGeometry::load`] for the geometry; [`RobotError::UnknownLink`] for a
/// per-link count naming no link with geometry; [`RobotError::InvalidParameter`] for a
/// zero count or a negative or non-finite tolerance; [`RobotError::Spherize`] for a link
/// whose meshes enclose nothing (a flat sheet) or have too few distinct points.
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
    let targets = allocate(&with, options);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let work = |(link, target): (&LinkGeometry, &Target)| {
        let result = spherize_link(link, *target, options);
        progress(&SpherizeProgress {
            done: done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1,
            total: with.len(),
            link: link.link.clone(),
        });
        result
    };
    #[cfg(feature = "parallel")]
    let links: Result<Vec<LinkSpheres>, RobotError> = {
        use rayon::prelude::*;
        with.par_iter().zip(targets.par_iter()).map(work).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let links: Result<Vec<LinkSpheres>, RobotError> =
        with.iter().zip(targets.iter()).map(work).collect();
    Ok(RobotSpheres {
        robot: robot.to_owned(),
        source: options.source,
        links: links?,
        links_without_geometry: without.into_iter().map(|g| g.link).collect(),
    })
}

/// The most spheres [`spherize`] gives one link: planners use tens; ten thousand is far
/// past any use, and far less than would exhaust memory or time.
pub const MAX_SPHERES_PER_LINK: usize = 10_000;

fn validate(options: &SpherizeOptions) -> Result<(), RobotError> {
    let zero = |value: usize| RobotError::InvalidParameter {
        name: "sphere count",
        value: value as f64,
        requirement: "at least 1",
    };
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
    match options.budget {
        SphereBudget::Total(0) | SphereBudget::PerLink(0) => return Err(zero(0)),
        SphereBudget::Tolerance(length)
            if !(length.value() >= 0.0 && length.value().is_finite()) =>
        {
            return Err(RobotError::InvalidParameter {
                name: "tolerance",
                value: length.value(),
                requirement: "finite and non-negative",
            });
        }
        _ => {}
    }
    if options.per_link.values().any(|&n| n == 0) || options.max_spheres_per_link == 0 {
        return Err(zero(0));
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
fn allocate(links: &[LinkGeometry], options: &SpherizeOptions) -> Vec<Target> {
    let fixed = |g: &LinkGeometry| options.per_link.get(&g.link).copied();
    match options.budget {
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
            let weights: Vec<f64> = free.iter().map(|&i| weight(&links[i])).collect();
            let shares = divide(total.saturating_sub(taken), &weights);
            let mut targets: Vec<Target> = links
                .iter()
                .map(|g| Target::Count(fixed(g).unwrap_or(1)))
                .collect();
            for (&i, share) in free.iter().zip(shares) {
                targets[i] = Target::Count(share);
            }
            targets
        }
    }
}

/// A link's share of a total: its area times a complexity factor.
fn weight(link: &LinkGeometry) -> f64 {
    let complexity = 1.0 + 0.25 * (link.triangles().max(12) as f64 / 12.0).log2();
    link.area().max(f64::MIN_POSITIVE) * complexity
}

/// `total` split in proportion to `weights`, at least 1 each, by largest remainders.
fn divide(total: usize, weights: &[f64]) -> Vec<usize> {
    let n = weights.len();
    if n == 0 {
        return Vec::new();
    }
    if total <= n {
        return vec![1; n];
    }
    let spare = (total - n) as f64;
    let sum: f64 = weights.iter().sum();
    let exact: Vec<f64> = weights.iter().map(|w| spare * w / sum).collect();
    let mut shares: Vec<usize> = exact.iter().map(|e| 1 + e.floor() as usize).collect();
    let mut left = total - shares.iter().sum::<usize>();
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

/// One part of a link: its meshes (joined) or one primitive.
enum Part<'a> {
    Mesh(&'a sphaera_mesh::TriMesh),
    Primitive(&'a crate::Primitive),
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
    let mut parts: Vec<Part<'_>> = Vec::new();
    if let Some(mesh) = &link.mesh {
        parts.push(Part::Mesh(mesh));
    }
    parts.extend(link.primitives.iter().map(Part::Primitive));
    let surface = match &link.mesh {
        Some(mesh) => Some(Surface::new(mesh).map_err(|e| fail(e.to_string()))?),
        None => None,
    };
    let areas: Vec<f64> = parts
        .iter()
        .map(|p| match p {
            Part::Mesh(m) => m.surface_area(),
            Part::Primitive(p) => p.area(),
        })
        .collect();
    let counts: Vec<Option<usize>> = match target {
        Target::Count(n) => divide(n, &areas).into_iter().map(Some).collect(),
        Target::Tolerance(_) => vec![None; parts.len()],
    };
    let mut spheres: Vec<Sphere> = Vec::new();
    let mut worst: f64 = 0.0;
    let mut covered = 0usize;
    let mut samples = 0usize;
    let mut trees_used = false;
    for (part, count) in parts.iter().zip(counts) {
        match part {
            Part::Mesh(_) => {
                let surface = surface
                    .as_ref()
                    .ok_or_else(|| fail("no surface".to_owned()))?;
                let fit = match (count, target) {
                    (Some(n), _) => mesh_spheres(surface, n, options).map_err(&fail)?,
                    (None, Target::Tolerance(t)) => {
                        mesh_spheres_within(surface, t, options).map_err(&fail)?
                    }
                    (None, Target::Count(n)) => mesh_spheres(surface, n, options).map_err(&fail)?,
                };
                worst = worst.max(fit.protrusion);
                covered += fit.covered;
                samples += fit.samples;
                spheres.extend(fit.spheres);
            }
            Part::Primitive(p) => {
                let (set, protrusion, from_tree) = primitive_spheres(p, count, target, options);
                trees_used |= from_tree;
                worst = worst.max(protrusion);
                let points = p.surface_points(500);
                samples += points.len();
                // The points lie on the surface the spheres are fitted to (a sphere link's
                // sphere is the link itself): a relative slack of 10⁻⁹ keeps rounding from
                // counting them out.
                covered += points
                    .iter()
                    .filter(|&&q| {
                        set.iter()
                            .any(|s| s.center.distance(q) <= s.radius * (1.0 + 1e-9))
                    })
                    .count();
                spheres.extend(set);
            }
        }
    }
    let bounding_sphere =
        minimum_enclosing_ball_of_balls(&spheres).map_err(|e| fail(e.to_string()))?;
    // A quantile never exceeds the maximum; rounding in the sampled distances could make
    // it (1e-17 above an exact 0 on a sphere link).
    let p95 = percentile_protrusion(&spheres, surface.as_ref(), &link.primitives, 0.95).min(worst);
    let report = LinkReport {
        link: link.link.clone(),
        files: link.files.iter().map(|p| p.display().to_string()).collect(),
        triangles: link
            .mesh
            .as_ref()
            .map_or(0, sphaera_mesh::TriMesh::triangle_count),
        primitives: link.primitives.len(),
        diagonal: link.diagonal(),
        budget: match target {
            Target::Count(n) => Some(n),
            Target::Tolerance(_) => None,
        },
        tolerance: match target {
            Target::Count(_) => None,
            Target::Tolerance(t) => Some(t),
        },
        meets_tolerance: match target {
            Target::Count(_) => None,
            Target::Tolerance(t) => Some(worst <= t),
        },
        spheres: spheres.len(),
        worst_protrusion: worst,
        p95_protrusion: p95,
        coverage: if samples == 0 {
            1.0
        } else {
            covered as f64 / samples as f64
        },
        // Primitives' own layouts cover by construction; a sphere-tree's cover is
        // certified only when the tree certifies it.
        coverage_certified: options.tree.certify_coverage || !(trees_used || link.mesh.is_some()),
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok(LinkSpheres {
        link: link.link.clone(),
        spheres,
        bounding_sphere,
        report,
    })
}

/// A primitive's spheres: its analytic layout, or a sphere-tree of a mesh inside it
/// (grown by the mesh's gap, so that it covers the primitive) when that is tighter; the
/// protrusion is exact either way (the primitive is convex). The flag says whether the
/// sphere-tree's set was taken.
fn primitive_spheres(
    primitive: &crate::Primitive,
    count: Option<usize>,
    target: Target,
    options: &SpherizeOptions,
) -> (Vec<Sphere>, f64, bool) {
    let tolerance = match (count, target) {
        (None, Target::Tolerance(t)) => Some(t),
        _ => None,
    };
    let (layout, reach) = match (count, target) {
        (None, Target::Tolerance(t)) => primitive.spherize_within(t, options.max_spheres_per_link),
        (Some(n), _) | (None, Target::Count(n)) => primitive.spherize(n),
    };
    let analytic = (layout, reach, false);
    if tolerance.is_some_and(|t| analytic.1 <= t) || count.is_some_and(|n| n < 4) {
        return analytic;
    }
    let Some((mesh, gap)) = primitive.inscribed_mesh() else {
        return analytic;
    };
    let Ok(surface) = Surface::new(&mesh) else {
        return analytic;
    };
    let fit = match (count, target) {
        (None, Target::Tolerance(t)) => mesh_spheres_within(&surface, (t - gap).max(0.0), options),
        (Some(n), _) | (None, Target::Count(n)) => mesh_spheres(&surface, n, options),
    };
    let Ok(fit) = fit else {
        return analytic;
    };
    let grown: Vec<Sphere> = fit
        .spheres
        .iter()
        .map(|s| Sphere::new(s.center, s.radius + gap))
        .collect();
    let protrusion = grown
        .iter()
        .map(|s| primitive.protrusion(s))
        .fold(0.0, f64::max);
    if protrusion < analytic.1 {
        (grown, protrusion, true)
    } else {
        analytic
    }
}

/// A mesh part's spheres and their fit.
struct MeshFit {
    spheres: Vec<Sphere>,
    protrusion: f64,
    covered: usize,
    samples: usize,
}

/// The leaves of a depth-1 sphere-tree of branch `count`, with their certified fit.
fn mesh_spheres(
    surface: &Surface,
    count: usize,
    options: &SpherizeOptions,
) -> Result<MeshFit, String> {
    // Leaves cannot be tighter than the medial spheres they are reduced from, which are
    // refined to `error_fraction` of the root's error: many leaves need a smaller
    // fraction (⅛ up to 48 spheres, falling as 1/√count to 1/20 from 300).
    let fraction = (0.125 * (48.0 / count.max(1) as f64).sqrt()).clamp(0.05, 0.125);
    let tree_options = options
        .tree
        .clone()
        .with_depth(1)
        .with_branch(count)
        .with_error_fraction(options.tree.error_fraction.min(fraction))
        .with_min_spheres_per_node(options.tree.min_spheres_per_node.max((3 * count).min(400)));
    let tree = sphaera_spheretree::build(surface, &tree_options).map_err(|e| e.to_string())?;
    let spheres = tree.level_spheres(tree.level_count().saturating_sub(1));
    let fit = evaluate_set(surface, &spheres, &EvaluationOptions::default())
        .map_err(|e| e.to_string())?;
    Ok(MeshFit {
        spheres,
        protrusion: fit.worst_upper,
        covered: fit.coverage.samples - fit.coverage.uncovered,
        samples: fit.coverage.samples,
    })
}

/// The fewest spheres (a doubling, then a bisection of the count) whose certified
/// protrusion is at most `tolerance`; the most allowed when none is.
fn mesh_spheres_within(
    surface: &Surface,
    tolerance: f64,
    options: &SpherizeOptions,
) -> Result<MeshFit, String> {
    let max = options.max_spheres_per_link;
    let mut failed = 0usize;
    let mut count = 1usize;
    let mut tightest: Option<MeshFit> = None;
    let found = loop {
        let fit = mesh_spheres(surface, count, options)?;
        if fit.protrusion <= tolerance {
            break fit;
        }
        // Doubling the count no longer helps by 5 %: the tree's samples and error
        // fraction set the floor; more spheres would only cost time.
        let floor = tightest
            .as_ref()
            .is_some_and(|t| count >= 128 && fit.protrusion > 0.95 * t.protrusion);
        if tightest
            .as_ref()
            .is_none_or(|t| fit.protrusion < t.protrusion)
        {
            tightest = Some(fit);
        }
        if floor || count >= max {
            return tightest.ok_or_else(|| "no spheres".to_owned());
        }
        failed = count;
        count = (2 * count).min(max);
    };
    let (mut low, mut high, mut best) = (failed, count, found);
    while high - low > 1 {
        let mid = low + (high - low) / 2;
        let fit = mesh_spheres(surface, mid, options)?;
        if fit.protrusion <= tolerance {
            high = mid;
            best = fit;
        } else {
            low = mid;
        }
    }
    Ok(best)
}

/// The `q` quantile of the distance to the link's solid over points spread by area on
/// the boundary of the union of `spheres` (points inside another sphere are not on it).
fn percentile_protrusion(
    spheres: &[Sphere],
    surface: Option<&Surface>,
    primitives: &[crate::Primitive],
    q: f64,
) -> f64 {
    const POINTS: f64 = 6_000.0;
    let total: f64 = spheres.iter().map(|s| s.radius * s.radius).sum();
    if total <= 0.0 {
        return 0.0;
    }
    let unit = crate::Primitive::new(
        crate::Shape::Sphere { radius: 1.0 },
        glam::DAffine3::IDENTITY,
    );
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
fn solid_distance(p: DVec3, surface: Option<&Surface>, primitives: &[crate::Primitive]) -> f64 {
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
