//! Sphere-trees built to what a scene asks: every instance's spheres meet its tolerance,
//! checked against an independent evaluation (`evaluate_set`: the worst error is at
//! least its lower bound) and brute force (the spheres cover dense surface samples, and
//! no sampled point of them lies farther outside the object than the tolerance); a
//! tolerance is built once per model, a finer one only when no tree meets it; tolerances
//! that need deep trees; a flat sheet in a scene; a tolerance below a model's finest or out
//! of reach is an error naming the model, not a panic; collisions descend the trees built;
//! the four shared meshes at 2 %.

#![allow(clippy::float_cmp)]

mod common;

use std::sync::Arc;

use proptest::prelude::*;
use sphaera_mesh::geometry::Similarity;
use sphaera_mesh::{DVec3, Length, Sphere, TriMesh};
use sphaera_scene::{
    Budget, Instance, InstanceDetail, ModelOptions, ObjectModel, Scene, SceneError, Tolerance,
};
use sphaera_spheretree::evaluate::{EvaluationOptions, evaluate_set};
use sphaera_spheretree::{Effort, SphereTreeOptions};

/// A wavy open sheet of `n × n` squares: no inside, so only the minimax trees cover it.
fn sheet(n: usize) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            positions.push(DVec3::new(x, y, 0.08 * (5.0 * x).sin() * (4.0 * y).cos()));
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    TriMesh::new(positions, triangles).expect("a sheet")
}

/// The test meshes, a sheet among them.
fn meshes() -> Vec<(&'static str, TriMesh)> {
    let mut meshes = common::meshes();
    meshes.push(("sheet", sheet(8)));
    meshes
}

/// Models whose base tree is the root alone: every finer tolerance needs a tree built.
fn options() -> ModelOptions {
    common::options().with_tree(SphereTreeOptions::default().with_depth(0))
}

/// Points on the sphere and inside it: 48 on its boundary, 16 within.
fn sphere_points(sphere: &Sphere, seed: u64) -> Vec<DVec3> {
    let boundary = sphaera_tests::point_sets::fibonacci_sphere(48);
    let inside = sphaera_tests::point_sets::random_in_cube(40, seed)
        .into_iter()
        .map(|p| 2.0 * p - DVec3::ONE)
        .filter(|p| p.length() <= 1.0)
        .take(16);
    boundary
        .into_iter()
        .chain(inside)
        .map(|d| sphere.center + d * sphere.radius)
        .collect()
}

/// Brute force on `model`: the spheres of `nodes` of `tree` cover `samples` of its
/// surface, and no sampled point of theirs lies farther outside the object than
/// `tolerance` (exact signed distances); an independent evaluation of the set
/// (`evaluate_set`) finds no error above the tolerance either.
fn check_spheres(
    model: &ObjectModel,
    tree: &sphaera_spheretree::SphereTree,
    nodes: &[usize],
    tolerance: f64,
    samples: &[DVec3],
    seed: u64,
) -> Result<(), String> {
    let slack = 1e-9 * model.diagonal();
    let spheres: Vec<Sphere> = nodes.iter().map(|&i| tree.nodes()[i].sphere).collect();
    for (&node, sphere) in nodes.iter().zip(&spheres) {
        for p in sphere_points(sphere, seed ^ node as u64) {
            let closest = model.surface().signed_closest(p).expect("a finite point");
            if !closest.inside && closest.closest.distance > tolerance + slack {
                return Err(format!(
                    "node {node}: a point of its sphere is {} outside, over {tolerance}",
                    closest.closest.distance
                ));
            }
        }
    }
    for &p in samples {
        if !spheres
            .iter()
            .any(|s| s.center.distance(p) <= s.radius + slack)
        {
            return Err(format!("the surface point {p} is in no sphere"));
        }
    }
    let options = EvaluationOptions::default().with_coverage_samples(2_000);
    let evaluated = evaluate_set(model.surface(), &spheres, &options).map_err(|e| e.to_string())?;
    if evaluated.worst_lower > tolerance + slack {
        return Err(format!(
            "evaluate_set: an error of at least {} over {tolerance}",
            evaluated.worst_lower
        ));
    }
    if evaluated.coverage.uncovered > 0 {
        return Err(format!(
            "evaluate_set: {} coverage samples uncovered",
            evaluated.coverage.uncovered
        ));
    }
    Ok(())
}

