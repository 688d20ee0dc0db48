//! Polyline queries against brute force (every segment), in 2D and 3D, open and closed,
//! fresh and coherent; and the failure cases.

// Exact zeros and exact vertex coordinates are part of the contract checked here.
#![allow(clippy::float_cmp)]

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use sphaera_sweep::polyline::{
    Polyline, PolylineClosest, PolylineDefect, PolylineFeature, PolylinePoint,
    PolylineSessionOptions,
};
use sphaera_sweep::{SweepError, Tolerance};
use sphaera_tests::random::Lcg64;

/// The closest point of `[a, b]` to `p`, written independently of the library.
fn brute_segment<P: PolylinePoint>(p: P, a: P, b: P) -> f64 {
    let ab = b - a;
    let len2 = ab.dot(ab);
    let t = if len2 == 0.0 {
        0.0
    } else {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    };
    (p - (a + ab * t)).length()
}

/// The distance from `p` to `polyline` over every segment.
fn brute<P: PolylinePoint>(polyline: &Polyline<P>, p: P) -> f64 {
    (0..polyline.segment_count())
        .map(|i| {
            let (a, b) = polyline.segment(i).expect("in range");
            brute_segment(p, a, b)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The scale under which a distance counts as zero (for the relative comparison).
fn scale<P: PolylinePoint>(polyline: &Polyline<P>) -> f64 {
    polyline.diagonal().max(1e-300)
}

/// `answer` is exact (1e-12 relative) and self-consistent for `p`.
fn check_exact<P: PolylinePoint>(polyline: &Polyline<P>, p: P, answer: &PolylineClosest<P>) {
    let truth = brute(polyline, p);
    let tol = 1e-12 * truth.max(1e-3 * scale(polyline));
    assert!(
        (answer.distance - truth).abs() <= tol,
        "distance {} but brute force {truth} at {p:?}",
        answer.distance
    );
    assert!(((p - answer.point).length() - answer.distance).abs() <= tol);
    let (a, b) = polyline.segment(answer.segment).expect("a valid segment");
    assert!((0.0..=1.0).contains(&answer.parameter));
    let on = a + (b - a) * answer.parameter;
    assert!((on - answer.point).length() <= tol);
    let n = polyline.points().len();
    match answer.feature {
        PolylineFeature::Vertex(v) => {
            assert!(v < n);
            assert_eq!(polyline.points()[v], answer.point);
        }
        PolylineFeature::SegmentInterior => {
            assert!(answer.parameter > 0.0 && answer.parameter < 1.0);
        }
    }
}

/// `[lower, upper]` contains the truth and is at most `gap` wide (unless exact).
fn check_bounds<P: PolylinePoint>(polyline: &Polyline<P>, p: P, lower: f64, upper: f64) {
    let truth = brute(polyline, p);
    let slack = 1e-12 * truth.max(1e-3 * scale(polyline));
    assert!(
        lower <= truth + slack && truth <= upper + slack,
        "[{lower}, {upper}] misses {truth}"
    );
    assert!(lower >= 0.0);
}

/// Independent queries (one fresh session each and one shared session), a coherent
/// random walk, and anytime queries, all against brute force.
fn check_all<P: PolylinePoint>(polyline: &Polyline<P>, queries: &[P], step: P) {
    for by_tree in [true, false] {
        check_engine(polyline, queries, step, by_tree);
    }
}

/// [`check_all`] with one engine.
fn check_engine<P: PolylinePoint>(polyline: &Polyline<P>, queries: &[P], step: P, by_tree: bool) {
    let options = PolylineSessionOptions::default().with_exact_by_tree(by_tree);
    let mut shared = polyline.session_with(&options);
    for &p in queries {
        check_exact(
            polyline,
            p,
            &polyline.session_with(&options).closest(p).expect("finite"),
        );
        check_exact(polyline, p, &shared.closest(p).expect("finite"));
    }
    // A coherent walk: small steps, never resetting for jumps.
    let mut walk = polyline.session_with(&options.with_jump_factor(f64::INFINITY));
    let mut p = queries[0];
    for i in 0..40 {
        let wiggle = if i % 3 == 0 { step * -0.5 } else { step };
        p = p + wiggle;
        check_exact(polyline, p, &walk.closest(p).expect("finite"));
        // Again, barely moved: usually answered inside the safe ball.
        let q = p + step * 1e-3;
        check_exact(polyline, q, &walk.closest(q).expect("finite"));
    }
    // Anytime queries.
    let mut anytime = polyline.session_with(&options);
    for (i, &p) in queries.iter().enumerate() {
        let tolerance = 0.5 / (1.0 + i as f64);
        let b = anytime
            .closest_within(p, Tolerance::Absolute(tolerance))
            .expect("finite");
        check_bounds(polyline, p, b.lower, b.upper);
        assert!(b.gap() <= tolerance || b.closest.is_some());
        if let Some(c) = b.closest {
            check_exact(polyline, p, &c);
            assert_eq!((b.lower, b.upper), (c.distance, c.distance));
        }
        let r = anytime
            .closest_within(p, Tolerance::RelativeToUpper(0.1))
            .expect("finite");
        check_bounds(polyline, p, r.lower, r.upper);
        assert!(r.gap() <= 0.1 * r.upper + 1e-15 || r.closest.is_some());
        let budget = anytime.closest_with_budget(p, i % 4).expect("finite");
        check_bounds(polyline, p, budget.lower, budget.upper);
        assert!(budget.splits <= i % 4);
    }
}

fn coordinate() -> impl Strategy<Value = f64> {
    -10.0..10.0_f64
}

fn points3() -> impl Strategy<Value = Vec<DVec3>> {
    (
        prop::collection::vec((coordinate(), coordinate(), coordinate()), 2..60),
        prop::collection::vec(0..60_usize, 0..4),
    )
        .prop_map(|(raw, repeats)| {
            let mut points: Vec<DVec3> = raw
                .into_iter()
                .map(|(x, y, z)| DVec3::new(x, y, z))
                .collect();
            for r in repeats {
                let i = r % points.len();
                points.insert(i, points[i]);
            }
            points
        })
}

fn points2() -> impl Strategy<Value = Vec<DVec2>> {
    points3().prop_map(|p| p.into_iter().map(|v| DVec2::new(v.x, v.y)).collect())
}

fn queries3() -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec((-15.0..15.0_f64, -15.0..15.0_f64, -15.0..15.0_f64), 1..12)
        .prop_map(|q| q.into_iter().map(|(x, y, z)| DVec3::new(x, y, z)).collect())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    #[test]
    fn polylines_3d_match_brute_force(
        points in points3(),
        closed in any::<bool>(),
        queries in queries3(),
        step in (-0.3..0.3_f64, -0.3..0.3_f64, -0.3..0.3_f64),
    ) {
        let Ok(polyline) = Polyline::new(points, closed) else {
            return Ok(()); // all coincident: checked elsewhere
        };
        check_all(&polyline, &queries, DVec3::new(step.0, step.1, step.2));
    }

    #[test]
    fn polylines_2d_match_brute_force(
        points in points2(),
        closed in any::<bool>(),
        queries in queries3(),
        step in (-0.3..0.3_f64, -0.3..0.3_f64),
    ) {
        let Ok(polyline) = Polyline::new(points, closed) else {
            return Ok(());
        };
        let queries: Vec<DVec2> = queries.iter().map(|q| DVec2::new(q.x, q.y)).collect();
        check_all(&polyline, &queries, DVec2::new(step.0, step.1));
    }

    #[test]
    fn queries_on_the_polyline_are_at_distance_zero(
        points in points3(),
        closed in any::<bool>(),
        picks in prop::collection::vec((0..100_usize, 0.0..=1.0_f64), 1..10),
    ) {
        let Ok(polyline) = Polyline::new(points, closed) else {
            return Ok(());
        };
        let mut session = polyline.session();
        for (segment, t) in picks {
            let (a, b) = polyline.segment(segment % polyline.segment_count()).expect("in range");
            let p = a + (b - a) * t;
            let answer = session.closest(p).expect("finite");
            check_exact(&polyline, p, &answer);
            prop_assert!(answer.distance <= 1e-12 * polyline.diagonal());
        }
    }
}

/// A smooth noisy curve for the larger deterministic tests.
fn helix(n: usize) -> Vec<DVec3> {
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.02;
            DVec3::new(a.cos(), a.sin(), 0.05 * a)
                + 0.01 * DVec3::new((7.0 * a).sin(), 0.0, (5.0 * a).cos())
        })
        .collect()
}

