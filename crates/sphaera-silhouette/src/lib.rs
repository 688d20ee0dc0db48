//! # sphaera-silhouette
//!
//! View-dependent **distance labels** after Mata, Pastor and Rodríguez (*Mesh
//! simplification using distance labels for view-independent silhouette preservation*,
//! `shared/papers/silhouette-distance-labels-mata-pastor-rodriguez.md`): for a set of
//! views, how far each vertex, edge and face of a mesh lies from the silhouette in the
//! image, so that a simplifier can keep the error small near contours, from any view.
//!
//! What it gives: camera sets with constant-time nearest-view lookup, conservative mesh
//! mapping, binary images with the internal silhouettes cut out, exact Euclidean and
//! chamfer distance transforms, labels per view carried back to vertices, edges and
//! faces, compact storage and interpolation for new views. On top of the labels, the
//! level of detail they guide (section 3.3): extracted view by view from
//! `sphaera-simplify`'s progressive hierarchy, coherently from one view to the next, with
//! the certified error bound of each region ([`ViewDependent`]); or per-vertex weights for
//! the static simplifier ([`contour_weights`]). To judge the result: the image-space
//! silhouette error ([`coverage`], [`silhouette_difference`], [`contour_displacement`],
//! [`contour_displacement_seen`] for what a frame shows)
//! and pictures made by code ([`shaded_picture`], the paper's Fig. 3, and
//! [`overlay_picture`]). Labels are saved to and loaded from versioned label files
//! checked against the mesh they belong to ([`Labels::save`], [`Labels::load`]). The
//! `sphaera silhouette` subcommand runs all of it on a mesh file.
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_silhouette::{Interpolation, LabelOptions, Labels, ViewSet};
//!
//! let mesh = shapes::sphere(1.0, 16)?;
//! let views = ViewSet::regular(45.0)?; // 26 views
//! let labels = Labels::compute(&mesh, &views, &LabelOptions::default().with_resolution(64))?;
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
//! - **Binary image**: cells under some face are object. With [`Contours::All`], cells
//!   under a face that holds a silhouette vertex (one shared by faces toward and away
//!   from the camera) that no other face hides (a depth buffer per view) are background,
//!   which brings out the internal silhouettes the camera sees (the paper's Fig. 2, where
//!   hidden ones cut too); the default, [`Contours::External`], keeps the outline alone.
//! - **Distance transform** ([`DistanceTransform`]): exact Euclidean (separable, linear
//!   time) or the paper's two-pass 3–4 chamfer.
//! - **Labels** ([`label_view`], [`Labels`]): a face gets the smallest distance over its
//!   cells, an edge over the cells it crosses, a vertex the distance of its own cell (see
//!   [`ViewLabels::vertices`] for why); stored as `u16` sixteenths of a cell; new views
//!   interpolate the nearest or the `n` nearest views' labels.
//! - **Label files** ([`Labels::save`], [`Labels::load`], [`Labels::load_with`] by a
//!   file policy, [`Labels::write_to`], [`Labels::read_from`]): the paper's Algorithm 1
//!   stores the labels; a file holds them with their settings and the mesh's
//!   [`MeshFingerprint`], and is read back only for that mesh
//!   ([`Labels::check_settings`] tells whether they are the ones asked for). See *Label
//!   files* below.
//!
//! - **Level of detail** ([`ViewDependent::extract`]): the contour region is the
//!   triangles with a corner at most `threshold` cells from the silhouette once the
//!   triangle's own error bound is counted ([`ContourRegion`]; the paper counts the
//!   corner alone); its allowed error is the smaller of `e · f` and a quarter of a cell
//!   ([`ContourTolerance`]), elsewhere `e`. Labels of the outline alone ([`Contours::External`])
//!   make a narrower region than with the internal silhouettes ([`Contours::All`]). The
//!   hierarchy is refined until every triangle's error-sphere bound meets its allowance,
//!   so the result carries a certified bound per region, which the paper's extraction
//!   does not. The refinement to `e` everywhere is kept between views; a new view redoes
//!   only its contour region.
//!
//! ```
//! use sphaera_mesh::{DVec3, shapes};
//! use sphaera_silhouette::{
//!     ContourTolerance, Interpolation, LabelOptions, Labels, ViewDependent, ViewSet,
//! };
//! use sphaera_simplify::{Hierarchy, SimplifyOptions};
//!
//! let mesh = shapes::torus(1.0, 0.3, 32)?;
//! let views = ViewSet::regular(30.0)?;
//! let labels = Labels::compute(&mesh, &views, &LabelOptions::default().with_resolution(64))?;
//! let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default())?;
//! let mut lod = ViewDependent::new(&hierarchy, &labels)?;
//! let error = 0.02 * mesh.bounding_box_diagonal();
//! let view = lod.extract(
//!     DVec3::new(0.2, 0.3, 0.9),
//!     Interpolation::Average(4),
//!     ContourTolerance::new(error),
//! )?;
//! // In the contour region: within ¼ e and ¼ cell of the 64² images.
//! assert!(view.contour_error <= view.contour_allowance);
//! assert!(view.contour_allowance <= 0.25 * error && view.other_error <= error);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Label files
//!
//! Labelling a large mesh takes seconds, every view rasterized and transformed; reading
//! its labels back is one pass over 2 bytes per vertex per view. A file is written atomically and
//! holds the labels with the settings they were computed with and the fingerprint of
//! their mesh; a reader refuses another version, a damaged file (two checksums), a
//! header whose counts pass the caps (before allocating), and another mesh, each with an
//! error naming the file and the problem ([`SilhouetteError::LabelFile`]).
//!
//! ```
//! use sphaera_mesh::{DVec3, TriMesh, shapes};
//! use sphaera_silhouette::{LabelOptions, Labels, ViewSet};
//!
//! let mesh = shapes::sphere(1.0, 12)?;
//! let views = ViewSet::regular(45.0)?;
//! let options = LabelOptions::default().with_resolution(32);
//! let labels = Labels::compute(&mesh, &views, &options)?;
//! let dir = tempfile::tempdir()?;
//! let path = dir.path().join("sphere.labels");
//! labels.save(&mesh, &path)?;
//!
//! // A later run: the labels read back equal, and are the ones asked for.
//! let loaded = Labels::load(&path, &mesh)?;
//! assert_eq!(loaded, labels);
//! loaded.check_settings(&views, &options)?;
//!
//! // The same sphere twice as large is another mesh: its labels are refused.
//! let scaled: Vec<DVec3> = mesh.positions().iter().map(|&p| 2.0 * p).collect();
//! let scaled = TriMesh::new(scaled, mesh.triangles().to_vec())?;
//! assert!(Labels::load(&path, &scaled).is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
#![doc = include_str!("label_file.md")]
//!
//! # Errors
//!
//! [`SilhouetteError`]: a step that does not divide 180°, a zero resolution, a zero or
//! non-finite direction, a parameter beyond its cap (a step below 1.40625°, more than
//! [`MAX_VIEWS`] views; a resolution above [`MAX_RESOLUTION`]; more than [`MAX_LABELS`]
//! labels, vertices × views; more than [`MAX_FACE_GRID_ENTRIES`] face–cell pairs), a perspective camera inside the bounding sphere, an empty mesh;
//! labels of another mesh, a hierarchy that moves vertices, a negative error or factor;
//! a label file that cannot be read or used ([`SilhouetteError::LabelFile`] with its
//! [`LabelFileProblem`]), labels used with a mesh they were not computed for
//! ([`SilhouetteError::LabelsOfOtherMesh`]) or of other settings
//! ([`SilhouetteError::LabelSettingsMismatch`]).
//!
//! # Performance
//!
//! Measured on the 2-core reference machine: the labels of the 69k bunny from 266 views
//! at 512², the exact distance transform against `imageproc`'s (ours is faster), and an
//! extraction for a new view, from scratch and from the previous frame, with the share of
//! the label lookup (`cargo bench -p sphaera-eval --bench silhouette_labels`); the same
//! on meshes up to the 871k dragon (`cargo run --release -p sphaera-eval -- --out
//! docs/charts --only silhouette_time_vs_faces`), where the lookup stays a small part of
//! a frame. Against the simplifier a user would otherwise run (`sphaera_simplify::simplify`
//! at as many triangles), on every closed mesh of the shared data and on procedural shapes
//! nobody tuned it for, the defaults (the outline's labels, [`ContourRegion::Widened`], a
//! quarter of a cell) are compared with it at equal triangle counts, judged by a
//! rasteriser of the test crate's own (`cargo run --release -p
//! sphaera-eval -- --out docs/charts --only silhouette_vs_simplify`); the nearest
//! camera's labels pop less along an orbit than the mean of the 4 nearest
//! (`--only silhouette_temporal`). The paper's rules reproduced, against the hierarchy's
//! unweighted levels, with the object-space bounds against measured Hausdorff distances:
//! `--only silhouette_error_vs_triangles`. Every figure is in the section *Silhouette
//! labels and level of detail (`sphaera-silhouette`, issue 18)* of `docs/benchmarks.md`
//! in the repository.
//!
//! # Feature flags
#![doc = document_features::document_features!()]
//!
//! # See also
//!
//! `sphaera-simplify` (the hierarchy and the static simplifier the weights feed),
//! `sphaera-sweep` (the certified Hausdorff distance used to check the bounds), and
//! `sphaera silhouette` in the CLI.

