//! The signed solid angle of a triangle and the exact (brute-force) generalized winding number.

use std::f64::consts::PI;

use glam::DVec3;

use sphaera_mesh::{TriMesh, geometry::Triangle};

/// The signed solid angle `Ω` that `triangle` subtends at `p`, in steradians, in `[−2π, 2π]`.
///
/// Positive when `p` sees the triangle's back, that is when `p` lies on the side opposite to
/// the counter-clockwise normal `(b − a) × (c − a)` — so for an outward-oriented closed mesh
/// the solid angles of an interior point sum to `4π`.
///
/// Computed with the formula of Van Oosterom and Strackee (1983), with `atan2` so that it is
/// robust for every configuration (including obtuse solid angles beyond `π`):
///
/// ```text
/// tan(Ω / 2) = a · (b × c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|)
/// ```
///
/// where `a`, `b`, `c` are the corners relative to `p`.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::Triangle;
/// use sphaera_query::winding::triangle_solid_angle;
///
/// // One face of an octahedron centred at the origin subtends one eighth of the sphere.
/// let face = Triangle::new(DVec3::X, DVec3::Y, DVec3::Z);
/// let omega = triangle_solid_angle(&face, DVec3::ZERO);
/// assert!((omega - 4.0 * std::f64::consts::PI / 8.0).abs() < 1e-12);
/// // Seen from the side its normal points to, the sign is negative.
/// assert!(triangle_solid_angle(&face, DVec3::splat(1.0)) < 0.0);
/// ```
///
/// # Panics
///
/// Never. A point on the triangle's plane (including its corners and edges) gives `0` or
/// a value of either sign, never NaN; non-finite input gives NaN.
///
/// # Performance
///
/// Three square roots and one `atan2`. The rate of brute force, one solid angle per
/// triangle, is in the section *Inside/outside (generalized winding number)* of
/// `docs/benchmarks.md` in the repository.
#[inline]
pub fn triangle_solid_angle(triangle: &Triangle, p: DVec3) -> f64 {
    solid_angle_of_corners(triangle.a - p, triangle.b - p, triangle.c - p)
}

/// [`triangle_solid_angle`] for corners already relative to the query point.
#[inline]
pub(crate) fn solid_angle_of_corners(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let numerator = a.dot(b.cross(c));
    let denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * numerator.atan2(denominator)
}

