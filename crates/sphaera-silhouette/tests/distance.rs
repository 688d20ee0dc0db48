//! The distance transforms against brute force: the exact Euclidean transform equals the
//! smallest distance to a background pixel (or to the ring of pixels just outside the
//! image), and the 3–4 chamfer stays within its known bounds of it.
// Labels of 0 and exact distances are compared exactly on purpose.
#![allow(clippy::float_cmp)]

use proptest::prelude::*;
use sphaera_silhouette::DistanceTransform;

/// The smallest distance from each object pixel to a background pixel, the ring outside
/// the image counting as background.
fn brute(object: &[bool], width: usize, height: usize) -> Vec<f32> {
    let (w, h) = (width as i64, height as i64);
    let mut background: Vec<(i64, i64)> = Vec::new();
    for y in -1..=h {
        for x in -1..=w {
            let outside = x < 0 || y < 0 || x >= w || y >= h;
            if outside || !object[(y * w + x) as usize] {
                background.push((x, y));
            }
        }
    }
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            if !object[(y * w + x) as usize] {
                return 0.0;
            }
            background
                .iter()
                .map(|&(bx, by)| (((bx - x).pow(2) + (by - y).pow(2)) as f64).sqrt())
                .fold(f64::INFINITY, f64::min) as f32
        })
        .collect()
}

fn image() -> impl Strategy<Value = (usize, usize, Vec<bool>)> {
    (1_usize..20, 1_usize..20, 0.0_f64..1.0).prop_flat_map(|(w, h, density)| {
        (
            Just(w),
            Just(h),
            proptest::collection::vec(proptest::bool::weighted(density), w * h),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(300)))]

    #[test]
    fn euclidean_equals_brute_force((w, h, object) in image()) {
        let exact = DistanceTransform::Euclidean.apply(&object, w, h);
        let reference = brute(&object, w, h);
        for (i, (&a, &b)) in exact.iter().zip(&reference).enumerate() {
            prop_assert!((a - b).abs() <= 1e-5 * b.max(1.0), "pixel {i}: {a} against {b}");
        }
    }

    #[test]
    fn chamfer_is_within_its_bounds((w, h, object) in image()) {
        let chamfer = DistanceTransform::Chamfer.apply(&object, w, h);
        let reference = brute(&object, w, h);
        for (i, (&c, &e)) in chamfer.iter().zip(&reference).enumerate() {
            // 3–4 weights: diagonals 4/3 against √2, knight moves 7/3 against √5.
            prop_assert!(c >= 0.94 * e - 1e-5 && c <= 1.09 * e + 1e-5, "pixel {i}: {c} against {e}");
            prop_assert_eq!(c == 0.0, e == 0.0);
        }
    }
}

#[test]
fn full_and_empty_images_and_one_pixel() {
    for transform in [DistanceTransform::Euclidean, DistanceTransform::Chamfer] {
        // All object: distance to the outside ring.
        let full = transform.apply(&[true; 25], 5, 5);
        assert_eq!(full[12], 3.0, "{transform:?}: the center of 5 × 5");
        assert_eq!(full[0], 1.0, "{transform:?}: a corner");
        assert!(transform.apply(&[false; 9], 3, 3).iter().all(|&d| d == 0.0));
        assert_eq!(transform.apply(&[true], 1, 1), vec![1.0]);
    }
}