mod camera;
mod caps;
mod coverage;
mod distance;
mod error;
mod label_file;
mod labels;
mod lod;
mod picture;
mod raster;
mod views;

pub use camera::ViewCamera;
pub use caps::{MAX_FACE_GRID_ENTRIES, MAX_LABELS, MAX_RESOLUTION, MAX_VIEWS};
/// The old name of [`ViewCamera`] (renamed so that `sphaera-scene`'s `Camera`, the user's
/// perspective camera, is the workspace's only `Camera`).
#[deprecated(since = "0.2.0", note = "renamed `ViewCamera`")]
pub type Camera = ViewCamera;
pub use coverage::{
    bounding_sphere, contour_displacement, contour_displacement_seen, coverage,
    coverage_of_projection, silhouette_difference,
};
pub use distance::DistanceTransform;
pub use error::{LabelFileProblem, SilhouetteError};
pub use label_file::{LABEL_FILE_MAGIC, LABEL_FILE_VERSION, MeshFingerprint};
pub use labels::{
    Contours, Interpolation, LABEL_SCALE, LabelOptions, Labels, ViewLabels, label_view,
};
pub use lod::{ContourRegion, ContourTolerance, Extraction, ViewDependent, contour_weights};
pub use picture::{Picture, overlay_picture, shaded_picture};
pub use raster::FaceGrid;
pub use views::{Projection, ViewSet};

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