/// Checks an instance's detail: its level cut and its smallest cut, by brute force.
fn check_detail(
    instance: &Instance,
    detail: &InstanceDetail,
    samples: &[DVec3],
    seed: u64,
) -> Result<(), String> {
    let model = &instance.model;
    let trees = model.trees();
    let tree = trees[detail.tree.index].tree();
    let need = detail.model_tolerance;
    let scale = instance.pose.scale();
    let over = |e: f64| e.is_nan() || e > detail.tolerance * (1.0 + 1e-12);
    if over(detail.spheres.error) || over(detail.cut.error) {
        return Err(format!("reported errors over the tolerance: {detail:?}"));
    }
    let level = tree.cut_at(detail.spheres.level);
    if level.len() != detail.spheres.count {
        return Err(format!(
            "{} spheres reported, {} in the cut",
            detail.spheres.count,
            level.len()
        ));
    }
    check_spheres(model, tree, &level, need, samples, seed)?;
    let (cut, error) = common::smallest_cut(model, tree, need);
    if cut.len() != detail.cut.count || error * scale != detail.cut.error {
        return Err(format!(
            "the smallest cut: {} spheres, error {error}: {detail:?}",
            cut.len()
        ));
    }
    check_spheres(model, tree, &cut, need, samples, seed)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(20)))]

    /// Random tolerances (world or relative) on random meshes (a sheet among them) at
    /// random scales: every instance's spheres meet its tolerance, checked by an
    /// independent evaluation and brute force; a tolerance below the model's finest is an
    /// error naming it.
    #[test]
    fn every_instance_meets_its_tolerance_by_brute_force(
        mesh in 0usize..5,
        relative in 0.008..0.15f64,
        log_scales in prop::collection::vec(-1.5..1.5f64, 1..4),
        world in any::<bool>(),
        seed in 0u64..1_000,
    ) {
        let (name, mesh) = meshes().swap_remove(mesh);
        let model = Arc::new(ObjectModel::build(name, mesh, &options()).expect("a model"));
        let finest = 0.01 * model.diagonal();
        let mut scene = Scene::new();
        for (k, s) in log_scales.iter().enumerate() {
            let pose = common::pose(DVec3::new(3.0 * k as f64, 0.0, 0.0), DVec3::Y, k as f64, 2f64.powf(*s));
            scene.add(format!("{name}-{k}"), Arc::clone(&model), pose);
        }
        let tolerance = if world {
            Tolerance::Absolute(relative * model.diagonal())
        } else {
            Tolerance::RelativeToDiagonal(relative)
        };
        let need = |scale: f64| match tolerance {
            Tolerance::Absolute(t) => t / scale,
            _ => relative * model.diagonal(),
        };
        let smallest = scene.instances().iter().map(|i| need(i.pose.scale())).fold(f64::INFINITY, f64::min);
        let report = match scene.detail(None, tolerance) {
            Ok(report) => report,
            Err(SceneError::ToleranceBelowFinest { model: named, tolerance: t, .. }) => {
                // Only a tolerance below the model's finest is refused, and it says so.
                prop_assert!(smallest < finest && t == smallest && named == name, "{t} {smallest}");
                return Ok(());
            }
            Err(other) => return Err(TestCaseError::fail(other.to_string())),
        };
        prop_assert!(smallest >= finest);
        let samples = sphaera_tests::hausdorff::surface_points(model.mesh(), 3_000, seed);
        for (instance, detail) in scene.instances().iter().zip(&report.instances) {
            let scale = instance.pose.scale();
            prop_assert_eq!(detail.model_tolerance, need(scale));
            prop_assert_eq!(detail.tolerance, need(scale) * scale);
            prop_assert_eq!(check_detail(instance, detail, &samples, seed), Ok(()), "{}", name);
        }
        // One tolerance tree at most: built to the finest need, it meets the others.
        prop_assert!(report.trees_built <= 1);
        prop_assert_eq!(model.trees().len(), 1 + report.trees_built);
    }
}

