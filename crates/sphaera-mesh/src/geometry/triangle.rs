//! Triangle geometry: area, normal, centroid.

use glam::DVec3;

/// The geometry of one triangle, corners `a`, `b`, `c` in counter-clockwise order.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::Triangle;
///
/// let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
/// assert_eq!(t.area(), 0.5);
/// assert_eq!(t.unit_normal(), Some(DVec3::Z));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// First corner.
    pub a: DVec3,
    /// Second corner.
    pub b: DVec3,
    /// Third corner.
    pub c: DVec3,
}

impl Triangle {
    /// The triangle `a`, `b`, `c`.
    pub const fn new(a: DVec3, b: DVec3, c: DVec3) -> Self {
        Self { a, b, c }
    }

    /// The corners as an array.
    pub fn corners(&self) -> [DVec3; 3] {
        [self.a, self.b, self.c]
    }

    /// `(b − a) × (c − a)`: normal direction with length twice the area.
    pub fn scaled_normal(&self) -> DVec3 {
        (self.b - self.a).cross(self.c - self.a)
    }

    /// The unit normal, or `None` for a degenerate (zero-area) triangle.
    pub fn unit_normal(&self) -> Option<DVec3> {
        self.scaled_normal().try_normalize()
    }

    /// The area.
    pub fn area(&self) -> f64 {
        0.5 * self.scaled_normal().length()
    }

    /// The centroid.
    pub fn centroid(&self) -> DVec3 {
        (self.a + self.b + self.c) / 3.0
    }

    /// The point `a + u (b − a) + v (c − a)` for barycentric-like parameters `u`, `v`.
    pub fn point_at(&self, u: f64, v: f64) -> DVec3 {
        self.a + u * (self.b - self.a) + v * (self.c - self.a)
    }

    /// Whether the triangle has zero area relative to its size: the area is at most
    /// `relative_tolerance` times the squared longest edge.
    pub fn is_degenerate(&self, relative_tolerance: f64) -> bool {
        let longest = (self.b - self.a)
            .length_squared()
            .max((self.c - self.b).length_squared())
            .max((self.a - self.c).length_squared());
        self.scaled_normal().length() <= relative_tolerance * longest
    }
}
