//! `Scene::silhouette_detail`: the outline meets the tolerance and the interior its
//! multiple, both certified; an interior multiple of 1 is the uniform choice or finer;
//! mirrors, powers of two and bad options.

#![cfg(feature = "silhouette")]
#![allow(clippy::float_cmp)]

mod common;

use std::sync::Arc;

use proptest::prelude::*;
use sphaera_mesh::geometry::Similarity;
use sphaera_mesh::{DVec3, shapes};
use sphaera_scene::{
    Camera, ObjectModel, Scene, SceneError, SilhouetteDetailOptions, SilhouetteOptions, Tolerance,
};

fn options(interior: f64) -> SilhouetteDetailOptions {
    SilhouetteDetailOptions::default().with_interior(interior)
}

fn camera(eye: DVec3) -> Camera {
    Camera::perspective(eye, DVec3::ZERO, 50.0, 1280, 720).expect("a camera")
}

/// A torus fine enough for the outline to matter, built once.
fn torus() -> Arc<ObjectModel> {
    static MODEL: std::sync::OnceLock<Arc<ObjectModel>> = std::sync::OnceLock::new();
    Arc::clone(MODEL.get_or_init(|| {
        let mesh = shapes::torus(1.0, 0.35, 40).expect("torus");
        Arc::new(ObjectModel::build("torus", mesh, &common::options()).expect("model"))
    }))
}

/// `n` points spread evenly over the unit sphere (a Fibonacci lattice); the `i`-th.
fn spread(i: usize, n: usize) -> DVec3 {
    let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
    let angle = i as f64 * std::f64::consts::PI * (3.0 - 5.0_f64.sqrt());
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * angle.cos(), r * angle.sin(), z)
}

/// The most pixels any sampled point of `bound` moves on the image when it moves by
/// `world` units, over points the camera sees (beyond the near plane, within the image's
/// half-diagonal angle) and directions spread over the sphere: measured by projecting
/// both ends, independently of the camera's certified bound.
fn sampled_pixels(camera: &Camera, bound: &sphaera_mesh::Sphere, world: f64) -> f64 {
    let seen = |p: DVec3| {
        let v = p - camera.eye();
        let z = v.dot(camera.forward());
        let angle = (z / v.length()).clamp(-1.0, 1.0).acos();
        (z >= camera.near() && angle <= camera.half_diagonal_angle())
            .then(|| camera.project(p).map(|(xy, _)| xy))
            .flatten()
    };
    let mut most = 0.0_f64;
    for i in 0..48 {
        for depth in [0.0, 0.5, 1.0] {
            let p = bound.center + spread(i, 48) * bound.radius * depth;
            let Some(from) = seen(p) else { continue };
            for j in 0..24 {
                if let Some(to) = seen(p + spread(j, 24) * world) {
                    most = most.max((to - from).length());
                }
            }
        }
    }
    most
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    /// Every choice meets its tolerances, its measures are the camera's bound on its world
    /// errors, the contour is never coarser than the interior, and a multiple of 1 is the
    /// uniform level or finer.
    #[test]
    fn outlines_meet_the_tolerance_and_interiors_its_multiple(
        placements in prop::collection::vec(
            (0usize..4, prop::array::uniform3(-4.0..4.0f64), prop::array::uniform3(-1.0..1.0f64),
             0.0..6.3f64, 0.3..3.0f64),
            1..5),
        eye in prop::array::uniform3(-12.0..12.0f64),
        pixels in 0.3..8.0f64,
        interior in 1.0..10.0f64,
    ) {
        let placements: Vec<(usize, Similarity)> = placements
            .into_iter()
            .map(|(m, t, axis, angle, scale)| {
                (m, common::pose(DVec3::from_array(t), DVec3::from_array(axis), angle, scale))
            })
            .collect();
        let scene = common::scene(&placements);
        let eye = DVec3::from_array(eye) + DVec3::new(0.0, 0.0, 15.0);
        let camera = camera(eye);
        let tolerance = Tolerance::Pixels(pixels);
        let report = scene.silhouette_detail(&camera, tolerance, &options(interior)).expect("report");
        prop_assert_eq!(report.instances.len(), scene.len());
        for (choice, instance) in report.instances.iter().zip(scene.instances()) {
            prop_assert!(choice.meets, "{choice:?}");
            prop_assert!(choice.contour_measured <= pixels);
            prop_assert!(choice.interior_measured <= pixels * interior);
            // The measures bound what the camera shows: no sampled point of the instance's
            // bounding sphere, moved by the world error, moves further on the image.
            let bound = instance.bounding_sphere();
            for (world, measured) in [
                (choice.contour_error, choice.contour_measured),
                (choice.interior_error, choice.interior_measured),
            ] {
                let sampled = sampled_pixels(&camera, &bound, world);
                prop_assert!(
                    sampled <= measured * (1.0 + 1e-9) + 1e-12,
                    "a move of {} shows as {} px, measured {} px", world, sampled, measured
                );
            }
            prop_assert!(choice.contour_triangles <= choice.triangles);
            prop_assert!(choice.triangles <= instance.model.mesh().triangle_count());
            // Drawn at the camera's pixels, the outline moved within the tolerance and a
            // pixel of sampling (a pixel's diagonal: the measure is between pixel
            // centres).
            if let Some(moved) = choice.outline_pixels {
                prop_assert!(
                    moved <= pixels + std::f64::consts::SQRT_2,
                    "outline moved {} px for {} px: {:?}", moved, pixels, choice
                );
            }
        }
        let strict = scene.silhouette_detail(&camera, tolerance, &options(1.0)).expect("report");
        // The uniform meshes are those detail chooses (when every instance's spheres can
        // meet the tolerance too: a near one may need a tree finer than the models build).
        let detail = match scene.detail(Some(&camera), tolerance) {
            Ok(detail) => detail,
            Err(SceneError::ToleranceBelowFinest { .. }) => return Ok(()),
            Err(other) => return Err(TestCaseError::fail(other.to_string())),
        };
        for ((one, choice), uniform) in strict.instances.iter().zip(&report.instances).zip(&detail.instances) {
            prop_assert!(one.meets && one.interior_measured <= pixels);
            prop_assert!(one.triangles <= uniform.mesh.count, "{one:?} against {uniform:?}");
            prop_assert_eq!(choice.uniform_triangles, uniform.mesh.count);
        }
    }
}

