//! Pictures and the contour displacement: the displacement equals a brute-force search on
//! random images, the shaded picture's silhouette is the coverage image and its greys
//! follow the values, the overlay colours every cell by which image covers it, and bad
//! inputs are named.

use proptest::prelude::*;
use sphaera_mesh::{DVec3, shapes};
use sphaera_silhouette::{
    Contours, DistanceTransform, Projection, SilhouetteError, bounding_sphere,
    contour_displacement, contour_displacement_seen, coverage, label_view, overlay_picture,
    shaded_picture,
};

/// The farthest a cell of one image outside the other lies from the other's nearest
/// cell, both ways, by trying every pair.
fn brute_displacement(a: &[bool], b: &[bool], n: usize) -> Option<f64> {
    brute_displacement_seen(a, b, n, &vec![true; n * n])
}

/// The same from the cells `seen` only, to the other's nearest cell seen or not.
fn brute_displacement_seen(a: &[bool], b: &[bool], n: usize, seen: &[bool]) -> Option<f64> {
    let cells = |x: &[bool], only_seen: bool| -> Vec<(f64, f64)> {
        (0..n * n)
            .filter(|&c| x[c] && (seen[c] || !only_seen))
            .map(|c| ((c % n) as f64, (c / n) as f64))
            .collect()
    };
    let (sa, sb) = (cells(a, true), cells(b, true));
    let (ca, cb) = (cells(a, false), cells(b, false));
    match (sa.is_empty(), sb.is_empty()) {
        (true, true) => return Some(0.0),
        (false, _) if cb.is_empty() => return None,
        (_, false) if ca.is_empty() => return None,
        _ => {}
    }
    let one_way = |from: &[(f64, f64)], to: &[(f64, f64)]| {
        from.iter()
            .map(|&(x, y)| {
                to.iter()
                    .map(|&(u, v)| (u - x).hypot(v - y))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    Some(one_way(&sa, &cb).max(one_way(&sb, &ca)))
}

fn image_pair() -> impl Strategy<Value = (usize, Vec<bool>, Vec<bool>)> {
    (1_usize..14).prop_flat_map(|n| {
        (
            Just(n),
            prop::collection::vec(prop::bool::weighted(0.3), n * n),
            prop::collection::vec(prop::bool::weighted(0.3), n * n),
        )
    })
}

proptest! {
    #[test]
    fn displacement_equals_brute_force((n, a, b) in image_pair()) {
        let fast = contour_displacement(&a, &b, n);
        let brute = brute_displacement(&a, &b, n);
        match (fast, brute) {
            (Some(x), Some(y)) => prop_assert!((x - y).abs() < 1e-4, "{x} vs {y}"),
            (x, y) => prop_assert_eq!(x, y),
        }
    }

    #[test]
    fn displacement_seen_equals_brute_force(
        ((n, a, b), seen) in image_pair().prop_flat_map(|(n, a, b)| {
            (Just((n, a, b)), prop::collection::vec(prop::bool::weighted(0.6), n * n))
        })
    ) {
        let fast = contour_displacement_seen(&a, &b, n, &seen);
        let brute = brute_displacement_seen(&a, &b, n, &seen);
        match (fast, brute) {
            (Some(x), Some(y)) => prop_assert!((x - y).abs() < 1e-4, "{x} vs {y}"),
            (x, y) => prop_assert_eq!(x, y),
        }
    }
}

#[test]
fn displacement_of_a_single_far_cell_is_its_distance() {
    // One covered cell in each corner: the distance transform's edge ring is nearer than
    // the other image, so the direct search answers.
    let n = 40;
    let mut a = vec![false; n * n];
    let mut b = vec![false; n * n];
    a[0] = true;
    b[n * n - 1] = true;
    let d = contour_displacement(&a, &b, n).unwrap();
    assert!((d - (2.0_f64 * 39.0 * 39.0).sqrt()).abs() < 1e-9, "{d}");
    assert_eq!(contour_displacement(&a, &a, n), Some(0.0));
    assert_eq!(contour_displacement(&a, &vec![false; n * n], n), None);
}

#[test]
fn the_shaded_picture_shows_the_coverage_and_the_values() {
    let sphere = shapes::sphere(1.0, 24).unwrap();
    let frame = bounding_sphere(&sphere).unwrap();
    let n = 64;
    let covered = coverage(&sphere, frame, DVec3::Z, Projection::Orthographic, n).unwrap();
    let labels = label_view(
        &sphere,
        DVec3::Z,
        Projection::Orthographic,
        n,
        DistanceTransform::Euclidean,
        Contours::All,
    )
    .unwrap();
    let picture = shaded_picture(
        &sphere,
        frame,
        DVec3::Z,
        Projection::Orthographic,
        n,
        &labels.vertices,
        20.0,
    )
    .unwrap();
    assert_eq!((picture.size, picture.rgb.len()), (n, n * n * 3));
    // Top row first: cell (i, j) from the bottom is pixel (i, n − 1 − j).
    let pixel = |i: usize, j: usize| {
        let k = 3 * ((n - 1 - j) * n + i);
        [picture.rgb[k], picture.rgb[k + 1], picture.rgb[k + 2]]
    };
    for j in 0..n {
        for i in 0..n {
            assert_eq!(
                pixel(i, j) != [255, 255, 255],
                covered[j * n + i],
                "cell {i},{j}"
            );
        }
    }
    // Dark at the outline, light at the centre.
    let center = pixel(n / 2, n / 2)[0];
    let rim = (0..n).find(|&i| covered[(n / 2) * n + i]).unwrap();
    assert!(pixel(rim, n / 2)[0] < 40 && center > 200, "{rim} {center}");

    // Bad inputs are named.
    assert!(matches!(
        shaded_picture(
            &sphere,
            frame,
            DVec3::Z,
            Projection::Orthographic,
            n,
            &[1.0],
            1.0
        ),
        Err(SilhouetteError::ValueCountMismatch { values: 1, .. })
    ));
    for scale in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert!(matches!(
            shaded_picture(
                &sphere,
                frame,
                DVec3::Z,
                Projection::Orthographic,
                n,
                &labels.vertices,
                scale
            ),
            Err(SilhouetteError::InvalidParameter { name: "scale", .. })
        ));
    }
    assert!(matches!(
        shaded_picture(
            &sphere,
            frame,
            DVec3::Z,
            Projection::Perspective { distance: 0.5 },
            n,
            &labels.vertices,
            1.0
        ),
        Err(SilhouetteError::CameraInside { .. })
    ));
    // A view along a face plane and a one-pixel picture still draw.
    let cube = shapes::cube(1.0, 1).unwrap();
    let values = vec![1.0; cube.vertex_count()];
    let cube_frame = bounding_sphere(&cube).unwrap();
    for (direction, size) in [(DVec3::X, 16), (DVec3::new(1.0, 1.0, 1.0), 1)] {
        let p = shaded_picture(
            &cube,
            cube_frame,
            direction,
            Projection::Orthographic,
            size,
            &values,
            1.0,
        )
        .unwrap();
        assert_eq!(p.rgb.len(), size * size * 3);
    }
}

#[test]
fn the_overlay_colours_each_cell_by_who_covers_it() {
    let a = [true, true, false, false];
    let b = [true, false, true, false];
    let p = overlay_picture(&a, &b, 2);
    // Bottom row (cells 0, 1) is the picture's second row.
    let rows: Vec<&[u8]> = p.rgb.chunks(6).collect();
    assert_eq!(&rows[1][..3], &[190, 190, 190]);
    assert_eq!(&rows[1][3..], &[215, 40, 40]);
    assert_eq!(&rows[0][..3], &[40, 90, 215]);
    assert_eq!(&rows[0][3..], &[255, 255, 255]);
}
