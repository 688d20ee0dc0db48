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
    Invalid(Violation),
}

/// The first broken invariant [`Delaunay::validate`](crate::Delaunay::validate) found, in
/// [`DelaunayError::Invalid`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Violation {
    /// A tetrahedron has a repeated vertex or more than one infinite vertex.
    #[error("tetrahedron {tetrahedron} has vertices {vertices:?}")]
    BadVertices {
        /// The tetrahedron.
        tetrahedron: u32,
        /// Its vertices.
        vertices: [u32; 4],
    },
    /// A finite tetrahedron is flat or negatively oriented.
    #[error("tetrahedron {tetrahedron} {vertices:?} is not positive")]
    NotPositive {
        /// The tetrahedron.
        tetrahedron: u32,
        /// Its vertices.
        vertices: [u32; 4],
    },
    /// A tetrahedron lacks a live neighbour across a face.
    #[error("tetrahedron {tetrahedron} has no live neighbour {face}")]
    MissingNeighbour {
        /// The tetrahedron.
        tetrahedron: u32,
        /// The face (opposite vertex `face`).
        face: usize,
    },
    /// Two tetrahedra do not list each other exactly once.
    #[error("neighbours {tetrahedron} and {neighbour} are not symmetric")]
    AsymmetricNeighbours {
        /// The tetrahedron.
        tetrahedron: u32,
        /// Its neighbour.
        neighbour: u32,
    },
    /// Neighbours do not share the face between them.
    #[error("tetrahedra {tetrahedron} and {neighbour} do not share a face")]
    NoSharedFace {
        /// The tetrahedron.
        tetrahedron: u32,
        /// Its neighbour.
        neighbour: u32,
    },
    /// A face is not locally Delaunay: the neighbour's apex conflicts.
    #[error("face between {tetrahedron} and {neighbour} is not locally Delaunay (vertex {apex})")]
    NotLocallyDelaunay {
        /// The tetrahedron.
        tetrahedron: u32,
        /// Its neighbour.
        neighbour: u32,
        /// The neighbour's vertex opposite the shared face.
        apex: u32,
    },
    /// A vertex's duplicate flag and its incident tetrahedron disagree.
    #[error("vertex {vertex}: duplicate flag and incidence disagree")]
    DuplicateIncidence {
        /// The vertex.
        vertex: usize,
    },
    /// A vertex's incident tetrahedron does not contain it.
    #[error("vertex {vertex} points at tetrahedron {tetrahedron} without it")]
    WrongIncidence {
        /// The vertex.
        vertex: usize,
        /// The tetrahedron it points at.
        tetrahedron: u32,
    },
}

/// Why a medial approximation could not be built or refined.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MedialError {
    /// The mesh is empty or invalid.
    #[error(transparent)]
    Mesh(#[from] sphaera_mesh::MeshError),
    /// The surface has no meaningful inside, or a sampling or query parameter is out of
    /// range.
    #[error(transparent)]
    Query(#[from] sphaera_query::QueryError),
    /// A surface sample has a NaN or infinite coordinate.
    #[error("surface sample {index} has a NaN or infinite coordinate")]
    NonFiniteSample {
        /// Index of the sample.
        index: usize,
    },
    /// Too few distinct surface samples for a tetrahedralization.
    #[error("the medial approximation needs at least 4 distinct, non-coplanar samples: {0}")]
    TooFewSamples(DelaunayError),
    /// A numeric parameter is out of its domain (NaN, negative, too small).
    #[error("invalid `{name}` ({value}): must be {requirement}")]
    InvalidParameter {
        /// The parameter's name as it appears in the API, e.g. `"max_error"`.
        name: &'static str,
        /// The value supplied.
        value: f64,
        /// What the value must be, e.g. `"a non-negative number"`.
        requirement: &'static str,
    },
    /// More samples than 32-bit sample ids can name.
    #[error("{count} samples: more than 32-bit ids can name")]
    TooManySamples {
        /// The number of samples given.
        count: usize,
    },
    /// A region refers to a sample that does not exist.
    #[error("region sample {index} is out of range ({count} samples)")]
    RegionOutOfRange {
        /// The bad index.
        index: u32,
        /// The number of samples.
        count: usize,
    },
}
