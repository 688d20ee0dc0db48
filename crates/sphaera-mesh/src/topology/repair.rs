//! Repair helpers: drop degenerate triangles, duplicate triangles, unreferenced vertices.

use super::report::duplicate_flags;
use crate::{MeshError, TriMesh};

/// What a triangle filter ([`drop_degenerate_triangles`], [`drop_duplicate_triangles`])
/// removed.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2], [2, 0, 1]])?;
/// let (clean, report) = topology::drop_duplicate_triangles(&mesh);
/// assert_eq!(clean.triangle_count(), 1);
/// assert_eq!(report.removed_triangle_count, 1);
/// assert_eq!(report.kept_triangles, vec![0]);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct TriangleFilterReport {
    /// Triangles removed in total.
    pub removed_triangle_count: usize,
    /// Of those, triangles with a repeated vertex index.
    pub repeated_index_count: usize,
    /// Of those, triangles with distinct indices but (relatively) zero area.
    pub zero_area_count: usize,
    /// Of those, triangles with the vertex set of an earlier kept triangle.
    pub duplicate_count: usize,
    /// For each triangle of the output, its index in the input.
    pub kept_triangles: Vec<u32>,
}

/// Removes triangles with a repeated vertex index or a zero area.
///
/// A triangle has zero area when twice its area (the length of the cross product of two
/// edges) is at most `relative_tolerance` times its squared longest edge ([`Triangle::is_degenerate`](crate::geometry::Triangle::is_degenerate));
/// `0.0` removes only exactly collinear corners, `1e-12` also near-collinear slivers.
/// Vertices are kept (see [`drop_unreferenced_vertices`]).
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `relative_tolerance` is negative, NaN or infinite.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(2.0, 0.0, 0.0)],
///     vec![[0, 1, 2], [0, 0, 1], [0, 1, 3]],
/// )?;
/// let (clean, report) = topology::drop_degenerate_triangles(&mesh, 0.0)?;
/// assert_eq!(clean.triangles(), &[[0, 1, 2]]);
/// assert_eq!((report.repeated_index_count, report.zero_area_count), (1, 1));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
pub fn drop_degenerate_triangles(
    mesh: &TriMesh,
    relative_tolerance: f64,
) -> Result<(TriMesh, TriangleFilterReport), MeshError> {
    if !(relative_tolerance.is_finite() && relative_tolerance >= 0.0) {
        return Err(MeshError::InvalidParameter {
            name: "relative_tolerance",
            value: relative_tolerance,
            requirement: "finite and non-negative",
        });
    }
    let mut report = TriangleFilterReport::default();
    let mut kept = Vec::with_capacity(mesh.triangle_count());
    for (t, (tri, geometry)) in mesh
        .triangles()
        .iter()
        .zip(mesh.triangle_iter())
        .enumerate()
    {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            report.repeated_index_count += 1;
        } else if geometry.is_degenerate(relative_tolerance) {
            report.zero_area_count += 1;
        } else {
            kept.push(*tri);
            report.kept_triangles.push(t as u32);
        }
    }
    report.removed_triangle_count = report.repeated_index_count + report.zero_area_count;
    Ok((rebuild(mesh, kept)?, report))
}

/// Removes every triangle whose vertex set (in any order or orientation) equals that of
/// an earlier triangle; the first one is kept.
///
/// Indices are compared as given: weld first ([`weld_vertices`](super::weld_vertices)) to
/// catch duplicates that use different copies of the same positions.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y],
///     vec![[0, 1, 2], [0, 2, 1], [1, 2, 0]],
/// )?;
/// let (clean, report) = topology::drop_duplicate_triangles(&mesh);
/// assert_eq!(clean.triangles(), &[[0, 1, 2]]);
/// assert_eq!(report.duplicate_count, 2);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Performance
///
/// `O(F log F)` (a sort of the sorted index triples).
pub fn drop_duplicate_triangles(mesh: &TriMesh) -> (TriMesh, TriangleFilterReport) {
    let flags = duplicate_flags(mesh.triangles());
    let mut report = TriangleFilterReport::default();
    let mut kept = Vec::with_capacity(mesh.triangle_count());
    for (t, (tri, &duplicate)) in mesh.triangles().iter().zip(&flags).enumerate() {
        if duplicate {
            report.duplicate_count += 1;
        } else {
            kept.push(*tri);
            report.kept_triangles.push(t as u32);
        }
    }
    report.removed_triangle_count = report.duplicate_count;
    // Only the positions are copied (the triangles were rebuilt above).
    let positions = mesh.positions().to_vec();
    // Same positions and a subset of checked triangles: construction cannot fail, but
    // fall back to the input rather than panic if that invariant were ever broken.
    let clean = TriMesh::new(positions, kept).unwrap_or_else(|_| mesh.clone());
    (clean, report)
}

