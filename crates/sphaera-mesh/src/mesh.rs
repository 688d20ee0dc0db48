//! The indexed triangle mesh.

use glam::DVec3;

use crate::{Aabb, MeshError, geometry::Triangle};

/// An indexed triangle mesh: `f64` vertex positions and triangles of three vertex indices.
///
/// Construction checks that every coordinate is finite and every index is in range, and
/// says which vertex or triangle is wrong. Nothing else is required: the mesh may be open,
/// non-manifold, contain degenerate or duplicate triangles, or unreferenced vertices (real
/// scans do). [`crate::topology`] reports those properties, and its repair helpers remove
/// them when asked.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::TriMesh;
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )?;
/// assert_eq!(mesh.triangle_count(), 4);
/// assert!((mesh.surface_area() - (1.5 + 3f64.sqrt() / 2.0)).abs() < 1e-12);
///
/// // Bad input is an error that says what is wrong, never a panic.
/// let err = TriMesh::new(vec![DVec3::ZERO], vec![[0, 1, 2]]).unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "triangle 0 refers to vertex 1, but the mesh has only 1 vertices"
/// );
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// A mesh of the given positions and triangles.
    ///
    /// # Errors
    ///
    /// - [`MeshError::NonFiniteCoordinate`] if a coordinate is NaN or infinite;
    /// - [`MeshError::IndexOutOfRange`] if a triangle refers to a missing vertex;
    /// - [`MeshError::TooManyVertices`] if there are more than `u32::MAX` vertices;
    /// - [`MeshError::TooManyTriangles`] if `3 × triangle count ≥ u32::MAX − 1` (more than
    ///   about 1.43 billion triangles): topology code numbers the corners `3t + i` as `u32`
    ///   and keeps `u32::MAX` and `u32::MAX − 1` as sentinels.
    ///
    /// An empty mesh (no triangles) is allowed here; operations that need a surface return
    /// [`MeshError::EmptyMesh`].
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        check_positions(&positions)?;
        check_triangle_count(triangles.len())?;
        check_triangles(&triangles, positions.len())?;
        Ok(Self {
            positions,
            triangles,
        })
    }

    /// The vertex positions.
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// The triangles, as counter-clockwise (outward normal by the right-hand rule) triples
    /// of vertex indices.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Number of vertices (referenced or not).
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Whether the mesh has no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The geometry of triangle `t`, or `None` if there is no such triangle.
    pub fn triangle(&self, t: usize) -> Option<Triangle> {
        self.triangles.get(t).map(|&tri| self.triangle_of(tri))
    }

    /// Iterator over the geometry of every triangle, in index order.
    pub fn triangle_iter(&self) -> impl ExactSizeIterator<Item = Triangle> + '_ {
        self.triangles.iter().map(|&tri| self.triangle_of(tri))
    }

    /// The geometry of a triangle given by vertex indices that were checked at construction.
    fn triangle_of(&self, [a, b, c]: [u32; 3]) -> Triangle {
        // Indices were range-checked in `new`, and `positions` never shrinks without a
        // re-check, so these lookups cannot fail.
        Triangle::new(
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        )
    }

    /// The box of the vertices that some triangle uses ([`Aabb::EMPTY`] for an empty mesh).
    ///
    /// Unreferenced vertices (the Stanford bunny has 1,113) are ignored, so the box and its
    /// diagonal describe the surface.
    pub fn bounding_box(&self) -> Aabb {
        self.triangles.iter().flatten().fold(Aabb::EMPTY, |b, &v| {
            b.grown_by_point(self.positions[v as usize])
        })
    }

    /// Length of [`TriMesh::bounding_box`]'s diagonal: the scale relative errors refer to.
    pub fn bounding_box_diagonal(&self) -> f64 {
        self.bounding_box().diagonal()
    }

    /// Total area of the triangles.
    pub fn surface_area(&self) -> f64 {
        // `fold` from +0.0: `sum()` of an empty `f64` iterator is −0.0.
        self.triangle_iter().fold(0.0, |area, t| area + t.area())
    }

    /// Replaces every vertex position (for deforming meshes), keeping the triangles.
    ///
    /// # Errors
    ///
    /// [`MeshError::VertexCountMismatch`] if the count differs, and
    /// [`MeshError::NonFiniteCoordinate`] for a NaN or infinite coordinate; the mesh is
    /// unchanged on error.
    pub fn set_positions(&mut self, positions: Vec<DVec3>) -> Result<(), MeshError> {
        if positions.len() != self.positions.len() {
            return Err(MeshError::VertexCountMismatch {
                expected: self.positions.len(),
                actual: positions.len(),
            });
        }
        check_positions(&positions)?;
        self.positions = positions;
        Ok(())
    }

    /// Checks positions as [`TriMesh::new`] does: no more than `u32` indices address, every
    /// coordinate finite (a failure names the vertex and axis). For structures that take
    /// new positions for a mesh they already hold.
    ///
    /// # Errors
    ///
    /// [`MeshError::TooManyVertices`], [`MeshError::NonFiniteCoordinate`].
    pub fn check_positions(positions: &[DVec3]) -> Result<(), MeshError> {
        check_positions(positions)
    }

    /// Splits the mesh into its positions and triangles.
    pub fn into_parts(self) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        (self.positions, self.triangles)
    }
}

