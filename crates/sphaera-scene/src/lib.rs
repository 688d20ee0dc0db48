//! # sphaera-scene
//!
//! Model no more than a scene needs. Each mesh is built once into an [`ObjectModel`]: its
//! sphere-tree (Bradshaw and O'Sullivan, *Adaptive Medial-Axis Approximation for
//! Sphere-Tree Construction*, 2004) and its simplification hierarchy with error spheres,
//! every level with a certified error. A [`Scene`] places shared models with poses. Then:
//!
//! - [`Scene::detail`] picks, for every instance, the **coarsest** sphere-tree level and
//!   the coarsest mesh level whose certified error meets a [`Tolerance`]: world units, a
//!   fraction of each object's size, or pixels on a perspective [`Camera`]'s image
//!   (certified there too, see [`Camera::pixels_per_unit`]), and the smallest cut through
//!   the sphere-tree that meets it ([`CutChoice`]: coarse nodes where they are tight
//!   enough, often far fewer spheres than a level). The [`DetailReport`] gives each
//!   choice, its error, and the totals against full detail.
//! - [`Scene::collide`] finds every contact within a [`Budget`]: a broad phase over the
//!   instances' bounding spheres, then the paper's interruptible tree-against-tree
//!   traversal for every close pair, **all pairs one level at a time**, so the answer
//!   improves monotonically as the budget grows. Each contact carries its error bound.
//! - With the `silhouette` feature, `Scene::silhouette_detail` keeps each instance's
//!   **outline** within the tolerance and lets its interior be coarser (a multiple of
//!   it), from the model's silhouette labels (Mata, Pastor and Rodríguez), both regions'
//!   errors certified.
//! - [`SceneDescription`] reads a JSON scene file (meshes, instances with poses, a camera)
//!   with errors that name the file and the entry.
//!
//! # Quick start
//!
//! ```
//! use std::sync::Arc;
//! use sphaera_mesh::geometry::Similarity;
//! use sphaera_scene::{Budget, Camera, DVec3, ModelOptions, ObjectModel, Scene, Tolerance};
//! use sphaera_spheretree::SphereTreeOptions;
//!
//! // Small trees keep this example fast; the defaults are depth 3, branch 8.
//! let tree = SphereTreeOptions::default().with_depth(2).with_branch(4).with_samples(600)
//!     .with_initial_spheres(60).with_min_spheres_per_node(20);
//! let options = ModelOptions::default().with_tree(tree);
//! let torus = Arc::new(ObjectModel::build("torus", sphaera_mesh::shapes::torus(1.0, 0.3, 32)?, &options)?);
//!
//! let mut scene = Scene::new();
//! for i in 0..4 {
//!     let pose = Similarity::from_translation(DVec3::new(2.5 * i as f64, 0.0, -5.0 * i as f64))?;
//!     scene.add(format!("torus-{i}"), Arc::clone(&torus), pose);
//! }
//!
//! // Two pixels on a 1280×720 image: the far tori take coarser meshes.
//! let camera = Camera::perspective(DVec3::new(0.0, 1.0, 6.0), DVec3::new(2.0, 0.0, -5.0), 60.0, 1280, 720)?;
//! let report = scene.detail(Some(&camera), Tolerance::Pixels(2.0))?;
//! let triangles: Vec<usize> = report.instances.iter().map(|d| d.mesh.count).collect();
//! assert!(triangles[3] < triangles[0] && report.triangles < report.full_triangles);
//! assert!(report.instances.iter().all(|d| d.mesh.meets && d.mesh.measured <= 2.0));
//! // These small trees are too coarse for two pixels up close: the finest level is
//! // taken, and the report says so.
//! assert!(!report.instances[0].spheres.meets && !report.all_meet);
//!
//! // For physics, a tolerance in world units: the tori's roots are enough at 2 units.
//! let coarse = scene.detail(None, Tolerance::World(2.0))?;
//! assert!(coarse.instances.iter().all(|d| d.spheres.level == 0 && d.spheres.meets));
//!
//! // Nothing touches: the broad phase finds no close pair.
//! let contacts = scene.collide(&Budget::Unlimited)?;
//! assert!(contacts.pairs.is_empty());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Scene files
//!
//! [`SceneDescription::read`] takes JSON naming meshes, the instances with their poses,
//! and a camera; `sphaera scene SCENE.json` reads the same files:
//!
//! ```json
//! {
//!   "meshes": { "bunny": "meshes/bunny.obj", "link": "/abs/path/link6.stl" },
//!   "instances": [
//!     { "name": "front", "mesh": "bunny", "position": [0, 0, 0] },
//!     { "mesh": "bunny", "position": [0.3, 0, -2], "rotation_degrees": [0, 90, 0], "scale": 2 },
//!     { "mesh": "link", "quaternion": [0, 0, 0.7071068, 0.7071068] }
//!   ],
//!   "camera": { "eye": [0, 0.1, 1], "target": [0, 0.1, 0], "fov_y_degrees": 60,
//!               "width": 1280, "height": 720 }
//! }
//! ```
//!
//! - `meshes` maps a name to a mesh file (any format `sphaera_mesh::io` reads: OBJ, PLY,
//!   STL, OFF, glTF/GLB), relative to the scene file's folder unless absolute. A name
//!   given twice is an error.
//! - Each instance names its mesh and may give a `name` (default `MESH-INDEX`), a
//!   `position` (default the origin), a rotation as `rotation_degrees` (rotations about
//!   x, then y, then z, in degrees) or as a unit `quaternion` `[x, y, z, w]` (not both),
//!   and a uniform `scale` (default 1).
//! - `camera` is optional: needed for tolerances in pixels. `near` is optional.
//!
//! Unknown keys are errors (a misspelt `"rotation_degree"` must not be silently
//! ignored), and every error names the file and the entry. Each mesh is read and built
//! into one [`ObjectModel`], shared by all its instances.
//!
//! # Performance
//!
//! Choosing detail and colliding are cheap next to building the models: an
//! [`ObjectModel`] costs about its sphere-tree (2–3 s for a mesh of 4k–13k triangles with
//! the default depth 3 on the 2-core reference machine), and is built once per mesh.
//! Measured on that machine (2026-11-27, `cargo bench -p sphaera-eval --bench
//! scene_vs_rapier`, 200 low-res bunnies, everything from scratch per call):
//! [`Scene::collide`] to the leaves takes 1.42 ms, where rapier's collision pipeline on
//! compounds of the same balls takes 24.8 ms; [`Scene::detail`] at 2 pixels takes
//! 1.34 ms for all 200 instances (levels, mesh rungs and smallest cuts), and
//! `Scene::silhouette_detail` 28.9 ms. In rapier, 200 falling bodies on the ball
//! compounds `Scene::detail` chooses for 10 % of each object's size step in 3.0 ms, 11×
//! faster than on rapier's convex decomposition, with no true mesh penetrating another;
//! at the default trees' finest level (about 2 %) convex decomposition is 4× faster. The
//! figures, the experiment and what was tried are in the repository's
//! `docs/benchmarks.md` ("Scenes: detail and collision").
//!
//! # Errors
//!
//! Every fallible function returns [`SceneError`]: the crates' own errors pass through
//! ([`SceneError::Mesh`], [`SceneError::SphereTree`], [`SceneError::Simplify`]), and scene
//! files report the file and the entry ([`SceneError::ParseFile`] with line and column,
//! [`SceneError::InvalidEntry`] naming `instances[3] ("name")`, `meshes.NAME` or
//! `camera`).
//!
//! # See also
//!
//! `sphaera-spheretree` (the trees and the single-pair traversal
//! [`sphaera_spheretree::collide::collide`]), `sphaera-simplify` (the hierarchy and its
//! error spheres), and the `sphaera scene` command of `sphaera-cli`.
//!
//! # Feature flags
#![doc = document_features::document_features!()]

mod camera;
mod collide;
mod detail;
mod error;
mod file;
mod model;
mod scene;
#[cfg(feature = "silhouette")]
mod silhouette;
mod tolerance;

pub use camera::Camera;
pub use collide::{CollisionSummary, PairContacts, SceneCollision};
pub use detail::{CutChoice, DetailReport, InstanceDetail, LevelChoice};
pub use error::SceneError;
pub use file::{CameraEntry, InstanceEntry, LoadedScene, SceneDescription, SceneFile};
pub use glam::DVec3;
pub use model::{MeshLevel, ModelOptions, ObjectModel, SilhouetteOptions};
pub use scene::{Instance, Scene};
#[cfg(feature = "silhouette")]
pub use silhouette::{SilhouetteChoice, SilhouetteDetailOptions, SilhouetteReport};
pub use sphaera_mesh::Sphere;
pub use sphaera_spheretree::collide::{Budget, Contact, CostModel, TraversalStats};
pub use tolerance::Tolerance;

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