/// A tolerance asked twice builds once; a coarser one, or a finer one that the tree built
/// already meets, builds nothing; a finer one builds again, to the finer of it and half
/// the finest tolerance built before.
#[test]
fn each_tolerance_is_built_once_and_finer_ones_only_when_needed() {
    let (name, mesh) = common::meshes().swap_remove(2);
    let model = Arc::new(ObjectModel::build(name, mesh, &options()).expect("a model"));
    let mut scene = Scene::new();
    scene.add("a", Arc::clone(&model), Similarity::IDENTITY);
    scene.add("b", Arc::clone(&model), Similarity::IDENTITY);
    let first = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.08))
        .expect("detail");
    assert_eq!(first.trees_built, 1, "two instances, one build");
    assert!(
        first
            .instances
            .iter()
            .all(|d| d.tree.built && d.tree.index == 1)
    );
    assert!(first.tree_seconds > 0.0 && first.instances[0].tree.build_seconds > 0.0);
    let again = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.08))
        .expect("detail");
    assert_eq!(again.trees_built, 0);
    assert!(
        again
            .instances
            .iter()
            .all(|d| !d.tree.built && d.tree.index == 1)
    );
    assert_eq!(
        again.clone().without_times(),
        unbuilt(first.clone().without_times())
    );
    let coarser = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.2))
        .expect("detail");
    assert_eq!(coarser.trees_built, 0);
    // Finer than asked before, but what the tree built reaches: nothing to build.
    let reached = model.trees()[1].worst_error() / model.diagonal();
    assert!(reached <= 0.08);
    let met = scene
        .detail(None, Tolerance::RelativeToDiagonal(reached))
        .expect("detail");
    assert_eq!((met.trees_built, model.trees().len()), (0, 2));
    // Finer than every tree: built, to the finer of the tolerance and half of 8 %.
    let finer = scene
        .detail(
            None,
            Tolerance::RelativeToDiagonal(0.06_f64.min(0.99 * reached)),
        )
        .expect("detail");
    assert_eq!(finer.trees_built, 1);
    let built = &model.trees()[2];
    assert_eq!(built.tolerance(), Some(0.04 * model.diagonal()));
    assert!(built.worst_error() <= 0.04 * model.diagonal());
    assert!(finer.instances.iter().all(|d| d.tree.index == 2));
    // Each request takes the fewest spheres its trees offer: 20 % still takes the same
    // cut (against a finer full detail now).
    let coarse_again = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.2))
        .expect("detail");
    for (a, b) in coarse_again.instances.iter().zip(&coarser.instances) {
        assert_eq!(
            (a.tree.index, a.spheres.level),
            (b.tree.index, b.spheres.level)
        );
        assert_eq!(
            (a.spheres.count, a.spheres.error),
            (b.spheres.count, b.spheres.error)
        );
        assert_eq!(a.full_spheres, model.trees()[2].leaf_count());
    }
}

/// The report as a request that built nothing would give it.
fn unbuilt(mut report: sphaera_scene::DetailReport) -> sphaera_scene::DetailReport {
    report.trees_built = 0;
    for instance in &mut report.instances {
        instance.tree.built = false;
    }
    report
}

/// Requests from many threads at once build the tree once.
#[test]
fn concurrent_requests_build_once() {
    let (name, mesh) = common::meshes().swap_remove(2);
    let model = ObjectModel::build(name, mesh, &options()).expect("a model");
    let tolerance = 0.05 * model.diagonal();
    let built: Vec<bool> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|_| s.spawn(|| model.tree_for(tolerance).expect("a tree").1))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("no panic"))
            .collect()
    });
    assert_eq!(built.iter().filter(|&&b| b).count(), 1, "{built:?}");
    assert_eq!(model.trees().len(), 2);
}