/// Rejects more vertices than `u32` indices address and any non-finite coordinate (named
/// by vertex and axis).
pub(crate) fn check_positions(positions: &[DVec3]) -> Result<(), MeshError> {
    if positions.len() > u32::MAX as usize {
        return Err(MeshError::TooManyVertices {
            count: positions.len(),
        });
    }
    for (vertex, p) in positions.iter().enumerate() {
        if !p.is_finite() {
            let (axis, value) = [('x', p.x), ('y', p.y), ('z', p.z)]
                .into_iter()
                .find(|(_, v)| !v.is_finite())
                .unwrap_or(('x', p.x));
            return Err(MeshError::NonFiniteCoordinate {
                vertex,
                axis,
                value,
            });
        }
    }
    Ok(())
}

/// Rejects triangle counts whose corner numbers `3t + i` would reach the `u32` sentinels
/// (`u32::MAX − 1` and `u32::MAX`) that topology code reserves.
fn check_triangle_count(count: usize) -> Result<(), MeshError> {
    if count.saturating_mul(3) >= u32::MAX as usize - 1 {
        return Err(MeshError::TooManyTriangles { count });
    }
    Ok(())
}

fn check_triangles(triangles: &[[u32; 3]], vertex_count: usize) -> Result<(), MeshError> {
    for (triangle, tri) in triangles.iter().enumerate() {
        if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(MeshError::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_coordinate_is_reported_with_vertex_and_axis() {
        let err = TriMesh::new(
            vec![DVec3::ZERO, DVec3::new(1.0, f64::NAN, 0.0), DVec3::Y],
            vec![[0, 1, 2]],
        )
        .unwrap_err();
        assert!(matches!(
            err,
            MeshError::NonFiniteCoordinate {
                vertex: 1,
                axis: 'y',
                ..
            }
        ));
    }

    #[test]
    fn infinite_coordinate_is_rejected() {
        let err = TriMesh::new(vec![DVec3::new(0.0, 0.0, f64::INFINITY)], vec![]).unwrap_err();
        assert!(matches!(
            err,
            MeshError::NonFiniteCoordinate { axis: 'z', .. }
        ));
    }

    #[test]
    fn out_of_range_index_is_reported_with_triangle() {
        let err = TriMesh::new(vec![DVec3::ZERO; 3], vec![[0, 1, 2], [0, 1, 7]]).unwrap_err();
        assert!(matches!(
            err,
            MeshError::IndexOutOfRange {
                triangle: 1,
                index: 7,
                vertex_count: 3
            }
        ));
    }

    #[test]
    fn bounding_box_ignores_unreferenced_vertices() {
        let mesh = TriMesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::splat(100.0)],
            vec![[0, 1, 2]],
        )
        .unwrap();
        assert_eq!(
            mesh.bounding_box(),
            Aabb::new(DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0))
        );
    }

    #[test]
    fn too_many_triangles_for_u32_corner_numbers_is_rejected() {
        // The largest count whose corner count 3t (and so every corner 3t + i) stays below
        // the sentinel u32::MAX - 1.
        let max_ok = (u32::MAX as usize - 2) / 3;
        assert!(3 * max_ok < u32::MAX as usize - 1);
        assert!(3 * (max_ok + 1) >= u32::MAX as usize - 1);
        assert!(check_triangle_count(max_ok).is_ok());
        assert!(matches!(
            check_triangle_count(max_ok + 1),
            Err(MeshError::TooManyTriangles { count }) if count == max_ok + 1
        ));
        assert!(matches!(
            check_triangle_count(usize::MAX),
            Err(MeshError::TooManyTriangles { .. })
        ));
        assert!(check_triangle_count(0).is_ok());
    }

    #[test]
    fn empty_mesh_surface_area_is_positive_zero() {
        let area = TriMesh::default().surface_area();
        assert_eq!(area.to_bits(), 0.0f64.to_bits());
    }

    #[test]
    fn set_positions_keeps_mesh_on_error() {
        let mut mesh =
            TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let before = mesh.clone();
        assert!(mesh.set_positions(vec![DVec3::ZERO]).is_err());
        assert!(
            mesh.set_positions(vec![DVec3::ZERO, DVec3::NAN, DVec3::Y])
                .is_err()
        );
        assert_eq!(mesh, before);
    }
}
