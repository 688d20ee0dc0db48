//! Level of detail guided by labels: every triangle of an extraction meets its allowance
//! (checked again from the output), factor 0 keeps the contour exact, a larger error or
//! factor never gives more triangles, the static weights freeze the contour, and the
//! errors are named.
// Weights of exactly 0 and 1 are compared exactly on purpose.
#![allow(clippy::float_cmp)]

use sphaera_mesh::{DVec3, shapes};
use sphaera_silhouette::{
    ContourTolerance, Contours, DistanceTransform, Interpolation, LabelOptions, Labels,
    SilhouetteError, ViewDependent, ViewSet, contour_weights,
};
use sphaera_simplify::{Hierarchy, Placement, SimplifyOptions, simplify};

fn setup() -> (sphaera_mesh::TriMesh, Hierarchy, Labels) {
    let mesh = shapes::torus(1.0, 0.35, 40).unwrap();
    let hierarchy =
        Hierarchy::build(&mesh, &SimplifyOptions::default().with_target_triangles(60)).unwrap();
    let views = ViewSet::regular(30.0).unwrap();
    let labels = Labels::compute(
        &mesh,
        &views,
        &LabelOptions::default()
            .with_resolution(96)
            .with_contours(Contours::All),
    )
    .unwrap();
    (mesh, hierarchy, labels)
}

#[test]
fn every_triangle_meets_its_allowance() {
    let (mesh, hierarchy, labels) = setup();
    let diagonal = mesh.bounding_box_diagonal();
    let mut extractor = ViewDependent::new(&hierarchy, &labels).unwrap();
    let mut previous = usize::MAX;
    for (direction, interpolation) in [
        (DVec3::Z, Interpolation::Nearest),
        (DVec3::new(0.4, -0.3, 0.7), Interpolation::Average(4)),
        (DVec3::X, Interpolation::Nearest),
    ] {
        for factor in [0.0, 0.25, 1.0] {
            let tolerance = ContourTolerance {
                error: 0.02 * diagonal,
                factor,
                threshold: 3.0,
                cells: f64::INFINITY,
            };
            let out = extractor
                .extract(direction, interpolation, tolerance)
                .unwrap();
            assert!(
                out.other_error <= tolerance.error,
                "{factor}: {}",
                out.other_error
            );
            assert!(
                out.contour_error <= tolerance.error * factor,
                "{factor}: {}",
                out.contour_error
            );
            assert!(
                out.contour_triangles > 0
                    && out.contour_triangles <= out.simplified.mesh.triangle_count()
            );
            assert_eq!(out.in_contour.len(), out.simplified.mesh.triangle_count());
            assert_eq!(
                out.in_contour.iter().filter(|&&c| c).count(),
                out.contour_triangles
            );
            // The whole mesh's bound is the larger of the two regions'.
            assert!(out.simplified.error_bound <= out.contour_error.max(out.other_error) + 1e-12);
            if direction == DVec3::X {
                assert!(
                    out.simplified.mesh.triangle_count() <= previous,
                    "a larger factor, no more triangles"
                );
                previous = out.simplified.mesh.triangle_count();
            }
        }
    }
    // A larger error never needs more triangles.
    let mut count = |error: f64| {
        extractor
            .extract(
                DVec3::Z,
                Interpolation::Nearest,
                ContourTolerance {
                    error: error * diagonal,
                    factor: 0.5,
                    threshold: 2.0,
                    cells: f64::INFINITY,
                },
            )
            .unwrap()
            .simplified
            .mesh
            .triangle_count()
    };
    let (coarse, middle, fine) = (count(0.05), count(0.01), count(0.002));
    assert!(
        coarse <= middle && middle <= fine,
        "{coarse} {middle} {fine}"
    );
}

/// Moving from view to view reuses the first phase and redoes the contour only: the
/// meshes are the ones a fresh extractor gives for each view, whatever came before
/// (including a change of error and back).
#[test]
fn coherent_extraction_equals_extraction_from_scratch() {
    let (mesh, hierarchy, labels) = setup();
    let diagonal = mesh.bounding_box_diagonal();
    let tolerance = |error: f64, factor: f64| ContourTolerance {
        error: error * diagonal,
        factor,
        threshold: 2.0,
        cells: f64::INFINITY,
    };
    let mut moving = ViewDependent::new(&hierarchy, &labels).unwrap();
    let path = (0..12).map(|i| {
        let a = f64::from(i) * 0.13;
        (
            DVec3::new(a.cos(), 0.3 * a.sin(), a.sin()),
            if i % 3 == 0 {
                Interpolation::Average(4)
            } else {
                Interpolation::Nearest
            },
            tolerance(
                if i == 7 { 0.04 } else { 0.015 },
                if i % 2 == 0 { 0.25 } else { 0.0 },
            ),
        )
    });
    for (direction, interpolation, tolerance) in path {
        let coherent = moving.extract(direction, interpolation, tolerance).unwrap();
        let fresh = ViewDependent::new(&hierarchy, &labels)
            .unwrap()
            .extract(direction, interpolation, tolerance)
            .unwrap();
        assert_eq!(coherent.simplified, fresh.simplified);
        assert_eq!(coherent.in_contour, fresh.in_contour);
        assert_eq!(
            (coherent.contour_error, coherent.other_error),
            (fresh.contour_error, fresh.other_error)
        );
    }
}

