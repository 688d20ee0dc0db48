//! # Sphaera
//!
//! Hierarchical, sphere-based approximation of triangle meshes: fast and certified distance
//! queries, bounding sphere-trees for collision detection, tolerance-bounded and
//! silhouette-aware simplification, HAL trees, and scenes modelled with no more detail
//! than they need.
//!
//! This crate is the facade: it re-exports the focused Sphaera crates under short module
//! names, one [`Error`] that every crate's error converts into (so `?` works across
//! crates), and a [`prelude`] with the types almost every program needs. Depend on a
//! single crate (for example `sphaera-mesh`) if that is all you use.
//!
//! | module | crate | paper | what it does |
//! |---|---|---|---|
//! | [`mesh`] | `sphaera-mesh` | | the kernel: indexed triangle meshes, half-edge topology, validation and repair, geometric primitives, procedural test shapes (and, under their old paths, the two crates below) |
//! | [`io`] | `sphaera-io` | | file I/O: OBJ, PLY, STL, OFF; glTF 2.0 with the default feature `gltf`; atomic writes |
//! | [`query`] | `sphaera-query` | | the box tree and exact closest points, winding numbers, the `Surface` (inside test and signed closest points), surface sampling, sampled Hausdorff distances |
//! | `simplify` (feature `simplify`) | `sphaera-simplify` | Guéziec 2001 (error spheres) | edge-collapse simplification whose reported error bound holds in both directions, and its progressive hierarchy |
//! | `sweep` (feature `sweep`) | `sphaera-sweep` | Guéziec 2001 (Meshsweeper) | exact and anytime closest-point queries, coherent sessions, motion, polylines and certified Hausdorff distances |
//! | `medial` (feature `medial`) | `sphaera-medial` | Bradshaw & O'Sullivan 2004 | robust incremental 3D Delaunay tetrahedralization, its Voronoi dual, and the adaptive medial-axis approximation with guaranteed sample coverage |
//! | `spheretree` (feature `spheretree`) | `sphaera-spheretree` | Bradshaw & O'Sullivan 2004 | sphere-trees for collision detection: the minimax construction (the default: built to a depth, to a tolerance as deep as needed, or to exactly N spheres; solids and sheets alike), the paper's merge, burst, expand-select and combined reducers, octree, grid and Hubbard baselines; coverage of the whole surface certified at every level, fit evaluation, interruptible traversal and exports |
//! | `hal` (feature `hal`) | `sphaera-hal` | Veltkamp | HAL trees: hierarchical approximation and localization of polygons, polylines and closed genus-0 meshes by signed discs and balls |
//! | `silhouette` (feature `silhouette`) | `sphaera-silhouette` | Mata, Pastor & Rodríguez | view-dependent distance-transform silhouette labels and the silhouette-preserving level of detail they guide |
//! | `robot` (feature `robot`) | `sphaera-robot` | Bradshaw & O'Sullivan 2004 | URDF robots: every link spherized in its own frame with certified coverage (meshes by sphere-trees, primitives analytically), forward kinematics, the spherized URDF, MoveIt SRDF, cuRobo YAML and JSON |
//! | `scene` (feature `scene`) | `sphaera-scene` | | object models built once per mesh, scenes of posed instances, per-instance detail from certified errors (world units, a fraction of each object, pixels on a camera), budgeted collision over a whole scene, JSON scene files |
//!
//! See `docs/architecture.md` in the repository for how the crates fit together, and
//! `docs/benchmarks.md` for every measured figure.
//!
//! # The library in one story
//!
//! Load a mesh and inspect it:
//!
//! ```
//! use sphaera::prelude::*;
//! use sphaera::mesh::{io, topology};
//!
//! // Any OBJ, PLY, STL, OFF or glTF file; here, one written first.
//! let path = std::env::temp_dir().join(format!("sphaera-story-{}.obj", std::process::id()));
//! io::write_obj(&path, &sphaera::mesh::shapes::torus(1.0, 0.3, 48)?)?;
//! let torus: TriMesh = io::load(&path)?;
//! std::fs::remove_file(&path)?;
//!
//! let report = topology::analyze(&torus);
//! assert!(report.is_closed && report.genus == Some(1));
//! # Ok::<(), sphaera::Error>(())
//! ```
//!
//! Simplify it with a bound that holds both ways, and check the bound against the
//! certified Hausdorff distance:
//!
//! ```
//! use sphaera::prelude::*;
//! use sphaera::simplify::simplify;
//! use sphaera::sweep::{HausdorffOptions, hausdorff};
//!
//! let torus = sphaera::mesh::shapes::torus(1.0, 0.3, 48)?;
//! let options = SimplifyOptions::default().with_max_error(Length::RelativeToDiagonal(0.02));
//! let coarse = simplify(&torus, &options)?;
//! assert!(coarse.mesh.triangle_count() < torus.triangle_count() / 2);
//! assert!(coarse.error_bound <= 0.02 * torus.bounding_box_diagonal());
//!
//! let measured = hausdorff(&torus, &coarse.mesh, &HausdorffOptions::default())?;
//! assert!(measured.lower <= coarse.error_bound);
//! # Ok::<(), sphaera::Error>(())
//! ```
//!
//! Query distances:
//!
//! ```
//! use sphaera::prelude::*;
//!
//! let torus = sphaera::mesh::shapes::torus(1.0, 0.3, 48)?;
//! let tree = TriangleTree::new(&torus)?;
//! let answer = tree.closest(DVec3::new(0.0, 0.0, 2.0))?;
//! assert!((answer.distance - (5f64.sqrt() - 0.3)).abs() < 0.01);
//! # Ok::<(), sphaera::Error>(())
//! ```
//!
//! Build a sphere-tree whose every level covers the surface, certified; to a tolerance
//! (as deep as each part needs, every leaf within it, certified), or with exactly the
//! number of spheres a budget allows; a flat sheet (no inside) gets spheres as well:
//!
//! ```
//! use sphaera::prelude::*;
//!
//! let torus = Surface::new(&sphaera::mesh::shapes::torus(1.0, 0.3, 48)?)?;
//! let options = SphereTreeOptions::default().with_depth(2).with_branch(4);
//! let tree: SphereTree = sphaera::spheretree::build(&torus, &options)?;
//! assert_eq!(tree.level_count(), 3);
//! assert_eq!(tree.coverage().len(), 3);
//!
//! let tolerance = Length::RelativeToDiagonal(0.03);
//! let fine = sphaera::spheretree::build(&torus, &SphereTreeOptions::default().with_tolerance(tolerance))?;
//! let within = 0.03 * torus.diagonal();
//! assert!(fine.leaves().iter().all(|&leaf| fine.nodes()[leaf].error <= within));
//!
//! let budget = SphereTreeOptions::default().with_depth(1).with_branch(12);
//! assert_eq!(sphaera::spheretree::build(&torus, &budget)?.level(1).len(), 12);
//!
//! let sheet = Surface::solid_or_shell(&sphaera::mesh::shapes::square_sheet(1.0, 4)?)?;
//! assert!(!sheet.has_inside());
//! assert_eq!(sphaera::spheretree::build(&sheet, &budget)?.level(1).len(), 12);
//! # Ok::<(), sphaera::Error>(())
//! ```
//!
//! Model no more than a scene needs: the coarsest levels each instance can take.
//!
//! ```
//! use std::sync::Arc;
//! use sphaera::prelude::*;
//! use sphaera::mesh::geometry::Similarity;
//! use sphaera::scene::{Camera, Tolerance};
//!
//! let torus = sphaera::mesh::shapes::torus(1.0, 0.3, 48)?;
//! let options = ModelOptions::default().with_tree(
//!     SphereTreeOptions::default().with_depth(2).with_branch(4).with_samples(800)
//!         .with_initial_spheres(80).with_min_spheres_per_node(20),
//! );
//! let model = Arc::new(ObjectModel::build("torus", torus, &options)?);
//! let mut scene = Scene::new();
//! for i in 0..5 {
//!     let pose = Similarity::from_translation(DVec3::new(0.0, 0.0, -8.0 * i as f64))?;
//!     scene.add(format!("torus-{i}"), Arc::clone(&model), pose);
//! }
//! let camera = Camera::perspective(DVec3::new(0.0, 2.0, 6.0), DVec3::new(0.0, 0.0, -10.0), 50.0, 1280, 720)?;
//! let report = scene.detail(Some(&camera), Tolerance::Pixels(1.0))?;
//! assert!(report.triangles < report.full_triangles);
//! // Farther away, coarser.
//! let counts: Vec<usize> = report.instances.iter().map(|d| d.mesh.count).collect();
//! assert!(counts.windows(2).all(|w| w[0] >= w[1]));
//!
//! // Contacts within a budget: none here, the tori are apart.
//! assert!(scene.collide(&Budget::Unlimited)?.pairs.is_empty());
//! # Ok::<(), sphaera::Error>(())
//! ```
//!
//! Spheres for a robot's motion planner: every link covered in its own frame.
//!
//! ```
//! use sphaera::robot::{MeshResolver, PlannerFormat, SphereBudget, SpherizeOptions, Urdf, spherize};
//!
//! let urdf = Urdf::parse(r#"<robot name="gripper">
//!   <link name="palm"><collision><geometry><box size="0.08 0.2 0.04"/></geometry></collision></link>
//! </robot>"#, "gripper.urdf")?;
//! let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(12));
//! let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options)?;
//! assert!(robot.links[0].report.coverage_certified);
//! let yaml = PlannerFormat::CuroboSpheres.render(&urdf, &robot)?; // cuRobo's collision_spheres
//! assert!(yaml.contains("\"palm\":"));
//! // A complete cuRobo robot file, MuJoCo's MJCF, MoveIt's SRDF: with the self-collision
//! // matrix, computed when the robot has none.
//! let robot_file = PlannerFormat::Curobo.render(&urdf, &robot)?;
//! assert!(robot_file.contains("base_link: \"palm\""));
//! # Ok::<(), sphaera::Error>(())
//! ```
//!
//! # Errors
//!
//! Every crate has its own error type; [`Error`] wraps each transparently (its message is
//! the crate's), so one function can use several crates with `?`. Each crate's error is
//! `#[non_exhaustive]`, says what was wrong and where, and none of the crates panics on
//! user input.
//!
//! # Performance
//!
//! The facade adds nothing at run time. Each crate's documentation says what was
//! measured and names its section of the repository's `docs/benchmarks.md`, which has
//! every measured figure, with the machine, the date and the command that made each
//! number, beside the peer libraries measured in the same run.
//!
//! # See also
//!
//! The `sphaera` command-line tool (`sphaera-cli`), one subcommand per capability, and
//! the single crates above for users who need only one of them.
//!
//! # Feature flags
#![doc = document_features::document_features!()]

