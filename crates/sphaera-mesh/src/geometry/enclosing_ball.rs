//! Minimum enclosing ball of points.
//!
//! # Algorithm
//!
//! An iterative support-set method in the spirit of Gärtner's pivoting variant of Welzl's
//! algorithm ("Fast and robust smallest enclosing balls", ESA 1999): keep a support set of
//! at most four points and its smallest enclosing ball; find the input point farthest from
//! the centre; if it lies outside, replace the ball by the smallest enclosing ball of the
//! support set plus that point (at most five points, solved exactly by trying every subset
//! of at most four of them as the boundary set). The radius grows strictly at every step and
//! only finitely many support sets exist, so the loop ends; no recursion, no randomness.
//! The loop is shared with the ball-of-balls method (`enclosing_ball_core`).
//!
//! Every candidate ball is scored by the largest distance from its centre to the five
//! points, never by its own circumradius, so nearly degenerate (collinear, coplanar) boundary
//! sets can never produce a too-small ball: they simply lose to a better candidate.

use glam::DVec3;
use smallvec::SmallVec;

use super::circumsphere::{
    ball_through_two_points, circumball_of_triangle, circumsphere, covering_radius,
};
use super::enclosing_ball_core::{self, Item};
use crate::{MeshError, Sphere};

/// The name used in error messages.
const OPERATION: &str = "minimum enclosing ball of points";

/// A minimum enclosing ball with the input points that determine it.
#[derive(Clone, Debug, PartialEq)]
pub struct EnclosingBall {
    /// The ball: every input item lies inside it.
    pub sphere: Sphere,
    /// Indices (into the input slice) of at most four items on the ball's boundary that
    /// determine it, in increasing order.
    pub support: SmallVec<[usize; 4]>,
}

/// The smallest ball containing all `points`.
///
/// Exact up to rounding: every point lies inside the returned ball in floating point
/// (`p.distance(center) <= radius` and `contains_point(p, 0.0)` hold for every input), and
/// the radius exceeds the optimal one by a few units in the last place for well-spread
/// inputs. Duplicates, collinear, coplanar and cospherical points are handled; a single point
/// gives a ball of radius 0. The result is deterministic (it depends only on the input
/// order).
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::minimum_enclosing_ball;
///
/// let points = [DVec3::X, -DVec3::X, DVec3::Y * 0.5, DVec3::Z * 0.2];
/// let ball = minimum_enclosing_ball(&points)?;
/// assert!(ball.center.length() < 1e-15);
/// assert!((ball.radius - 1.0).abs() < 1e-15);
/// assert!(points.iter().all(|&p| ball.contains_point(p, 0.0)));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// - [`MeshError::EmptyInput`] when `points` is empty.
/// - [`MeshError::NonFiniteInput`] when a point has a NaN or infinite coordinate.
/// - [`MeshError::InvalidParameter`] (named `points`) when the enclosing ball's radius
///   would exceed `f64::MAX` (coordinates near the ends of the `f64` range).
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// `O(n)` per pivot step, and few pivot steps in practice (no bench times it yet: see the
/// section *Other primitives (no bench yet)* of `docs/benchmarks.md` in the repository).
/// No allocation, except a copy of the input when its bounding box is larger than 1e100
/// or smaller than 1e-100: such inputs are solved translated and scaled to unit size
/// (exactly, by a power of two) so that squared distances neither overflow nor underflow.
pub fn minimum_enclosing_ball(points: &[DVec3]) -> Result<Sphere, MeshError> {
    minimum_enclosing_ball_with_support(points).map(|ball| ball.sphere)
}

