//! Errors of the silhouette labels.

use std::path::PathBuf;

use thiserror::Error;

use crate::MeshFingerprint;

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
    /// A label file that cannot be opened, read, written or used: `problem` says why
    /// (`<stream>` stands for `path` when the labels came from a reader or went to a
    /// writer rather than a file).
    #[error("label file {}: {problem}", path.display())]
    LabelFile {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        #[source]
        problem: LabelFileProblem,
    },
    /// Labels used with, or written for, a mesh other than the one they were computed
    /// for (other counts, or the same counts and other positions or triangles).
    #[error("{}", other_mesh("the labels belong", labels, mesh))]
    LabelsOfOtherMesh {
        /// The mesh the labels were computed for.
        labels: MeshFingerprint,
        /// The mesh given.
        mesh: MeshFingerprint,
    },
    /// Labels computed with other settings than the ones asked for (the view step, the
    /// projection, the resolution, the distance transform or the contours).
    #[error("the labels were computed with {setting} {labels}, not {asked}")]
    LabelSettingsMismatch {
        /// Which setting: `"step"`, `"projection"`, `"resolution"`, `"transform"` or
        /// `"contours"`.
        setting: &'static str,
        /// The labels' value, as users type it (`"30°"`, `"orthographic"`, `"128"`, …).
        labels: String,
        /// The value asked for.
        asked: String,
    },
    /// Interpolation over zero views, or more views than the set has.
    #[error("cannot average the labels of {asked} nearest views out of {available}")]
    InvalidNearest {
        /// How many views were asked for.
        asked: usize,
        /// How many the set has.
        available: usize,
    },
}

/// Why a label file cannot be read, written or used (in [`SilhouetteError::LabelFile`]).
///
/// The file's layout is in the documentation of
/// [`Labels::write_to`](crate::Labels::write_to).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LabelFileProblem {
    /// The file does not start with the label files' magic bytes.
    #[error("it is not a sphaera label file (it does not start with `SPHLABEL`)")]
    NotLabelFile,
    /// A format version this library does not read.
    #[error(
        "it is label file version {found}, and this library reads version {supported} only: \
         compute the labels again"
    )]
    UnsupportedVersion {
        /// The file's version.
        found: u32,
        /// The version this library reads and writes ([`LABEL_FILE_VERSION`](crate::LABEL_FILE_VERSION)).
        supported: u32,
    },
    /// The file ends before what its header announces.
    #[error("it is truncated: it ends after {found} bytes, {needed} needed")]
    Truncated {
        /// Bytes the file has.
        found: u64,
        /// Bytes needed: the header, or everything the header announces.
        needed: u64,
    },
    /// The file goes on after what its header announces.
    #[error("it has bytes after the {expected} its header announces")]
    TrailingBytes {
        /// Bytes the header announces.
        expected: u64,
    },
    /// A checksum does not match: the file was damaged.
    #[error(
        "its {part} checksum does not match (stored {stored:016x}, computed {computed:016x}): \
         the file is damaged"
    )]
    Checksum {
        /// `"header"` or `"file"`.
        part: &'static str,
        /// The checksum in the file.
        stored: u64,
        /// The checksum of the bytes read.
        computed: u64,
    },
    /// The header holds a value this library refuses: an unknown code, a view step,
    /// resolution or perspective distance labels cannot have, or counts beyond
    /// [`MAX_VIEWS`](crate::MAX_VIEWS), [`MAX_RESOLUTION`](crate::MAX_RESOLUTION) or
    /// [`MAX_LABELS`](crate::MAX_LABELS) (checked before anything is allocated).
    #[error("its header is invalid: {source}")]
    Header {
        /// What is wrong with the value.
        source: Box<SilhouetteError>,
    },
    /// The file holds the labels of another mesh.
    #[error("{}", other_mesh("it belongs", labels, mesh))]
    OtherMesh {
        /// The mesh the file's labels were computed for.
        labels: MeshFingerprint,
        /// The mesh given.
        mesh: MeshFingerprint,
    },
    /// The file policy refuses the file: it is not a regular file (a folder, a device, a
    /// pipe), lies outside the allowed folder, or is larger than the cap.
    #[error("{refusal}")]
    Refused {
        /// Why.
        #[source]
        refusal: sphaera_io::FileRefusal,
    },
    /// Opening, reading or writing failed (the file does not exist, a folder is missing,
    /// the disk is full, the reader or writer failed).
    #[error("{source}")]
    Io {
        /// The operating system's error.
        source: std::io::Error,
    },
}

impl LabelFileProblem {
    /// The problem of an error of the file policy or the atomic write.
    pub(crate) fn from_io(error: sphaera_io::IoError) -> Self {
        match error {
            sphaera_io::IoError::Refused { refusal, .. } => Self::Refused { refusal },
            sphaera_io::IoError::Io { source, .. } => Self::Io { source },
            other => Self::Io {
                source: std::io::Error::other(other),
            },
        }
    }
}

/// The message for labels of another mesh: the counts when they differ, else the
/// fingerprints.
fn other_mesh(subject: &str, labels: &MeshFingerprint, mesh: &MeshFingerprint) -> String {
    if (labels.vertices, labels.triangles) == (mesh.vertices, mesh.triangles) {
        format!(
            "{subject} to another mesh: the same counts ({} vertices, {} triangles) but other \
             positions or triangles (fingerprint {:032x}, the mesh's {:032x})",
            labels.vertices,
            labels.triangles,
            labels.hash(),
            mesh.hash()
        )
    } else {
        format!(
            "{subject} to another mesh: labels of {} vertices and {} triangles, the mesh has {} \
             vertices and {} triangles",
            labels.vertices, labels.triangles, mesh.vertices, mesh.triangles
        )
    }
}