#[cfg(feature = "hal")]
pub use sphaera_hal as hal;
pub use sphaera_io as io;
#[cfg(feature = "medial")]
pub use sphaera_medial as medial;
pub use sphaera_query as query;

/// The triangle-mesh kernel (`sphaera-mesh`), with the file formats (`sphaera-io`, also
/// [`sphaera::io`](crate::io)) and the spatial queries (`sphaera-query`, also
/// [`sphaera::query`](crate::query)) under the paths they had before the three were cut
/// apart: `sphaera::mesh::io`, `sphaera::mesh::winding`, `sphaera::mesh::Surface`...
pub mod mesh {
    pub use sphaera_io as io;
    pub use sphaera_mesh::*;
    pub use sphaera_query::{
        QueryError, Surface, bvh, closest, measure, sampling, surface, winding,
    };
}
#[cfg(feature = "robot")]
pub use sphaera_robot as robot;
#[cfg(feature = "scene")]
pub use sphaera_scene as scene;
#[cfg(feature = "silhouette")]
pub use sphaera_silhouette as silhouette;
#[cfg(feature = "simplify")]
pub use sphaera_simplify as simplify;
#[cfg(feature = "spheretree")]
pub use sphaera_spheretree as spheretree;
#[cfg(feature = "sweep")]
pub use sphaera_sweep as sweep;