#[test]
fn a_long_coherent_path_on_a_helix_is_exact_and_mostly_constant_time() {
    let polyline = Polyline::open(helix(5000)).expect("valid");
    let mut session = polyline.session();
    for i in 0..2000 {
        let a = f64::from(i) * 1e-3;
        let p = DVec3::new(1.5 * a.cos(), 1.5 * a.sin(), 0.05 * a + 0.3);
        let answer = session.closest(p).expect("finite");
        if i % 50 == 0 {
            check_exact(&polyline, p, &answer);
        }
        // A tiny move stays in the safe ball (the ball is small on a finely sampled curve:
        // the neighbouring segment's lower bound exceeds the answer by a second-order gap).
        let q = p + DVec3::splat(1e-9);
        let again = session.closest(q).expect("finite");
        if i % 50 == 0 {
            check_exact(&polyline, q, &again);
        }
    }
    let stats = session.stats();
    assert_eq!(stats.queries, 4000);
    // Not all: an answer at a shared vertex ties with the neighbouring segment (radius 0).
    assert!(stats.constant_time >= 1000, "{stats:?}");
    assert!(stats.splits < 2000 * 20, "{stats:?}");
}

#[test]
fn the_centre_of_a_polygonal_circle_splits_every_capsule_and_is_exact() {
    for n in [3, 4, 17, 1000, 10_000] {
        let circle: Vec<DVec2> = (0..n)
            .map(|i| DVec2::from_angle(std::f64::consts::TAU * f64::from(i) / f64::from(n)))
            .collect();
        let polyline = Polyline::closed(circle.clone()).expect("valid");
        let paper = PolylineSessionOptions::default().with_exact_by_tree(false);
        let mut session = polyline.session_with(&paper);
        let answer = session.closest(DVec2::ZERO).expect("finite");
        // The tree finds a segment at the same distance.
        let tree = polyline.session().closest(DVec2::ZERO).expect("finite");
        assert!((tree.distance - answer.distance).abs() < 1e-15);
        check_exact(&polyline, DVec2::ZERO, &answer);
        let expected = (std::f64::consts::PI / f64::from(n)).cos();
        assert!((answer.distance - expected).abs() < 1e-12);
        // The linear worst case of the paper: every inner capsule was split.
        assert_eq!(session.stats().splits, polyline.segment_count() - 1);
        // In 3D, tilted.
        let tilted: Vec<DVec3> = circle
            .iter()
            .map(|v| DVec3::new(v.x, v.y * 0.6, v.y * 0.8) + DVec3::splat(5.0))
            .collect();
        let polyline = Polyline::closed(tilted).expect("valid");
        let center = DVec3::splat(5.0);
        for options in [paper, PolylineSessionOptions::default()] {
            let answer = polyline
                .session_with(&options)
                .closest(center)
                .expect("finite");
            check_exact(&polyline, center, &answer);
        }
    }
}

