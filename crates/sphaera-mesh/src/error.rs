//! The one error type of `sphaera-mesh`.

use std::path::PathBuf;

/// Everything that can go wrong in `sphaera-mesh`.
///
/// Every variant says what was wrong and where (vertex, triangle, file line or byte offset),
/// so a user can fix the input without a debugger. Messages are lowercase and carry no final
/// period, so they compose into larger messages (`"cannot load bunny.obj: {error}"`).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    // ----------------------------------------------------------------------------------
    // Construction and validation (mesh.rs).
    // ----------------------------------------------------------------------------------
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite {axis} coordinate ({value})")]
    NonFiniteCoordinate {
        /// Index of the offending vertex.
        vertex: usize,
        /// The axis: `'x'`, `'y'` or `'z'`.
        axis: char,
        /// The offending value.
        value: f64,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error(
        "triangle {triangle} refers to vertex {index}, but the mesh has only {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// Index of the offending triangle.
        triangle: usize,
        /// The out-of-range vertex index.
        index: u32,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// More vertices than a `u32` index can address.
    #[error("the mesh has {count} vertices, more than a u32 index can address")]
    TooManyVertices {
        /// Number of vertices supplied.
        count: usize,
    },
    /// The operation needs at least one triangle.
    #[error("the mesh has no triangles")]
    EmptyMesh,
    /// A per-vertex array does not have one entry per vertex.
    #[error("expected {expected} per-vertex values, got {actual}")]
    VertexCountMismatch {
        /// Number of vertices in the mesh.
        expected: usize,
        /// Number of values supplied.
        actual: usize,
    },
    /// A numeric parameter is out of its valid range (NaN, negative, zero where positive
    /// is needed...).
    #[error("parameter `{name}` is {value}, but it must be {requirement}")]
    InvalidParameter {
        /// The parameter's name as it appears in the API.
        name: &'static str,
        /// The value supplied.
        value: f64,
        /// What the value must be, e.g. `"finite and positive"`.
        requirement: &'static str,
    },

    // ----------------------------------------------------------------------------------
    // File input and output (io/).
    // ----------------------------------------------------------------------------------
    /// The operating system refused to read or write a file.
    #[error("cannot access {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },

    // (io/: add file-format variants here)



    // ----------------------------------------------------------------------------------
    // Topology (topology/).
    // ----------------------------------------------------------------------------------

    // (topology/: add variants here)



    // ----------------------------------------------------------------------------------
    // Geometry, inside/outside, sampling and shapes.
    // ----------------------------------------------------------------------------------

    // (geometry/, winding/, sampling.rs, shapes/: add variants here)

    // sampling and shapes
    /// A procedural shape's parameters ask for more vertices than the shape builders allow.
    #[error(
        "the shape `{shape}` would have about {vertices} vertices, more than the limit of {limit}; lower the resolution or make the proportions less extreme"
    )]
    ShapeTooLarge {
        /// The shape's name, e.g. `"torus"`.
        shape: &'static str,
        /// The estimated number of vertices.
        vertices: f64,
        /// The largest number of vertices a shape builder produces.
        limit: usize,
    },
    /// The triangles of a mesh to be sampled have zero total area.
    #[error(
        "the mesh's {triangle_count} triangles have zero total area, so it has no surface to sample"
    )]
    ZeroSurfaceArea {
        /// Number of triangles in the mesh.
        triangle_count: usize,
    },
}
