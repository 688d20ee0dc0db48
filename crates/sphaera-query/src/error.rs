//! The error type of `sphaera-query`: queries that have no meaningful answer for the mesh
//! or point given.

use sphaera_mesh::MeshError;

/// Everything that can go wrong building a spatial query structure or asking it.
///
/// Every variant says what was wrong. Messages are lowercase and carry no final period, so
/// they compose into larger messages.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum QueryError {
    /// The operation needs at least one triangle.
    #[error("the mesh has no triangles")]
    EmptyMesh,
    /// A numeric parameter is out of its valid range (NaN, negative, zero where positive
    /// is needed, more memory than can be reserved...).
    #[error("parameter `{name}` is {value}, but it must be {requirement}")]
    InvalidParameter {
        /// The parameter's name as it appears in the API.
        name: &'static str,
        /// The value supplied.
        value: f64,
        /// What the value must be, e.g. `"finite and positive"`.
        requirement: &'static str,
    },
    /// Positions given to refit a tree do not have one entry per vertex of its mesh.
    #[error("expected {expected} per-vertex values, got {actual}")]
    VertexCountMismatch {
        /// Number of vertices in the mesh.
        expected: usize,
        /// Number of values supplied.
        actual: usize,
    },
    /// More input items than 32-bit indices can address.
    #[error("{operation}: {count} items, more than 32-bit indices can address")]
    TooManyItems {
        /// The operation, e.g. `"box tree"`.
        operation: &'static str,
        /// The number of items given.
        count: usize,
    },
    /// The mesh has more triangles than the winding-number tree's `u32` indices address.
    #[error("the mesh has {count} triangles, more than u32 triangle indices can address")]
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

    /// Inside and outside are meaningless for this mesh as a [`Surface`](crate::Surface)
    /// sees it: too few probes across its surface see the winding number jump from about
    /// 1 inside to about 0 outside (a flat sheet, an open patch, an inside-out mesh).
    #[error(
        "the mesh has no meaningful inside: only {:.0} % of probes across its surface see \
         the winding number jump from 1 to 0 (a flat sheet or open patch?)",
        fraction * 100.0
    )]
    NoInside {
        /// Fraction of probes with a clear jump (at least one half is required).
        fraction: f64,
    },

    /// A query point has a NaN or infinite coordinate.
    #[error("the query point ({x}, {y}, {z}) is not finite")]
    NonFiniteQuery {
        /// The x coordinate given.
        x: f64,
        /// The y coordinate given.
        y: f64,
        /// The z coordinate given.
        z: f64,
    },
    /// The triangles of a mesh to be sampled have zero total area.
    #[error(
        "the mesh's {triangle_count} triangles have zero total area, so it has no surface to sample"
    )]
    ZeroSurfaceArea {
        /// Number of triangles in the mesh.
        triangle_count: usize,
    },
    /// The mesh is not a valid mesh (a failure of `sphaera-mesh`).
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

impl QueryError {
    /// `Ok(p)` for a finite query point, else [`QueryError::NonFiniteQuery`] naming it.
    pub(crate) fn check_query(p: glam::DVec3) -> Result<glam::DVec3, Self> {
        if p.is_finite() {
            Ok(p)
        } else {
            Err(Self::NonFiniteQuery {
                x: p.x,
                y: p.y,
                z: p.z,
            })
        }
    }
}
