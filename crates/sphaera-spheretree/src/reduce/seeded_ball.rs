//! The minimum enclosing ball of a union of point sets whose own balls are known: the
//! merge reducer asks for it once per candidate pair, so it must not cost a full solve.

use glam::DVec3;
use sphaera_mesh::Sphere;
use sphaera_mesh::geometry::minimum_enclosing_ball_with_support;

/// Points a seeded solve's core set may hold before it gives up on seeding and solves the
/// whole set (never reached in practice: a handful of points suffice).
const MAX_CORE: usize = 64;

/// A point counts as outside the core's ball when it is farther than the radius by more
/// than this fraction of it (rounding of the core's solve).
const OUTSIDE_TOLERANCE: f64 = 1e-12;

/// A minimum enclosing ball, the points on its boundary that determine it (at most four)
/// and the nearest point of the set to its centre.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SeededBall {
    /// The ball, its radius the largest distance from its centre to a point of the set
    /// (so every point is inside despite rounding).
    pub sphere: Sphere,
    /// The support points: the seed of the next union's solve.
    pub support: Vec<DVec3>,
    /// The smallest distance from the centre to a point of the set.
    pub nearest: f64,
}

/// The minimum enclosing ball of the points `points()` yields, starting from `seed` (points
/// of the set, e.g. the supports of the balls of two subsets). A core set — the seed — is
/// solved exactly, the farthest point outside its ball joins it, and so on until no point
/// is outside. The ball only grows and the core is a subset of the points, so the result
/// is the minimum enclosing ball of the whole set; each round is one pass over the points
/// plus a solve of a few points, and a good seed needs one or two rounds instead of the
/// dozens of passes a cold solve makes.
///
/// `None` when the set is empty or not finite.
pub(crate) fn seeded_enclosing_ball<I>(points: impl Fn() -> I, seed: &[DVec3]) -> Option<SeededBall>
where
    I: Iterator<Item = DVec3>,
{
    let mut core: Vec<DVec3> = seed.to_vec();
    if core.is_empty() {
        core.push(points().next()?);
    }
    loop {
        // Never in practice: a core this large gives way to a solve of the whole set,
        // which contains every point and so ends the loop.
        let whole = core.len() > MAX_CORE;
        if whole {
            core = points().collect();
        }
        let ball = minimum_enclosing_ball_with_support(&core).ok()?;
        let center = ball.sphere.center;
        let (far, far_point, near) = points().fold(
            (0.0, center, f64::INFINITY),
            |(far, far_point, near): (f64, DVec3, f64), p| {
                let d = p.distance(center);
                if d > far {
                    (d, p, near.min(d))
                } else {
                    (far, far_point, near.min(d))
                }
            },
        );
        if whole || far <= ball.sphere.radius * (1.0 + OUTSIDE_TOLERANCE) {
            return Some(SeededBall {
                sphere: Sphere::new(center, ball.sphere.radius.max(far)),
                support: ball.support.iter().map(|&i| core[i]).collect(),
                nearest: near,
            });
        }
        core.push(far_point);
    }
}

#[cfg(test)]
mod tests {
    use super::seeded_enclosing_ball;
    use glam::DVec3;
    use proptest::prelude::*;
    use sphaera_mesh::geometry::minimum_enclosing_ball;

    fn point() -> impl Strategy<Value = DVec3> {
        (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    proptest! {
        /// The seeded ball of a union equals the cold solve of the whole union, whatever
        /// the seed (the supports of the parts, a single point, nothing).
        #[test]
        fn seeded_ball_is_the_minimum_enclosing_ball(
            a in prop::collection::vec(point(), 1..60),
            b in prop::collection::vec(point(), 1..60),
            seed_kind in 0..3usize,
        ) {
            let all: Vec<DVec3> = a.iter().chain(&b).copied().collect();
            let reference = minimum_enclosing_ball(&all).unwrap();
            let seed: Vec<DVec3> = match seed_kind {
                0 => {
                    let part = |s: &[DVec3]| seeded_enclosing_ball(|| s.iter().copied(), &[]).unwrap().support;
                    part(&a).into_iter().chain(part(&b)).collect()
                }
                1 => vec![b[0]],
                _ => Vec::new(),
            };
            let ball = seeded_enclosing_ball(|| all.iter().copied(), &seed).unwrap();
            let scale = reference.radius.max(1.0);
            prop_assert!((ball.sphere.radius - reference.radius).abs() <= 1e-9 * scale);
            prop_assert!(ball.sphere.center.distance(reference.center) <= 1e-6 * scale);
            for p in &all {
                prop_assert!(ball.sphere.contains_point(*p, 0.0));
            }
            let nearest = all.iter().map(|p| p.distance(ball.sphere.center)).fold(f64::INFINITY, f64::min);
            prop_assert!((ball.nearest - nearest).abs() <= 1e-12 * scale);
            prop_assert!(!ball.support.is_empty() && ball.support.len() <= 4);
        }
    }

    #[test]
    fn empty_set_has_no_ball() {
        assert!(seeded_enclosing_ball(std::iter::empty, &[]).is_none());
    }
}