#[test]
fn static_weights_freeze_the_contour_of_every_view() {
    let (mesh, _, labels) = setup();
    // From every view, every vertex of a torus is near some silhouette.
    let all = contour_weights(&labels, &[], 1.0, 0.0).unwrap();
    assert!(all.iter().all(|&w| w == 0.0));
    let weights = contour_weights(&labels, &[0, 7, 20], 1.0, 0.0).unwrap();
    assert!(weights.contains(&0.0) && weights.contains(&1.0));
    let out = simplify(
        &mesh,
        &SimplifyOptions::default()
            .with_weights(weights.clone())
            .with_target_ratio(0.2),
    )
    .unwrap();
    for (i, &o) in out.original_vertex.iter().enumerate() {
        if weights[o as usize] == 0.0 {
            assert!(out.vertex_radii[i] <= 0.0, "contour vertex {o} moved");
        }
    }
    // One view only: fewer vertices in its contour than in three views' together.
    let one = contour_weights(&labels, &[0], 1.0, 0.0).unwrap();
    let zeros = |w: &[f64]| w.iter().filter(|&&x| x == 0.0).count();
    assert!(zeros(&one) < zeros(&weights));
    assert!(matches!(
        contour_weights(&labels, &[], 1.0, -1.0),
        Err(SilhouetteError::InvalidParameter { name: "factor", .. })
    ));
}

#[test]
fn mismatched_inputs_are_refused() {
    let (mesh, hierarchy, labels) = setup();
    let other = shapes::sphere(1.0, 10).unwrap();
    let other_labels = Labels::compute(
        &other,
        &ViewSet::regular(90.0).unwrap(),
        &LabelOptions::default()
            .with_resolution(16)
            .with_transform(DistanceTransform::Chamfer),
    )
    .unwrap();
    assert!(matches!(
        ViewDependent::new(&hierarchy, &other_labels),
        Err(SilhouetteError::MeshMismatch { .. })
    ));
    let optimal = Hierarchy::build(
        &mesh,
        &SimplifyOptions::default()
            .with_placement(Placement::Optimal)
            .with_target_triangles(60),
    )
    .unwrap();
    assert!(matches!(
        ViewDependent::new(&optimal, &labels),
        Err(SilhouetteError::NotSubset)
    ));
    let mut extractor = ViewDependent::new(&hierarchy, &labels).unwrap();
    for (error, factor) in [
        (-1.0, 0.5),
        (f64::NAN, 0.5),
        (0.1, f64::INFINITY),
        (0.1, 1.5),
    ] {
        assert!(matches!(
            extractor.extract(
                DVec3::Z,
                Interpolation::Nearest,
                ContourTolerance {
                    error,
                    factor,
                    threshold: 1.0,
                    cells: f64::INFINITY,
                }
            ),
            Err(SilhouetteError::InvalidParameter { .. })
        ));
    }
}

/// Scaling by a power of two scales the extraction exactly: the same triangles, the
/// positions and bounds scaled, the same contour region.
#[test]
fn scaling_by_a_power_of_two_scales_the_extraction_exactly() {
    let mesh = shapes::torus(1.0, 0.35, 24).unwrap();
    let views = ViewSet::regular(30.0).unwrap();
    let extract = |scale: f64| {
        let scaled = sphaera_mesh::TriMesh::new(
            mesh.positions().iter().map(|&p| p * scale).collect(),
            mesh.triangles().to_vec(),
        )
        .unwrap();
        let labels = Labels::compute(
            &scaled,
            &views,
            &LabelOptions::default()
                .with_resolution(64)
                .with_contours(Contours::External),
        )
        .unwrap();
        let hierarchy = Hierarchy::build(&scaled, &SimplifyOptions::default()).unwrap();
        ViewDependent::new(&hierarchy, &labels)
            .unwrap()
            .extract(
                DVec3::new(0.3, -0.5, 0.8),
                Interpolation::Average(4),
                ContourTolerance {
                    error: 0.03 * scale,
                    factor: 0.25,
                    threshold: 2.0,
                    cells: f64::INFINITY,
                },
            )
            .unwrap()
    };
    let reference = extract(1.0);
    for scale in [0.25, 8.0, 2f64.powi(-20), 2f64.powi(30)] {
        let scaled = extract(scale);
        let (a, b) = (&reference.simplified, &scaled.simplified);
        assert_eq!(a.mesh.triangles(), b.mesh.triangles(), "scale {scale}");
        assert_eq!(a.original_vertex, b.original_vertex);
        assert_eq!(reference.in_contour, scaled.in_contour);
        for (p, q) in a.mesh.positions().iter().zip(b.mesh.positions()) {
            assert_eq!(*p * scale, *q);
        }
        assert_eq!(reference.contour_error * scale, scaled.contour_error);
        assert_eq!(reference.other_error * scale, scaled.other_error);
    }
}