fn rebuild(mesh: &TriMesh, triangles: Vec<[u32; 3]>) -> Result<TriMesh, MeshError> {
    TriMesh::new(mesh.positions().to_vec(), triangles)
}

/// What [`drop_unreferenced_vertices`] removed.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// let mesh = TriMesh::new(vec![DVec3::ONE, DVec3::ZERO, DVec3::X, DVec3::Y], vec![[1, 2, 3]])?;
/// let (clean, report) = topology::drop_unreferenced_vertices(&mesh);
/// assert_eq!(clean.triangles(), &[[0, 1, 2]]);
/// assert_eq!(report.vertex_map, vec![None, Some(0), Some(1), Some(2)]);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct UnreferencedReport {
    /// Vertices removed.
    pub removed_vertex_count: usize,
    /// For each input vertex, its index in the output (`None` if removed).
    pub vertex_map: Vec<Option<u32>>,
}

/// Removes the vertices no triangle uses, keeping the order of the others, and remaps the
/// triangles.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::splat(9.0), DVec3::X, DVec3::Y],
///     vec![[0, 2, 3]],
/// )?;
/// let (clean, report) = topology::drop_unreferenced_vertices(&mesh);
/// assert_eq!(clean.positions(), &[DVec3::ZERO, DVec3::X, DVec3::Y]);
/// assert_eq!(report.removed_vertex_count, 1);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
pub fn drop_unreferenced_vertices(mesh: &TriMesh) -> (TriMesh, UnreferencedReport) {
    let mut used = vec![false; mesh.vertex_count()];
    for &v in mesh.triangles().iter().flatten() {
        used[v as usize] = true;
    }
    let mut vertex_map = vec![None; mesh.vertex_count()];
    let mut positions = Vec::new();
    for (v, (&u, &p)) in used.iter().zip(mesh.positions()).enumerate() {
        if u {
            vertex_map[v] = Some(positions.len() as u32);
            positions.push(p);
        }
    }
    let triangles: Vec<[u32; 3]> = mesh
        .triangles()
        .iter()
        // Every referenced vertex was given a new index just above.
        .map(|t| t.map(|v| vertex_map[v as usize].unwrap_or(0)))
        .collect();
    let removed_vertex_count = mesh.vertex_count() - positions.len();
    // Referenced vertices are kept and remapped consistently: construction cannot fail
    // (invariant); fall back to the input rather than panic.
    let clean = TriMesh::new(positions, triangles).unwrap_or_else(|_| mesh.clone());
    (
        clean,
        UnreferencedReport {
            removed_vertex_count,
            vertex_map,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn relative_tolerance_catches_slivers() {
        let mesh = TriMesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1e-9, 0.0)],
            vec![[0, 1, 2]],
        )
        .unwrap();
        let (kept, _) = drop_degenerate_triangles(&mesh, 0.0).unwrap();
        assert_eq!(kept.triangle_count(), 1);
        let (dropped, report) = drop_degenerate_triangles(&mesh, 1e-6).unwrap();
        assert_eq!(dropped.triangle_count(), 0);
        assert_eq!(report.zero_area_count, 1);
        assert!(drop_degenerate_triangles(&mesh, f64::NAN).is_err());
    }

    #[test]
    fn empty_mesh_is_fine_everywhere() {
        let mesh = TriMesh::default();
        assert_eq!(drop_degenerate_triangles(&mesh, 0.0).unwrap().0, mesh);
        assert_eq!(drop_duplicate_triangles(&mesh).0, mesh);
        assert_eq!(drop_unreferenced_vertices(&mesh).0, mesh);
    }
}
