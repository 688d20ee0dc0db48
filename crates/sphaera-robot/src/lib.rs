//! # sphaera-robot
//!
//! Whole-robot sphere models that motion planners can trust. GPU and SIMD planners
//! (cuRobo, VAMP, MoveIt's collision checks) represent each link of a robot by a few
//! spheres; a sphere set that misses part of a link is a crash the planner cannot see.
//! This crate reads a URDF ([`Urdf`]), loads every link's collision (or visual) meshes
//! in the link's own frame with their `<origin xyz rpy>` and `<mesh scale>`, resolving
//! `package://` and relative paths ([`MeshResolver`]), and spherizes every link
//! ([`spherize`]) so that its spheres **cover every point of its surface**, with a
//! **certified worst protrusion** (how far any sphere reaches beyond the link), to the
//! budget asked ([`SphereBudget`]):
//!
//! - **exactly `N` spheres per link** ([`SphereBudget::PerLink`]): the link's meshes get
//!   a one-level minimax sphere-tree of `N` spheres (`sphaera-spheretree`), its boxes,
//!   cylinders, spheres and capsules ([`Primitive`]) analytic sets; never more, and fewer
//!   only where a link cannot use them, with the reason in its report
//!   ([`LinkReport::shortfall`]: a sphere primitive is its own sphere);
//! - **exactly `N` spheres in all** ([`SphereBudget::Total`]), divided among the links in
//!   proportion to what each needs (per-link counts taken out first);
//! - **a tolerance** ([`SphereBudget::Tolerance`]), absolute or relative to each link:
//!   every link's certified worst protrusion within it, with as few spheres as the leaves
//!   of a minimax tolerance tree need, or an error that says why not.
//!
//! Because every link's spheres cover that link in its own frame, the spheres moved by
//! the robot's forward kinematics ([`Urdf::link_poses`]) cover the posed robot at any
//! joint configuration. Which pairs of links a planner need not test against each other
//! is the self-collision matrix ([`self_collision_matrix`]: MoveIt's rules on the
//! spheres over 10,000 seeded random configurations, [`KinematicChain`] posing them).
//! The results go out in the planners' formats ([`PlannerFormat`]): the spherized URDF,
//! MoveIt's SRDF sidecar with its `<disable_collisions>`, a complete cuRobo robot file
//! ([`curobo_robot_yaml`]) or its `collision_spheres` block, MuJoCo's MJCF ([`mjcf`]), or
//! JSON with a tree per link (its bounding sphere, groups of nearby spheres, then the
//! spheres, each enclosing its children, for planners that stop early) and a report per
//! link (spheres asked and given, worst and 95th-percentile protrusion, coverage, time).
//!
//! # Quick start
//!
//! ```
//! use sphaera_robot::{
//!     Effort, Length, LinkGeometry, MeshResolver, PlannerFormat, SelfCollisionOptions,
//!     SphereBudget, SpherizeOptions, Urdf, self_collision_matrix, spherize, spherize_geometry,
//! };
//!
//! let urdf = Urdf::parse(r#"
//!   <robot name="arm">
//!     <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
//!     <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><capsule radius="0.04" length="0.4"/></geometry></collision></link>
//!     <joint name="shoulder" type="revolute">
//!       <parent link="base"/><child link="upper"/><origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
//!     </joint>
//!   </robot>"#, "arm.urdf")?;
//! let resolver = MeshResolver::new(urdf.folder());
//!
//! // A tolerance: every link within 1 cm of its surface, with as few spheres as it needs.
//! let options = SpherizeOptions::default().with_budget(SphereBudget::Tolerance(Length::Absolute(0.01)));
//! let robot = spherize(&urdf, &resolver, &options)?;
//! for link in &robot.links {
//!     assert!(link.report.worst_protrusion <= 0.01 && link.report.coverage == 1.0);
//! }
//! let yaml = PlannerFormat::CuroboSpheres.render(&urdf, &robot)?;
//! assert!(yaml.starts_with("collision_spheres:\n  \"base\":"));
//!
//! // Which pairs of links a planner need not test: here the two joined by the shoulder.
//! let matrix = self_collision_matrix(&urdf, &robot, &SelfCollisionOptions::default())?;
//! assert!(matrix.is_disabled("base", "upper"));
//! // A complete cuRobo robot file and MuJoCo's MJCF carry it.
//! let robot_file = PlannerFormat::Curobo.render(&urdf, &robot)?;
//! assert!(robot_file.contains("self_collision_ignore:\n      \"base\": [\"upper\"]"));
//! let mjcf = PlannerFormat::Mjcf.render(&urdf, &robot)?;
//! assert!(mjcf.contains(r#"<exclude body1="base" body2="upper"/>"#));
//!
//! // Exactly 10 spheres in all, divided by what each link needs.
//! let options = SpherizeOptions::default().with_budget(SphereBudget::Total(10));
//! assert_eq!(spherize(&urdf, &resolver, &options)?.sphere_count(), 10);
//!
//! // A mesh link (here a procedural one) gets exactly the count asked for.
//! let rod = LinkGeometry {
//!     link: "rod".to_owned(),
//!     mesh: Some(sphaera_mesh::shapes::capsule(0.03, 0.3, 12)?),
//!     files: Vec::new(),
//!     primitives: Vec::new(),
//! };
//! let options = SpherizeOptions::default()
//!     .with_budget(SphereBudget::PerLink(6))
//!     .with_effort(Effort::Quick);
//! let robot = spherize_geometry("rod", vec![rod], &options, &|_| {})?;
//! let report = &robot.links[0].report;
//! assert_eq!((report.spheres, report.budget), (6, Some(6)));
//! assert!(report.coverage_certified && report.shortfall.is_none());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # The method in brief
//!
//! - **Reading** ([`Urdf::read`]): `roxmltree` parses the XML (errors carry the line and
//!   column); every number, size, radius and scale is checked (a zero scale, a negative
//!   radius, an unknown geometry are errors naming the line and the link).
//! - **Geometry** ([`LinkGeometry::load`]): each mesh element is resolved, loaded (OBJ,
//!   PLY, STL, OFF, glTF), scaled per axis (a mirroring scale flips the triangles),
//!   placed by its origin and joined with the link's other meshes; primitives are
//!   placed. For spherizing, vertices at identical positions are welded (OBJ and STL
//!   files often repeat them per triangle), and the meshes are the solid they enclose
//!   or, when they enclose nothing (an open patch, a flat plate), a shell
//!   (`Surface::solid_or_shell`; [`LinkReport::shell`]).
//! - **Counts**: a link's count is divided among its meshes and primitives by area;
//!   what a primitive cannot use goes to the meshes. The meshes get a one-level minimax
//!   tree of exactly their count (`SphereTreeOptions::with_depth(1).with_branch(n)`),
//!   whose spheres cover the surface by construction. A link with more parts than
//!   spheres gets one sphere per part, the two whose enclosing ball is smallest merged
//!   until the count is reached.
//! - **Totals**: the links with their own count keep it; the rest is divided among the
//!   other links by surface area times `1 + ¼·log₂(triangles / 12)` (largest
//!   remainders, at least one each), summing to the total exactly; spheres a link cannot
//!   use are passed on to the links that use all theirs.
//! - **Tolerances**: the meshes get the leaves of a minimax tolerance tree
//!   (`SphereTreeOptions::with_tolerance`: refined only where a sphere reaches farther,
//!   each node into the fewest children that meet it); primitives the fewest analytic
//!   spheres. A link that would need more than
//!   [`SpherizeOptions::max_spheres_per_link`] (1,000) spheres is an error.
//! - **Certified protrusion**: on a closed manifold ([`LinkReport::closed`]) the tree's
//!   node errors bound each sphere's protrusion and a branch and bound tightens the
//!   worst. On open or non-manifold meshes a point can leave the enclosed solid through a
//!   hole without crossing the surface, so the node errors need not hold there: every
//!   sphere is evaluated in full by branch and bound instead, and under a tolerance a
//!   leaf that reaches farther is replaced by spheres fitted to the surface that meets
//!   it taken as a shell (within the tolerance of that surface, hence of the link).
//!   Primitives' protrusion is exact (they are convex).
//! - **Spherizing** ([`spherize`]): links in parallel (`parallel` feature), the same
//!   spheres either way.
//!
//! # Errors
//!
//! [`RobotError`]: a file that cannot be read, malformed XML (line and column), an
//! invalid element (line, link and element), a mesh found nowhere (every path tried),
//! a mesh that cannot be loaded (link and file), a zero count or a tolerance that is not
//! positive and finite ([`RobotError::InvalidParameter`]), a total too small for the
//! links ([`RobotError::Budget`]), a tolerance that needs too many spheres
//! ([`RobotError::ToleranceUnreachable`]), a link that cannot be spherized, an option
//! naming no link.
//!
//! # Performance and accuracy
//!
#![doc = include_str!("performance.md")]
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! `sphaera-spheretree` (the sphere-trees, their certificates, and the YAML writer),
//! `sphaera-mesh` (the mesh readers and the surface's inside test), and `sphaera urdf`
//! (also `sphaera robot`) in `sphaera-cli`.

