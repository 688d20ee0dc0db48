//! The HAL tests' reference (`sphaera_tests::regions`) against answers known in closed
//! form: rectangles and boxes located by comparing coordinates (points exactly on their
//! sides included), a self-crossing star under the even–odd rule, boxes meeting by the
//! overlap of their intervals, and segments whose meeting is drawn by hand.

use glam::{DQuat, DVec2, DVec3};
use proptest::prelude::*;
use sphaera_mesh::{TriMesh, shapes};
use sphaera_tests::regions::{self, Side};

/// A quarter-unit grid position in `[-1, 1]`, exact in binary.
fn quarter(k: i32) -> f64 {
    f64::from(k) * 0.25
}

/// Where `x` lies in the axis-aligned box `[lo, hi]` by comparing coordinates.
fn in_box(lo: &[f64], hi: &[f64], x: &[f64]) -> Side {
    let within = x.iter().zip(lo).zip(hi).all(|((v, l), h)| l <= v && v <= h);
    let strictly = x.iter().zip(lo).zip(hi).all(|((v, l), h)| l < v && v < h);
    match (within, strictly) {
        (_, true) => Side::Inside,
        (true, false) => Side::Boundary,
        (false, _) => Side::Outside,
    }
}

fn moved(mesh: &TriMesh, f: impl Fn(DVec3) -> DVec3) -> TriMesh {
    TriMesh::new(
        mesh.positions().iter().map(|&p| f(p)).collect(),
        mesh.triangles().to_vec(),
    )
    .unwrap()
}

#[test]
fn segments_meet_as_drawn() {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    let cases = [
        (
            (p(0.0, 0.0), p(2.0, 2.0), p(0.0, 2.0), p(2.0, 0.0)),
            true,
            "crossing",
        ),
        (
            (p(0.0, 0.0), p(2.0, 0.0), p(1.0, 0.0), p(1.0, 5.0)),
            true,
            "a T",
        ),
        (
            (p(0.0, 0.0), p(2.0, 0.0), p(1.0, 0.0), p(3.0, 0.0)),
            true,
            "collinear overlap",
        ),
        (
            (p(0.0, 0.0), p(2.0, 0.0), p(2.0, 0.0), p(3.0, 1.0)),
            true,
            "shared end",
        ),
        (
            (p(0.0, 0.0), p(2.0, 0.0), p(3.0, 0.0), p(4.0, 0.0)),
            false,
            "collinear apart",
        ),
        (
            (p(0.0, 0.0), p(2.0, 0.0), p(0.0, 1.0), p(2.0, 1.0)),
            false,
            "parallel",
        ),
        (
            (p(0.0, 0.0), p(2.0, 0.0), p(2.5, -1.0), p(2.5, 1.0)),
            false,
            "past the end",
        ),
        (
            (p(1.0, 1.0), p(1.0, 1.0), p(0.0, 0.0), p(2.0, 2.0)),
            true,
            "a point on it",
        ),
        (
            (p(3.0, 3.0), p(3.0, 3.0), p(0.0, 0.0), p(2.0, 2.0)),
            false,
            "a point beyond",
        ),
        (
            (p(1.0, 1.0), p(1.0, 1.0), p(1.0, 1.0), p(1.0, 1.0)),
            true,
            "one point twice",
        ),
        (
            (p(0.0, 2.0), p(0.0, 0.0), p(0.0, 1.0), p(0.0, 3.0)),
            true,
            "vertical overlap",
        ),
        (
            (p(0.0, 2.0), p(0.0, 0.0), p(0.0, 2.5), p(0.0, 3.0)),
            false,
            "vertical apart",
        ),
    ];
    for ((a, b, c, d), expected, name) in cases {
        for (a, b, c, d) in [(a, b, c, d), (b, a, d, c), (c, d, a, b)] {
            assert_eq!(regions::segments_meet(a, b, c, d), expected, "{name}");
        }
    }
}

#[test]
fn a_self_crossing_star_follows_the_even_odd_rule() {
    // The pentagram: its centre is wound twice (even: outside), its tips once.
    let star: Vec<DVec2> = (0..5)
        .map(|i| DVec2::from_angle(std::f64::consts::TAU * f64::from(i * 2) / 5.0))
        .collect();
    assert_eq!(
        regions::locate_in_outline(&star, DVec2::ZERO),
        Side::Outside
    );
    let tip = DVec2::from_angle(0.0) * 0.9;
    assert_eq!(regions::locate_in_outline(&star, tip), Side::Inside);
    assert_eq!(
        regions::locate_in_outline(&star, DVec2::new(2.0, 0.0)),
        Side::Outside
    );
    assert_eq!(regions::locate_in_outline(&star, star[0]), Side::Boundary);
    // Degenerate rings hold nothing but their own points.
    assert_eq!(regions::locate_in_outline(&[], DVec2::ZERO), Side::Outside);
    let flat = [DVec2::ZERO, DVec2::X, DVec2::X * 2.0];
    assert_eq!(
        regions::locate_in_outline(&flat, DVec2::new(0.5, 0.0)),
        Side::Boundary
    );
    assert_eq!(
        regions::locate_in_outline(&flat, DVec2::new(0.5, 0.1)),
        Side::Outside
    );
}

