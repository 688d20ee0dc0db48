//! Spherizing every link: budgets, the minimax sphere-tree of each link's meshes, the
//! analytic sets of its primitives, and the report of each link.

mod budget;
mod link;
mod mesh_fit;
mod options;
mod primitive_fit;
mod protrusion;
mod report;

use sphaera_mesh::Sphere;

use crate::RobotError;
use crate::geometry::{LinkGeometry, MeshResolver};
use crate::primitive::Primitive;
use crate::urdf::Urdf;

pub use options::{MAX_SPHERES_PER_LINK, SphereBudget, SpherizeOptions};
pub use report::{LinkReport, LinkSpheres, RobotSpheres};

use budget::{Target, allocate, pass_on_unused};
use link::spherize_link;
use options::validate;
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
    let mut robot = spherize_geometry(&urdf.name, geometry, options, progress)?;
    if let Some(self_collision) = &options.self_collision {
        robot.self_collision = Some(crate::self_collision_matrix(urdf, &robot, self_collision)?);
    }
    Ok(robot)
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
    let with_names: std::collections::HashSet<&str> =
        with.iter().map(|g| g.link.as_str()).collect();
    for name in options.per_link.keys() {
        if !with_names.contains(name.as_str()) {
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
        self_collision: None,
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
            // Analytic layouts cover by construction (each sphere circumscribes a cell of
            // a tiling of the primitive's surface, or is the sphere itself); the points
            // check the construction, and a point left out withdraws the claim.
            certified: covered == points.len(),
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
