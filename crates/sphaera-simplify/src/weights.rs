//! Per-vertex tolerance weights: how much of the error bound a region may use.

use sphaera_mesh::TriMesh;
use sphaera_mesh::topology::{HalfEdgeMesh, VertexId};

use crate::SimplifyError;

/// Validated weights, indexed by half-edge-mesh vertex (copies of a non-manifold vertex
/// share their source's weight).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Weights(Vec<f64>);

impl Weights {
    /// Checks `weights` against `mesh` (one finite non-negative value per vertex, not all
    /// 0 among the vertices triangles use).
    pub fn validate(mesh: &TriMesh, weights: &[f64]) -> Result<(), SimplifyError> {
        if weights.len() != mesh.vertex_count() {
            return Err(SimplifyError::LengthMismatch {
                name: "weights",
                actual: weights.len(),
                expected: mesh.vertex_count(),
            });
        }
        if let Some((index, &value)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !(w.is_finite() && **w >= 0.0))
        {
            return Err(SimplifyError::InvalidVertexValue {
                name: "weights",
                index,
                value,
                requirement: "finite and non-negative",
            });
        }
        let used_positive = mesh
            .triangles()
            .iter()
            .flatten()
            .any(|&v| weights.get(v as usize).is_some_and(|&w| w > 0.0));
        if used_positive {
            Ok(())
        } else {
            Err(SimplifyError::AllWeightsZero)
        }
    }

    /// The weights of `half_edges`' vertices from validated input weights.
    pub fn for_mesh(half_edges: &HalfEdgeMesh, weights: &[f64]) -> Self {
        Self(
            (0..half_edges.vertex_count() as u32)
                .map(|v| {
                    let source = half_edges.original_vertex(VertexId(v));
                    weights.get(source as usize).copied().unwrap_or(1.0)
                })
                .collect(),
        )
    }

    /// The weight of every collapse out of `u`: the smallest weight over `u` and its
    /// neighbours (every vertex of the region that changes, the parent included). 0 means
    /// the collapse is forbidden.
    pub fn of_vertex(&self, mesh: &HalfEdgeMesh, u: VertexId) -> f64 {
        let w = |x: VertexId| self.0.get(x.0 as usize).copied().unwrap_or(1.0);
        mesh.neighbors(u).fold(w(u), |m, x| m.min(w(x)))
    }
}
