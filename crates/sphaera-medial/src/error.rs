//! Errors of the tetrahedralization and of the medial approximation.

/// Why a Delaunay tetrahedralization could not be built or changed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DelaunayError {
    /// A point has a NaN or infinite coordinate.
    #[error("point {index} has a NaN or infinite coordinate")]
    NonFinite {
        /// Index of the point (for `insert`, the id it would have had).
        index: usize,
    },
    /// Fewer than four distinct points: no tetrahedron exists.
    #[error("a tetrahedralization needs at least 4 distinct points, got {distinct}")]
    TooFewPoints {
        /// The number of distinct points.
        distinct: usize,
    },
    /// All points lie on one plane (dimension 2), line (1) or point (0).
    #[error("all points lie in a {dimension}-dimensional flat: nothing to tetrahedralize")]
    Flat {
        /// The dimension of the affine hull of the points.
        dimension: usize,
    },
    /// More points than 32-bit vertex ids can name.
    #[error("{count} points: more than 32-bit vertex ids can name")]
    TooManyPoints {
        /// The number of points.
        count: usize,
    },
    /// [`Delaunay::validate`](crate::Delaunay::validate) found a broken invariant (a bug:
    /// please report it with the input).
    #[error("invalid tetrahedralization: {0}")]
    Invalid(String),
}

/// Why a medial approximation could not be built or refined.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MedialError {
    /// The mesh is empty or invalid.
    #[error(transparent)]
    Mesh(#[from] sphaera_mesh::MeshError),
    /// A surface sample has a NaN or infinite coordinate.
    #[error("surface sample {index} has a NaN or infinite coordinate")]
    NonFiniteSample {
        /// Index of the sample.
        index: usize,
    },
    /// Too few distinct surface samples for a tetrahedralization.
    #[error("the medial approximation needs at least 4 distinct, non-coplanar samples: {0}")]
    TooFewSamples(DelaunayError),
    /// A parameter is out of range.
    #[error("invalid parameter: {0}")]
    InvalidParameter(String),
    /// A region refers to a sample that does not exist.
    #[error("region sample {index} is out of range ({count} samples)")]
    RegionOutOfRange {
        /// The bad index.
        index: u32,
        /// The number of samples.
        count: usize,
    },
}