/// Any error of a Sphaera crate: each crate's error, boxed and wrapped transparently (the
/// message and the source are the crate's), and I/O errors. The box keeps
/// `Result<T, sphaera::Error>` two words wide.
///
/// # Examples
///
/// ```
/// use sphaera::prelude::*;
///
/// fn coarse_torus() -> Result<usize, sphaera::Error> {
///     let torus = sphaera::mesh::shapes::torus(1.0, 0.3, 24)?; // MeshError
///     let options = SimplifyOptions::default().with_target_ratio(0.25);
///     let coarse = sphaera::simplify::simplify(&torus, &options)?; // SimplifyError
///     Ok(coarse.mesh.triangle_count())
/// }
/// assert!(coarse_torus()? < 300);
///
/// let error: sphaera::Error = sphaera::mesh::shapes::torus(-1.0, 0.3, 24).unwrap_err().into();
/// assert!(matches!(error, sphaera::Error::Mesh(_)));
/// # Ok::<(), sphaera::Error>(())
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// From `sphaera-mesh`: invalid or empty meshes, refused edits, bad transforms.
    #[error(transparent)]
    Mesh(Box<sphaera_mesh::MeshError>),
    /// From `sphaera-io`: files that cannot be read or written, malformed files.
    #[error(transparent)]
    File(Box<sphaera_io::IoError>),
    /// From `sphaera-query`: meshes without a meaningful inside, bad query parameters.
    #[error(transparent)]
    Query(Box<sphaera_query::QueryError>),
    /// From `sphaera-simplify`.
    #[cfg(feature = "simplify")]
    #[error(transparent)]
    Simplify(Box<sphaera_simplify::SimplifyError>),
    /// From `sphaera-sweep`.
    #[cfg(feature = "sweep")]
    #[error(transparent)]
    Sweep(Box<sphaera_sweep::SweepError>),
    /// From `sphaera-medial`'s Delaunay tetrahedralization.
    #[cfg(feature = "medial")]
    #[error(transparent)]
    Delaunay(Box<sphaera_medial::DelaunayError>),
    /// From `sphaera-medial`'s medial-axis approximation.
    #[cfg(feature = "medial")]
    #[error(transparent)]
    Medial(Box<sphaera_medial::MedialError>),
    /// From `sphaera-spheretree`.
    #[cfg(feature = "spheretree")]
    #[error(transparent)]
    SphereTree(Box<sphaera_spheretree::SphereTreeError>),
    /// From `sphaera-hal`.
    #[cfg(feature = "hal")]
    #[error(transparent)]
    Hal(Box<sphaera_hal::HalError>),
    /// From `sphaera-silhouette`.
    #[cfg(feature = "silhouette")]
    #[error(transparent)]
    Silhouette(Box<sphaera_silhouette::SilhouetteError>),
    /// From `sphaera-scene`.
    #[cfg(feature = "scene")]
    #[error(transparent)]
    Scene(Box<sphaera_scene::SceneError>),
    /// From `sphaera-robot`.
    #[cfg(feature = "robot")]
    #[error(transparent)]
    Robot(Box<sphaera_robot::RobotError>),
    /// An I/O error outside the crates' own file readers.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// `From` for each boxed variant of [`Error`] (boxed so that `Result<T, Error>` stays
