//! The one sphere type shared by every Sphaera crate.

use glam::DVec3;

/// A ball: every point within `radius` of `center`.
///
/// This is the single sphere type of the Sphaera workspace: error spheres, medial spheres,
/// sphere-tree nodes and enclosing balls all use it.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::Sphere;
///
/// let s = Sphere::new(DVec3::ZERO, 2.0);
/// assert!(s.contains_point(DVec3::new(0.0, 2.0, 0.0), 0.0));
/// assert!(s.contains_sphere(&Sphere::new(DVec3::X, 1.0), 0.0));
/// assert_eq!(s.signed_distance(DVec3::new(5.0, 0.0, 0.0)), 3.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Sphere {
    /// The centre.
    pub center: DVec3,
    /// The radius (non-negative for a valid sphere).
    pub radius: f64,
}

impl Sphere {
    /// The sphere of the given centre and radius.
    pub const fn new(center: DVec3, radius: f64) -> Self {
        Self { center, radius }
    }

    /// Whether the centre is finite and the radius finite and non-negative.
    pub fn is_valid(&self) -> bool {
        self.center.is_finite() && self.radius.is_finite() && self.radius >= 0.0
    }

    /// Distance from `p` to the sphere's surface: negative inside, positive outside.
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        p.distance(self.center) - self.radius
    }

    /// Whether `p` lies within the ball grown by `tolerance`.
    ///
    /// A negative `tolerance` shrinks the ball; once `radius + tolerance` is negative the
    /// ball is empty and contains no point.
    pub fn contains_point(&self, p: DVec3, tolerance: f64) -> bool {
        let r = self.radius + tolerance;
        r >= 0.0 && p.distance_squared(self.center) <= r * r
    }

    /// Whether `other` lies within this ball grown by `tolerance`.
    ///
    /// A negative `tolerance` shrinks the ball; once `radius + tolerance` is negative the
    /// ball is empty and contains nothing.
    pub fn contains_sphere(&self, other: &Sphere, tolerance: f64) -> bool {
        let r = self.radius + tolerance;
        r >= 0.0 && other.center.distance(self.center) + other.radius <= r
    }

    /// Whether the two balls share a point.
    ///
    /// Balls whose radii sum to a negative value (invalid spheres) never intersect.
    pub fn intersects(&self, other: &Sphere) -> bool {
        let r = self.radius + other.radius;
        r >= 0.0 && other.center.distance_squared(self.center) <= r * r
    }

    /// Volume of the ball.
    pub fn volume(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3)
    }

    /// The axis-aligned box of the ball.
    pub fn bounding_box(&self) -> crate::Aabb {
        crate::Aabb::new(
            self.center - DVec3::splat(self.radius),
            self.center + DVec3::splat(self.radius),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_tolerance_larger_than_radius_contains_nothing() {
        let s = Sphere::new(DVec3::ZERO, 1.0);
        // (1 - 3)^2 = 4 >= |(2,0,0)|^2 used to make this "contained".
        assert!(!s.contains_point(DVec3::new(2.0, 0.0, 0.0), -3.0));
        assert!(!s.contains_point(DVec3::ZERO, -1.5));
        assert!(s.contains_point(DVec3::new(0.5, 0.0, 0.0), -0.5));
        assert!(!s.contains_point(DVec3::new(0.6, 0.0, 0.0), -0.5));
        assert!(!s.contains_point(DVec3::ZERO, f64::NAN));
    }

    #[test]
    fn negative_tolerance_larger_than_radius_contains_no_sphere() {
        let s = Sphere::new(DVec3::ZERO, 1.0);
        assert!(!s.contains_sphere(&Sphere::new(DVec3::ZERO, -5.0), -3.0));
        assert!(s.contains_sphere(&Sphere::new(DVec3::ZERO, 0.5), -0.5));
        assert!(!s.contains_sphere(&Sphere::new(DVec3::ZERO, 0.6), -0.5));
    }

    #[test]
    fn negative_radii_sum_does_not_intersect() {
        let a = Sphere::new(DVec3::ZERO, 1.0);
        let b = Sphere::new(DVec3::new(2.0, 0.0, 0.0), -4.0);
        // (1 - 4)^2 = 9 >= 4 used to report an intersection.
        assert!(!a.intersects(&b));
        assert!(a.intersects(&Sphere::new(DVec3::new(2.0, 0.0, 0.0), 1.0)));
        assert!(!a.intersects(&Sphere::new(DVec3::new(2.1, 0.0, 0.0), 1.0)));
    }
}
