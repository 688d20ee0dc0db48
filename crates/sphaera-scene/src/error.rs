//! Errors of object models, scenes, cameras, tolerances and scene files.

use std::path::PathBuf;

/// Why a model, a scene or a scene file could not be made or used.
///
/// Messages are lowercase without a final period, so they compose into larger messages.
///
/// # Examples
///
/// ```
/// use sphaera_scene::{SceneError, Tolerance};
///
/// let error = "-2px".parse::<Tolerance>().unwrap_err();
/// assert!(matches!(error, SceneError::InvalidTolerance { .. }));
/// assert_eq!(
///     error.to_string(),
///     "invalid tolerance `-2px`: must be a non-negative number of world units (`0.01`), a percentage of each object's diagonal (`0.5%`) or pixels (`2px`)"
/// );
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// A mesh is empty or invalid, or a pose is not a similarity.
    #[error(transparent)]
    Mesh(#[from] sphaera_mesh::MeshError),
    /// A mesh file named in a scene could not be read.
    #[error(transparent)]
    File(#[from] sphaera_io::IoError),
    /// A model's surface has no meaningful inside, or a query parameter is out of range.
    #[error(transparent)]
    Query(#[from] sphaera_query::QueryError),
    /// A model's simplification hierarchy could not be built.
    #[error(transparent)]
    Simplify(#[from] sphaera_simplify::SimplifyError),
    /// A model's sphere-tree could not be built, or a collision budget is invalid.
    #[error(transparent)]
    SphereTree(#[from] sphaera_spheretree::SphereTreeError),
    /// A silhouette-aware extraction failed.
    #[cfg(feature = "silhouette")]
    #[error(transparent)]
    Silhouette(#[from] sphaera_silhouette::SilhouetteError),
    /// A model has no silhouette labels (they could not be computed with its options).
    #[cfg(feature = "silhouette")]
    #[error("model `{model}` has no silhouette labels: {reason}")]
    NoSilhouetteLabels {
        /// The model's name.
        model: String,
        /// Why the labelling failed.
        reason: String,
    },
    /// Silhouette labels given to a model (`ObjectModel::with_silhouette_labels`, a scene
    /// file's `labels`) that it cannot use: they belong to another mesh, or were computed
    /// with other settings than its `ModelOptions::silhouette`.
    #[cfg(feature = "silhouette")]
    #[error("model `{model}`: its silhouette labels cannot be used: {source}")]
    SilhouetteLabels {
        /// The model's name.
        model: String,
        /// Why (boxed: it keeps the error small).
        source: Box<sphaera_silhouette::SilhouetteError>,
    },
    /// A tolerance is NaN, negative, infinite or does not parse.
    #[error(
        "invalid tolerance `{text}`: must be a non-negative number of world units (`0.01`), a percentage of each object's diagonal (`0.5%`) or pixels (`2px`)"
    )]
    InvalidTolerance {
        /// The tolerance as given.
        text: String,
    },
    /// A detail request needs a tolerance below the model's finest
    /// ([`ModelOptions::finest_tolerance`](crate::ModelOptions::finest_tolerance)) that no
    /// tree of the model meets.
    #[error(
        "model `{model}`: the tolerance {tolerance:.4e} ({:.4} % of its diagonal {diagonal:.4e}) is below its finest, {finest:.4e} ({:.4} %); lower the finest tolerance (`ModelOptions::finest_tolerance`, `sphaera scene --finest`) to build trees that fine",
        100.0 * .tolerance / .diagonal,
        100.0 * .finest / .diagonal
    )]
    ToleranceBelowFinest {
        /// The model's name.
        model: String,
        /// The tolerance needed, in the model's units.
        tolerance: f64,
        /// The finest tolerance it builds trees to, in the model's units.
        finest: f64,
        /// The model's bounding-box diagonal.
        diagonal: f64,
    },
    /// A model could not build a sphere-tree to a tolerance: the tolerance is out of
    /// reach ([`sphaera_spheretree::SphereTreeError::ToleranceUnreachable`], which gives
    /// the figures: the worst leaf error reached, the spheres and levels built, the
    /// limits) or the tolerance trees' options are invalid.
    #[error(
        "model `{model}`: the tolerance {tolerance:.4e} ({:.4} % of its diagonal {diagonal:.4e}) cannot be met: {reason}",
        100.0 * .tolerance / .diagonal
    )]
    ToleranceTree {
        /// The model's name.
        model: String,
        /// The tolerance needed, in the model's units.
        tolerance: f64,
        /// The model's bounding-box diagonal.
        diagonal: f64,
        /// Why the tree could not be built (shared: a tolerance found out of reach is
        /// remembered, and finer requests fail with the same reason).
        reason: std::sync::Arc<sphaera_spheretree::SphereTreeError>,
    },
    /// A tolerance in pixels was asked for without a camera.
    #[error("a tolerance in pixels needs a camera")]
    NoCamera,
    /// A camera parameter is out of its domain.
    #[error("invalid camera: `{name}` ({value}) must be {requirement}")]
    InvalidCamera {
        /// The parameter, e.g. `"fov_y_degrees"`.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// An option is out of its domain, e.g. a silhouette-aware interior multiple below 1.
    #[error("invalid option: `{name}` ({value}) must be {requirement}")]
    InvalidOption {
        /// The option, e.g. `"interior"`.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// An instance names a model the scene does not hold, or an index is out of range.
    #[error("instance {index} is out of range (the scene has {count})")]
    NoSuchInstance {
        /// The index asked for.
        index: usize,
        /// The number of instances.
        count: usize,
    },
    /// A scene file could not be read, or the file policy refuses it.
    #[error("cannot read the scene file {}: {source}", path.display())]
    ReadFile {
        /// The scene file.
        path: PathBuf,
        /// Why: the operating system's error, or the policy's refusal.
        source: Box<sphaera_io::IoError>,
    },
    /// A scene file is not valid JSON of the scene schema (an unknown key, a missing
    /// field, a wrong type); the message names the line and column.
    #[error("{}: {message}", path.display())]
    ParseFile {
        /// The scene file.
        path: PathBuf,
        /// What is wrong and where (from the JSON reader).
        message: String,
    },
    /// An entry of a scene file is well-formed JSON but meaningless (a NaN position, a
    /// zero scale, an undefined mesh name, a mesh file that cannot be loaded).
    #[error("{}: {place}: {message}", path.display())]
    InvalidEntry {
        /// The scene file.
        path: PathBuf,
        /// The entry, e.g. `instances[3] ("bunny-2")` or `meshes.bunny`.
        place: String,
        /// What is wrong with it.
        message: String,
    },
}
