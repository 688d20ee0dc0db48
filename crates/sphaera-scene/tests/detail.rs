//! `Scene::detail` against brute force: the chosen cut of the tree the spheres are taken
//! from meets the tolerance by its certified error (recomputed here) and every coarser cut
//! fails it, no other tree offers fewer spheres, the smallest cut is recomputed, a
//! tolerance below a model's finest is an error; the camera's pixel bound holds for
//! random displacements; the mesh ladder is the hierarchy's selective refinement; scaling
//! by powers of two gives identical choices.

#![allow(clippy::float_cmp)]

mod common;

use proptest::prelude::*;
use sphaera_mesh::{DVec3, Sphere};
use sphaera_scene::{Camera, ObjectModel, SceneError, Tolerance};

/// The camera sees `p`: beyond the near plane and within the image's corner angle.
fn seen(camera: &Camera, p: DVec3) -> bool {
    let v = p - camera.eye();
    let z = v.dot(camera.forward());
    z >= camera.near() && v.angle_between(camera.forward()) <= camera.half_diagonal_angle()
}

fn unit(v: DVec3) -> DVec3 {
    v.try_normalize().unwrap_or(DVec3::X)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(512)))]

    /// Any two seen points of a sphere `error` apart land at most `projected_error` apart.
    /// Every case checks a displacement: the point is placed where the camera sees it
    /// (within half the image's corner angle, deep enough that a move of `error` stays
    /// in view and beyond the near plane), and the sphere around it anywhere.
    #[test]
    fn the_pixel_bound_holds_for_any_displacement(
        eye in prop::array::uniform3(-10.0..10.0f64),
        look in prop::array::uniform3(-1.0..1.0f64),
        fov in 10.0..150.0f64,
        width in 1u32..4000,
        height in 1u32..3000,
        off_axis in 0.0..1.0f64,
        azimuth in 0.0..std::f64::consts::TAU,
        farther in 0.0..30.0f64,
        radius in 0.01..5.0f64,
        inside in prop::array::uniform3(-1.0..1.0f64),
        direction in prop::array::uniform3(-1.0..1.0f64),
        error in 1e-4..0.5f64,
    ) {
        let eye = DVec3::from_array(eye);
        let camera = Camera::perspective(eye, eye + unit(DVec3::from_array(look)), fov, width, height)
            .expect("a camera");
        let half = 0.5 * camera.half_diagonal_angle();
        let (right, up) = camera.forward().any_orthonormal_pair();
        let angle = off_axis * half;
        let ray = camera.forward() * angle.cos()
            + (right * azimuth.cos() + up * azimuth.sin()) * angle.sin();
        // Within `half` of the axis, a move of `error` turns the ray by at most
        // asin(error / distance) ≤ half, and lowers the depth by at most `error`.
        let distance = (camera.near() + error) / half.cos() + error / half.sin() + farther;
        let p = eye + ray * distance;
        let q = p + unit(DVec3::from_array(direction)) * error;
        prop_assert!(seen(&camera, p) && seen(&camera, q), "{p} {q}");
        let sphere = Sphere::new(p - DVec3::from_array(inside).clamp_length_max(1.0) * radius, radius);
        let bound = camera.projected_error(&sphere, error);
        prop_assert!(bound.is_some(), "a seen point's sphere said unseen");
        let bound = bound.unwrap_or_default();
        let (pp, _) = camera.project(p).expect("in front");
        let (qq, _) = camera.project(q).expect("in front");
        prop_assert!(
            pp.distance(qq) <= bound * (1.0 + 1e-9),
            "moved {} px, bound {bound}", pp.distance(qq)
        );
    }

    /// An unseen sphere is said unseen only when no point of it is seen: points of spheres
    /// anywhere, including behind the camera.
    #[test]
    fn a_sphere_said_unseen_has_no_seen_point(
        eye in prop::array::uniform3(-10.0..10.0f64),
        look in prop::array::uniform3(-1.0..1.0f64),
        fov in 10.0..150.0f64,
        center in prop::array::uniform3(-20.0..20.0f64),
        radius in 0.01..5.0f64,
        inside in prop::array::uniform3(-1.0..1.0f64),
        error in 1e-4..0.5f64,
    ) {
        let eye = DVec3::from_array(eye);
        let camera = Camera::perspective(eye, eye + unit(DVec3::from_array(look)), fov, 640, 480)
            .expect("a camera");
        let sphere = Sphere::new(DVec3::from_array(center), radius);
        let p = sphere.center + DVec3::from_array(inside).clamp_length_max(1.0) * radius;
        if camera.projected_error(&sphere, error).is_none() {
            prop_assert!(!seen(&camera, p), "a seen point in a sphere said unseen");
        }
    }

    /// The chosen levels are the coarsest that meet the tolerance, for random poses,
    /// tolerances and cameras.
    #[test]
    fn the_chosen_levels_are_the_coarsest_that_meet(
        placements in prop::collection::vec(
            (0usize..4, prop::array::uniform3(-20.0..20.0f64), prop::array::uniform3(-1.0..1.0f64),
             0.0..6.3f64, -2.0..2.0f64),
            1..12,
        ),
        kind in 0usize..3,
        amount in 0.0..1.0f64,
        eye in prop::array::uniform3(-30.0..30.0f64),
    ) {
        let placements: Vec<_> = placements
            .into_iter()
            .map(|(m, t, axis, angle, log_scale)| {
                (m, common::pose(DVec3::from_array(t), DVec3::from_array(axis), angle, 2f64.powf(log_scale)))
            })
            .collect();
        let scene = common::scene(&placements);
        let tolerance = match kind {
            0 => Tolerance::Absolute(amount * 0.5),
            1 => Tolerance::RelativeToDiagonal(amount * 0.2),
            _ => Tolerance::Pixels(amount * 20.0),
        };
        let camera = Camera::perspective(DVec3::from_array(eye), DVec3::ZERO, 60.0, 1280, 720)
            .expect("a camera");
        let report = match scene.detail(Some(&camera), tolerance) {
            Ok(report) => report,
            // Only a tolerance below a model's finest (1 % of its diagonal here) is
            // refused, naming a model of the scene.
            Err(SceneError::ToleranceBelowFinest { model, tolerance: need, finest, diagonal }) => {
                prop_assert!(need < finest && finest == 0.01 * diagonal, "{need} {finest}");
                prop_assert!(scene.instances().iter().any(|i| i.model.name() == model));
                return Ok(());
            }
            Err(other) => return Err(TestCaseError::fail(other.to_string())),
        };
        prop_assert_eq!(report.instances.len(), scene.len());
        for (instance, detail) in scene.instances().iter().zip(&report.instances) {
            let model = &instance.model;
            let s = instance.pose.scale();
            // Brute force: every level's error measured in the tolerance's unit.
            let measure = |e: f64| -> Option<f64> {
                match tolerance {
                    Tolerance::Absolute(_) => Some(e * s),
                    Tolerance::RelativeToDiagonal(_) => Some(e / model.mesh().bounding_box_diagonal()),
                    Tolerance::Pixels(_) => camera.projected_error(
                        &instance.pose.sphere(&model.bounding_sphere()), e * s),
                }
            };
            // The mesh: the coarsest ladder level whose measured error meets the
            // tolerance (a level that cannot be seen at all meets any tolerance in pixels).
            let ladder: Vec<f64> = model.mesh_levels().iter().map(|l| l.error_bound).collect();
            let meets = |e: f64| measure(e).is_none_or(|m| m <= tolerance.value());
            let level = ladder.iter().position(|&e| meets(e)).expect("the input meets");
            let mesh = detail.mesh;
            prop_assert!(mesh.meets && mesh.level == level && mesh.levels == ladder.len(), "{detail:?}");
            prop_assert_eq!(mesh.count, model.mesh_levels()[level].triangles);
            prop_assert_eq!(mesh.error, ladder[level] * s);
            // The tolerance asked of the model: the largest error that meets the
            // tolerance for this instance.
            let need = detail.model_tolerance;
            prop_assert_eq!(detail.tolerance, need * s);
            // (`t / s · s` may round a unit in the last place above `t`.)
            let meets = |e: f64| measure(e).is_none_or(|m| m <= tolerance.value() * (1.0 + 1e-15));
            prop_assert!(meets(need), "{detail:?}");
            match tolerance {
                Tolerance::Absolute(t) => prop_assert_eq!(need, t / s),
                Tolerance::RelativeToDiagonal(t) => prop_assert_eq!(need, t * model.diagonal()),
                Tolerance::Pixels(_) => {}
            }
            // The spheres: the coarsest cut of the tree they come from whose certified
            // error (recomputed here) meets the need; every coarser cut fails it.
            let trees = model.trees();
            let used = &trees[detail.tree.index];
            let tree = used.tree();
            prop_assert_eq!(detail.tree.tolerance, used.tolerance());
            prop_assert_eq!(detail.tree.leaves, tree.leaves().len());
            let spheres = detail.spheres;
            let level = spheres.level;
            let error = common::level_error(model, tree, level, need);
            prop_assert_eq!(error.map(|e| e * s), Some(spheres.error), "{:?}", detail);
            for coarser in 0..level {
                prop_assert!(common::level_error(model, tree, coarser, need).is_none(), "{detail:?}");
            }
            prop_assert!(spheres.error <= need * s * (1.0 + 1e-15) && meets(spheres.error / s));
            prop_assert!(spheres.measured <= tolerance.value() * (1.0 + 1e-12), "{detail:?}");
            let node_error = tree.cut_at(level).iter().map(|&i| tree.nodes()[i].error).fold(f64::NEG_INFINITY, f64::max);
            prop_assert_eq!(spheres.node_error, node_error * s);
            prop_assert!(spheres.error <= spheres.node_error);
            prop_assert_eq!(spheres.count, tree.cut_at(level).len());
            prop_assert_eq!(spheres.levels, tree.level_count());
            // No other tree of the model offers fewer spheres.
            for other in &trees {
                if let Some(l) = (0..other.tree().level_count())
                    .find(|&l| common::level_error(model, other.tree(), l, need).is_some())
                {
                    prop_assert!(other.tree().cut_at(l).len() >= spheres.count, "{detail:?}");
                }
            }
            let full = model.collision_tree().leaf_count();
            prop_assert_eq!((spheres.finest, detail.full_spheres), (full, full));
            // The smallest cut, recomputed: never more spheres than the level cut.
            let cut = &detail.cut;
            let (nodes, cut_error) = common::smallest_cut(model, tree, need);
            prop_assert_eq!(cut.count, nodes.len());
            prop_assert_eq!(cut.error, cut_error * s);
            prop_assert!(cut.count >= 1 && cut.count <= spheres.count, "{detail:?}");
            prop_assert!(cut.deepest_level <= level);
            prop_assert!(cut.measured <= tolerance.value() * (1.0 + 1e-12), "{detail:?}");
            let seen = camera.pixels_per_unit(&instance.pose.sphere(&model.bounding_sphere()));
            prop_assert_eq!(detail.visible, seen.is_some());
        }
        let spheres: usize = report.instances.iter().map(|d| d.spheres.count).sum();
        prop_assert_eq!(report.spheres, spheres);
        let cut_spheres: usize = report.instances.iter().map(|d| d.cut.count).sum();
        prop_assert_eq!(report.cut_spheres, cut_spheres);
        let full: usize = report.instances.iter().map(|d| d.full_spheres).sum();
        prop_assert_eq!(report.full_spheres, full);
        prop_assert!(report.spheres <= report.full_spheres);
        let triangles: usize = report.instances.iter().map(|d| d.mesh.count).sum();
        prop_assert_eq!(report.triangles, triangles);
        prop_assert!(report.triangles <= report.full_triangles);
    }
}

