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
    // winding
    /// The mesh has more triangles than a `u32` index can address.
    #[error("the mesh has {count} triangles, more than a u32 index can address")]
    TooManyTriangles {
        /// Number of triangles supplied.
        count: usize,
    },
    /// Inside/outside is not meaningful: the mesh does not enclose a volume (for example a
    /// lone open sheet), as measured by `winding::WindingNumber::check_solid`.
    #[error(
        "the mesh does not enclose a volume: the largest |winding number| next to its surface is {max_abs_winding:.3}, below {threshold} (is it an open sheet?)"
    )]
    NotSolid {
        /// The largest `|w|` found at the probe points next to the surface (about ½ for a
        /// sheet, 1 for a solid).
        max_abs_winding: f64,
        /// The smallest value accepted.
        threshold: f64,
    },
    /// The mesh encloses a volume but its triangles face inward, so the winding number is
    /// −1 inside and every point reads as outside.
    #[error(
        "the mesh is oriented inward: the median winding number just behind its triangles is {median_inner_winding:.3} instead of about 1 (flip the triangles)"
    )]
    InwardOrientation {
        /// The median winding number just behind the probe triangles (about 0 when every
        /// triangle faces inward).
        median_inner_winding: f64,
    },
}