#[test]
fn invalid_points_are_clear_errors() {
    let defect = |result: Result<(), SweepError>| match result {
        Err(SweepError::InvalidPolyline(defect)) => Some(defect),
        _ => None,
    };
    assert_eq!(
        defect(Polyline::<DVec3>::open(vec![]).map(|_| ())),
        Some(PolylineDefect::TooFewPoints { count: 0 })
    );
    assert_eq!(
        defect(Polyline::closed(vec![DVec2::ONE]).map(|_| ())),
        Some(PolylineDefect::TooFewPoints { count: 1 })
    );
    assert_eq!(
        defect(
            Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::new(0.0, f64::NAN, 0.0)]).map(|_| ())
        ),
        Some(PolylineDefect::NonFinitePoint { index: 2 })
    );
    assert_eq!(
        defect(Polyline::open(vec![DVec2::new(f64::INFINITY, 0.0), DVec2::X]).map(|_| ())),
        Some(PolylineDefect::NonFinitePoint { index: 0 })
    );
    assert_eq!(
        defect(Polyline::closed(vec![DVec3::ONE; 5]).map(|_| ())),
        Some(PolylineDefect::AllCoincident { count: 5 })
    );
    let message = Polyline::open(vec![DVec2::X, DVec2::X])
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert_eq!(message, "invalid polyline: all 2 points coincide");
}

#[test]
fn non_finite_queries_and_tolerances_are_errors_and_the_session_survives() {
    let polyline = Polyline::open(vec![DVec2::ZERO, DVec2::X]).expect("valid");
    let mut session = polyline.session();
    // In 2D the error reports z = 0.
    let Err(SweepError::NonFiniteQuery { x, y, z }) = session.closest(DVec2::new(f64::NAN, 1.0))
    else {
        panic!("a NaN query must be an error");
    };
    assert!(x.is_nan() && y == 1.0 && z == 0.0);
    assert!(matches!(
        session.closest(DVec2::new(f64::NAN, 1.0)),
        Err(SweepError::NonFiniteQuery { .. })
    ));
    assert!(matches!(
        session.closest_within(DVec2::new(0.0, f64::NEG_INFINITY), Tolerance::Absolute(0.1)),
        Err(SweepError::NonFiniteQuery { .. })
    ));
    assert!(matches!(
        session.closest_within(DVec2::ONE, Tolerance::RelativeToUpper(-1.0)),
        Err(SweepError::InvalidParameter { .. })
    ));
    assert!(matches!(
        session.closest_within(DVec2::ONE, Tolerance::Absolute(f64::NAN)),
        Err(SweepError::InvalidParameter { .. })
    ));
    let answer = session.closest(DVec2::new(0.5, 2.0)).expect("finite");
    assert_eq!(answer.point, DVec2::new(0.5, 0.0));
    assert_eq!(answer.feature, PolylineFeature::SegmentInterior);
}

