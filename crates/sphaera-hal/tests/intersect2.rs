//! Intersection detection of 2D HAL trees against brute force: random grid polygons (shared
//! edges, touching vertices, containment), nested and identical polygons, open polylines,
//! and the real neighbours Belgium and the Netherlands.

use glam::DVec2;
use proptest::prelude::*;
use sphaera_hal::{HalTree2, Polyline2, intersects_brute, segments_intersect};
use sphaera_tests::regions;

/// Whether the outlines meet, by the reference outside this crate
/// (`sphaera_tests::regions`: its own exact segment test and a winding number); the
/// crate's own [`intersects_brute`], a documented reference users call, is checked
/// against it too.
fn reference(a: &Polyline2, b: &Polyline2) -> bool {
    let expected = regions::outlines_meet(a.points(), a.is_closed(), b.points(), b.is_closed());
    assert_eq!(
        intersects_brute(a, b),
        expected,
        "intersects_brute: {a:?} against {b:?}"
    );
    expected
}

fn outline(points: &[(f64, f64)], closed: bool) -> Polyline2 {
    let points = points.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
    if closed {
        Polyline2::polygon(points).unwrap()
    } else {
        Polyline2::open(points).unwrap()
    }
}

fn both(a: &Polyline2, b: &Polyline2) -> bool {
    let (ta, tb) = (HalTree2::build(a).unwrap(), HalTree2::build(b).unwrap());
    let expected = reference(a, b);
    assert_eq!(ta.intersects(&tb), expected, "{a:?} against {b:?}");
    assert_eq!(tb.intersects(&ta), expected, "symmetry");
    expected
}

#[test]
fn segments_touch_cross_overlap_or_miss() {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    assert!(segments_intersect(
        p(0.0, 0.0),
        p(2.0, 2.0),
        p(0.0, 2.0),
        p(2.0, 0.0)
    ));
    assert!(segments_intersect(
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(1.0, 0.0),
        p(1.0, 5.0)
    ));
    assert!(segments_intersect(
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(1.0, 0.0),
        p(3.0, 0.0)
    ));
    assert!(segments_intersect(
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(2.0, 0.0),
        p(3.0, 1.0)
    ));
    assert!(!segments_intersect(
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(3.0, 0.0),
        p(4.0, 0.0)
    ));
    assert!(!segments_intersect(
        p(0.0, 0.0),
        p(2.0, 0.0),
        p(0.0, 1.0),
        p(2.0, 1.0)
    ));
    assert!(segments_intersect(
        p(1.0, 1.0),
        p(1.0, 1.0),
        p(0.0, 0.0),
        p(2.0, 2.0)
    ));
}

#[test]
fn nested_identical_touching_and_apart() {
    let square = |lo: f64, hi: f64| outline(&[(lo, lo), (hi, lo), (hi, hi), (lo, hi)], true);
    assert!(both(&square(0.0, 10.0), &square(2.0, 3.0)), "nested");
    assert!(both(&square(0.0, 10.0), &square(0.0, 10.0)), "identical");
    assert!(
        both(&square(0.0, 1.0), &square(1.0, 2.0)),
        "touching at a corner"
    );
    assert!(!both(&square(0.0, 1.0), &square(1.5, 2.0)), "apart");
    let zigzag = outline(&[(0.0, 0.0), (1.0, 3.0), (2.0, 0.0), (3.0, 3.0)], false);
    assert!(!both(&zigzag, &square(4.0, 5.0)));
    assert!(both(&zigzag, &square(0.5, 1.5)));
    // An open polyline inside a polygon meets its region (GEOS's semantics), though not
    // its outline.
    assert!(both(
        &outline(&[(2.0, 2.0), (3.0, 2.5)], false),
        &square(0.0, 10.0)
    ));
}