#[test]
fn the_interior_is_coarser_and_the_outline_as_fine() {
    let mut scene = Scene::new();
    scene.add("torus", torus(), Similarity::IDENTITY);
    let camera = camera(DVec3::new(0.0, -4.0, 3.0));
    let tolerance = Tolerance::Pixels(4.0);
    let strict = scene
        .silhouette_detail(&camera, tolerance, &options(1.0))
        .expect("strict");
    let mut last = strict.triangles;
    for interior in [2.0, 4.0, 8.0] {
        let report = scene
            .silhouette_detail(&camera, tolerance, &options(interior))
            .expect("report");
        let torus = &report.instances[0];
        assert!(torus.meets && torus.contour_measured <= 4.0, "{torus:?}");
        // Drawn at the camera's pixels, the outline moved within the tolerance (and a
        // pixel of sampling) however coarse the interior.
        let moved = torus
            .outline_pixels
            .expect("a tolerance in pixels, all in front");
        assert!(
            moved <= 4.0 + std::f64::consts::SQRT_2,
            "{interior}: {moved}"
        );
        assert!(torus.contour_triangles > 0);
        assert!(
            report.triangles <= last,
            "{interior}: {} after {last}",
            report.triangles
        );
        last = report.triangles;
    }
    // This small torus bottoms out at its base mesh; the bunny saves more (see the
    // CLI's demonstration). With the paper's corner rule it saved 12 % here, but its
    // outline then moved 4.1 pixels for a tolerance of 4 (measured as above): the region
    // widened by each triangle's error bound keeps it at 2.8 and saves 6 %.
    assert!(
        100 * last < 95 * strict.triangles,
        "8× interior: {last} of {}",
        strict.triangles
    );
    assert!(strict.triangles <= strict.uniform_triangles);
}

/// A mirrored instance seen from the mirrored eye is the same picture: the same mesh.
#[test]
fn a_mirror_pose_sees_the_mirrored_view() {
    let mirror =
        Similarity::new(glam::DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0))).expect("a mirror");
    let eye = DVec3::new(2.5, -3.0, 2.0);
    let mut plain = Scene::new();
    plain.add("torus", torus(), Similarity::IDENTITY);
    let mut mirrored = Scene::new();
    mirrored.add("torus", torus(), mirror);
    let tolerance = Tolerance::RelativeToDiagonal(0.002);
    let a = plain
        .silhouette_detail(&camera(eye), tolerance, &options(4.0))
        .expect("plain");
    let b = mirrored
        .silhouette_detail(
            &camera(eye * DVec3::new(-1.0, 1.0, 1.0)),
            tolerance,
            &options(4.0),
        )
        .expect("mirrored");
    assert_eq!(a.instances[0].triangles, b.instances[0].triangles);
    assert_eq!(a.instances[0].contour_error, b.instances[0].contour_error);
}

