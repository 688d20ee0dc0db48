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
    pub fn contains_point(&self, p: DVec3, tolerance: f64) -> bool {
        p.distance_squared(self.center) <= (self.radius + tolerance).powi(2)
    }

    /// Whether `other` lies within this ball grown by `tolerance`.
    pub fn contains_sphere(&self, other: &Sphere, tolerance: f64) -> bool {
        other.center.distance(self.center) + other.radius <= self.radius + tolerance
    }

    /// Whether the two balls share a point.
    pub fn intersects(&self, other: &Sphere) -> bool {
        other.center.distance_squared(self.center) <= (self.radius + other.radius).powi(2)
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