/// small: the crates' errors are about 120 bytes).
macro_rules! from_boxed {
    ($($(#[$cfg:meta])* $variant:ident($error:ty)),* $(,)?) => {
        $(
            $(#[$cfg])*
            impl From<$error> for Error {
                fn from(error: $error) -> Self {
                    Self::$variant(Box::new(error))
                }
            }
        )*
    };
}

from_boxed! {
    Mesh(sphaera_mesh::MeshError),
    File(sphaera_io::IoError),
    Query(sphaera_query::QueryError),
    #[cfg(feature = "simplify")]
    Simplify(sphaera_simplify::SimplifyError),
    #[cfg(feature = "sweep")]
    Sweep(sphaera_sweep::SweepError),
    #[cfg(feature = "medial")]
    Delaunay(sphaera_medial::DelaunayError),
    #[cfg(feature = "medial")]
    Medial(sphaera_medial::MedialError),
    #[cfg(feature = "spheretree")]
    SphereTree(sphaera_spheretree::SphereTreeError),
    #[cfg(feature = "hal")]
    Hal(sphaera_hal::HalError),
    #[cfg(feature = "silhouette")]
    Silhouette(sphaera_silhouette::SilhouetteError),
    #[cfg(feature = "scene")]
    Scene(sphaera_scene::SceneError),
    #[cfg(feature = "robot")]
    Robot(sphaera_robot::RobotError),
}

/// `Result` with [`Error`] as its default error.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// The types almost every Sphaera program needs (those of the enabled features).
///
/// Names that two crates share (`Tolerance`, `Camera`) are left to their modules.
pub mod prelude {
    pub use sphaera_mesh::{Aabb, DVec3, Length, MeshError, Sphere, TriMesh};
    pub use sphaera_query::closest::TriangleTree;
    pub use sphaera_query::{QueryError, Surface};
    #[cfg(feature = "scene")]
    pub use sphaera_scene::{Budget, ModelOptions, ObjectModel, Scene};
    #[cfg(feature = "simplify")]
    pub use sphaera_simplify::{Hierarchy, Simplified, SimplifyOptions};
    #[cfg(feature = "spheretree")]
    pub use sphaera_spheretree::{Method, SphereTree, SphereTreeOptions};
    #[cfg(feature = "sweep")]
    pub use sphaera_sweep::Sweeper;
}

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