#[test]
fn the_mesh_ladder_is_the_hierarchys_selective_refinement() {
    for model in common::models() {
        let ladder = model.mesh_levels();
        assert!(ladder.len() >= 3, "{}: {ladder:?}", model.name());
        for pair in ladder.windows(2) {
            assert!(
                pair[0].triangles < pair[1].triangles,
                "{}: {pair:?}",
                model.name()
            );
            assert!(
                pair[0].error_bound > pair[1].error_bound,
                "{}: {pair:?}",
                model.name()
            );
        }
        let finest = ladder.last().expect("a level");
        assert_eq!(finest.triangles, model.mesh().triangle_count());
        assert_eq!(finest.error_bound, 0.0);
        for (level, entry) in ladder.iter().enumerate() {
            assert!(entry.error_bound <= entry.requested || level == 0);
            let mesh = model.mesh_level(level).expect("in range");
            assert_eq!(
                mesh.mesh.triangle_count(),
                entry.triangles,
                "{}",
                model.name()
            );
            assert_eq!(mesh.error_bound, entry.error_bound, "{}", model.name());
            // The certified bound holds against a sampled Hausdorff distance.
            let measured =
                sphaera_tests::reference_hausdorff(model.mesh(), &mesh.mesh, 2_000, 1).symmetric();
            assert!(
                measured <= entry.error_bound * (1.0 + 1e-9) + 1e-12,
                "{}",
                model.name()
            );
        }
    }
}