/// Scaling the scene and the camera by a power of two gives the same meshes, the errors
/// scaled exactly and the same pixels.
#[test]
fn powers_of_two_give_identical_choices() {
    for exponent in [-40, -3, 5, 40] {
        let k = 2f64.powi(exponent);
        let mut base = Scene::new();
        let mut scaled = Scene::new();
        for (i, t) in [DVec3::ZERO, DVec3::new(3.0, 0.0, -6.0)]
            .into_iter()
            .enumerate()
        {
            let pose = |s: f64| {
                Similarity::new(glam::DAffine3::from_scale_rotation_translation(
                    DVec3::splat(s),
                    glam::DQuat::from_rotation_z(0.3 * i as f64),
                    t * s,
                ))
                .expect("pose")
            };
            base.add(format!("t{i}"), torus(), pose(1.0));
            scaled.add(format!("t{i}"), torus(), pose(k));
        }
        let eye = DVec3::new(0.5, -4.0, 3.0);
        for (tolerance, scaled_tolerance) in [
            (Tolerance::Pixels(1.5), Tolerance::Pixels(1.5)),
            (Tolerance::Absolute(0.01), Tolerance::Absolute(0.01 * k)),
            (
                Tolerance::RelativeToDiagonal(0.003),
                Tolerance::RelativeToDiagonal(0.003),
            ),
        ] {
            let a = base
                .silhouette_detail(&camera(eye), tolerance, &options(3.0))
                .expect("base");
            let b = scaled
                .silhouette_detail(&camera(eye * k), scaled_tolerance, &options(3.0))
                .expect("scaled");
            for (x, y) in a.instances.iter().zip(&b.instances) {
                assert_eq!(x.triangles, y.triangles, "2^{exponent} {tolerance}");
                assert_eq!(x.contour_error * k, y.contour_error);
                assert_eq!(x.interior_error * k, y.interior_error);
                assert_eq!(x.contour_measured, y.contour_measured);
            }
        }
    }
}

#[test]
fn bad_options_are_refused_with_the_reason() {
    let mut scene = Scene::new();
    scene.add("torus", torus(), Similarity::IDENTITY);
    let camera = camera(DVec3::new(0.0, -4.0, 3.0));
    for bad in [
        options(0.5),
        options(f64::NAN),
        options(f64::INFINITY),
        SilhouetteDetailOptions::default().with_threshold_cells(f32::NAN),
    ] {
        let error = scene
            .silhouette_detail(&camera, Tolerance::Pixels(1.0), &bad)
            .expect_err("refused");
        assert!(matches!(error, SceneError::InvalidOption { .. }), "{error}");
    }
    assert_eq!(
        scene
            .silhouette_detail(&camera, Tolerance::Pixels(1.0), &options(0.5))
            .expect_err("refused")
            .to_string(),
        "invalid option: `interior` (0.5) must be a finite multiple of the tolerance of at least 1"
    );
    let error = scene
        .silhouette_detail(&camera, Tolerance::Pixels(f64::NAN), &options(2.0))
        .expect_err("NaN");
    assert!(matches!(error, SceneError::InvalidTolerance { .. }));

    // A view step that does not divide 180°: the model has no labels, and says why.
    let model_options =
        common::options().with_silhouette(SilhouetteOptions::default().with_step_degrees(7.0));
    let model = ObjectModel::build(
        "odd-views",
        shapes::sphere(1.0, 8).expect("sphere"),
        &model_options,
    )
    .expect("the model builds without labels");
    assert!(model.silhouette_labels().is_err());
    let mut scene = Scene::new();
    scene.add("ball", Arc::new(model), Similarity::IDENTITY);
    let error = scene
        .silhouette_detail(&camera, Tolerance::Pixels(1.0), &options(2.0))
        .expect_err("no labels");
    let message = error.to_string();
    assert!(
        matches!(error, SceneError::NoSilhouetteLabels { .. }) && message.contains("odd-views"),
        "{message}"
    );
}

/// Out of view, an instance takes its coarsest mesh whatever its outline.
#[test]
fn an_instance_out_of_view_is_coarsest() {
    let mut scene = Scene::new();
    scene.add(
        "behind",
        torus(),
        Similarity::from_translation(DVec3::new(0.0, 40.0, -30.0)).expect("pose"),
    );
    let camera = Camera::perspective(
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::new(0.0, -1.0, 5.0),
        40.0,
        640,
        480,
    )
    .expect("camera");
    let report = scene
        .silhouette_detail(&camera, Tolerance::Pixels(0.5), &options(2.0))
        .expect("report");
    let choice = &report.instances[0];
    assert!(!choice.visible && choice.meets);
    assert_eq!(choice.triangles, torus().mesh_levels()[0].triangles);
}

/// In front of the eye but outside the frame (a case proptest found): the instance is
/// coarsest, and drawing it finds nothing of its outline on the image to have moved.
#[test]
fn an_instance_beside_the_frame_shows_no_outline() {
    for angle in [0.0, 0.7, 2.1, 4.4] {
        let pose = common::pose(DVec3::new(0.0, -3.89, 3.83), DVec3::X, angle, 0.3);
        let scene = common::scene(&[(0, pose)]);
        let camera = camera(DVec3::new(0.0, 0.0, 6.76));
        let report = scene
            .silhouette_detail(&camera, Tolerance::Pixels(0.3), &options(1.0))
            .expect("report");
        let choice = &report.instances[0];
        assert!(!choice.visible && choice.meets, "{choice:?}");
        assert_eq!(choice.outline_pixels, Some(0.0), "{angle}: {choice:?}");
    }
}