/// A tolerance below a model's finest is refused with an error naming the model and the
/// figures, not a fallback; the trees built for coarser needs are kept, and lowering the
/// finest tolerance builds it.
#[test]
fn a_tolerance_below_the_finest_is_an_error_naming_the_model() {
    let (name, mesh) = common::meshes().swap_remove(1);
    let model = Arc::new(ObjectModel::build(name, mesh, &options()).expect("a model"));
    let mut scene = Scene::new();
    scene.add("near", Arc::clone(&model), Similarity::IDENTITY);
    let small = Similarity::new(glam::DAffine3::from_scale(DVec3::splat(0.125))).expect("pose");
    scene.add("small", Arc::clone(&model), small);
    // 0.5 % of the diagonal for the first (below the 1 % finest), 4 % for the second.
    let error = scene
        .detail(None, Tolerance::Absolute(0.005 * model.diagonal()))
        .expect_err("below the finest");
    let SceneError::ToleranceBelowFinest {
        model: named,
        tolerance,
        finest,
        diagonal,
    } = &error
    else {
        panic!("{error:?}");
    };
    assert_eq!((named.as_str(), *diagonal), (name, model.diagonal()));
    assert!(*tolerance < *finest && *finest == 0.01 * model.diagonal());
    let message = error.to_string();
    assert!(
        message.contains(name) && message.contains("0.5000 %") && message.contains("finest"),
        "{message}"
    );
    // The small instance alone is met.
    let mut alone = Scene::new();
    alone.add("small", Arc::clone(&model), small);
    let report = alone
        .detail(None, Tolerance::Absolute(0.005 * model.diagonal()))
        .expect("4 % of the model");
    assert!(report.instances[0].tree.built);
    let refused = model.tree_for(0.001 * model.diagonal()).expect_err("below");
    assert!(matches!(refused, SceneError::ToleranceBelowFinest { .. }));
    // Lowering the finest tolerance builds it.
    let lower = ObjectModel::build(
        name,
        common::meshes().swap_remove(1).1,
        &options().with_finest_tolerance(Length::RelativeToDiagonal(0.004)),
    )
    .expect("a model");
    let (tree, built) = lower.tree_for(0.005 * lower.diagonal()).expect("a tree");
    assert!(built && tree.worst_error() <= 0.005 * lower.diagonal());
}

/// A tolerance out of reach of any tree (10⁻⁶ of a flat square's size, with no finest
/// tolerance to stop it) is an error naming the model and the library's figures, not a
/// panic; a later, finer request fails the same way without building.
#[test]
fn an_unreachable_tolerance_is_an_error_not_a_panic() {
    let name = "square";
    let mesh = sphaera_mesh::shapes::square_sheet(1.0, 1).expect("a square");
    // Branch 128: the 128² nodes of the second level, all over the tolerance, would have
    // more than the library's 2^21 nodes as children, so it refuses after two levels.
    let options = options()
        .with_finest_tolerance(Length::Absolute(0.0))
        .with_tolerance_tree(
            SphereTreeOptions::default()
                .with_branch(128)
                .with_effort(Effort::Quick),
        );
    let model = Arc::new(ObjectModel::build(name, mesh, &options).expect("a model"));
    let mut scene = Scene::new();
    scene.add("square", Arc::clone(&model), Similarity::IDENTITY);
    let started = std::time::Instant::now();
    let error = scene
        .detail(None, Tolerance::RelativeToDiagonal(1e-6))
        .expect_err("out of reach");
    let SceneError::ToleranceTree {
        model: named,
        reason,
        ..
    } = &error
    else {
        panic!("{error:?}");
    };
    assert_eq!(named, name);
    assert!(
        matches!(
            **reason,
            sphaera_spheretree::SphereTreeError::ToleranceUnreachable { .. }
        ),
        "{reason:?}"
    );
    let message = error.to_string();
    assert!(
        message.contains(name) && message.contains("cannot meet") && message.contains("limit"),
        "{message}"
    );
    let again = scene
        .detail(None, Tolerance::RelativeToDiagonal(1e-7))
        .expect_err("out of reach");
    assert!(
        matches!(again, SceneError::ToleranceTree { .. }),
        "{again:?}"
    );
    assert_eq!(model.trees().len(), 1, "nothing was kept");
    // Not a long build either (the library refuses what would not fit before building).
    assert!(started.elapsed().as_secs() < 60);
    // A tolerance within reach still works.
    assert!(
        scene
            .detail(None, Tolerance::RelativeToDiagonal(0.05))
            .is_ok()
    );
}

