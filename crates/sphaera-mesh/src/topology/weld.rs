//! Welding vertices with identical or nearby positions.

use std::collections::HashMap;

use glam::DVec3;

use crate::{MeshError, TriMesh};

/// What [`weld_vertices`] changed.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X], vec![[0, 1, 2], [3, 2, 1]])?;
/// let (_, report) = topology::weld_vertices(&mesh, 0.0)?;
/// assert_eq!(report.merged_vertex_count, 1);
/// assert_eq!(report.vertex_map, vec![0, 1, 2, 1]);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct WeldReport {
    /// Vertices that were merged into another one (input count − output count).
    pub merged_vertex_count: usize,
    /// For each input vertex, its index in the welded mesh.
    pub vertex_map: Vec<u32>,
}

/// Merges vertices closer than `tolerance` (absolute distance, in mesh units).
///
/// **Cluster rule** (deterministic, order-based): vertices are visited in index order;
/// a vertex joins the *lowest-index representative* within distance `≤ tolerance` of it,
/// or becomes a representative itself when there is none. So every vertex is within
/// `tolerance` of its representative, representatives are more than `tolerance` apart,
/// and the representative (the lowest index of its cluster) keeps its exact position —
/// positions are never averaged. `tolerance = 0` merges exactly identical coordinates
/// (`-0.0` equals `0.0`).
///
/// The welded mesh keeps the representatives in their original order, and every
/// triangle remapped; nothing else is removed (triangles that become degenerate stay —
/// chain [`drop_degenerate_triangles`](super::drop_degenerate_triangles) if needed).
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `tolerance` is negative, NaN or infinite.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology};
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1e-9, 0.0), DVec3::ONE],
///     vec![[0, 1, 2], [3, 4, 2]],
/// )?;
/// let (welded, report) = topology::weld_vertices(&mesh, 1e-6)?;
/// assert_eq!(welded.vertex_count(), 4);
/// assert_eq!(welded.triangles(), &[[0, 1, 2], [1, 3, 2]]);
/// assert_eq!(report.vertex_map, vec![0, 1, 2, 1, 3]);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Performance
///
/// Expected linear time: a sort of the positions for `tolerance = 0`, otherwise a hash
/// grid of cell size `tolerance` holding the representatives (each vertex checks the 27
/// cells around it). A tolerance much larger than the typical edge puts many vertices in
/// one cell and degrades towards quadratic time.
pub fn weld_vertices(mesh: &TriMesh, tolerance: f64) -> Result<(TriMesh, WeldReport), MeshError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(MeshError::InvalidParameter {
            name: "tolerance",
            value: tolerance,
            requirement: "finite and non-negative",
        });
    }
    let positions = mesh.positions();
    let rep = if tolerance == 0.0 {
        identical_position_representatives(positions)
    } else {
        nearby_position_representatives(positions, tolerance)
    };
    let mut vertex_map = vec![0u32; positions.len()];
    let mut new_positions = Vec::new();
    for (v, &r) in rep.iter().enumerate() {
        if r as usize == v {
            vertex_map[v] = new_positions.len() as u32;
            new_positions.push(positions[v]);
        } else {
            // Representatives precede their members, so their new index is already set.
            vertex_map[v] = vertex_map[r as usize];
        }
    }
    let triangles = mesh
        .triangles()
        .iter()
        .map(|t| t.map(|v| vertex_map[v as usize]))
        .collect();
    let merged_vertex_count = positions.len() - new_positions.len();
    let welded = TriMesh::new(new_positions, triangles)?;
    Ok((
        welded,
        WeldReport {
            merged_vertex_count,
            vertex_map,
        },
    ))
}

/// Coordinates as a sortable, hashable key (`-0.0` normalised to `0.0`).
fn position_key(p: DVec3) -> [u64; 3] {
    [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits())
}

