//! Minimum enclosing ball of balls.
//!
//! # Algorithm
//!
//! The same iterative support-set method as
//! [`minimum_enclosing_ball`](super::minimum_enclosing_ball), with the "farthest" item being
//! the ball that reaches farthest from the current centre (`|c − cᵢ| + rᵢ`). The smallest
//! enclosing ball of at most five balls is found by trying every subset of at most four of
//! them as the set of internally tangent balls, with the centre in the affine hull of their
//! centres (Fischer and Gärtner, "The smallest enclosing ball of balls", 2004, show the
//! optimal centre is a convex combination of the tangent balls' centres): writing the centre
//! as `c₀ + x`, the tangency conditions `|x − vⱼ| = R − rⱼ` become a linear system in `x` and
//! `R` plus one quadratic equation in `R`. Both roots are kept, and every candidate centre is
//! scored by the largest reach of all five balls, so no root selection or degeneracy
//! threshold can make the answer too small.

use glam::DVec3;
use smallvec::SmallVec;

use super::EnclosingBall;
use super::enclosing_ball_core::{self, Item};
use crate::{MeshError, Sphere};

/// The name used in error messages.
const OPERATION: &str = "minimum enclosing ball of balls";

/// The smallest ball containing all `balls`.
///
/// Every input ball lies inside the result in floating point
/// (`result.contains_sphere(ball, 0.0)` holds for every input), and the radius is optimal up
/// to rounding. Balls of radius 0 are points; a ball containing all others is returned as is.
/// Deterministic.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::Sphere;
/// use sphaera_mesh::geometry::minimum_enclosing_ball_of_balls;
///
/// let balls = [Sphere::new(-DVec3::X, 1.0), Sphere::new(2.0 * DVec3::X, 2.0)];
/// let ball = minimum_enclosing_ball_of_balls(&balls)?;
/// assert!((ball.radius - 3.0).abs() < 1e-15);
/// assert!((ball.center - DVec3::X).length() < 1e-15);
/// assert!(balls.iter().all(|b| ball.contains_sphere(b, 0.0)));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// - [`MeshError::EmptyInput`] when `balls` is empty.
/// - [`MeshError::NonFiniteInput`] when a centre has a NaN or infinite coordinate.
/// - [`MeshError::InvalidParameter`] (named `balls`) when the enclosing ball's radius
///   would exceed `f64::MAX` (coordinates near the ends of the `f64` range).
/// - [`MeshError::InvalidRadius`] when a radius is negative, NaN or infinite.
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
pub fn minimum_enclosing_ball_of_balls(balls: &[Sphere]) -> Result<Sphere, MeshError> {
    minimum_enclosing_ball_of_balls_with_support(balls).map(|ball| ball.sphere)
}

/// [`minimum_enclosing_ball_of_balls`], also returning the indices of the support balls
/// (at most four, internally tangent to the result, in increasing order).
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::Sphere;
/// use sphaera_mesh::geometry::minimum_enclosing_ball_of_balls_with_support;
///
/// let balls = [Sphere::new(DVec3::ZERO, 5.0), Sphere::new(DVec3::X, 1.0)];
/// let ball = minimum_enclosing_ball_of_balls_with_support(&balls)?;
/// assert_eq!(ball.support.as_slice(), &[0]);
/// assert_eq!(ball.sphere, balls[0]);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// As [`minimum_enclosing_ball_of_balls`].
///
/// # Panics
///
/// Never.
pub fn minimum_enclosing_ball_of_balls_with_support(
    balls: &[Sphere],
) -> Result<EnclosingBall, MeshError> {
    for (index, ball) in balls.iter().enumerate() {
        if !ball.center.is_finite() {
            return Err(MeshError::NonFiniteInput {
                operation: OPERATION,
                index,
            });
        }
        if !(ball.radius.is_finite() && ball.radius >= 0.0) {
            return Err(MeshError::InvalidRadius {
                operation: OPERATION,
                index,
                radius: ball.radius,
            });
        }
    }
    let ball = enclosing_ball_core::solve(balls).ok_or(MeshError::EmptyInput {
        operation: OPERATION,
    })?;
    if !ball.sphere.radius.is_finite() {
        return Err(MeshError::InvalidParameter {
            name: "balls",
            value: ball.sphere.radius,
            requirement: "within a ball whose radius is at most f64::MAX",
        });
    }
    Ok(ball)
}

