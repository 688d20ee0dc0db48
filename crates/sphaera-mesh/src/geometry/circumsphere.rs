//! Balls through two, three and four points (the support balls of enclosing-ball methods).
//!
//! All formulas work relative to the first point (subtracting it first keeps the cancellation
//! small) and use the cross-product form of the circumcentre, so a well-shaped input gives a
//! centre accurate to a few units in the last place of the input's extent. The returned
//! radius is the largest distance from the centre to the given points, so every given point
//! lies inside the returned ball in floating point.

use glam::DVec3;

use crate::Sphere;

/// Relative size below which a cross or triple product is treated as zero: the rounding
/// error of those products is a few `f64::EPSILON` times the product of the lengths.
const DEGENERACY_TOLERANCE: f64 = 16.0 * f64::EPSILON;

/// The smallest ball with `a` and `b` on its boundary: centred at their midpoint.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::ball_through_two_points;
///
/// let s = ball_through_two_points(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0));
/// assert_eq!(s.center, DVec3::X);
/// assert_eq!(s.radius, 1.0);
/// ```
///
/// # Panics
///
/// Never.
pub fn ball_through_two_points(a: DVec3, b: DVec3) -> Sphere {
    let center = a + 0.5 * (b - a);
    let farthest = center.distance_squared(a).max(center.distance_squared(b));
    Sphere::new(center, covering_radius(farthest))
}

/// The smallest ball with `a`, `b`, `c` on its boundary: the circumcircle of the triangle,
/// as a ball centred in the triangle's plane.
///
/// Returns `None` when the points are collinear (or coincide) up to rounding:
/// `|(b − a) × (c − a)| ≤ 16 ε |b − a| |c − a|`.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::circumball_of_triangle;
///
/// let s = circumball_of_triangle(DVec3::X, DVec3::Y, -DVec3::X).unwrap();
/// assert!(s.center.length() < 1e-15);
/// assert!((s.radius - 1.0).abs() < 1e-15);
/// assert!(circumball_of_triangle(DVec3::ZERO, DVec3::X, 2.0 * DVec3::X).is_none());
/// ```
///
/// # Panics
///
/// Never. Non-finite input returns `None`.
pub fn circumball_of_triangle(a: DVec3, b: DVec3, c: DVec3) -> Option<Sphere> {
    let u = b - a;
    let v = c - a;
    let w = u.cross(v);
    let w_squared = w.length_squared();
    let tolerance = DEGENERACY_TOLERANCE * u.length() * v.length();
    if w_squared.is_nan() || w_squared <= tolerance * tolerance {
        return None;
    }
    let offset =
        (u.length_squared() * v.cross(w) + v.length_squared() * w.cross(u)) / (2.0 * w_squared);
    finite_ball(a + offset, &[a, b, c])
}

