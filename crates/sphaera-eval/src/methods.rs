//! The simplification methods compared by the `simplify_error_vs_time` experiment and the
//! `simplify_vs_meshopt` bench, so both measure exactly the same calls.
//!
//! - **Sphaera**: [`simplify`] with each placement of [`PLACEMENTS`], boundary locked (the
//!   default), stopped by a triangle count only.
//! - **meshopt** 0.7.0 (meshoptimizer's `meshopt_simplify`): positions converted to `f32`
//!   once, before timing; target index count `3 × triangles`, target error `f32::MAX` so
//!   that only the count stops it, and [`MESHOPT_OPTIONS`] = `LockBorder`, the constraint
//!   Sphaera's default applies (its boundary vertices are never removed). Its output index
//!   buffer refers to the input vertex array (no vertex is moved), so its surface is
//!   measured with the original `f64` positions.

use anyhow::{Context, Result};
use meshopt::VertexDataAdapter;
use sphaera::{
    mesh::TriMesh,
    simplify::{Placement, Simplified, SimplifyOptions, simplify},
};

/// Every placement measured, with its name in tables and charts. Adding a placement to the
/// experiment and the bench is one line here.
pub const PLACEMENTS: &[(&str, Placement)] = &[
    ("subset", Placement::Subset),
    ("optimal", Placement::Optimal),
];

/// meshopt's options: lock the topological border, as Sphaera does by default.
pub const MESHOPT_OPTIONS: meshopt::SimplifyOptions = meshopt::SimplifyOptions::LockBorder;

/// The triangle target of a ratio: `ceil(ratio × triangles)`, what
/// [`SimplifyOptions::target_ratio`] aims at, used for both methods.
pub fn target_triangles(mesh: &TriMesh, ratio: f64) -> usize {
    // A ratio in (0, 1] of a count below 2^53 is exact enough in f64.
    (ratio * mesh.triangle_count() as f64).ceil() as usize
}

/// Sphaera's simplification of `mesh` to `triangles`, with `placement`.
pub fn sphaera_simplify(
    mesh: &TriMesh,
    placement: Placement,
    triangles: usize,
) -> Result<Simplified> {
    simplify(
        mesh,
        &SimplifyOptions::default()
            .with_placement(placement)
            .with_target_triangles(triangles),
    )
    .context("Sphaera's simplifier failed")
}

/// A mesh in meshopt's input format: `f32` positions and a flat index buffer.
pub struct MeshoptInput {
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
}

impl MeshoptInput {
    /// Converts `mesh` (positions rounded to `f32`).
    pub fn new(mesh: &TriMesh) -> Self {
        Self {
            positions: mesh
                .positions()
                .iter()
                .map(|p| p.as_vec3().to_array())
                .collect(),
            indices: mesh.triangles().iter().flatten().copied().collect(),
        }
    }

    /// meshopt's simplification to at most `triangles` triangles (see the module
    /// documentation for the options): the output index buffer, into the input vertices.
    pub fn simplify(&self, triangles: usize) -> Result<Vec<u32>> {
        let bytes: &[u8] = meshopt::typed_to_bytes(&self.positions);
        let adapter = VertexDataAdapter::new(bytes, size_of::<[f32; 3]>(), 0)
            .context("meshopt rejects the vertex buffer")?;
        Ok(meshopt::simplify(
            &self.indices,
            &adapter,
            3 * triangles,
            f32::MAX,
            MESHOPT_OPTIONS,
            None,
        ))
    }
}

/// The surface of meshopt's output: the input's `f64` positions with `indices` (unreferenced
/// vertices do not change any distance to or from the surface).
pub fn meshopt_surface(input: &TriMesh, indices: &[u32]) -> Result<TriMesh> {
    let triangles = indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    TriMesh::new(input.positions().to_vec(), triangles).context("meshopt's output is invalid")
}
