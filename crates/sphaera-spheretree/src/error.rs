//! Errors of sphere-tree construction, evaluation and file formats.

/// Why a sphere-tree could not be built, evaluated, read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SphereTreeError {
    /// The mesh is empty or invalid.
    #[error(transparent)]
    Mesh(#[from] sphaera_mesh::MeshError),
    /// The medial approximation failed (no inside, too few samples, ...).
    #[error(transparent)]
    Medial(#[from] sphaera_medial::MedialError),
    /// A parameter is out of its domain.
    #[error("invalid parameter: {0}")]
    InvalidParameter(String),
    /// A sphere has a NaN or infinite centre or radius, or a negative radius.
    #[error("sphere {index} is not a valid sphere (NaN, infinite or negative radius)")]
    InvalidSphere {
        /// Index of the sphere in the input.
        index: usize,
    },
    /// A sphere-tree file could not be parsed.
    #[error("line {line}: {message}")]
    Format {
        /// 1-based line number.
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// An evaluation was asked for a set without spheres (its error and coverage would be
    /// meaningless).
    #[error("the sphere set is empty")]
    EmptySphereSet,
    /// A sphere-tree read from a file is inconsistent (levels, parents and children that
    /// do not match, a wrong format tag or version).
    #[error("invalid sphere-tree: {0}")]
    InvalidTree(String),
}