#[test]
fn a_tolerance_in_pixels_needs_a_camera_and_bad_tolerances_are_refused() {
    let scene = common::scene(&[(0, sphaera_mesh::geometry::Similarity::IDENTITY)]);
    assert!(matches!(
        scene.detail(None, Tolerance::Pixels(1.0)),
        Err(SceneError::NoCamera)
    ));
    for bad in [
        Tolerance::Absolute(f64::NAN),
        Tolerance::RelativeToDiagonal(-0.1),
        Tolerance::Absolute(f64::INFINITY),
    ] {
        assert!(matches!(
            scene.detail(None, bad),
            Err(SceneError::InvalidTolerance { .. })
        ));
    }
    // An empty scene has an empty report.
    let empty = sphaera_scene::Scene::new()
        .detail(None, Tolerance::Absolute(1.0))
        .expect("a report");
    assert!(empty.instances.is_empty() && empty.full_triangles == 0);
    assert_eq!(
        (empty.spheres_saved_percent, empty.triangles_saved_percent),
        (0.0, 0.0)
    );
}

/// Poses scaled by 2^k with the tolerance scaled alike give identical choices, with
/// errors scaled exactly; models built on meshes scaled by 2^k have errors scaled exactly.
#[test]
fn scaling_by_powers_of_two_gives_identical_choices() {
    let placements: Vec<_> = (0..8)
        .map(|k| {
            let t = DVec3::new(k as f64 * 1.7, (k % 3) as f64, -(k as f64));
            (
                k,
                common::pose(t, DVec3::new(1.0, 2.0, 3.0), k as f64, 1.0 + k as f64 / 8.0),
            )
        })
        .collect();
    // Models of their own: the trees both scenes take are those these requests build.
    let models = common::fresh_models();
    let base = common::scene_of(&models, &placements);
    let camera = Camera::perspective(DVec3::new(3.0, 2.0, 8.0), DVec3::ZERO, 50.0, 1920, 1080)
        .expect("a camera");
    for k in [-30i32, -1, 3, 40] {
        let f = 2f64.powi(k);
        let scaled_placements: Vec<_> = placements
            .iter()
            .map(|&(m, p)| {
                let a = p.affine();
                let scaled = glam::DAffine3 {
                    matrix3: a.matrix3 * f,
                    translation: a.translation * f,
                };
                (
                    m,
                    sphaera_mesh::geometry::Similarity::new(scaled).expect("similarity"),
                )
            })
            .collect();
        let scaled = common::scene_of(&models, &scaled_placements);
        let scaled_camera = Camera::perspective(camera.eye() * f, DVec3::ZERO, 50.0, 1920, 1080)
            .expect("a camera")
            .with_near(camera.near() * f)
            .expect("near");
        for (tolerance, scaled_tolerance, cam, scaled_cam) in [
            (
                Tolerance::Absolute(0.05),
                Tolerance::Absolute(0.05 * f),
                None,
                None,
            ),
            (
                Tolerance::RelativeToDiagonal(0.01),
                Tolerance::RelativeToDiagonal(0.01),
                None,
                None,
            ),
            (
                Tolerance::Pixels(8.0),
                Tolerance::Pixels(8.0),
                Some(&camera),
                Some(&scaled_camera),
            ),
        ] {
            let a = base.detail(cam, tolerance).expect("report");
            let b = scaled.detail(scaled_cam, scaled_tolerance).expect("report");
            for (x, y) in a.instances.iter().zip(&b.instances) {
                assert_eq!(
                    (x.tree.index, x.spheres.level, x.mesh.level),
                    (y.tree.index, y.spheres.level, y.mesh.level),
                    "2^{k} {tolerance}"
                );
                assert_eq!(x.model_tolerance, y.model_tolerance, "2^{k} {tolerance}");
                assert_eq!(x.mesh.error * f, y.mesh.error, "2^{k}");
                assert_eq!(x.spheres.error * f, y.spheres.error, "2^{k}");
                assert_eq!(x.cut.count, y.cut.count, "2^{k} {tolerance}");
                assert_eq!(x.cut.error * f, y.cut.error, "2^{k}");
            }
        }
    }
    // A model of a mesh scaled by 2^k: every error scaled exactly.
    let (name, mesh) = common::meshes().swap_remove(1);
    let f = 2f64.powi(-12);
    let scaled_mesh = sphaera_tests::awkward::mapped(&mesh, |p| p * f, false);
    let a = ObjectModel::build(name, mesh, &common::options()).expect("model");
    let b = ObjectModel::build(name, scaled_mesh, &common::options()).expect("model");
    let scaled_errors: Vec<f64> = a.tree_errors().iter().map(|e| e * f).collect();
    assert_eq!(scaled_errors, b.tree_errors());
    assert_eq!(a.mesh_levels().len(), b.mesh_levels().len());
    for (x, y) in a.mesh_levels().iter().zip(b.mesh_levels()) {
        assert_eq!(
            (x.triangles, x.error_bound * f),
            (y.triangles, y.error_bound)
        );
    }
}