/// [`minimum_enclosing_ball`], also returning the indices of the support points.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::minimum_enclosing_ball_with_support;
///
/// let points = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(2.0, 1.0, 0.0)];
/// let ball = minimum_enclosing_ball_with_support(&points)?;
/// assert_eq!(ball.support.as_slice(), &[0, 1]);
/// assert_eq!(ball.sphere.radius, 2.0);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// As [`minimum_enclosing_ball`].
///
/// # Panics
///
/// Never.
pub fn minimum_enclosing_ball_with_support(points: &[DVec3]) -> Result<EnclosingBall, MeshError> {
    if let Some(index) = points.iter().position(|p| !p.is_finite()) {
        return Err(MeshError::NonFiniteInput {
            operation: OPERATION,
            index,
        });
    }
    let ball = enclosing_ball_core::solve(points).ok_or(MeshError::EmptyInput {
        operation: OPERATION,
    })?;
    if !ball.sphere.radius.is_finite() {
        return Err(MeshError::InvalidParameter {
            name: "points",
            value: ball.sphere.radius,
            requirement: "within a ball whose radius is at most f64::MAX",
        });
    }
    Ok(ball)
}

/// A point is an item whose extent is its squared distance from the centre.
impl Item for DVec3 {
    fn extent_from(&self, center: DVec3) -> f64 {
        self.distance_squared(center)
    }

    fn center(&self) -> DVec3 {
        *self
    }

    fn boundary_centers(boundary: &[Self]) -> SmallVec<[DVec3; 2]> {
        circumcenter(boundary).into_iter().collect()
    }

    fn radius_for_extent(extent: f64) -> f64 {
        covering_radius(extent)
    }

    fn half_bounds(&self) -> (DVec3, DVec3) {
        (0.5 * *self, 0.5 * *self)
    }

    fn mapped(&self, offset: DVec3, scale: f64) -> Self {
        (*self - offset) * scale
    }
}