/// Where extraction must not fail: a sphere (no internal silhouette), labels at one cell
/// a side, threshold 0, a view along a face plane of a cube, and a view equidistant from
/// four cameras; every triangle still meets its allowance.
#[test]
fn awkward_settings_still_meet_every_allowance() {
    let cases = [
        (shapes::sphere(1.0, 20).unwrap(), 64, 0.0, DVec3::Z),
        (shapes::sphere(1.0, 20).unwrap(), 1, 2.0, DVec3::X),
        (shapes::cube(1.0, 6).unwrap(), 32, 1.0, DVec3::X),
        // Between four 90° cameras: (±1, 0, 0), (0, ±1, 0) around the equator's corner.
        (
            shapes::torus(1.0, 0.3, 20).unwrap(),
            32,
            2.0,
            DVec3::new(1.0, 1.0, 0.0),
        ),
    ];
    for (mesh, resolution, threshold, direction) in cases {
        let views = ViewSet::regular(90.0).unwrap();
        let labels = Labels::compute(
            &mesh,
            &views,
            &LabelOptions::default().with_resolution(resolution),
        )
        .unwrap();
        let hierarchy = Hierarchy::build(&mesh, &SimplifyOptions::default()).unwrap();
        let mut lod = ViewDependent::new(&hierarchy, &labels).unwrap();
        let error = 0.05 * mesh.bounding_box_diagonal();
        for interpolation in [Interpolation::Nearest, Interpolation::Average(4)] {
            let out = lod
                .extract(
                    direction,
                    interpolation,
                    ContourTolerance {
                        error,
                        factor: 0.5,
                        threshold,
                        cells: f64::INFINITY,
                    },
                )
                .unwrap();
            assert!(out.simplified.mesh.triangle_count() > 0);
            assert!(out.other_error <= error && out.contour_error <= 0.5 * error);
        }
    }
}

/// A view the labels do not have is an error naming it, not a panic (issue 40).
#[test]
fn weights_for_a_view_out_of_range_are_refused() {
    let (_, _, labels) = setup();
    let past = labels.views().len();
    for views in [vec![past], vec![0, usize::MAX]] {
        let error = contour_weights(&labels, &views, 1.0, 0.0).unwrap_err();
        assert!(
            matches!(
                error,
                SilhouetteError::InvalidParameter { name: "view", .. }
            ),
            "{error}"
        );
    }
    assert!(contour_weights(&labels, &[past - 1], 1.0, 0.0).is_ok());
}

#[test]
fn a_camera_position_sets_the_view_and_the_scale() {
    let (mesh, hierarchy, labels) = setup();
    let mut lod = ViewDependent::new(&hierarchy, &labels).unwrap();
    let tolerance = ContourTolerance::new(0.02 * mesh.bounding_box_diagonal());
    let ball = sphaera_silhouette::bounding_sphere(&mesh).unwrap();
    let (centre, radius) = (ball.center, ball.radius);
    let toward = DVec3::new(0.3, -0.2, 0.9).normalize();
    let mut previous = 0.0;
    // From far away to near (in radii of the ball): the view is the same, the outline
    // grows, its allowance shrinks, and every triangle meets its own.
    for distance in [1e6, 10.0, 3.0, 1.2] {
        let out = lod
            .extract_at(
                centre + toward * (distance * radius),
                Interpolation::Nearest,
                tolerance,
            )
            .unwrap();
        assert!(out.contour_error <= out.contour_allowance);
        assert!(out.other_error <= tolerance.error);
        assert!(out.contour_allowance <= tolerance.error * tolerance.factor);
        if previous > 0.0 {
            assert!(out.contour_allowance <= previous, "{distance}");
        }
        previous = out.contour_allowance;
    }
    // Far away it is the orthographic view from that direction.
    let far = lod
        .extract_at(centre + toward * 1e9, Interpolation::Nearest, tolerance)
        .unwrap();
    let along = lod
        .extract(toward, Interpolation::Nearest, tolerance)
        .unwrap();
    assert_eq!(
        far.simplified.mesh.triangles(),
        along.simplified.mesh.triangles()
    );
    for eye in [
        centre,
        centre + DVec3::X * (0.5 * radius),
        DVec3::splat(f64::NAN),
        DVec3::splat(f64::INFINITY),
    ] {
        assert!(
            matches!(
                lod.extract_at(eye, Interpolation::Nearest, tolerance),
                Err(SilhouetteError::CameraInside { .. })
            ),
            "{eye}"
        );
    }
}