mod chain;
mod error;
mod formats;
mod geometry;
mod kinematics;
mod primitive;
mod self_collision;
mod spherize;
mod urdf;

pub use chain::{ActiveJoint, JointMotion, JointSource, JointStep, KinematicChain};
pub use error::RobotError;
pub use formats::{
    CuroboOptions, MjcfOptions, PlannerFormat, curobo_robot_yaml, curobo_yaml, json, mjcf,
    spherized_urdf, srdf, write_atomic,
};
pub use geometry::{GeometrySource, LinkGeometry, MeshResolver};
pub use primitive::{Primitive, Shape};
pub use self_collision::{
    DisableReason, LinkPair, MAX_SELF_COLLISION_SAMPLES, SelfCollisionMatrix, SelfCollisionOptions,
    self_collision_matrix,
};
pub use sphaera_mesh::{Length, Sphere};
pub use sphaera_spheretree::Effort;
pub use spherize::{
    LinkReport, LinkSpheres, MAX_SPHERES_PER_LINK, RobotSpheres, SphereBudget, SpherizeOptions,
    SpherizeProgress, spherize, spherize_geometry, spherize_with_progress,
};
pub use urdf::{Element, Geometry, Inertial, Joint, JointKind, Link, Mimic, Origin, Urdf};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