#[test]
fn empty_meshes_hold_and_meet_nothing() {
    let cube = shapes::cube(1.0, 2).unwrap();
    let empty = TriMesh::default();
    assert_eq!(regions::locate_in_solid(&empty, DVec3::ZERO), Side::Outside);
    assert!(!regions::solids_meet(&empty, &cube));
    assert!(!regions::solids_meet(&cube, &empty));
}

#[test]
fn the_winding_number_of_an_open_surface_is_refused() {
    let one = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    let judged =
        std::panic::catch_unwind(|| regions::locate_in_solid(&one, DVec3::new(0.2, 0.2, 0.1)));
    assert!(
        judged.is_err(),
        "a single triangle's winding number is not an integer"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// A rectangle, either way round, located by comparing coordinates: points on a
    /// quarter grid land exactly on its sides and corners.
    #[test]
    fn rectangles_locate_as_their_coordinates(
        corners in ((-4i32..0, -4i32..0), (1i32..5, 1i32..5)),
        queries in prop::collection::vec((-5i32..6, -5i32..6), 1..40),
        reversed in any::<bool>(),
    ) {
        let ((x0, y0), (x1, y1)) = corners;
        let (lo, hi) = ([quarter(x0), quarter(y0)], [quarter(x1), quarter(y1)]);
        let mut ring = vec![
            DVec2::new(lo[0], lo[1]),
            DVec2::new(hi[0], lo[1]),
            DVec2::new(hi[0], hi[1]),
            DVec2::new(lo[0], hi[1]),
        ];
        if reversed {
            ring.reverse();
        }
        for (qx, qy) in queries {
            let x = [quarter(qx), quarter(qy)];
            prop_assert_eq!(
                regions::locate_in_outline(&ring, DVec2::from(x)),
                in_box(&lo, &hi, &x)
            );
        }
    }

    /// A cube, either orientation, located by comparing coordinates (points on its faces,
    /// edges and corners included), and rotated about its centre (no longer exact: points
    /// well inside or well outside only).
    #[test]
    fn cubes_locate_as_their_coordinates(
        queries in prop::collection::vec((-5i32..6, -5i32..6, -5i32..6), 1..30),
        inverted in any::<bool>(),
        angles in (0.0f64..6.3, 0.0f64..6.3),
    ) {
        let mut cube = shapes::cube(2.0, 2).unwrap();
        if inverted {
            let (p, t) = cube.into_parts();
            cube = TriMesh::new(p, t.into_iter().map(|[a, b, c]| [a, c, b]).collect()).unwrap();
        }
        let rotation = DQuat::from_euler(glam::EulerRot::XYZ, angles.0, angles.1, 0.0);
        let turned = moved(&cube, |p| rotation * p);
        for (qx, qy, qz) in queries {
            let x = [quarter(qx), quarter(qy), quarter(qz)];
            let expected = in_box(&[-1.0; 3], &[1.0; 3], &x);
            prop_assert_eq!(regions::locate_in_solid(&cube, DVec3::from(x)), expected);
            let depth = x.iter().map(|v| (v.abs() - 1.0).abs()).fold(f64::INFINITY, f64::min);
            if depth > 0.1 {
                prop_assert_eq!(regions::locate_in_solid(&turned, rotation * DVec3::from(x)), expected);
            }
        }
    }

    /// Two boxes meet when their intervals overlap on every axis (closed: touching faces,
    /// edges and corners meet); nested boxes meet without their surfaces touching.
    #[test]
    fn boxes_meet_when_their_intervals_overlap(
        shift in (-9i32..10, -9i32..10, -9i32..10),
        small in any::<bool>(),
    ) {
        let a = shapes::cube(2.0, 2).unwrap();
        let half = if small { 0.25 } else { 1.0 };
        let offset = DVec3::new(quarter(shift.0), quarter(shift.1), quarter(shift.2));
        let b = moved(&shapes::cube(2.0 * half, 1).unwrap(), |p| p + offset);
        let expected = offset.to_array().iter().all(|d| d.abs() <= 1.0 + half);
        prop_assert_eq!(regions::solids_meet(&a, &b), expected, "offset {}", offset);
        prop_assert_eq!(regions::solids_meet(&b, &a), expected);
    }
}

/// A sphere mesh inside a larger one meets it, one beside it does not; located points
/// agree with the distance to the centre away from the facets.
#[test]
fn spheres_nest_and_separate() {
    let big = shapes::sphere(1.0, 24).unwrap();
    let small = shapes::sphere(0.3, 12).unwrap();
    assert!(regions::solids_meet(&big, &small), "nested");
    assert!(!regions::solids_meet(
        &big,
        &moved(&small, |p| p + DVec3::X * 1.5)
    ));
    assert!(regions::solids_meet(
        &big,
        &moved(&small, |p| p + DVec3::X * 1.1)
    ));
    let mut rng = sphaera_tests::SplitMix64::new(5);
    for _ in 0..500 {
        let x = DVec3::new(
            rng.range(-1.3, 1.3),
            rng.range(-1.3, 1.3),
            rng.range(-1.3, 1.3),
        );
        // The facets lie within 1 − cos(π/24)·cos(π/24) < 0.02 of the unit sphere.
        let r = x.length();
        if r < 0.97 {
            assert_eq!(regions::locate_in_solid(&big, x), Side::Inside, "{x}");
        } else if r > 1.0 {
            assert_eq!(regions::locate_in_solid(&big, x), Side::Outside, "{x}");
        }
    }
}
