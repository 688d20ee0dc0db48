//! # sphaera-silhouette
//!
//! View-dependent **distance labels** after Mata, Pastor and Rodríguez (*Mesh
//! simplification using distance labels for view-independent silhouette preservation*,
//! `shared/papers/silhouette-distance-labels-mata-pastor-rodriguez.md`): for a set of
//! views, how far each vertex, edge and face of a mesh lies from the silhouette in the
//! image, so that a simplifier can keep the error small near contours, from any view.
//!
//! Status (issue 18, in progress): camera sets with constant-time nearest-view lookup,
//! conservative mesh mapping, binary images with the internal silhouettes cut out, exact
//! Euclidean and chamfer distance transforms, labels per view carried back to vertices,
//! edges and faces, compact storage and interpolation for new views. Not yet: the level
//! of detail guided by the labels (section 3.3), the CLI, the evaluation.
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_silhouette::{DistanceTransform, Interpolation, Labels, ViewSet};
//!
//! let mesh = shapes::sphere(1.0, 16)?;
//! let views = ViewSet::regular(45.0)?; // 26 views
//! let labels = Labels::compute(&mesh, &views, 64, DistanceTransform::Euclidean)?;
//! // One u16 per vertex per view.
//! assert_eq!(labels.storage_bytes(), 2 * mesh.positions().len() * views.len());
//! // Seen from above, the equator is the silhouette (label 0) and the pole is deep
//! // inside the disc (about half the grid).
//! let top = labels.for_view(DVec3::Z, Interpolation::Nearest)?;
//! let pole = mesh.positions().iter().position(|p| p.z > 0.999).unwrap();
//! assert!(top[pole] > 20.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # The method in brief
//!
//! - **Views** ([`ViewSet`]): a latitude–longitude grid every `step` degrees (266 views at
//!   15°), orthographic or perspective; the nearest view, and the `n` nearest, in
//!   constant time.
//! - **Mapping** ([`FaceGrid`]): every face projected and rasterized conservatively (every
//!   cell it touches) onto a square grid over the bounding sphere's image.
//! - **Binary image**: cells under some face are object; cells under a face that holds a
//!   silhouette vertex (one shared by faces toward and away from the camera) are
//!   background, which brings out the internal silhouettes (the paper's Fig. 2).
//! - **Distance transform** ([`DistanceTransform`]): exact Euclidean (separable, linear
//!   time) or the paper's two-pass 3–4 chamfer.
//! - **Labels** ([`label_view`], [`Labels`]): a face gets the smallest distance over its
//!   cells, an edge over the cells it crosses, a vertex the distance of its own cell (see
//!   [`ViewLabels::vertices`] for why); stored as `u16` sixteenths of a cell; new views
//!   interpolate the nearest or the `n` nearest views' labels.
//!
//! # Errors
//!
//! [`SilhouetteError`]: a step that does not divide 180°, a zero resolution, a zero or
//! non-finite direction, a perspective camera inside the bounding sphere, an empty mesh.

mod camera;
mod distance;
mod error;
mod labels;
mod raster;
mod views;

pub use camera::Camera;
pub use distance::DistanceTransform;
pub use error::SilhouetteError;
pub use labels::{Interpolation, LABEL_SCALE, Labels, ViewLabels, label_view};
pub use raster::FaceGrid;
pub use views::{Projection, ViewSet};