/// Tolerance trees need the minimax method: other options are an error naming the model.
#[test]
fn tolerance_trees_with_a_method_that_cannot_build_them_say_why() {
    let (name, mesh) = common::meshes().swap_remove(2);
    let options = options().with_tolerance_tree(
        SphereTreeOptions::default().with_method(sphaera_spheretree::Method::Combined),
    );
    let model = Arc::new(ObjectModel::build(name, mesh, &options).expect("a model"));
    let mut scene = Scene::new();
    scene.add("torus", model, Similarity::IDENTITY);
    let why = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.05))
        .expect_err("not minimax")
        .to_string();
    assert!(
        why.contains(name) && why.contains("tolerance") && why.contains("minimax"),
        "{why}"
    );
}

/// Tolerances that need deep trees (0.3 % of a torus's diagonal: five levels and more at
/// branch 4) are met, checked by brute force; every coarser tolerance is then met from
/// the same tree, coarser cuts for coarser tolerances, without building.
#[test]
fn tolerances_that_need_deep_trees_are_met() {
    let (name, mesh) = common::meshes().swap_remove(2);
    let options = options()
        .with_tolerance_tree(
            SphereTreeOptions::default()
                .with_branch(4)
                .with_effort(Effort::Quick),
        )
        .with_finest_tolerance(Length::RelativeToDiagonal(1e-3));
    let model = Arc::new(ObjectModel::build(name, mesh, &options).expect("a model"));
    let mut scene = Scene::new();
    scene.add("torus", Arc::clone(&model), Similarity::IDENTITY);
    let report = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.003))
        .expect("a deep tree");
    let detail = &report.instances[0];
    assert!(
        detail.tree.built && detail.spheres.levels >= 5,
        "{detail:?}"
    );
    let samples = sphaera_tests::hausdorff::surface_points(model.mesh(), 4_000, 3);
    assert_eq!(
        check_detail(&scene.instances()[0], detail, &samples, 3),
        Ok(())
    );
    let mut previous = detail.spheres.count;
    for relative in [0.006, 0.012, 0.05, 0.2] {
        let coarser = scene
            .detail(None, Tolerance::RelativeToDiagonal(relative))
            .expect("detail");
        let d = &coarser.instances[0];
        assert_eq!(coarser.trees_built, 0, "{relative}");
        assert!(d.spheres.count <= previous, "{relative}: {d:?}");
        assert!(d.spheres.saved_percent >= 0.0 && d.full_spheres == detail.full_spheres);
        assert_eq!(
            check_detail(&scene.instances()[0], d, &samples, 3),
            Ok(()),
            "{relative}"
        );
        previous = d.spheres.count;
    }
    assert!(previous < detail.spheres.count);
}

/// A flat sheet (no inside) among solids: its model is a shell, its trees are built on it,
/// and its spheres meet the tolerance by brute force, the solids' too.
#[test]
fn a_flat_sheet_in_a_scene_meets_the_tolerance() {
    let sheet = sphaera_mesh::shapes::square_sheet(1.0, 6).expect("a sheet");
    let ring = sphaera_mesh::shapes::ring_sheet(0.5, 0.2, 24).expect("a ring");
    let mut models = vec![
        Arc::new(ObjectModel::build("sheet", sheet, &options()).expect("a sheet model")),
        Arc::new(ObjectModel::build("ring", ring, &options()).expect("a ring model")),
    ];
    let (name, ball) = common::meshes().swap_remove(0);
    models.push(Arc::new(
        ObjectModel::build(name, ball, &options()).expect("a ball"),
    ));
    assert!(!models[0].surface().has_inside() && !models[1].surface().has_inside());
    assert!(models[2].surface().has_inside());
    let placements: Vec<_> = (0..3)
        .map(|k| {
            (
                k,
                common::pose(
                    DVec3::new(1.5 * k as f64, 0.0, 0.0),
                    DVec3::X,
                    0.3 * k as f64,
                    1.0,
                ),
            )
        })
        .collect();
    let scene = common::scene_of(&models, &placements);
    let report = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.02))
        .expect("detail");
    for (instance, detail) in scene.instances().iter().zip(&report.instances) {
        let samples = sphaera_tests::hausdorff::surface_points(instance.model.mesh(), 3_000, 5);
        assert_eq!(
            check_detail(instance, detail, &samples, 5),
            Ok(()),
            "{}",
            detail.name
        );
        assert!(detail.spheres.error <= 0.02 * instance.diagonal() * (1.0 + 1e-12));
    }
    // Collisions descend the sheet's tree too.
    assert!(
        scene
            .collide(&Budget::Unlimited)
            .expect("collide")
            .completed
    );
}

