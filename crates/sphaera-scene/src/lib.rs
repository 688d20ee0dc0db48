//! # sphaera-scene
//!
//! Model no more than a scene needs, and no less. Each mesh is built once into an
//! [`ObjectModel`]: its sphere-trees (the minimax construction of `sphaera-spheretree`,
//! or the paper's, Bradshaw and O'Sullivan, *Adaptive Medial-Axis Approximation for
//! Sphere-Tree Construction*, 2004) and its simplification hierarchy with error spheres,
//! every level with a certified error. A [`Scene`] places shared models with poses. Then:
//!
//! - [`Scene::detail`] gives every instance the spheres and the mesh its [`Tolerance`]
//!   needs: world units, a fraction of each object's size, or pixels on a perspective
//!   [`Camera`]'s image (certified there too, see [`Camera::pixels_per_unit`]). **Every
//!   tolerance asked is met, or the request is an error**: a model whose trees do not
//!   reach it builds a minimax tree to it (every leaf's certified error within it,
//!   refined only where needed; [`sphaera_spheretree::SphereTreeOptions::with_tolerance`]),
//!   once per model and tolerance, and keeps it ([`ObjectModel::tree_for`]); each
//!   instance then takes the coarsest cut [`SphereTree::cut_at`](sphaera_spheretree::SphereTree::cut_at)`(level)`
//!   whose **certified error** meets its tolerance ([`SphereChoice`]: each sphere's node
//!   error, or the bound of the sphere evaluated on the exact surface where that is
//!   smaller), the smallest cut of mixed levels ([`CutChoice`]), and the coarsest mesh
//!   level. The [`DetailReport`] gives each choice, its certified error, the tree it came
//!   from and whether it was built for it, and the spheres and triangles saved against
//!   full detail. A tolerance that cannot be met (below the model's
//!   [finest](ModelOptions::finest_tolerance), or out of reach of any tree) is an error
//!   naming the model and the figures.
//! - [`Scene::collide`] finds every contact within a [`Budget`]: a broad phase over the
//!   instances' bounding spheres, then the paper's interruptible tree-against-tree
//!   traversal of every close pair's finest trees, **all pairs one level at a time**, so
//!   the answer improves monotonically as the budget grows. Each contact carries its
//!   error bound.
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
//! use sphaera_scene::{Budget, Camera, DVec3, ModelOptions, ObjectModel, Scene, SceneError, Tolerance};
//! use sphaera_spheretree::SphereTreeOptions;
//!
//! // A small base tree (depth 1) keeps the model cheap: finer tolerances get trees of
//! // their own when a request needs them.
//! let options = ModelOptions::default().with_tree(SphereTreeOptions::default().with_depth(1));
//! let torus = Arc::new(ObjectModel::build("torus", sphaera_mesh::shapes::torus(1.0, 0.3, 32)?, &options)?);
//!
//! let mut scene = Scene::new();
//! for i in 0..4 {
//!     let pose = Similarity::from_translation(DVec3::new(2.5 * i as f64, 0.0, -5.0 * i as f64))?;
//!     scene.add(format!("torus-{i}"), Arc::clone(&torus), pose);
//! }
//!
//! // Eight pixels on a 1280×720 image: every torus within them, certified; the far ones
//! // take fewer spheres and coarser meshes.
//! let camera = Camera::perspective(DVec3::new(0.0, 1.0, 6.0), DVec3::new(2.0, 0.0, -5.0), 60.0, 1280, 720)?;
//! let report = scene.detail(Some(&camera), Tolerance::Pixels(8.0))?;
//! assert!(report.instances.iter().all(|d| d.spheres.measured <= 8.0 && d.mesh.measured <= 8.0));
//! let spheres: Vec<usize> = report.instances.iter().map(|d| d.spheres.count).collect();
//! let triangles: Vec<usize> = report.instances.iter().map(|d| d.mesh.count).collect();
//! assert!(spheres[3] < spheres[0] && triangles[3] < triangles[0]);
//! // The base tree was too coarse up close: one tree was built for the tolerance, for
//! // all four tori, and asking again (the next frame) builds nothing.
//! assert_eq!(report.trees_built, 1);
//! assert_eq!(scene.detail(Some(&camera), Tolerance::Pixels(8.0))?.trees_built, 0);
//!
//! // For physics, a tolerance in world units: the tori's roots are enough at 2 units.
//! let coarse = scene.detail(None, Tolerance::Absolute(2.0))?;
//! assert!(coarse.instances.iter().all(|d| d.spheres.count == 1 && d.spheres.error <= 2.0));
//!
//! // A tolerance no tree is built for (below the finest, 0.1 % of a model's size by
//! // default) is an error naming the model, not a looser answer.
//! let refused = scene.detail(None, Tolerance::RelativeToDiagonal(1e-4)).unwrap_err();
//! assert!(matches!(&refused, SceneError::ToleranceBelowFinest { model, .. } if model == "torus"));
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
//!               "width": 1280, "height": 720 },
//!   "labels": { "bunny": "meshes/bunny.labels" }
//! }
//! ```
//!
//! - `meshes` maps a name to a mesh file (any format `sphaera_io` reads: OBJ, PLY,
//!   STL, OFF, glTF/GLB), relative to the scene file's folder unless absolute. A name
//!   given twice is an error.
//! - Each instance names its mesh and may give a `name` (default `MESH-INDEX`), a
//!   `position` (default the origin), a rotation as `rotation_degrees` (rotations about
//!   x, then y, then z, in degrees) or as a unit `quaternion` `[x, y, z, w]` (not both),
//!   and a uniform `scale` (default 1).
//! - `camera` is optional: needed for tolerances in pixels. `near` is optional.
//! - `labels` is optional (feature `silhouette`; not read without it): silhouette label
//!   files by mesh name, read by the same file policy as the meshes, which the models
//!   use instead of labelling (`ObjectModel::with_silhouette_labels` checks them: the
//!   labels of that mesh, computed with [`ModelOptions::silhouette`]'s settings; the
//!   error names the model and the file). Write one with `Labels::save` on a model's
//!   `silhouette_labels()`, or with `sphaera silhouette MESH --labels FILE --step 30
//!   --resolution 128` for the default options.
//!
//! Unknown keys are errors (a misspelt `"rotation_degree"` must not be silently
//! ignored), and every error names the file and the entry. Each mesh is read and built
//! into one [`ObjectModel`], shared by all its instances.
//!
//! # Performance
//!
//! Building sphere-trees is the cost; choosing detail and colliding are cheap next to
//! it. A model builds its base tree and its hierarchy up front ([`ObjectModel::build`]),
//! its HAL tree and silhouette labels on first use, and a tree per tolerance finer than
//! its trees reach, once, when a request needs it: **only what the scene asks for**.
//! [`Scene::detail`] builds the trees of different models on every core at once with
//! the `parallel` feature. Choosing detail once the trees are built walks their cuts,
//! evaluating a node's sphere only where its node error is over a tolerance and probing
//! its boundary does not already show it cannot meet it: the first time a tolerance is
//! asked this costs evaluations, later requests only the walk.
//!
//! The times of [`Scene::collide`] and [`Scene::detail`] on 200 low-res bunnies, beside
//! rapier's collision pipeline (`cargo bench -p sphaera-eval --bench scene_vs_rapier`),
//! and of falling objects in rapier with Sphaera's colliders, are in the section *Scenes:
//! detail and collision (`sphaera-scene`, issue 21)* of `docs/benchmarks.md` in the
//! repository. The demo run `cargo run --release -p sphaera-cli -- scene bunny_lowres.obj
//! fandisk.obj spot.obj duck.obj --tolerance 2%` on the shared meshes (pybullet's duck;
//! base trees of the root alone, the command's default) was timed by hand, also with
//! `--effort default` and at 1 %; its tree sizes and times are not kept there.
//!
//! # Errors
//!
//! Every fallible function returns [`SceneError`]: the crates' own errors pass through
//! ([`SceneError::Mesh`], [`SceneError::SphereTree`], [`SceneError::Simplify`]), a
//! tolerance that cannot be met names the model, the tolerance and its share of the
//! model's diagonal ([`SceneError::ToleranceBelowFinest`]; [`SceneError::ToleranceTree`]
//! with the library's reason, such as
//! [`ToleranceUnreachable`](sphaera_spheretree::SphereTreeError::ToleranceUnreachable)
//! with the worst error reached, the spheres and levels built and the limits), and scene
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
mod trees;

pub use camera::Camera;
pub use collide::{CollisionSummary, PairContacts, SceneCollision};
pub use detail::{CutChoice, DetailReport, InstanceDetail, LevelChoice, SphereChoice, TreeChoice};
pub use error::SceneError;
pub use file::{CameraEntry, InstanceEntry, LoadedScene, SceneDescription, SceneFile};
pub use glam::DVec3;
pub use model::{MAX_MESH_LADDER_LEVELS, MeshLevel, ModelOptions, ObjectModel, SilhouetteOptions};
pub use scene::{Instance, Scene};
#[cfg(feature = "silhouette")]
pub use silhouette::{SilhouetteChoice, SilhouetteDetailOptions, SilhouetteReport};
pub use sphaera_mesh::Sphere;
pub use sphaera_spheretree::collide::{Budget, Contact, CostModel, TraversalStats};
pub use tolerance::Tolerance;
pub use trees::ModelTree;

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