/// With the `hal` feature, a model of a closed genus-0 mesh has its HAL tree; a torus
/// says why it has none.
#[cfg(feature = "hal")]
#[test]
fn models_carry_their_hal_tree_where_the_mesh_allows_one() {
    for model in common::models() {
        match (model.name(), model.hal_tree()) {
            ("torus", Err(why)) => assert!(why.to_string().contains("genus"), "{why}"),
            ("torus", Ok(_)) => panic!("a torus has no HAL tree"),
            (name, tree) => {
                let tree = tree.unwrap_or_else(|e| panic!("{name}: {e}"));
                assert!(tree.depth() > 0, "{name}");
                assert_eq!(tree.mesh().triangle_count(), model.mesh().triangle_count());
            }
        }
    }
}

/// The same scene gets the same detail on one thread and on two (and, through `cargo
/// xtask test`, without the `parallel` feature: the digest is recorded), models and all.
#[test]
fn the_same_detail_on_any_number_of_threads() {
    let placements: Vec<_> = (0..12)
        .map(|k| {
            let t = DVec3::new(0.6 * (k % 4) as f64, 0.4 * (k / 4) as f64, -1.5 * k as f64);
            (
                k,
                common::pose(t, DVec3::new(2.0, 1.0, k as f64), 0.5 * k as f64, 1.0),
            )
        })
        .collect();
    let camera = Camera::perspective(
        DVec3::new(1.0, 1.0, 4.0),
        DVec3::new(1.0, 0.5, -8.0),
        55.0,
        1280,
        720,
    )
    .expect("a camera");
    // Fresh models for each run: the trees are built in the run, on its threads.
    let run = |threads: usize| {
        let scene = common::scene_of(&common::fresh_models(), &placements);
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
            .install(|| {
                scene
                    .detail(Some(&camera), Tolerance::Pixels(5.0))
                    .expect("detail")
                    .without_times()
            })
    };
    let one = run(1);
    assert_eq!(one, run(2));
    let mut digest: u64 = 0xcbf2_9ce4_8422_2325;
    let mut mix = |x: u64| {
        digest ^= x;
        digest = digest.wrapping_mul(0x0100_0000_01b3);
    };
    for d in &one.instances {
        mix(d.spheres.level as u64);
        mix(d.spheres.count as u64);
        mix(d.spheres.error.to_bits());
        mix(d.spheres.measured.to_bits());
        mix(d.mesh.level as u64);
        mix(d.mesh.count as u64);
        mix(d.mesh.error.to_bits());
        mix(d.mesh.measured.to_bits());
        mix(d.cut.count as u64);
        mix(d.cut.error.to_bits());
        mix(d.cut.measured.to_bits());
        mix(d.model_tolerance.to_bits());
        mix(d.tree.index as u64);
        mix(d.tree.leaves as u64);
        mix(u64::from(d.tree.built));
    }
    mix(one.trees_built as u64);
    assert!(
        one.triangles < one.full_triangles,
        "{} of {} triangles",
        one.triangles,
        one.full_triangles,
    );
    assert_eq!(
        digest, 0x6acb_86c7_e2da_3a06,
        "digest {digest:#018x}, {} spheres, {} triangles",
        one.spheres, one.triangles
    );
}
