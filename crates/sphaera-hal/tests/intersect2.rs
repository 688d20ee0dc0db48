//! Intersection detection of 2D HAL trees against brute force: random grid polygons (shared
//! edges, touching vertices, containment), nested and identical polygons, open polylines,
//! and the real neighbours Belgium and the Netherlands.

use glam::DVec2;
use proptest::prelude::*;
use sphaera_hal::{HalTree2, Polyline2, intersects_brute, segments_intersect};

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
    let expected = intersects_brute(a, b);
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
    // An open polyline inside a polygon does not meet its outline.
    assert!(!both(
        &outline(&[(2.0, 2.0), (3.0, 2.5)], false),
        &square(0.0, 10.0)
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

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