/// Powers of two: a model of a mesh scaled by 2^k, asked the tolerance scaled by 2^k,
/// gives the identical answer, every figure scaled exactly.
#[test]
fn a_mesh_scaled_by_a_power_of_two_gives_the_identical_answer_scaled() {
    for index in [1, 3] {
        let (name, mesh) = common::meshes().swap_remove(index);
        for k in [-9, 5] {
            let f = 2f64.powi(k);
            let scaled = sphaera_tests::awkward::mapped(&mesh, |p| p * f, false);
            let answer = |mesh: TriMesh, tolerance: f64| {
                let model = Arc::new(ObjectModel::build(name, mesh, &options()).expect("a model"));
                let mut scene = Scene::new();
                scene.add(name, Arc::clone(&model), Similarity::IDENTITY);
                scene.add(
                    "twice",
                    model,
                    common::pose(DVec3::X * 4.0 * f, DVec3::Z, 0.0, 2.0),
                );
                scene
                    .detail(None, Tolerance::Absolute(tolerance))
                    .expect("detail")
            };
            let t = 0.03 * mesh.bounding_box_diagonal();
            let a = answer(mesh.clone(), t);
            let b = answer(scaled, t * f);
            assert_eq!(a.trees_built, b.trees_built);
            assert_eq!(
                (a.spheres, a.cut_spheres, a.full_spheres),
                (b.spheres, b.cut_spheres, b.full_spheres)
            );
            for (x, y) in a.instances.iter().zip(&b.instances) {
                assert_eq!(
                    (x.tree.index, x.tree.leaves),
                    (y.tree.index, y.tree.leaves),
                    "{name} 2^{k}"
                );
                assert_eq!(x.tree.tolerance.map(|t| t * f), y.tree.tolerance);
                assert_eq!(
                    (x.spheres.level, x.spheres.count),
                    (y.spheres.level, y.spheres.count)
                );
                assert_eq!(x.spheres.error * f, y.spheres.error, "{name} 2^{k}");
                assert_eq!(x.spheres.node_error * f, y.spheres.node_error);
                assert_eq!((x.cut.count, x.cut.error * f), (y.cut.count, y.cut.error));
                assert_eq!(x.model_tolerance * f, y.model_tolerance);
                assert_eq!(
                    (x.mesh.level, x.mesh.error * f),
                    (y.mesh.level, y.mesh.error)
                );
            }
        }
    }
}