/// How far `ball` reaches from `center`: `|center − ball.center| + ball.radius`.
fn reach(center: DVec3, ball: &Sphere) -> f64 {
    ball.center.distance(center) + ball.radius
}

/// A ball is an item whose extent is its reach from the centre; the boundary centres are
/// those of the balls internally tangent to the boundary set (up to two per set).
impl Item for Sphere {
    fn extent_from(&self, center: DVec3) -> f64 {
        reach(center, self)
    }

    fn center(&self) -> DVec3 {
        self.center
    }

    fn boundary_centers(boundary: &[Self]) -> SmallVec<[DVec3; 2]> {
        tangent_centers(boundary)
    }

    fn radius_for_extent(extent: f64) -> f64 {
        extent
    }

    fn half_bounds(&self) -> (DVec3, DVec3) {
        let (c, r) = (0.5 * self.center, DVec3::splat(0.5 * self.radius));
        (c - r, c + r)
    }

    fn mapped(&self, offset: DVec3, scale: f64) -> Self {
        Sphere::new((self.center - offset) * scale, self.radius * scale)
    }
}

/// Candidate centres (in the affine hull of the centres) of balls internally tangent to all
/// of `balls` (1 to 4 of them): the solutions of the tangency system, finite ones only.
pub(crate) fn tangent_centers(balls: &[Sphere]) -> SmallVec<[DVec3; 2]> {
    let mut out = SmallVec::new();
    let Some((first, rest)) = balls.split_first() else {
        return out;
    };
    if rest.is_empty() {
        out.push(first.center);
        return out;
    }
    let (c0, r0) = (first.center, first.radius);
    let v: SmallVec<[DVec3; 3]> = rest.iter().map(|b| b.center - c0).collect();
    // x · vⱼ = eⱼ + R fⱼ for x = centre − c₀ in the span of the vⱼ.
    let e: SmallVec<[f64; 3]> = rest
        .iter()
        .zip(&v)
        .map(|(b, vj)| 0.5 * (vj.length_squared() - (b.radius - r0) * (b.radius + r0)))
        .collect();
    let f: SmallVec<[f64; 3]> = rest.iter().map(|b| b.radius - r0).collect();
    let Some((lambda_e, lambda_f)) = solve_gram(&v, &e, &f) else {
        return out;
    };
    let xe: DVec3 = v.iter().zip(&lambda_e).map(|(vi, l)| *l * *vi).sum();
    let xf: DVec3 = v.iter().zip(&lambda_f).map(|(vi, l)| *l * *vi).sum();
    // |xe + R xf|² = (R − r₀)²  ⇔  a R² + 2 b R + c = 0.
    let a = xf.length_squared() - 1.0;
    let b = xe.dot(xf) + r0;
    let c = xe.length_squared() - r0 * r0;
    let mut roots: SmallVec<[f64; 2]> = SmallVec::new();
    if a == 0.0 {
        if b != 0.0 {
            roots.push(-c / (2.0 * b));
        }
    } else {
        let discriminant = (b * b - a * c).max(0.0);
        let q = -(b + discriminant.sqrt().copysign(b));
        roots.push(q / a);
        if q != 0.0 {
            roots.push(c / q);
        }
    }
    for radius in roots {
        let center = c0 + xe + radius * xf;
        if center.is_finite() {
            out.push(center);
        }
    }
    out
}

