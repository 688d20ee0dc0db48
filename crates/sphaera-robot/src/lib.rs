//! # sphaera-robot
//!
//! Whole-robot sphere models that motion planners can trust. GPU and SIMD planners
//! (cuRobo, VAMP, MoveIt's collision checks) represent each link of a robot by a few
//! spheres; a sphere set that misses part of a link is a crash the planner cannot see.
//! This crate reads a URDF ([`Urdf`]), loads every link's collision (or visual) meshes
//! in the link's own frame with their `<origin xyz rpy>` and `<mesh scale>`, resolving
//! `package://` and relative paths ([`MeshResolver`]), and spherizes every link
//! ([`spherize`]) so that its spheres **cover every point of its surface, certified**:
//!
//! - meshes by a sphere-tree of Bradshaw and O'Sullivan's adaptive medial-axis method
//!   (`sphaera-spheretree`, one level of as many spheres as the link's budget), whose
//!   coverage of the surface is certified triangle piece by triangle piece and whose
//!   protrusion (how far a sphere reaches beyond the surface) is certified by branch and
//!   bound;
//! - boxes, cylinders, spheres and capsules analytically ([`Primitive`]): covering sets
//!   by construction, protrusion exact.
//!
//! Because every link's spheres cover that link in its own frame, the spheres moved by
//! the robot's forward kinematics ([`Urdf::link_poses`]) cover the posed robot at any
//! joint configuration. The results go out in the planners' formats
//! ([`PlannerFormat`]): the spherized URDF, MoveIt's SRDF sidecar, cuRobo's
//! `collision_spheres` YAML, or JSON with a tree per link (its bounding sphere, groups
//! of nearby spheres, then the spheres, each enclosing its children, for planners that
//! stop early) and a report per link (spheres, worst protrusion, 95th-percentile protrusion,
//! coverage, time).
//!
//! # Quick start
//!
//! ```
//! use sphaera_robot::{MeshResolver, PlannerFormat, SphereBudget, SpherizeOptions, Urdf, spherize};
//!
//! let urdf = Urdf::parse(r#"
//!   <robot name="arm">
//!     <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
//!     <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><capsule radius="0.04" length="0.4"/></geometry></collision></link>
//!     <joint name="shoulder" type="revolute">
//!       <parent link="base"/><child link="upper"/><origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
//!     </joint>
//!   </robot>"#, "arm.urdf")?;
//! // A tolerance: every link gets as few spheres as keep them within 1 cm of its surface.
//! let options = SpherizeOptions::default().with_budget(SphereBudget::Tolerance(sphaera_mesh::Length::Absolute(0.01)));
//! let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options)?;
//! for link in &robot.links {
//!     assert_eq!(link.report.meets_tolerance, Some(true));
//!     assert!(link.report.worst_protrusion <= 0.01 && link.report.coverage == 1.0);
//! }
//! let yaml = PlannerFormat::Curobo.render(&urdf, &robot)?;
//! assert!(yaml.starts_with("collision_spheres:\n  \"base\":"));
//! # Ok::<(), sphaera_robot::RobotError>(())
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
//!   placed. Open and non-manifold meshes are fine: the inside is the generalized
//!   winding number's.
//! - **Budgets** ([`SphereBudget`]): a count per link, a total divided by size and
//!   complexity, per-link overrides, or a tolerance, which picks each link's count (a
//!   doubling then a bisection of the count, each candidate certified).
//! - **Spherizing** ([`spherize`]): links in parallel; within a link the budget is split
//!   among its meshes and primitives by area.
//!
//! # Errors
//!
//! [`RobotError`]: a file that cannot be read, malformed XML (line and column), an
//! invalid element (line, link and element), a mesh found nowhere (every path tried),
//! a mesh that cannot be loaded (link and file), a link that cannot be spherized, an
//! option naming no link.
//!
//! # Performance
//!
//! Measured on the 2-core reference machine (`cargo bench -p sphaera-eval --bench
//! robot_spheres`, 2026-11-28): the whole Franka Panda (eleven collision meshes) at 40
//! spheres per link in 2.9 s on one thread and 1.6 s on two; the KUKA iiwa (eight
//! binary STLs of up to 3,038 triangles) in 4.4 s and 2.5 s. At 40 spheres per link the
//! certified worst protrusion is 0.38–0.67 of a voxel k-means baseline's on the Panda's
//! links (3.6–6.3 % of each link's diagonal), and 0.43–0.91 on the KUKA's
//! (`robot_protrusion_vs_spheres` in the repository's `docs/benchmarks.md`).
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! `sphaera-spheretree` (the sphere-trees, their certificates, and the YAML writer),
//! `sphaera-mesh` (the mesh readers and the surface's inside test), and `sphaera urdf`
//! in `sphaera-cli`.

mod error;
mod formats;
mod geometry;
mod kinematics;
mod primitive;
mod spherize;
mod urdf;

pub use error::RobotError;
pub use formats::{PlannerFormat, curobo_yaml, json, spherized_urdf, srdf, write_atomic};
pub use geometry::{GeometrySource, LinkGeometry, MeshResolver};
pub use primitive::{Primitive, Shape};
pub use sphaera_mesh::{Length, Sphere};
pub use spherize::{
    LinkReport, LinkSpheres, MAX_SPHERES_PER_LINK, RobotSpheres, SphereBudget, SpherizeOptions,
    SpherizeProgress, spherize, spherize_geometry, spherize_with_progress,
};
pub use urdf::{Element, Geometry, Joint, JointKind, Link, Mimic, Origin, Urdf};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
