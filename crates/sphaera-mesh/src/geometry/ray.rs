//! Ray–triangle intersection (Möller–Trumbore).

use glam::DVec3;

use super::Triangle;

/// Where a ray meets a triangle, from [`ray_triangle_intersection`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayTriangleHit {
    /// Ray parameter of the hit, `t ≥ 0`: the hit point is `origin + t · direction` (in units
    /// of the direction's length, which need not be 1).
    pub t: f64,
    /// Barycentric coordinates of the hit point with respect to `a`, `b`, `c`: each in
    /// `[0, 1]`, summing to 1 up to rounding.
    pub barycentric: [f64; 3],
    /// Whether the ray enters through the front face: the direction points against the
    /// triangle's normal `(b − a) × (c − a)` (counter-clockwise as seen from the origin).
    pub front_facing: bool,
}

/// The intersection of the ray `origin + t · direction` (`t ≥ 0`) with the triangle, or
/// `None` if the ray misses it.
///
/// Both faces are hit (no back-face culling; see [`RayTriangleHit::front_facing`]). Hits on
/// edges and corners count (barycentrics are tested inclusively). A ray parallel to the
/// triangle's plane, including one lying in it, and any ray against a zero-area triangle,
/// returns `None`.
///
/// For parity (inside/outside) counting, note that this floating-point test is not exact:
/// a ray through an edge shared by two triangles may hit both or neither of them. Parity
/// tests should pick a ray direction that avoids edges, or use exact predicates.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::{Triangle, ray_triangle_intersection};
///
/// let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
/// let hit = ray_triangle_intersection(DVec3::new(0.25, 0.25, 2.0), -DVec3::Z, &t).unwrap();
/// assert_eq!(hit.t, 2.0);
/// assert_eq!(hit.barycentric, [0.5, 0.25, 0.25]);
/// assert!(hit.front_facing);
/// assert!(ray_triangle_intersection(DVec3::new(0.25, 0.25, 2.0), DVec3::Z, &t).is_none());
/// ```
///
/// # Panics
///
/// Never. Non-finite input returns `None`.
///
/// # Performance
///
/// Constant time, no allocation.
pub fn ray_triangle_intersection(
    origin: DVec3,
    direction: DVec3,
    triangle: &Triangle,
) -> Option<RayTriangleHit> {
    let edge1 = triangle.b - triangle.a;
    let edge2 = triangle.c - triangle.a;
    let p = direction.cross(edge2);
    let determinant = edge1.dot(p);
    if determinant == 0.0 || !determinant.is_finite() {
        return None;
    }
    let inverse = 1.0 / determinant;
    let offset = origin - triangle.a;
    let u = offset.dot(p) * inverse;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = offset.cross(edge1);
    let v = direction.dot(q) * inverse;
    if !(v >= 0.0 && u + v <= 1.0) {
        return None;
    }
    let t = edge2.dot(q) * inverse;
    if !(t >= 0.0 && t.is_finite()) {
        return None;
    }
    Some(RayTriangleHit {
        t,
        barycentric: [1.0 - u - v, u, v],
        // determinant = −direction · normal.
        front_facing: determinant > 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point() -> impl Strategy<Value = DVec3> {
        (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    /// Well-shaped triangles and rays far from grazing, so the expected answer is stable.
    fn well_conditioned(t: &Triangle, origin: DVec3, target: DVec3) -> bool {
        let n = t.scaled_normal();
        let longest = (t.b - t.a)
            .length()
            .max((t.c - t.a).length())
            .max((t.c - t.b).length());
        let d = target - origin;
        n.length() > 0.05 * longest * longest
            && d.length() > 1e-3
            && n.normalize().dot(d.normalize()).abs() > 0.05
    }

    proptest! {
        #[test]
        fn rays_aimed_inside_hit_where_aimed(
            a in point(), b in point(), c in point(), origin in point(),
            u in 0.01..0.98f64, v in 0.01..0.98f64, far in 1.0..3.0f64,
        ) {
            let (u, v) = if u + v >= 0.99 { (0.99 - v, 0.99 - u) } else { (u, v) };
            let t = Triangle::new(a, b, c);
            let target = t.point_at(u, v);
            prop_assume!(well_conditioned(&t, origin, target));
            let hit = ray_triangle_intersection(origin, (target - origin) / far, &t).unwrap();
            prop_assert!((hit.t - far).abs() < 1e-9 * far);
            prop_assert!((hit.barycentric[1] - u).abs() < 1e-9 && (hit.barycentric[2] - v).abs() < 1e-9);
            let facing = (target - origin).dot(t.scaled_normal()) < 0.0;
            prop_assert_eq!(hit.front_facing, facing);
            // Pointing away misses.
            prop_assert!(ray_triangle_intersection(origin, origin - target, &t).is_none());
        }

        #[test]
        fn rays_aimed_outside_miss(
            a in point(), b in point(), c in point(), origin in point(),
            u in -2.0..2.0f64, v in -2.0..2.0f64,
        ) {
            prop_assume!(u < -0.01 || v < -0.01 || u + v > 1.01);
            let t = Triangle::new(a, b, c);
            let target = t.point_at(u, v);
            prop_assume!(well_conditioned(&t, origin, target));
            prop_assert!(ray_triangle_intersection(origin, target - origin, &t).is_none());
        }
    }

    #[test]
    fn parallel_and_degenerate_cases_miss() {
        let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
        assert!(ray_triangle_intersection(DVec3::new(-1.0, 0.2, 0.0), DVec3::X, &t).is_none());
        assert!(ray_triangle_intersection(DVec3::new(0.2, 0.2, 1.0), DVec3::X, &t).is_none());
        let flat = Triangle::new(DVec3::ZERO, DVec3::X, 2.0 * DVec3::X);
        assert!(ray_triangle_intersection(DVec3::new(0.5, 0.0, 1.0), -DVec3::Z, &flat).is_none());
        assert!(ray_triangle_intersection(DVec3::NAN, -DVec3::Z, &t).is_none());
        // Back face.
        let hit = ray_triangle_intersection(DVec3::new(0.2, 0.2, -1.0), DVec3::Z, &t).unwrap();
        assert!(!hit.front_facing);
        // Corner hits count.
        assert!(ray_triangle_intersection(DVec3::new(0.0, 0.0, 1.0), -DVec3::Z, &t).is_some());
    }
}
