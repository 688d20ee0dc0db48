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

    /// A mesh file (or byte buffer) is malformed: the data do not follow the format, or they
    /// describe invalid geometry (a NaN coordinate, an index out of range, a face with fewer
    /// than three vertices).
    ///
    /// `location` is a 1-based line for text formats and a 0-based byte offset for binary
    /// ones; `reason` is a structured [`crate::io::ParseReason`].
    #[error(
        "malformed {format} data{} at {location}: {reason}",
        crate::io::describe_path(path.as_deref())
    )]
    Parse {
        /// The file, when the data came from one ([`crate::io::read`] fills it in).
        path: Option<PathBuf>,
        /// The format the data were parsed as.
        format: crate::io::Format,
        /// Where in the data the problem is.
        location: crate::io::Location,
        /// What is wrong.
        reason: crate::io::ParseReason,
    },
    /// The mesh format of a file could not be determined: its extension is not one of
    /// `obj`, `ply`, `stl`, `off` (in any case), and its content does not look like any of
    /// them.
    #[error(
        "cannot tell the mesh format{}: the extension is not obj, ply, stl or off and the content is not recognised",
        crate::io::describe_path(path.as_deref())
    )]
    UnknownFormat {
        /// The file, when the data came from one.
        path: Option<PathBuf>,
    },
    /// Writing this format is not supported (only OBJ and PLY are written).
    #[error("writing {format} files is not supported (write obj or ply instead)")]
    UnsupportedWriteFormat {
        /// The requested format.
        format: crate::io::Format,
    },



    // ----------------------------------------------------------------------------------
    // Topology (topology/).
    // ----------------------------------------------------------------------------------

    // (topology/: add variants here)



    // ----------------------------------------------------------------------------------
    // Geometry, inside/outside, sampling and shapes.
    // ----------------------------------------------------------------------------------

    // (geometry/, winding/, sampling.rs, shapes/: add variants here)
}
