//! The error type of `sphaera-mesh`: invalid meshes and parameters, topology edits,
//! geometric constructions and shapes.

/// Everything that can go wrong in `sphaera-mesh` (reading and writing files fail with
/// `sphaera-io`'s `IoError`, spatial queries with `sphaera-query`'s `QueryError`, both of
/// which wrap this type).
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
    // Topology (topology/).
    // ----------------------------------------------------------------------------------
    /// A half-edge, vertex or face handle does not exist in this half-edge mesh, or
    /// refers to an element that a collapse deleted.
    #[error("{kind} {index} does not exist or was deleted")]
    InvalidHandle {
        /// What the handle names: `"half-edge"`, `"vertex"` or `"face"`.
        kind: &'static str,
        /// The handle's index.
        index: u32,
    },
    /// An edge collapse was refused because it would break the mesh (see
    /// [`crate::topology::CollapseRefusal`] for each reason and what to do).
    #[error("cannot collapse half-edge {halfedge} (vertex {from} into vertex {to}): {reason}")]
    CollapseRefused {
        /// The half-edge that was to be collapsed.
        halfedge: u32,
        /// Its origin, the vertex that would be removed.
        from: u32,
        /// Its target, the vertex that would be kept.
        to: u32,
        /// Why the collapse is not allowed.
        reason: crate::topology::CollapseRefusal,
    },
    /// A vertex split was given a collapse record that does not match the mesh: a record
    /// from another mesh, one already split, or one whose neighbourhood a later collapse
    /// still changes (split that one first; the reverse collapse order always works).
    #[error(
        "the collapse record of vertex {removed} into vertex {kept} does not match the mesh (already split, from another mesh, or its neighbourhood was changed by a later collapse that must be split first)"
    )]
    SplitMismatch {
        /// The vertex the record's collapse removed.
        removed: u32,
        /// The vertex the record's collapse kept.
        kept: u32,
    },

    // ----------------------------------------------------------------------------------
    // Geometry (geometry/).
    // ----------------------------------------------------------------------------------
    /// A geometric construction got no input items (points or balls).
    #[error("{operation} needs at least one input item, got none")]
    EmptyInput {
        /// The operation, e.g. `"minimum enclosing ball of points"`.
        operation: &'static str,
    },
    /// An input point or ball centre has a NaN or infinite coordinate.
    #[error("{operation}: input item {index} has a non-finite coordinate")]
    NonFiniteInput {
        /// The operation, e.g. `"minimum enclosing ball of points"`.
        operation: &'static str,
        /// Index of the offending item in the input slice.
        index: usize,
    },
    /// More input items than 32-bit indices can address.
    #[error("{operation}: {count} items, more than 32-bit indices can address")]
    TooManyItems {
        /// The operation, e.g. `"box tree"`.
        operation: &'static str,
        /// The number of items given.
        count: usize,
    },
    /// An input ball has a negative, NaN or infinite radius.
    #[error(
        "{operation}: ball {index} has radius {radius}, but it must be finite and non-negative"
    )]
    InvalidRadius {
        /// The operation, e.g. `"minimum enclosing ball of balls"`.
        operation: &'static str,
        /// Index of the offending ball in the input slice.
        index: usize,
        /// The radius supplied.
        radius: f64,
    },

    /// An affine map given to place a mesh or spheres is not a similarity (or not rigid,
    /// where a rigid motion is needed).
    #[error("invalid transform: {0}")]
    InvalidTransform(crate::geometry::TransformDefect),

    /// The mesh has more triangles than `u32` half-edge indices can address (three
    /// half-edges per triangle: at most 1,431,655,764 triangles).
    #[error(
        "the mesh has {count} triangles, more than the 1,431,655,764 that u32 half-edge indices can address"
    )]
    TooManyTriangles {
        /// Number of triangles supplied.
        count: usize,
    },

    // ----------------------------------------------------------------------------------
    // Shapes (shapes/).
    // ----------------------------------------------------------------------------------
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
}