/// The crate's segment test against the reference's on every pair of segments with ends
/// on a 3 × 3 grid (collinear overlaps, shared ends, degenerate segments included), and
/// on the same pairs rotated off the axes (no longer exact, so the two must still agree).
#[test]
fn segment_test_equals_the_reference_on_a_grid() {
    let grid: Vec<DVec2> = (0..9)
        .map(|i| DVec2::new(f64::from(i % 3), f64::from(i / 3)))
        .collect();
    let mut outcomes = [0_usize; 2];
    for &a in &grid {
        for &b in &grid {
            for &c in &grid {
                for &d in &grid {
                    for map in [
                        |p: DVec2| p,
                        |p: DVec2| DVec2::from_angle(0.3).rotate(p) * 7.1,
                    ] {
                        let [a, b, c, d] = [a, b, c, d].map(map);
                        let expected = regions::segments_meet(a, b, c, d);
                        assert_eq!(segments_intersect(a, b, c, d), expected, "{a} {b} {c} {d}");
                        outcomes[usize::from(expected)] += 1;
                    }
                }
            }
        }
    }
    assert!(outcomes[0] > 1000 && outcomes[1] > 1000, "{outcomes:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(96)))]

    #[test]
    fn intersection_equals_brute_force(
        a in prop::collection::vec((0i32..10, 0i32..10), 3..25),
        b in prop::collection::vec((0i32..10, 0i32..10), 2..25),
        shift in (-12i32..12, -12i32..12),
        closed in any::<bool>(),
    ) {
        let a: Vec<(f64, f64)> = a.iter().map(|&(x, y)| (f64::from(x), f64::from(y))).collect();
        let b: Vec<(f64, f64)> = b
            .iter()
            .map(|&(x, y)| (f64::from(x + shift.0), f64::from(y + shift.1)))
            .collect();
        let closed = closed && b.len() >= 3;
        both(&outline(&a, true), &outline(&b, closed));
    }
}

#[test]
fn belgium_meets_the_netherlands_and_not_norway() {
    let Some(data) = sphaera_tests::data_dir("belgium_meets_the_netherlands_and_not_norway") else {
        return;
    };
    let read = |name: &str| Polyline2::read_polygon(data.join("polygons").join(name)).unwrap();
    let (belgium, netherlands, norway, luxembourg) = (
        read("belgium.txt"),
        read("netherlands.txt"),
        read("norway.txt"),
        read("luxembourg.txt"),
    );
    assert!(both(&belgium, &netherlands));
    assert!(both(&belgium, &luxembourg));
    assert!(!both(&belgium, &norway));
    assert!(!both(&netherlands, &luxembourg));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// A placed outline answers as brute force on its mapped vertices.
    #[test]
    fn placed_intersection_equals_brute_force_on_the_mapped_outline(
        a in prop::collection::vec((0i32..10, 0i32..10), 3..20),
        b in prop::collection::vec((0i32..10, 0i32..10), 3..20),
        angle in 0.0f64..std::f64::consts::TAU,
        scale in 0.3f64..3.0,
        shift in (-12.0f64..12.0, -12.0f64..12.0),
    ) {
        use glam::DAffine2;
        let a: Vec<(f64, f64)> = a.iter().map(|&(x, y)| (f64::from(x), f64::from(y))).collect();
        let b: Vec<(f64, f64)> = b.iter().map(|&(x, y)| (f64::from(x), f64::from(y))).collect();
        let (first, second) = (outline(&a, true), outline(&b, true));
        let placement = DAffine2::from_scale_angle_translation(
            DVec2::splat(scale),
            angle,
            DVec2::new(shift.0, shift.1),
        );
        let mapped = Polyline2::polygon(
            second.points().iter().map(|&p| placement.transform_point2(p)).collect(),
        ).unwrap();
        let (ta, tb) = (HalTree2::build(&first).unwrap(), HalTree2::build(&second).unwrap());
        prop_assert_eq!(
            ta.intersects_placed(&tb, placement).unwrap(),
            reference(&first, &mapped)
        );
    }
}

#[test]
fn a_placement_must_be_a_proper_similarity() {
    use glam::{DAffine2, DMat2};
    use sphaera_hal::HalError;
    let square = outline(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)], true);
    let tree = HalTree2::build(&square).unwrap();
    for matrix in [
        DMat2::from_cols_array(&[-1.0, 0.0, 0.0, 1.0]),
        DMat2::from_cols_array(&[1.0, 0.0, 0.5, 1.0]),
        DMat2::from_cols_array(&[2.0, 0.0, 0.0, 1.0]),
        DMat2::ZERO,
        DMat2::from_cols_array(&[f64::NAN, 0.0, 0.0, 1.0]),
    ] {
        let placement = DAffine2::from_mat2(matrix);
        assert!(matches!(
            tree.intersects_placed(&tree, placement),
            Err(HalError::InvalidPlacement { .. })
        ));
    }
    let moved = DAffine2::from_translation(DVec2::new(0.5, 0.5));
    assert!(tree.intersects_placed(&tree, moved).unwrap());
    let far = DAffine2::from_translation(DVec2::new(5.0, 0.0));
    assert!(!tree.intersects_placed(&tree, far).unwrap());
}