/// The four shared meshes of the issue at 2 %: every one met (it used to say no level
/// met it and use the finest), one tree built per model, checked by an independent
/// evaluation; a second request builds nothing.
#[test]
fn the_four_shared_meshes_meet_two_percent() {
    let Some(data) = sphaera_tests::data_dir("the_four_shared_meshes_meet_two_percent") else {
        return;
    };
    let files = [
        "bunny_lowres.obj",
        "fandisk.obj",
        "spot.obj",
        "robots/objects/duck.obj",
    ];
    let options = ModelOptions::default().with_tree(SphereTreeOptions::default().with_depth(0));
    let mut scene = Scene::new();
    let mut models = Vec::new();
    for (k, file) in files.iter().enumerate() {
        let mesh = sphaera_io::load(data.join(file)).expect(file);
        let model = Arc::new(ObjectModel::build(*file, mesh, &options).expect(file));
        scene.add(
            *file,
            Arc::clone(&model),
            common::pose(DVec3::X * 20.0 * k as f64, DVec3::Y, 0.0, 1.0),
        );
        models.push(model);
    }
    let report = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.02))
        .expect("2 % met");
    assert_eq!(report.trees_built, files.len());
    for (model, detail) in models.iter().zip(&report.instances) {
        assert!(detail.spheres.measured <= 0.02 && detail.spheres.error <= 0.02 * model.diagonal());
        let trees = model.trees();
        let tree = trees[detail.tree.index].tree();
        let spheres = tree.cut_spheres(detail.spheres.level);
        let evaluated = evaluate_set(
            model.surface(),
            &spheres,
            &EvaluationOptions::default().with_coverage_samples(20_000),
        )
        .expect("an evaluation");
        assert!(
            evaluated.worst_lower <= 0.02 * model.diagonal(),
            "{}: {evaluated:?}",
            detail.name
        );
        assert_eq!(evaluated.coverage.uncovered, 0, "{}", detail.name);
    }
    assert_eq!(
        scene
            .detail(None, Tolerance::RelativeToDiagonal(0.02))
            .expect("again")
            .trees_built,
        0
    );
}

/// After detail has built tolerance trees, collisions descend them (leaves at several
/// depths): surfaces that cross are reported, contacts bound the distance, and every pair
/// agrees with the single-pair traversal of the same trees.
#[test]
fn collisions_descend_the_tolerance_trees() {
    let models: Vec<Arc<ObjectModel>> = common::meshes()
        .into_iter()
        .map(|(name, mesh)| Arc::new(ObjectModel::build(name, mesh, &options()).expect(name)))
        .collect();
    let placements: Vec<_> = (0..7)
        .map(|k| {
            let t = DVec3::new(0.55 * k as f64, 0.2 * (k % 2) as f64, 0.1 * (k % 3) as f64);
            (
                k,
                common::pose(t, DVec3::new(1.0, 2.0, k as f64), 0.9 * k as f64, 1.0),
            )
        })
        .collect();
    let scene = common::scene_of(&models, &placements);
    let report = scene
        .detail(None, Tolerance::RelativeToDiagonal(0.03))
        .expect("detail");
    // The ball's root is within 3 % already; the others need trees.
    assert!(report.trees_built >= models.len() - 1, "{report:?}");
    let found = scene.collide(&Budget::Unlimited).expect("collide");
    assert!(found.completed);
    let posed = |i: usize| {
        let instance = &scene.instances()[i];
        sphaera_tests::awkward::mapped(instance.model.mesh(), |p| instance.pose.point(p), false)
    };
    let mut touching = 0;
    let mut tolerance_pairs = 0;
    for a in 0..scene.len() {
        for b in a + 1..scene.len() {
            let distance = sphaera_tests::brute::solid_distance(&posed(a), &posed(b));
            let reported = found.pairs.iter().find(|p| (p.a, p.b) == (a, b));
            if distance == 0.0 {
                touching += 1;
                assert!(reported.is_some(), "{a} and {b} touch and were missed");
            }
            if let Some(pair) = reported {
                let bound = pair.separation_bound().expect("contacts");
                assert!(distance <= bound * (1.0 + 1e-9) + 1e-12, "{a}, {b}");
                let (ia, ib) = (&scene.instances()[a], &scene.instances()[b]);
                let (ta, tb) = (ia.model.collision_tree(), ib.model.collision_tree());
                tolerance_pairs +=
                    usize::from(ta.tolerance().is_some() && tb.tolerance().is_some());
                let single = sphaera_spheretree::collide(
                    ta.tree(),
                    &ia.pose,
                    tb.tree(),
                    &ib.pose,
                    &Budget::Unlimited,
                )
                .expect("collide");
                assert_eq!(single.contacts, pair.contacts);
                // Every contact is between spheres of the trees' leaves.
                for c in &pair.contacts {
                    assert!(ta.tree().nodes()[c.a].children.is_empty());
                    assert!(tb.tree().nodes()[c.b].children.is_empty());
                }
            }
        }
    }
    assert!(touching > 0, "the scene has touching pairs");
    assert!(
        tolerance_pairs > 0,
        "pairs of tolerance trees were descended"
    );
}