#[test]
fn a_single_segment_answers_in_constant_time_after_the_first_query() {
    let polyline = Polyline::open(vec![DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0)]).expect("valid");
    assert_eq!(polyline.node_count(), 1);
    let mut session = polyline.session();
    for i in 0..10 {
        let p = DVec3::new(f64::from(i) - 3.0, 1.0, 0.0);
        check_exact(&polyline, p, &session.closest(p).expect("finite"));
    }
    // One segment: the safe radius is infinite.
    assert_eq!(session.stats().constant_time, 9);
    assert_eq!(session.stats().splits, 0);
}

#[test]
fn repeated_points_vertices_and_far_queries() {
    let points = vec![
        DVec2::ZERO,
        DVec2::ZERO,
        DVec2::X,
        DVec2::X,
        DVec2::X,
        DVec2::ONE,
        DVec2::ONE,
    ];
    for closed in [false, true] {
        let polyline = Polyline::new(points.clone(), closed).expect("valid");
        let mut session = polyline.session();
        // On each vertex: distance zero, and the feature is a vertex at that point.
        for &v in &points {
            let answer = session.closest(v).expect("finite");
            assert_eq!(answer.distance, 0.0);
            match answer.feature {
                PolylineFeature::Vertex(i) => assert_eq!(polyline.points()[i], v),
                PolylineFeature::SegmentInterior => panic!("a vertex query gave an interior point"),
            }
        }
        // On the line.
        let on = session.closest(DVec2::new(0.25, 0.0)).expect("finite");
        assert_eq!(on.distance, 0.0);
        assert_eq!(on.feature, PolylineFeature::SegmentInterior);
        // Far away.
        for p in [DVec2::new(1e6, -3e6), DVec2::new(-1e9, 1e9)] {
            check_exact(&polyline, p, &session.closest(p).expect("finite"));
        }
    }
}

#[test]
fn the_reset_policy_keeps_answers_exact_and_is_counted() {
    let polyline = Polyline::closed(helix(3000)).expect("valid");
    let mut session = polyline.session_with(
        &PolylineSessionOptions::default()
            .with_max_front(8)
            .with_jump_factor(f64::INFINITY)
            .with_exact_by_tree(false),
    );
    let mut rng = Lcg64::with_increment(3, 1);
    let mut next = || rng.unit() * 4.0 - 2.0;
    for _ in 0..50 {
        let p = DVec3::new(next(), next(), next() + 2.0);
        check_exact(&polyline, p, &session.closest(p).expect("finite"));
    }
    assert!(session.stats().resets > 0);
    session.reset();
    assert_eq!(session.front_len(), 0);
    let p = DVec3::new(0.3, 0.1, 1.0);
    check_exact(&polyline, p, &session.closest(p).expect("finite"));
}

#[test]
fn sessions_are_deterministic() {
    let polyline = Polyline::open(helix(2000)).expect("valid");
    let run = || {
        let mut session = polyline.session();
        (0..200)
            .map(|i| {
                let a = f64::from(i) * 0.1;
                let answer = session
                    .closest(DVec3::new(a.sin(), 2.0 * a.cos(), 0.01 * a))
                    .expect("finite");
                (
                    answer.segment,
                    answer.distance.to_bits(),
                    answer.parameter.to_bits(),
                )
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(run(), run());
}

#[test]
fn a_long_polyline_builds_without_recursion_and_is_exact() {
    let polyline = Polyline::open(helix(200_000)).expect("valid");
    assert_eq!(polyline.node_count(), 2 * 199_999 - 1);
    let mut session = polyline.session();
    for p in [
        DVec3::new(2.0, 0.0, 10.0),
        DVec3::new(0.1, 0.2, 500.0),
        DVec3::splat(-50.0),
    ] {
        check_exact(&polyline, p, &session.closest(p).expect("finite"));
    }
}
