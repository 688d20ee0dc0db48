//! What spherizing gives: each link's spheres and report, and the robot's.

use serde::Serialize;
use sphaera_mesh::Sphere;

use crate::geometry::GeometrySource;
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
    /// Whether coverage of every point of the surface is certified: on the meshes by the
    /// sphere-tree's coverage certificate (every triangle piece inside one sphere); on a
    /// primitive by its layout's construction (each sphere circumscribes
    /// a cell of a tiling of the primitive's surface), checked on 500 points spread over
    /// the surface (a point left out makes this `false`).
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
    /// Which pairs of links a planner need not test against each other, when computed
    /// ([`SpherizeOptions::self_collision`](crate::SpherizeOptions::self_collision), or
    /// [`self_collision_matrix`](crate::self_collision_matrix) set here).
    pub self_collision: Option<crate::SelfCollisionMatrix>,
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