/// The sphere through the four points `a`, `b`, `c`, `d` (the circumsphere of the
/// tetrahedron). This is also "the ball through three points with a given fourth point".
///
/// Returns `None` when the points are coplanar (or collinear, or coincide) up to rounding:
/// `|u · (v × w)| ≤ 16 ε |u| |v| |w|` with `u, v, w` the edges from `a`.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::circumsphere;
///
/// let s = circumsphere(DVec3::X, DVec3::Y, DVec3::Z, -DVec3::X).unwrap();
/// assert!(s.center.length() < 1e-15);
/// assert!((s.radius - 1.0).abs() < 1e-15);
/// assert!(circumsphere(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE.with_z(0.0)).is_none());
/// ```
///
/// # Panics
///
/// Never. Non-finite input returns `None`.
pub fn circumsphere(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Option<Sphere> {
    let u = b - a;
    let v = c - a;
    let w = d - a;
    let vw = v.cross(w);
    let wu = w.cross(u);
    let uv = u.cross(v);
    let triple = u.dot(vw);
    let tolerance = DEGENERACY_TOLERANCE * u.length() * v.length() * w.length();
    if triple.is_nan() || triple.abs() <= tolerance {
        return None;
    }
    let offset = (u.length_squared() * vw + v.length_squared() * wu + w.length_squared() * uv)
        / (2.0 * triple);
    finite_ball(a + offset, &[a, b, c, d])
}

/// The smallest radius `r` with `r * r >= distance_squared` and `r >= sqrt(distance_squared)`
/// in floating point, so both [`Sphere::contains_point`] and a `distance <= radius` test
/// accept the point at that squared distance.
pub(crate) fn covering_radius(distance_squared: f64) -> f64 {
    let radius = distance_squared.sqrt();
    if radius * radius < distance_squared {
        radius.next_up()
    } else {
        radius
    }
}

/// The ball centred at `center` through the farthest of `points`, if finite.
fn finite_ball(center: DVec3, points: &[DVec3]) -> Option<Sphere> {
    let farthest = points
        .iter()
        .map(|p| p.distance_squared(center))
        .fold(0.0, f64::max);
    let radius = covering_radius(farthest);
    (center.is_finite() && radius.is_finite()).then_some(Sphere::new(center, radius))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point() -> impl Strategy<Value = DVec3> {
        (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    /// Relative spread of the distances from `center` to `points`.
    fn spread(center: DVec3, points: &[DVec3]) -> f64 {
        let d: Vec<f64> = points.iter().map(|p| p.distance(center)).collect();
        let max = d.iter().copied().fold(0.0, f64::max);
        let min = d.iter().copied().fold(f64::INFINITY, f64::min);
        (max - min) / max.max(1e-300)
    }

    proptest! {
        #[test]
        fn triangle_circumball_is_equidistant_and_in_plane(a in point(), b in point(), c in point()) {
            // Only well-shaped triangles have an accurate circumcentre.
            let n = (b - a).cross(c - a);
            prop_assume!(n.length() > 1e-3 * (b - a).length() * (c - a).length());
            let s = circumball_of_triangle(a, b, c).unwrap();
            prop_assert!(spread(s.center, &[a, b, c]) < 1e-9);
            prop_assert!(n.normalize().dot(s.center - a).abs() < 1e-9 * s.radius);
            for p in [a, b, c] {
                prop_assert!(s.contains_point(p, 0.0));
            }
        }

        #[test]
        fn circumsphere_is_equidistant(a in point(), b in point(), c in point(), d in point()) {
            let (u, v, w) = (b - a, c - a, d - a);
            prop_assume!(u.dot(v.cross(w)).abs() > 1e-3 * u.length() * v.length() * w.length());
            let s = circumsphere(a, b, c, d).unwrap();
            prop_assert!(spread(s.center, &[a, b, c, d]) < 1e-9);
        }

        #[test]
        fn coplanar_and_collinear_inputs_are_rejected(a in point(), b in point(), c in point(), s in -3.0..3.0f64, r in -3.0..3.0f64) {
            // d in the plane of a, b, c (exactly representable when the plane is z = const).
            let (a, b, c) = (a.with_z(1.5), b.with_z(1.5), c.with_z(1.5));
            let d = (a + s * (b - a) + r * (c - a)).with_z(1.5);
            prop_assert!(circumsphere(a, b, c, d).is_none());
            // Points differing only in x are exactly collinear.
            let on_line = DVec3::new(a.x + s, a.y, 1.5);
            let on_line_2 = DVec3::new(a.x + r, a.y, 1.5);
            prop_assert!(circumball_of_triangle(a, on_line, on_line_2).is_none());
        }

        #[test]
        fn two_point_ball_contains_both(a in point(), b in point()) {
            let s = ball_through_two_points(a, b);
            prop_assert!(s.contains_point(a, 0.0) && s.contains_point(b, 0.0));
            prop_assert!((2.0 * s.radius - a.distance(b)).abs() <= 1e-12 * (1.0 + a.distance(b)));
        }
    }

    #[test]
    fn repeated_points_are_degenerate() {
        assert!(circumball_of_triangle(DVec3::X, DVec3::X, DVec3::Y).is_none());
        assert!(circumsphere(DVec3::X, DVec3::X, DVec3::Y, DVec3::Z).is_none());
        assert!(circumsphere(DVec3::NAN, DVec3::X, DVec3::Y, DVec3::Z).is_none());
        let s = ball_through_two_points(DVec3::ONE, DVec3::ONE);
        assert_eq!(s, Sphere::new(DVec3::ONE, 0.0));
    }
}