/// Solves `G λ = rhs` for both right-hand sides, `G` the Gram matrix of `v` (1 to 3 vectors),
/// by Gaussian elimination with partial pivoting; `None` when `G` is singular up to rounding.
#[allow(clippy::type_complexity)]
fn solve_gram(
    v: &[DVec3],
    rhs_e: &[f64],
    rhs_f: &[f64],
) -> Option<(SmallVec<[f64; 3]>, SmallVec<[f64; 3]>)> {
    let k = v.len();
    let mut rows: SmallVec<[[f64; 5]; 3]> = SmallVec::new();
    for i in 0..k {
        let mut row = [0.0; 5];
        for (j, vj) in v.iter().enumerate() {
            row[j] = v.get(i)?.dot(*vj);
        }
        row[3] = *rhs_e.get(i)?;
        row[4] = *rhs_f.get(i)?;
        rows.push(row);
    }
    let scale = rows
        .iter()
        .enumerate()
        .map(|(i, row)| row[i])
        .fold(0.0, f64::max);
    for col in 0..k {
        let pivot = (col..k).max_by(|&p, &q| rows[p][col].abs().total_cmp(&rows[q][col].abs()))?;
        rows.swap(col, pivot);
        let pivot_row = rows[col];
        let pivot_value = pivot_row[col].abs();
        if pivot_value.is_nan() || pivot_value <= 64.0 * f64::EPSILON * scale {
            return None;
        }
        for (r, row) in rows.iter_mut().enumerate() {
            if r != col {
                let factor = row[col] / pivot_row[col];
                for (entry, p) in row.iter_mut().zip(pivot_row).skip(col) {
                    *entry -= factor * p;
                }
            }
        }
    }
    let lambda_e = rows.iter().enumerate().map(|(i, r)| r[3] / r[i]).collect();
    let lambda_f = rows.iter().enumerate().map(|(i, r)| r[4] / r[i]).collect();
    Some((lambda_e, lambda_f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Largest reach of `balls` from `center`.
    fn cost(balls: &[Sphere], center: DVec3) -> f64 {
        balls.iter().map(|b| reach(center, b)).fold(0.0, f64::max)
    }

    /// Brute force over all 1- to 4-ball tangency sets: the smallest candidate ball that is
    /// tangent to its set (radius at least each set radius) and contains every ball.
    fn brute_force_radius(balls: &[Sphere]) -> f64 {
        let n = balls.len();
        let scale = balls
            .iter()
            .map(|b| b.center.length() + b.radius)
            .fold(1.0, f64::max);
        let mut best = f64::INFINITY;
        for mask in 1u32..(1 << n) {
            if mask.count_ones() > 4 {
                continue;
            }
            let chosen: Vec<Sphere> = (0..n)
                .filter(|i| mask & (1 << i) != 0)
                .map(|i| balls[i])
                .collect();
            for center in tangent_centers(&chosen) {
                let r = cost(&chosen, center);
                if cost(balls, center) <= r + 1e-10 * scale {
                    best = best.min(r);
                }
            }
        }
        best
    }

    fn ball() -> impl Strategy<Value = Sphere> {
        prop_oneof![
            (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64, 0.0..4.0f64)
                .prop_map(|(x, y, z, r)| Sphere::new(DVec3::new(x, y, z), r)),
            // Integer grid: duplicates, coplanar and collinear centres, equal radii.
            (-1i8..=1, -1i8..=1, -1i8..=1, 0u8..3).prop_map(|(x, y, z, r)| {
                Sphere::new(
                    DVec3::new(f64::from(x), f64::from(y), f64::from(z)),
                    f64::from(r) * 0.5,
                )
            }),
            (-5.0..5.0f64, 0.0..1.0f64).prop_map(|(t, r)| Sphere::new(DVec3::new(t, -t, 1.0), r)),
        ]
    }

    fn check(balls: &[Sphere]) {
        let result = minimum_enclosing_ball_of_balls_with_support(balls).unwrap();
        let s = result.sphere;
        for b in balls {
            assert!(s.contains_sphere(b, 0.0), "{b:?} outside {s:?}");
        }
        let scale = balls
            .iter()
            .map(|b| b.center.length() + b.radius)
            .fold(1.0, f64::max);
        let brute = brute_force_radius(balls);
        assert!(
            (s.radius - brute).abs() <= 1e-9 * brute + 1e-12 * scale,
            "radius {} vs brute force {brute} for {balls:?}",
            s.radius
        );
        // Independent optimality check: the cost is convex, so no small step may lower it.
        let h = 1e-6 * scale;
        for x in -1..=1 {
            for y in -1..=1 {
                for z in -1..=1 {
                    let step = DVec3::new(f64::from(x), f64::from(y), f64::from(z)) * h;
                    assert!(cost(balls, s.center + step) >= s.radius - 1e-12 * scale);
                }
            }
        }
    }

    proptest! {
        #[test]
        fn matches_brute_force_on_small_sets(balls in prop::collection::vec(ball(), 1..=8)) {
            check(&balls);
        }

        #[test]
        fn points_as_balls_agree_with_the_point_method(
            points in prop::collection::vec((-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64), 1..40)
        ) {
            let points: Vec<DVec3> = points.into_iter().map(|(x, y, z)| DVec3::new(x, y, z)).collect();
            let balls: Vec<Sphere> = points.iter().map(|&p| Sphere::new(p, 0.0)).collect();
            let a = minimum_enclosing_ball_of_balls(&balls).unwrap();
            let b = super::super::minimum_enclosing_ball(&points).unwrap();
            prop_assert!((a.radius - b.radius).abs() <= 1e-9 * b.radius + 1e-12);
        }

        #[test]
        fn contains_large_sets(balls in prop::collection::vec(ball(), 50..200)) {
            let s = minimum_enclosing_ball_of_balls(&balls).unwrap();
            prop_assert!(balls.iter().all(|b| s.contains_sphere(b, 0.0)));
        }
    }

    #[test]
    fn invalid_inputs_are_errors() {
        assert!(matches!(
            minimum_enclosing_ball_of_balls(&[]),
            Err(MeshError::EmptyInput { .. })
        ));
        let bad = [Sphere::new(DVec3::ZERO, 1.0), Sphere::new(DVec3::X, -1.0)];
        assert!(matches!(
            minimum_enclosing_ball_of_balls(&bad),
            Err(MeshError::InvalidRadius { index: 1, .. })
        ));
        let bad = [Sphere::new(DVec3::INFINITY, 1.0)];
        assert!(matches!(
            minimum_enclosing_ball_of_balls(&bad),
            Err(MeshError::NonFiniteInput { index: 0, .. })
        ));
    }

    #[test]
    fn duplicates_and_nested_balls() {
        let b = Sphere::new(DVec3::ONE, 2.0);
        assert_eq!(minimum_enclosing_ball_of_balls(&[b; 6]).unwrap(), b);
        let nested = [
            Sphere::new(DVec3::ZERO, 1.0),
            Sphere::new(DVec3::ZERO, 3.0),
            Sphere::new(DVec3::X, 2.0),
        ];
        assert_eq!(minimum_enclosing_ball_of_balls(&nested).unwrap(), nested[1]);
    }

    #[test]
    fn four_unit_balls_on_a_regular_tetrahedron() {
        let corners = [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ];
        let balls: Vec<Sphere> = corners.iter().map(|&c| Sphere::new(c, 1.0)).collect();
        let s = minimum_enclosing_ball_of_balls(&balls).unwrap();
        assert!(s.center.length() < 1e-14);
        assert!((s.radius - (3f64.sqrt() + 1.0)).abs() < 1e-14);
    }

    #[test]
    fn huge_balls_give_a_finite_enclosing_ball() {
        let balls = [
            Sphere::new(DVec3::new(-1e200, 0.0, 0.0), 1e200),
            Sphere::new(DVec3::new(2e200, 0.0, 0.0), 2e200),
            Sphere::new(DVec3::new(0.0, 1e199, 0.0), 1e199),
        ];
        let ball = minimum_enclosing_ball_of_balls(&balls).unwrap();
        assert!(ball.radius.is_finite());
        assert!((ball.radius / 3e200 - 1.0).abs() < 1e-14, "{ball:?}");
        // Distances measured in units of 2^664 ≈ 1e200 (exact scaling, no overflow).
        let unit = 2f64.powi(-664);
        assert!(((ball.center - DVec3::new(1e200, 0.0, 0.0)) * unit).length() < 1e-13);
        for b in balls {
            let reach = ((b.center - ball.center) * unit).length() + b.radius * unit;
            assert!(reach <= ball.radius * unit);
        }
        let far = [
            Sphere::new(DVec3::splat(-f64::MAX), 1.0),
            Sphere::new(DVec3::splat(f64::MAX), f64::MAX),
        ];
        assert!(matches!(
            minimum_enclosing_ball_of_balls(&far),
            Err(MeshError::InvalidParameter { name: "balls", .. })
        ));
    }

    #[test]
    fn tiny_balls_keep_their_precision() {
        let balls = [
            Sphere::new(-DVec3::X * 1e-200, 1e-200),
            Sphere::new(2.0 * DVec3::X * 1e-200, 2e-200),
        ];
        let ball = minimum_enclosing_ball_of_balls(&balls).unwrap();
        assert!((ball.radius / 3e-200 - 1.0).abs() < 1e-14, "{ball:?}");
        assert!((ball.center / 1e-200 - DVec3::X).length() < 1e-14);
        assert!(balls.iter().all(|b| ball.contains_sphere(b, 0.0)));
    }
}