/// For each vertex, the lowest index with exactly the same coordinates.
pub(crate) fn identical_position_representatives(positions: &[DVec3]) -> Vec<u32> {
    let mut order: Vec<([u64; 3], u32)> = positions
        .iter()
        .enumerate()
        .map(|(i, &p)| (position_key(p), i as u32))
        .collect();
    order.sort_unstable();
    let mut rep: Vec<u32> = (0..positions.len() as u32).collect();
    let mut k = 0;
    while k < order.len() {
        let first = order[k].1;
        let mut j = k + 1;
        while j < order.len() && order[j].0 == order[k].0 {
            rep[order[j].1 as usize] = first;
            j += 1;
        }
        k = j;
    }
    rep
}

/// For each vertex, its representative under the greedy cluster rule of
/// [`weld_vertices`], found with a hash grid of cell size `tolerance > 0`.
fn nearby_position_representatives(positions: &[DVec3], tolerance: f64) -> Vec<u32> {
    // Cells slightly larger than the tolerance, so rounding in the division can never put
    // two points within `tolerance` more than one cell apart.
    let cell_size = tolerance * (1.0 + 1e-6);
    let cell_of = |p: DVec3| -> [i64; 3] {
        // Saturating float-to-int casts keep far-away points in valid (shared) cells;
        // every candidate is checked by exact distance, so only speed is affected.
        [p.x, p.y, p.z].map(|c| (c / cell_size).floor() as i64)
    };
    let tolerance_squared = tolerance * tolerance;
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut rep = Vec::with_capacity(positions.len());
    for (v, &p) in positions.iter().enumerate() {
        let cell = cell_of(p);
        let mut best: Option<u32> = None;
        for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                for dz in -1..=1i64 {
                    let key = [
                        cell[0].saturating_add(dx),
                        cell[1].saturating_add(dy),
                        cell[2].saturating_add(dz),
                    ];
                    let Some(members) = grid.get(&key) else {
                        continue;
                    };
                    // Members are in increasing index order: the first match is the
                    // cell's lowest-index candidate.
                    if let Some(&r) = members
                        .iter()
                        .find(|&&r| positions[r as usize].distance_squared(p) <= tolerance_squared)
                        && best.is_none_or(|b| r < b)
                    {
                        best = Some(r);
                    }
                }
            }
        }
        match best {
            Some(r) => rep.push(r),
            None => {
                rep.push(v as u32);
                grid.entry(cell).or_default().push(v as u32);
            }
        }
    }
    rep
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The cluster rule, by brute force.
    fn brute_force(positions: &[DVec3], tolerance: f64) -> Vec<u32> {
        let mut reps: Vec<u32> = Vec::new();
        let mut out = Vec::new();
        for (v, p) in positions.iter().enumerate() {
            match reps
                .iter()
                .find(|&&r| positions[r as usize].distance_squared(*p) <= tolerance * tolerance)
            {
                Some(&r) => out.push(r),
                None => {
                    reps.push(v as u32);
                    out.push(v as u32);
                }
            }
        }
        out
    }

    #[test]
    fn negative_or_nan_tolerance_is_rejected() {
        let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                weld_vertices(&mesh, bad),
                Err(MeshError::InvalidParameter {
                    name: "tolerance",
                    ..
                })
            ));
        }
    }

    #[test]
    fn zero_tolerance_merges_signed_zeros() {
        let positions = vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(-0.0, 1.0, 0.0)];
        assert_eq!(identical_position_representatives(&positions), vec![0, 0]);
    }

    proptest! {
        #[test]
        fn grid_weld_matches_brute_force(
            coords in prop::collection::vec((0u8..6, 0u8..6, 0u8..6), 1..60),
            tolerance in prop::sample::select(vec![0.05, 0.1, 0.3, 0.5, 1.0]),
        ) {
            // Coarse coordinates make many exact ties at the tolerance.
            let positions: Vec<DVec3> = coords
                .iter()
                .map(|&(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)) * 0.1)
                .collect();
            prop_assert_eq!(
                nearby_position_representatives(&positions, tolerance),
                brute_force(&positions, tolerance)
            );
            prop_assert_eq!(
                identical_position_representatives(&positions),
                brute_force(&positions, 0.0)
            );
        }
    }
}