/// The exact generalized winding number of `mesh` at `p`: the sum of the signed solid
/// angles of all triangles, divided by `4π` (Jacobson, Kavan and Sorkine-Hornung 2013).
///
/// For a closed, outward-oriented mesh it is `1` inside, `0` outside (and `k` inside `k`
/// nested copies). For an open mesh or a triangle soup it varies smoothly and stays close to
/// those values away from the holes, which is why it is the robust inside/outside test.
///
/// This is the reference the accelerated [`WindingNumber`](super::WindingNumber) is tested
/// against.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::TriMesh;
/// use sphaera_query::winding::winding_number_brute;
///
/// // A unit tetrahedron, outward oriented.
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )?;
/// assert!((winding_number_brute(&mesh, DVec3::splat(0.1)) - 1.0).abs() < 1e-12);
/// assert!(winding_number_brute(&mesh, DVec3::splat(2.0)).abs() < 1e-12);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Panics
///
/// Never. An empty mesh gives `0`; a point on the surface gives a finite value between the
/// values on either side; a non-finite `p` gives NaN.
///
/// # Performance
///
/// `O(triangles)` per point (one [`triangle_solid_angle`] each; the measured rate is in
/// the section *Inside/outside (generalized winding number)* of `docs/benchmarks.md` in the
/// repository): use [`WindingNumber`](super::WindingNumber) for more than a few points.
pub fn winding_number_brute(mesh: &TriMesh, p: DVec3) -> f64 {
    let total: f64 = mesh
        .triangle_iter()
        .map(|t| triangle_solid_angle(&t, p))
        .sum();
    total / (4.0 * PI)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use sphaera_mesh::shapes::fixtures;

    #[test]
    fn octant_face_is_one_eighth_of_the_sphere() {
        let face = Triangle::new(DVec3::X, DVec3::Y, DVec3::Z);
        let omega = triangle_solid_angle(&face, DVec3::ZERO);
        assert!((omega - PI / 2.0).abs() < 1e-14);
    }

    #[test]
    fn point_on_the_plane_gives_zero_not_nan() {
        let face = Triangle::new(DVec3::X, DVec3::Y, DVec3::Z);
        for p in [
            DVec3::X,
            (DVec3::X + DVec3::Y) / 2.0,
            DVec3::splat(1.0 / 3.0),
        ] {
            let omega = triangle_solid_angle(&face, p);
            assert!(omega.is_finite(), "{omega} at {p}");
        }
        let far_in_plane = DVec3::new(2.0, -1.0, 0.0);
        assert!(triangle_solid_angle(&face, far_in_plane).abs() < 1e-15);
    }

    #[test]
    fn near_hemisphere_solid_angle_is_accurate() {
        // A huge triangle seen from just below its centroid subtends almost 2π.
        let face = Triangle::new(
            DVec3::new(-1e6, -1e6, 0.0),
            DVec3::new(1e6, -1e6, 0.0),
            DVec3::new(0.0, 1e6, 0.0),
        );
        let omega = triangle_solid_angle(&face, DVec3::new(0.0, 0.0, -1e-3));
        assert!((omega - 2.0 * PI).abs() < 1e-6, "{omega}");
    }

    #[test]
    fn closed_shapes_have_winding_one_inside_zero_outside() {
        for (name, mesh) in fixtures::closed_shapes() {
            let c = mesh.bounding_box().center();
            let inside = fixtures::interior_point(name);
            let w_in = winding_number_brute(&mesh, inside);
            let w_out = winding_number_brute(&mesh, c + DVec3::new(5.0, 7.0, 3.0));
            assert!((w_in - 1.0).abs() < 1e-9, "{name}: w = {w_in}");
            assert!(w_out.abs() < 1e-9, "{name}: w = {w_out}");
        }
    }

    #[test]
    fn empty_mesh_gives_zero() {
        let mesh = TriMesh::default();
        assert!(winding_number_brute(&mesh, DVec3::ZERO).abs() < f64::EPSILON);
    }

    proptest! {
        /// Reversing the corner order negates the solid angle; rotating them leaves it.
        #[test]
        fn solid_angle_symmetries(
            a in prop::array::uniform3(-2.0..2.0f64),
            b in prop::array::uniform3(-2.0..2.0f64),
            c in prop::array::uniform3(-2.0..2.0f64),
            p in prop::array::uniform3(-2.0..2.0f64),
        ) {
            let (a, b, c, p) = (DVec3::from(a), DVec3::from(b), DVec3::from(c), DVec3::from(p));
            let omega = triangle_solid_angle(&Triangle::new(a, b, c), p);
            let rotated = triangle_solid_angle(&Triangle::new(b, c, a), p);
            let reversed = triangle_solid_angle(&Triangle::new(a, c, b), p);
            prop_assert!(omega.abs() <= 2.0 * PI + 1e-12);
            // Away from the plane the value is well conditioned.
            let n = (b - a).cross(c - a);
            prop_assume!(n.length() > 1e-3 && (p - a).dot(n).abs() > 1e-3 * n.length());
            prop_assert!((omega - rotated).abs() < 1e-9);
            prop_assert!((omega + reversed).abs() < 1e-9);
        }

        /// The solid angles of the four faces of a tetrahedron, seen from inside, sum to 4π
        /// (from outside, to 0).
        #[test]
        fn tetrahedron_solid_angles_sum_to_four_pi_inside(
            weights in prop::array::uniform4(0.05..1.0f64),
            outside in prop::array::uniform3(3.0..5.0f64),
        ) {
            let mesh = fixtures::tetrahedron();
            let total: f64 = weights.iter().sum();
            let corners = mesh.positions();
            let inside = weights
                .iter()
                .zip(corners)
                .fold(DVec3::ZERO, |acc, (w, v)| acc + *v * (*w / total));
            prop_assert!((winding_number_brute(&mesh, inside) - 1.0).abs() < 1e-9);
            prop_assert!(winding_number_brute(&mesh, DVec3::from(outside)).abs() < 1e-9);
        }
    }
}
