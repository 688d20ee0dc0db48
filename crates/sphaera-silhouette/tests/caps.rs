//! The caps on parameters that size memory (issue 38): each is refused just above its cap,
//! quickly and without allocating, with an error naming the parameter and the cap.

use glam::{DVec2, DVec3};
use sphaera_mesh::{Sphere, TriMesh, shapes};
use sphaera_silhouette::{
    Contours, DistanceTransform, FaceGrid, LabelOptions, Labels, MAX_LABELS, MAX_RESOLUTION,
    MAX_VIEWS, Projection, SilhouetteError, ViewSet, coverage, label_view, shaded_picture,
};

/// Asserts `error` is an `InvalidParameter` named `name` whose message names `cap`.
fn assert_capped(error: &SilhouetteError, name: &str, cap: &str) {
    assert!(
        matches!(error, SilhouetteError::InvalidParameter { name: n, .. } if *n == name),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(message.contains(name) && message.contains(cap), "{message}");
}

fn ball() -> TriMesh {
    shapes::sphere(1.0, 8).expect("sphere")
}

#[test]
fn a_view_step_below_the_cap_is_refused() {
    // 180°/128: the finest step, 32,514 views.
    let finest = ViewSet::regular(180.0 / 128.0).expect("the finest step");
    assert!(finest.len() <= MAX_VIEWS);
    assert_eq!(finest.len(), 2 + 127 * 256);
    // The reproducer, the next finer step that divides 180°, and absurd steps.
    for step in [0.00001, 180.0 / 129.0, 1e-300, f64::MIN_POSITIVE] {
        let error = ViewSet::regular(step).expect_err("too many views");
        assert_capped(&error, "step", "MAX_VIEWS");
    }
    // Steps that do not divide 180° are still refused as before.
    assert!(matches!(
        ViewSet::regular(7.0),
        Err(SilhouetteError::InvalidStep { .. })
    ));
}

#[test]
fn a_resolution_above_the_cap_is_refused_everywhere() {
    let mesh = ball();
    let frame = sphaera_silhouette::bounding_sphere(&mesh).expect("frame");
    let views = ViewSet::regular(90.0).expect("views");
    for resolution in [MAX_RESOLUTION + 1, 4_000_000_000, usize::MAX] {
        let labels = Labels::compute(
            &mesh,
            &views,
            &LabelOptions::default().with_resolution(resolution),
        )
        .expect_err("labels");
        assert_capped(&labels, "resolution", "MAX_RESOLUTION");
        let one = label_view(
            &mesh,
            DVec3::Z,
            Projection::Orthographic,
            resolution,
            DistanceTransform::Euclidean,
            Contours::All,
        )
        .expect_err("one view");
        assert_capped(&one, "resolution", "MAX_RESOLUTION");
        let covered = coverage(&mesh, frame, DVec3::Z, Projection::Orthographic, resolution)
            .expect_err("coverage");
        assert_capped(&covered, "resolution", "MAX_RESOLUTION");
        let values = vec![1.0; mesh.vertex_count()];
        let picture = shaded_picture(
            &mesh,
            frame,
            DVec3::Z,
            Projection::Orthographic,
            resolution,
            &values,
            1.0,
        )
        .expect_err("picture");
        assert_capped(&picture, "resolution", "MAX_RESOLUTION");
        let triangle = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let grid = FaceGrid::new(&[triangle], resolution).expect_err("grid");
        assert_capped(&grid, "resolution", "MAX_RESOLUTION");
    }
    // Zero is still its own error.
    assert!(matches!(
        FaceGrid::new(&[], 0),
        Err(SilhouetteError::InvalidResolution { resolution: 0 })
    ));
}

#[test]
fn the_resolution_cap_itself_is_accepted() {
    // A tiny mesh in a huge frame: the image is all background but for a few cells, so
    // the cap's 16.8 million cells cost only their 16 MB.
    let mesh = ball();
    let frame = Sphere {
        center: DVec3::ZERO,
        radius: 1e6,
    };
    let image = coverage(
        &mesh,
        frame,
        DVec3::Z,
        Projection::Orthographic,
        MAX_RESOLUTION,
    )
    .expect("the cap is accepted");
    assert_eq!(image.len(), MAX_RESOLUTION * MAX_RESOLUTION);
}

#[test]
fn more_labels_than_the_cap_are_refused_before_labelling() {
    // 16,746 vertices × 32,514 views: just above 2^29 labels.
    let mesh = shapes::sphere(1.0, 184).expect("sphere");
    let views = ViewSet::regular(180.0 / 128.0).expect("views");
    assert!(mesh.vertex_count() * views.len() > MAX_LABELS);
    let error = Labels::compute(&mesh, &views, &LabelOptions::default().with_resolution(1))
        .expect_err("too many labels");
    assert_capped(&error, "vertices × views", "MAX_LABELS");
    // A coarser step fits.
    let coarse = ViewSet::regular(90.0).expect("views");
    let labels = Labels::compute(&mesh, &coarse, &LabelOptions::default().with_resolution(4))
        .expect("within the cap");
    assert_eq!(
        labels.storage_bytes(),
        2 * mesh.vertex_count() * coarse.len()
    );
}
