//! Errors of the silhouette labels.

use thiserror::Error;

/// What can go wrong computing or using silhouette labels.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SilhouetteError {
    /// The angular step of a regular view set is not in `(0°, 90°]`, or does not divide
    /// 180°.
    #[error("a view step must divide 180° and lie in (0°, 90°], got {degrees}°")]
    InvalidStep {
        /// The step asked for, in degrees.
        degrees: f64,
    },
    /// A grid needs at least one cell a side.
    #[error("the label grid needs a resolution of at least 1 cell, got {resolution}")]
    InvalidResolution {
        /// The resolution asked for.
        resolution: usize,
    },
    /// A perspective camera must be outside the mesh's bounding sphere.
    #[error(
        "a perspective camera at {distance} bounding radii is inside the bounding sphere: it must be farther than 1"
    )]
    CameraInside {
        /// The camera's distance from the centre, in bounding radii.
        distance: f64,
    },
    /// A view direction of zero length or with NaN.
    #[error("a view direction must be finite and non-zero, got {direction:?}")]
    InvalidDirection {
        /// The direction given.
        direction: [f64; 3],
    },
    /// Labels asked for a mesh without triangles.
    #[error("the mesh has no triangles: nothing to label")]
    EmptyMesh,
    /// Labels and a hierarchy of different meshes.
    #[error("the labels are for {labels} vertices, the hierarchy's mesh has {hierarchy}")]
    MeshMismatch {
        /// Vertices the labels were computed for.
        labels: usize,
        /// Input vertices of the hierarchy.
        hierarchy: usize,
    },
    /// A hierarchy whose vertices are not the input's (full-edge placement moves them, so
    /// labels computed on the input no longer apply).
    #[error("the hierarchy must use Placement::Subset, so that its vertices keep their labels")]
    NotSubset,
    /// An allowed error that is negative or not finite, a factor outside `[0, 1]`, a NaN
    /// threshold or a non-positive scale; a parameter that sizes memory beyond its cap (a
    /// view step below 1.40625°, a resolution above [`MAX_RESOLUTION`](crate::MAX_RESOLUTION),
    /// more labels than [`MAX_LABELS`](crate::MAX_LABELS), more face–cell pairs than
    /// [`MAX_FACE_GRID_ENTRIES`](crate::MAX_FACE_GRID_ENTRIES)), with `requirement` naming
    /// the cap.
    #[error("{name} must be {requirement}, got {value}")]
    InvalidParameter {
        /// Which parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// Per-vertex values for a picture of another mesh.
    #[error("{values} values for a mesh of {vertices} vertices: one value per vertex")]
    ValueCountMismatch {
        /// Values given.
        values: usize,
        /// Vertices of the mesh.
        vertices: usize,
    },
    /// An error from the simplification hierarchy.
    #[error(transparent)]
    Simplify(#[from] sphaera_simplify::SimplifyError),
    /// Interpolation over zero views, or more views than the set has.
    #[error("cannot average the labels of {asked} nearest views out of {available}")]
    InvalidNearest {
        /// How many views were asked for.
        asked: usize,
        /// How many the set has.
        available: usize,
    },
}