/// The centre of the smallest ball with all of `points` (1 to 4) on its boundary, or `None`
/// for an affinely dependent set.
fn circumcenter(points: &[DVec3]) -> Option<DVec3> {
    match *points {
        [a] => Some(a),
        [a, b] => Some(ball_through_two_points(a, b).center),
        [a, b, c] => circumball_of_triangle(a, b, c).map(|s| s.center),
        [a, b, c, d] => circumsphere(a, b, c, d).map(|s| s.center),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Brute force: among all balls with 1 to 4 of the points on the boundary (centre in
    /// their affine hull, solved by Gaussian elimination of the Gram system, independently
    /// of the closed forms used above) that contain every point, the smallest radius.
    pub(crate) fn brute_force_radius(points: &[DVec3]) -> f64 {
        let n = points.len();
        let scale = points.iter().map(|p| p.length()).fold(1.0, f64::max);
        let mut best = f64::INFINITY;
        for mask in 1u32..(1 << n) {
            if mask.count_ones() > 4 {
                continue;
            }
            let chosen: Vec<DVec3> = (0..n)
                .filter(|i| mask & (1 << i) != 0)
                .map(|i| points[i])
                .collect();
            let Some(center) = gram_circumcenter(&chosen) else {
                continue;
            };
            let r = chosen
                .iter()
                .map(|p| p.distance(center))
                .fold(0.0, f64::max);
            if points
                .iter()
                .all(|p| p.distance(center) <= r * (1.0 + 1e-10) + 1e-12 * scale)
            {
                best = best.min(r);
            }
        }
        best
    }

    /// Centre in the affine hull equidistant from all points, by Gram elimination.
    fn gram_circumcenter(points: &[DVec3]) -> Option<DVec3> {
        let origin = points[0];
        let v: Vec<DVec3> = points[1..].iter().map(|&p| p - origin).collect();
        let k = v.len();
        let mut m = vec![vec![0.0; k + 1]; k];
        for i in 0..k {
            for j in 0..k {
                m[i][j] = 2.0 * v[i].dot(v[j]);
            }
            m[i][k] = v[i].length_squared();
        }
        let scale = (0..k).map(|i| m[i][i]).fold(0.0, f64::max);
        for col in 0..k {
            let pivot = (col..k).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
            m.swap(col, pivot);
            if m[col][col].abs() <= 1e-10 * scale {
                return None;
            }
            let pivot_row = m[col].clone();
            for (r, row) in m.iter_mut().enumerate() {
                if r != col {
                    let f = row[col] / pivot_row[col];
                    for (entry, p) in row.iter_mut().zip(&pivot_row).skip(col) {
                        *entry -= f * p;
                    }
                }
            }
        }
        let mut center = origin;
        for i in 0..k {
            center += (m[i][k] / m[i][i]) * v[i];
        }
        Some(center)
    }

    fn check(points: &[DVec3]) {
        let ball = minimum_enclosing_ball_with_support(points).unwrap();
        let s = ball.sphere;
        for &p in points {
            assert!(s.contains_point(p, 0.0), "{p:?} outside {s:?}");
            assert!(p.distance(s.center) <= s.radius);
        }
        for &i in &ball.support {
            assert!(i < points.len());
        }
        let brute = brute_force_radius(points);
        let scale = points.iter().map(|p| p.length()).fold(1.0, f64::max);
        assert!(
            (s.radius - brute).abs() <= 1e-9 * brute + 1e-12 * scale,
            "radius {} vs brute force {brute} for {points:?}",
            s.radius
        );
    }

    /// Points that are often duplicated, collinear, coplanar or cospherical.
    fn nasty_point() -> impl Strategy<Value = DVec3> {
        prop_oneof![
            (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64)
                .prop_map(|(x, y, z)| DVec3::new(x, y, z)),
            (-1i8..=1, -1i8..=1, -1i8..=1).prop_map(|(x, y, z)| DVec3::new(
                f64::from(x),
                f64::from(y),
                f64::from(z)
            )),
            (0.0..std::f64::consts::TAU, -1.0..1.0f64).prop_map(|(phi, z)| {
                let r = (1.0 - z * z).sqrt();
                DVec3::new(r * phi.cos(), r * phi.sin(), z) * 3.0 + DVec3::new(1.0, 2.0, 3.0)
            }),
            (-5.0..5.0f64).prop_map(|t| DVec3::new(t, 2.0 * t, -t)),
            (-5.0..5.0f64, -5.0..5.0f64).prop_map(|(x, y)| DVec3::new(x, y, 0.5)),
        ]
    }

    proptest! {
        #[test]
        fn matches_brute_force_on_small_sets(points in prop::collection::vec(nasty_point(), 1..=8)) {
            check(&points);
        }

        #[test]
        fn contains_large_random_sets(points in prop::collection::vec(nasty_point(), 50..300)) {
            let s = minimum_enclosing_ball(&points).unwrap();
            prop_assert!(points.iter().all(|&p| s.contains_point(p, 0.0)));
            // The support determines the ball: its own minimum ball has the same radius.
            let ball = minimum_enclosing_ball_with_support(&points).unwrap();
            let support: Vec<DVec3> = ball.support.iter().map(|&i| points[i]).collect();
            let inner = minimum_enclosing_ball(&support).unwrap();
            prop_assert!((inner.radius - s.radius).abs() <= 1e-9 * s.radius + 1e-12);
        }
    }

    #[test]
    fn empty_and_non_finite_inputs_are_errors() {
        assert!(matches!(
            minimum_enclosing_ball(&[]),
            Err(MeshError::EmptyInput { .. })
        ));
        let err = minimum_enclosing_ball(&[DVec3::ZERO, DVec3::new(0.0, f64::NAN, 0.0)]);
        assert!(matches!(
            err,
            Err(MeshError::NonFiniteInput { index: 1, .. })
        ));
    }

    #[test]
    fn single_point_and_duplicates() {
        let s = minimum_enclosing_ball(&[DVec3::ONE]).unwrap();
        assert_eq!(s, Sphere::new(DVec3::ONE, 0.0));
        let s = minimum_enclosing_ball(&[DVec3::ONE; 5]).unwrap();
        assert_eq!(s, Sphere::new(DVec3::ONE, 0.0));
    }

    #[test]
    fn many_cospherical_points() {
        // A Fibonacci sphere of 2,000 points, radius 7 around (1, -2, 3).
        let center = DVec3::new(1.0, -2.0, 3.0);
        let points: Vec<DVec3> = sphaera_tests::point_sets::fibonacci_sphere(2000)
            .into_iter()
            .map(|d| center + 7.0 * d)
            .collect();
        let s = minimum_enclosing_ball(&points).unwrap();
        assert!(s.center.distance(center) < 1e-9);
        assert!((s.radius - 7.0).abs() < 1e-9);
        assert!(points.iter().all(|&p| s.contains_point(p, 0.0)));
    }

    #[test]
    fn deterministic_and_collinear() {
        let points: Vec<DVec3> = (0..100)
            .map(|i| DVec3::new(f64::from(i) * 0.37 % 5.0, 0.0, 0.0))
            .collect();
        let a = minimum_enclosing_ball_with_support(&points).unwrap();
        let b = minimum_enclosing_ball_with_support(&points).unwrap();
        assert_eq!(a, b);
        let max = points.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
        let min = points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
        assert!((a.sphere.radius - 0.5 * (max - min)).abs() < 1e-14);
        assert_eq!(a.support.len(), 2);
    }

    #[test]
    fn huge_coordinates_give_a_finite_enclosing_ball() {
        // Squared extents of ±1e200 overflow; the ball used to come back with radius inf.
        let points = [
            DVec3::new(1e200, 0.0, 0.0),
            DVec3::new(-1e200, 0.0, 0.0),
            DVec3::new(0.0, 5e199, 0.0),
            DVec3::new(0.0, 0.0, -3e199),
        ];
        let ball = minimum_enclosing_ball(&points).unwrap();
        assert!(ball.radius.is_finite());
        assert!((ball.radius / 1e200 - 1.0).abs() < 1e-14, "{ball:?}");
        // Distances measured in units of 2^664 ≈ 1e200 (exact scaling, no overflow).
        let unit = 2f64.powi(-664);
        assert!((ball.center * unit).length() < 1e-13);
        for p in points {
            assert!(((p - ball.center) * unit).length() <= ball.radius * unit);
        }
        // Near the ends of the f64 range the radius itself is not representable.
        let corners = [DVec3::splat(f64::MAX), DVec3::splat(-f64::MAX)];
        assert!(matches!(
            minimum_enclosing_ball(&corners),
            Err(MeshError::InvalidParameter { name: "points", .. })
        ));
        // A lone huge point needs no rescaling.
        let lone = minimum_enclosing_ball(&[DVec3::splat(f64::MAX)]).unwrap();
        assert_eq!(lone, Sphere::new(DVec3::splat(f64::MAX), 0.0));
    }

    #[test]
    fn tiny_coordinates_keep_their_precision() {
        // Squared extents of 1e-200 underflow to zero.
        let unit = [DVec3::X, -DVec3::X, 0.5 * DVec3::Y, 0.2 * DVec3::Z];
        let tiny: Vec<DVec3> = unit.iter().map(|&p| p * 1e-200).collect();
        let ball = minimum_enclosing_ball(&tiny).unwrap();
        assert!((ball.radius / 1e-200 - 1.0).abs() < 1e-14, "{ball:?}");
        assert!(ball.center.length() < 1e-214);
        assert!(
            tiny.iter()
                .all(|&p| p.distance(ball.center) <= ball.radius * (1.0 + 1e-15))
        );
    }

    #[test]
    fn moderate_inputs_are_not_rescaled() {
        // Below the rescaling threshold the result is the plain solve, bit for bit.
        let points = [
            DVec3::new(1e99, 0.0, 0.0),
            DVec3::new(-1e99, 1.0, 0.0),
            DVec3::new(0.3e99, 0.7e99, 0.1e99),
        ];
        assert_eq!(
            minimum_enclosing_ball_with_support(&points).unwrap(),
            enclosing_ball_core::solve_as_given(&points).unwrap()
        );
    }
}
