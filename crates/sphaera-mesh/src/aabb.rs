//! Axis-aligned bounding boxes.

use glam::DVec3;

/// An axis-aligned box `[min, max]`.
///
/// An *empty* box has `min > max` on every axis (see [`Aabb::EMPTY`]); growing it by a point
/// gives the box of that point.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::Aabb;
///
/// let b = Aabb::from_points([DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0)]);
/// assert_eq!(b.diagonal(), 5.0);
/// assert!(b.contains_point(DVec3::new(1.0, 1.0, 0.0)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest coordinate on each axis.
    pub min: DVec3,
    /// Largest coordinate on each axis.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box: contains nothing, and is the identity of [`Aabb::union`].
    pub const EMPTY: Self = Self {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    /// The box `[min, max]`. The corners are taken as given; use
    /// [`Aabb::from_points`] when their order is unknown.
    pub const fn new(min: DVec3, max: DVec3) -> Self {
        Self { min, max }
    }

    /// The smallest box containing every point ([`Aabb::EMPTY`] for no points).
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, Self::grown_by_point)
    }

    /// Whether the box contains no point.
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// This box grown to contain `p`.
    #[must_use]
    pub fn grown_by_point(self, p: DVec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box containing both boxes.
    #[must_use]
    pub fn union(self, other: Self) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// This box with every face pushed out by `margin` (inward for a negative margin).
    #[must_use]
    pub fn expanded(self, margin: f64) -> Self {
        Self {
            min: self.min - DVec3::splat(margin),
            max: self.max + DVec3::splat(margin),
        }
    }

    /// The centre of the box.
    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// The edge lengths of the box (zero for an empty box).
    pub fn extent(&self) -> DVec3 {
        (self.max - self.min).max(DVec3::ZERO)
    }

    /// Length of the box's diagonal (zero for an empty box). Relative errors in Sphaera are
    /// reported against this length.
    pub fn diagonal(&self) -> f64 {
        self.extent().length()
    }

    /// Index of the longest axis (0 = x, 1 = y, 2 = z).
    pub fn longest_axis(&self) -> usize {
        let e = self.extent();
        if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        }
    }

    /// Whether `p` lies in the closed box.
    pub fn contains_point(&self, p: DVec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// Squared distance from `p` to the box (zero inside).
    pub fn distance_squared_to_point(&self, p: DVec3) -> f64 {
        let d = (self.min - p).max(p - self.max).max(DVec3::ZERO);
        d.length_squared()
    }

    /// Squared distance from `p` to the farthest point of the box.
    pub fn max_distance_squared_to_point(&self, p: DVec3) -> f64 {
        let d = (p - self.min).abs().max((p - self.max).abs());
        d.length_squared()
    }
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // the expected values are exact in binary
mod tests {
    use super::*;

    #[test]
    fn empty_box_is_union_identity() {
        let b = Aabb::new(DVec3::ZERO, DVec3::ONE);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.union(b), b);
        assert_eq!(Aabb::EMPTY.diagonal(), 0.0);
    }

    #[test]
    fn distances_to_box() {
        let b = Aabb::new(DVec3::ZERO, DVec3::ONE);
        assert_eq!(b.distance_squared_to_point(DVec3::splat(0.5)), 0.0);
        assert_eq!(b.distance_squared_to_point(DVec3::new(2.0, 0.5, 0.5)), 1.0);
        assert_eq!(b.max_distance_squared_to_point(DVec3::ZERO), 3.0);
    }
}
