//! Inside/outside by ray parity: the classical reference for closed meshes.

use glam::DVec3;

use sphaera_mesh::TriMesh;

/// Fixed, deterministic ray directions, none parallel to an axis or a diagonal (so rays
/// from grid-like points rarely graze the edges of axis-aligned meshes).
const DIRECTIONS: [[f64; 3]; 9] = [
    [0.618_034, 0.414_214, 0.732_051],
    [-0.302_776, 0.854_102, 0.236_068],
    [0.145_898, -0.567_764, 0.910_555],
    [-0.771_243, -0.236_068, -0.414_214],
    [0.853_553, -0.146_447, -0.5],
    [-0.1, 0.3, -0.948_683],
    [0.577_215, 0.664_742, -0.301_511],
    [-0.442_695, -0.881_374, 0.166_667],
    [0.923_880, 0.382_683, 0.029_833],
];

/// How many unambiguous casts vote.
const VOTES: usize = 3;

/// Whether `p` is inside the closed mesh `mesh`, by the parity of the number of
/// triangles a ray from `p` crosses; `None` when no ray gives an unambiguous count
/// (typically because `p` is on the surface).
///
/// Rays are cast along fixed non-axis directions. A ray that passes within a relative
/// `1e-9` of an edge or corner of a triangle, runs in the plane of a triangle, or
/// starts on a triangle is ambiguous and is re-cast along the next direction. The answer
/// is the majority of the first three unambiguous casts (or of all if fewer).
///
/// This is meaningful only for closed meshes (every edge shared by an even number of
/// triangles); for open meshes use the winding number. It is the brute-force reference the
/// winding-number classification is tested against.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::TriMesh;
/// use sphaera_query::winding::inside_by_ray_parity;
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )?;
/// assert_eq!(inside_by_ray_parity(&mesh, DVec3::splat(0.2)), Some(true));
/// assert_eq!(inside_by_ray_parity(&mesh, DVec3::splat(0.4)), Some(false));
/// assert_eq!(inside_by_ray_parity(&mesh, DVec3::ZERO), None); // a corner
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Panics
///
/// Never. An empty mesh gives `Some(false)`; a non-finite `p` gives `None`.
///
/// # Performance
///
/// `O(triangles)` per ray, three to nine rays per point: a test reference, not a fast
/// query.
pub fn inside_by_ray_parity(mesh: &TriMesh, p: DVec3) -> Option<bool> {
    if !p.is_finite() {
        return None;
    }
    let length_tolerance = 1e-9 * mesh.bounding_box_diagonal().max(f64::MIN_POSITIVE);
    let mut inside_votes = 0;
    let mut votes = 0;
    for direction in DIRECTIONS {
        let direction = DVec3::from(direction).normalize();
        if let Some(crossings) = count_crossings(mesh, p, direction, length_tolerance) {
            votes += 1;
            if crossings % 2 == 1 {
                inside_votes += 1;
            }
            if votes == VOTES {
                break;
            }
        }
    }
    match votes {
        0 => None,
        _ if 2 * inside_votes == votes => None,
        _ => Some(2 * inside_votes > votes),
    }
}

/// The number of triangles the ray `origin + t · direction` (`t > 0`) crosses, or `None`
/// if the ray grazes an edge, corner or triangle plane, or starts on a triangle.
fn count_crossings(
    mesh: &TriMesh,
    origin: DVec3,
    direction: DVec3,
    length_tolerance: f64,
) -> Option<usize> {
    const RELATIVE: f64 = 1e-9;
    let mut crossings = 0;
    for triangle in mesh.triangle_iter() {
        let (e1, e2) = (triangle.b - triangle.a, triangle.c - triangle.a);
        let normal = e1.cross(e2);
        let normal_length = normal.length();
        if normal_length == 0.0 {
            continue; // a degenerate triangle has no interior to cross
        }
        let s = origin - triangle.a;
        let h = direction.cross(e2);
        let det = e1.dot(h);
        if det.abs() <= RELATIVE * normal_length {
            // Parallel to the plane: ambiguous if the ray runs in (or next to) the plane.
            if s.dot(normal).abs() <= length_tolerance * normal_length {
                return None;
            }
            continue;
        }
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let v = direction.dot(q) / det;
        let t = e2.dot(q) / det;
        let w = 1.0 - u - v;
        if u < -RELATIVE || v < -RELATIVE || w < -RELATIVE || t < -length_tolerance {
            continue;
        }
        if u <= RELATIVE || v <= RELATIVE || w <= RELATIVE || t <= length_tolerance {
            return None;
        }
        crossings += 1;
    }
    Some(crossings)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::shapes::fixtures;

    #[test]
    fn directions_are_not_degenerate() {
        for d in DIRECTIONS {
            let d = DVec3::from(d).normalize();
            assert!(d.x.abs().min(d.y.abs()).min(d.z.abs()) > 0.02, "{d}");
        }
    }

    #[test]
    fn interior_points_of_closed_shapes_are_inside() {
        for (name, mesh) in fixtures::closed_shapes() {
            let p = fixtures::interior_point(name);
            assert_eq!(inside_by_ray_parity(&mesh, p), Some(true), "{name}");
            let far = DVec3::new(3.0, -4.0, 5.0);
            assert_eq!(inside_by_ray_parity(&mesh, far), Some(false), "{name}");
        }
    }

    #[test]
    fn points_on_the_surface_are_ambiguous() {
        let cube = fixtures::unit_cube();
        for p in [
            DVec3::new(0.5, 0.3, 0.0),
            DVec3::new(1.0, 1.0, 0.2),
            DVec3::ONE,
        ] {
            assert_eq!(inside_by_ray_parity(&cube, p), None, "{p}");
        }
    }

    #[test]
    fn rays_through_edges_and_corners_are_recast() {
        // Points from which the first direction passes exactly through a cube corner or edge.
        let cube = fixtures::unit_cube();
        let d = DVec3::from(DIRECTIONS[0]).normalize();
        for corner in [DVec3::ONE, DVec3::new(1.0, 1.0, 0.5)] {
            let inside = corner - 0.3 * d;
            let outside = corner - 3.0 * d;
            assert_eq!(inside_by_ray_parity(&cube, inside), Some(true));
            assert_eq!(inside_by_ray_parity(&cube, outside), Some(false));
        }
    }

    #[test]
    fn non_finite_and_empty_inputs() {
        let cube = fixtures::unit_cube();
        assert_eq!(inside_by_ray_parity(&cube, DVec3::NAN), None);
        assert_eq!(
            inside_by_ray_parity(&TriMesh::default(), DVec3::ZERO),
            Some(false)
        );
    }
}
