//! The points a polyline is made of: one small trait over `DVec2` and `DVec3`, and the
//! point–segment distance every other file uses.

use std::fmt::Debug;
use std::ops::{Add, Mul, Sub};

use glam::{DVec2, DVec3};

mod sealed {
    /// Keeps [`PolylinePoint`](super::PolylinePoint) implemented for `DVec2` and `DVec3` only.
    pub trait Sealed {}
    impl Sealed for glam::DVec2 {}
    impl Sealed for glam::DVec3 {}
}

/// A point of a 2D or 3D polyline: implemented for [`DVec2`] and [`DVec3`] (sealed), so
/// every polyline algorithm is written once for both dimensions.
///
/// # Examples
///
/// ```
/// use sphaera_sweep::polyline::PolylinePoint;
/// use glam::{DVec2, DVec3};
///
/// assert_eq!(DVec2::new(3.0, 4.0).dot(DVec2::new(3.0, 4.0)), 25.0);
/// assert_eq!(DVec3::new(1.0, 2.0, 3.0).coordinates(), [1.0, 2.0, 3.0]);
/// assert_eq!(DVec2::new(1.0, 2.0).coordinates(), [1.0, 2.0, 0.0]);
/// assert!(!DVec3::new(f64::NAN, 0.0, 0.0).is_finite());
/// ```
pub trait PolylinePoint:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f64, Output = Self>
    + sealed::Sealed
{
    /// The number of coordinates (2 or 3).
    const DIMENSION: usize;

    /// The dot product.
    fn dot(self, other: Self) -> f64;

    /// Whether every coordinate is finite (neither NaN nor infinite).
    fn is_finite(self) -> bool;

    /// The coordinates `[x, y, z]` (`z = 0` in 2D), for messages and bounding boxes.
    fn coordinates(self) -> [f64; 3];

    /// The largest absolute coordinate (the scale of the rounding of this point).
    fn max_abs(self) -> f64 {
        let [x, y, z] = self.coordinates();
        x.abs().max(y.abs()).max(z.abs())
    }

    /// The Euclidean length.
    fn length(self) -> f64 {
        self.dot(self).sqrt()
    }
}

impl PolylinePoint for DVec2 {
    const DIMENSION: usize = 2;

    fn dot(self, other: Self) -> f64 {
        DVec2::dot(self, other)
    }

    fn is_finite(self) -> bool {
        DVec2::is_finite(self)
    }

    fn coordinates(self) -> [f64; 3] {
        [self.x, self.y, 0.0]
    }
}

impl PolylinePoint for DVec3 {
    const DIMENSION: usize = 3;

    fn dot(self, other: Self) -> f64 {
        DVec3::dot(self, other)
    }

    fn is_finite(self) -> bool {
        DVec3::is_finite(self)
    }

    fn coordinates(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
}

/// The closest point of a segment to a query point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegmentHit<P> {
    /// The closest point.
    pub point: P,
    /// Its parameter along the segment, in `[0, 1]` (`0` at the start; `0` for a segment
    /// of zero length).
    pub parameter: f64,
    /// The squared distance to the query point.
    pub distance_squared: f64,
}

/// The closest point of segment `[a, b]` to `p`. The parameter is clamped to `[0, 1]`, and
/// the point is exactly `a` or `b` at the ends (never a rounded `a + (b − a)`).
pub(crate) fn closest_on_segment<P: PolylinePoint>(p: P, a: P, b: P) -> SegmentHit<P> {
    let ab = b - a;
    let length_squared = ab.dot(ab);
    let t = if length_squared > 0.0 {
        ((p - a).dot(ab) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let point = if t <= 0.0 {
        a
    } else if t >= 1.0 {
        b
    } else {
        a + ab * t
    };
    let d = p - point;
    SegmentHit {
        point,
        parameter: t,
        distance_squared: d.dot(d),
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values on exactly representable inputs
mod tests {
    use super::*;

    #[test]
    fn segment_ends_interior_and_degenerate() {
        let (a, b) = (DVec2::new(0.0, 0.0), DVec2::new(2.0, 0.0));
        let mid = closest_on_segment(DVec2::new(1.0, 3.0), a, b);
        assert_eq!(mid.point, DVec2::new(1.0, 0.0));
        assert_eq!(mid.parameter, 0.5);
        assert_eq!(mid.distance_squared, 9.0);
        let before = closest_on_segment(DVec2::new(-1.0, 0.0), a, b);
        assert_eq!((before.point, before.parameter), (a, 0.0));
        let after = closest_on_segment(DVec2::new(5.0, 4.0), a, b);
        assert_eq!((after.point, after.parameter), (b, 1.0));
        assert_eq!(after.distance_squared, 25.0);
        let point = DVec3::new(1.0, 1.0, 1.0);
        let degenerate = closest_on_segment(DVec3::ZERO, point, point);
        assert_eq!((degenerate.point, degenerate.parameter), (point, 0.0));
        assert_eq!(degenerate.distance_squared, 3.0);
    }
}
