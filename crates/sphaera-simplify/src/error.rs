//! The error type of `sphaera-simplify`.

use sphaera_mesh::MeshError;

/// Everything that can go wrong when simplifying.
///
/// Messages are lowercase without a final period, so they compose into larger messages.
///
/// # Examples
///
/// ```
/// use sphaera_simplify::SimplifyError;
///
/// let error = SimplifyError::InvalidParameter {
///     name: "target_ratio",
///     value: 1.5,
///     requirement: "in (0, 1]",
/// };
/// assert_eq!(error.to_string(), "invalid `target_ratio` (1.5): must be in (0, 1]");
/// assert_eq!(SimplifyError::EmptyMesh.to_string(), "the input mesh has no triangles");
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimplifyError {
    /// The input mesh has no triangles, so there is nothing to simplify.
    #[error("the input mesh has no triangles")]
    EmptyMesh,
    /// A builder parameter is out of its domain (NaN, negative, or out of range).
    #[error("invalid `{name}` ({value}): must be {requirement}")]
    InvalidParameter {
        /// The parameter's name as it appears in the API, e.g. `"target_ratio"`.
        name: &'static str,
        /// The value supplied.
        value: f64,
        /// What the value must be, e.g. `"in (0, 1]"`.
        requirement: &'static str,
    },
    /// A refinement was asked to split a vertex that is not in its current mesh (removed,
    /// or out of range).
    #[error("vertex {vertex} is not in the current mesh (removed or out of range)")]
    VertexNotPresent {
        /// The vertex asked for.
        vertex: u32,
    },
    /// Every per-vertex tolerance weight is 0, so no vertex may move and nothing can be
    /// simplified.
    #[error("every tolerance weight is 0: no region may move, so nothing can be simplified")]
    AllWeightsZero,
    /// A per-vertex array has the wrong length.
    #[error("`{name}` has {actual} entries, expected {expected} (one per input vertex)")]
    LengthMismatch {
        /// The parameter's name, e.g. `"weights"`.
        name: &'static str,
        /// Its length.
        actual: usize,
        /// The input's vertex count.
        expected: usize,
    },
    /// A per-vertex value is NaN, infinite or negative.
    #[error("`{name}`[{index}] = {value}: must be {requirement}")]
    InvalidVertexValue {
        /// The parameter's name, e.g. `"weights"`.
        name: &'static str,
        /// The input vertex.
        index: usize,
        /// The value given.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// A deformation method was called on a hierarchy built with
    /// [`Placement::Optimal`](crate::Placement::Optimal), whose placed vertices have no
    /// displacement or replay rule of their own.
    #[error("`{operation}` needs a hierarchy built with subset placement")]
    NeedsSubsetPlacement {
        /// The method called, e.g. `"replay"`.
        operation: &'static str,
    },
    /// An internal consistency check failed: a bug in this crate, reported instead of a
    /// panic. Please report it with the input that triggers it.
    #[error("internal error: {what}")]
    Internal {
        /// What was inconsistent.
        what: &'static str,
    },
    /// An error of the underlying mesh crate (building or editing the half-edge mesh).
    #[error("mesh error: {0}")]
    Mesh(#[from] MeshError),
}
