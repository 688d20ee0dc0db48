//! Camera sets: the regular grid's size, nearest views in constant time equal to a full
//! search, and the errors.

use proptest::prelude::*;
use sphaera_mesh::DVec3;
use sphaera_silhouette::{SilhouetteError, ViewSet};

fn brute_nearest(views: &ViewSet, d: DVec3, n: usize) -> Vec<usize> {
    let d = d.normalize();
    let mut all: Vec<usize> = (0..views.len()).collect();
    all.sort_by(|&a, &b| {
        (-views.direction(a).dot(d))
            .total_cmp(&-views.direction(b).dot(d))
            .then(a.cmp(&b))
    });
    all.truncate(n);
    all
}

#[test]
fn regular_sets_have_the_expected_views() {
    assert_eq!(ViewSet::regular(15.0).unwrap().len(), 266);
    assert_eq!(ViewSet::regular(90.0).unwrap().len(), 6);
    assert_eq!(ViewSet::regular(45.0).unwrap().len(), 26);
    for step in [0.0, -5.0, 7.0, 100.0, f64::NAN] {
        assert!(
            matches!(
                ViewSet::regular(step),
                Err(SilhouetteError::InvalidStep { .. })
            ),
            "{step}"
        );
    }
    let views = ViewSet::regular(30.0).unwrap();
    for k in 0..views.len() {
        assert!((views.direction(k).length() - 1.0).abs() < 1e-12);
        // A view's own direction finds it.
        assert_eq!(views.nearest(views.direction(k)).unwrap(), k);
    }
    assert!(views.clone().with_perspective(1.0).is_err());
    assert!(views.clone().with_perspective(f64::INFINITY).is_err());
    assert!(views.clone().with_perspective(3.0).is_ok());
    assert!(matches!(
        views.nearest(DVec3::ZERO),
        Err(SilhouetteError::InvalidDirection { .. })
    ));
    assert!(matches!(
        views.nearest_n(DVec3::X, 0),
        Err(SilhouetteError::InvalidNearest { .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(500)))]

    #[test]
    fn nearest_views_equal_a_full_search(
        x in -1.0_f64..1.0, y in -1.0_f64..1.0, z in -1.0_f64..1.0,
        step in prop::sample::select(vec![15.0, 22.5, 30.0, 45.0, 60.0, 90.0]),
        n in 1_usize..9,
    ) {
        let d = DVec3::new(x, y, z);
        prop_assume!(d.length() > 1e-3);
        let views = ViewSet::regular(step).unwrap();
        let n = n.min(views.len());
        prop_assert_eq!(views.nearest_n(d, n).unwrap(), brute_nearest(&views, d, n));
    }
}

#[test]
fn near_the_poles_and_on_ties() {
    let views = ViewSet::regular(15.0).unwrap();
    for d in [
        DVec3::new(1e-9, 0.0, 1.0),
        DVec3::new(0.0, 1e-6, -1.0),
        DVec3::new(0.3, 0.2, 0.999),
        // Equidistant from four cameras: the middle of a grid cell.
        DVec3::new(
            (7.5_f64.to_radians()).cos() * (7.5_f64.to_radians()).cos(),
            (7.5_f64.to_radians()).cos() * (7.5_f64.to_radians()).sin(),
            (7.5_f64.to_radians()).sin(),
        ),
    ] {
        for n in 1..=8 {
            assert_eq!(
                views.nearest_n(d, n).unwrap(),
                brute_nearest(&views, d, n),
                "{d} {n}"
            );
        }
    }
}
