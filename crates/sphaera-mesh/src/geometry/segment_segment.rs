//! Closest points between two segments (for capsules and polylines).

use glam::DVec3;

use super::closest_point_on_segment;

/// The closest pair of points between two segments, from [`closest_points_between_segments`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentPairClosestPoints {
    /// Parameter on the first segment: `point_on_first = p0 + s (p1 − p0)`, in `[0, 1]`.
    pub s: f64,
    /// Parameter on the second segment: `point_on_second = q0 + t (q1 − q0)`, in `[0, 1]`.
    pub t: f64,
    /// The closest point on the first segment.
    pub point_on_first: DVec3,
    /// The closest point on the second segment.
    pub point_on_second: DVec3,
    /// Squared distance between the two points.
    pub distance_squared: f64,
}

/// The closest points between the segments `p0 p1` and `q0 q1`.
///
/// The answer is the best of the interior solution (when the segments are not parallel and
/// it falls inside both) and the four endpoint-to-segment projections, so parallel,
/// overlapping and zero-length segments are handled without special thresholds, and the
/// returned points always lie on the segments. For parallel overlapping segments, the pair
/// returned is one of the (infinitely many) closest pairs, chosen deterministically.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::closest_points_between_segments;
///
/// // Two skew segments crossing at a distance of 1.
/// let c = closest_points_between_segments(
///     DVec3::new(-1.0, 0.0, 0.0),
///     DVec3::new(1.0, 0.0, 0.0),
///     DVec3::new(0.0, -1.0, 1.0),
///     DVec3::new(0.0, 1.0, 1.0),
/// );
/// assert_eq!((c.s, c.t), (0.5, 0.5));
/// assert_eq!(c.distance_squared, 1.0);
/// ```
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Constant time, no allocation.
pub fn closest_points_between_segments(
    p0: DVec3,
    p1: DVec3,
    q0: DVec3,
    q1: DVec3,
) -> SegmentPairClosestPoints {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    let mut best = {
        let hit = closest_point_on_segment(p0, q0, q1);
        pair(0.0, hit.t, p0, hit.point)
    };
    let mut consider = |candidate: SegmentPairClosestPoints| {
        if candidate.distance_squared < best.distance_squared {
            best = candidate;
        }
    };
    let hit = closest_point_on_segment(p1, q0, q1);
    consider(pair(1.0, hit.t, p1, hit.point));
    let hit = closest_point_on_segment(q0, p0, p1);
    consider(pair(hit.t, 0.0, hit.point, q0));
    let hit = closest_point_on_segment(q1, p0, p1);
    consider(pair(hit.t, 1.0, hit.point, q1));

    // Interior solution of the 2×2 normal equations.
    let r = p0 - q0;
    let a = d1.length_squared();
    let b = d1.dot(d2);
    let e = d2.length_squared();
    let c = d1.dot(r);
    let f = d2.dot(r);
    let denominator = a * e - b * b;
    if denominator > 0.0 {
        let s = (b * f - c * e) / denominator;
        let t = (a * f - b * c) / denominator;
        if s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0 {
            consider(pair(s, t, p0 + s * d1, q0 + t * d2));
        }
    }
    best
}

fn pair(s: f64, t: f64, first: DVec3, second: DVec3) -> SegmentPairClosestPoints {
    SegmentPairClosestPoints {
        s,
        t,
        point_on_first: first,
        point_on_second: second,
        distance_squared: first.distance_squared(second),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point() -> impl Strategy<Value = DVec3> {
        (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn check(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) {
        let c = closest_points_between_segments(p0, p1, q0, q1);
        let scale = 1.0
            + [p0, p1, q0, q1]
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max);
        // Brute force: dense sampling of both segments plus exact endpoint projections.
        let n = 120;
        let mut brute = f64::INFINITY;
        for i in 0..=n {
            let x = p0.lerp(p1, f64::from(i) / f64::from(n));
            for j in 0..=n {
                brute = brute.min(x.distance_squared(q0.lerp(q1, f64::from(j) / f64::from(n))));
            }
            brute = brute.min(closest_point_on_segment(x, q0, q1).distance_squared);
        }
        assert!(c.distance_squared.sqrt() <= brute.sqrt() + 1e-12 * scale);
        assert!((0.0..=1.0).contains(&c.s) && (0.0..=1.0).contains(&c.t));
        assert!(c.point_on_first.distance(p0.lerp(p1, c.s)) <= 1e-12 * scale);
        assert!(c.point_on_second.distance(q0.lerp(q1, c.t)) <= 1e-12 * scale);
        assert!(
            (c.point_on_first.distance_squared(c.point_on_second) - c.distance_squared).abs()
                <= 1e-12 * scale * scale
        );
    }

    proptest! {
        #[test]
        fn matches_brute_force(p0 in point(), p1 in point(), q0 in point(), q1 in point()) {
            check(p0, p1, q0, q1);
        }

        #[test]
        fn degenerate_pairs_match_brute_force(p0 in point(), p1 in point(), off in point(), s in -2.0..2.0f64, kind in 0..3u8) {
            match kind {
                // Parallel segments.
                0 => check(p0, p1, p0 + off, p0 + off + s * (p1 - p0)),
                // Collinear, overlapping or not.
                1 => check(p0, p1, p0.lerp(p1, s), p0.lerp(p1, s + 0.5)),
                // Zero-length segments.
                _ => check(p0, p0, off, if s > 0.0 { off } else { p1 }),
            }
        }
    }
}
