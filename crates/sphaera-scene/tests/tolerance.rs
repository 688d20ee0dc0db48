//! Sphere-trees built to what a scene asks: every instance's spheres meet its tolerance,
//! checked against brute force (the cut's spheres cover dense surface samples, and no
//! sampled point of them lies farther outside the object than the tolerance); a tolerance
//! is built once per model, a finer one only when no tree meets it; a tolerance below a
//! model's finest is said, not built; collisions descend the trees built.

#![allow(clippy::float_cmp)]

mod common;

use std::sync::Arc;

use proptest::prelude::*;
use sphaera_mesh::geometry::Similarity;
use sphaera_mesh::{DVec3, Length, Sphere, TriMesh};
use sphaera_scene::{Budget, ModelOptions, ObjectModel, Scene, SceneError, Tolerance};
use sphaera_spheretree::SphereTreeOptions;

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

/// Brute force on `model`: the spheres of `nodes` of tree `index` cover `samples` of
/// its surface, and no sampled point of theirs lies farther outside the object than
/// `tolerance` (exact signed distances); each node's error is at most the tolerance.
fn check_cut(
    model: &ObjectModel,
    index: usize,
    tolerance: f64,
    samples: &[DVec3],
    seed: u64,
) -> Result<usize, String> {
    let trees = model.trees();
    let tree = trees[index].tree();
    let cut = sphaera_spheretree::cut_for_tolerance(tree, tolerance);
    if !cut.meets_tolerance {
        return Err(format!("the cut of tree {index} does not meet {tolerance}"));
    }
    let slack = 1e-9 * model.diagonal();
    let spheres: Vec<Sphere> = cut.spheres(tree);
    for (&node, sphere) in cut.nodes.iter().zip(&spheres) {
        let error = tree.nodes()[node].error;
        if error > tolerance {
            return Err(format!("node {node}: error {error} over {tolerance}"));
        }
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
            return Err(format!("the surface point {p} is in no sphere of the cut"));
        }
    }
    Ok(spheres.len())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20))]

    /// Random tolerances (world or relative) on random meshes at random scales: every
    /// instance's spheres meet its tolerance, certified by the nodes' errors and checked
    /// by brute force; a tolerance below the model's finest is said plainly.
    #[test]
    fn every_instance_meets_its_tolerance_by_brute_force(
        mesh in 0usize..5,
        relative in 0.012..0.15f64,
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
            Tolerance::World(relative * model.diagonal())
        } else {
            Tolerance::Relative(relative)
        };
        let report = scene.detail(None, tolerance).expect("a report");
        let samples = sphaera_tests::hausdorff::surface_points(model.mesh(), 3_000, seed);
        for (instance, detail) in scene.instances().iter().zip(&report.instances) {
            let scale = instance.pose.scale();
            let need = match tolerance {
                Tolerance::World(t) => t / scale,
                _ => relative * model.diagonal(),
            };
            prop_assert_eq!(detail.model_tolerance, need);
            if !detail.cut.meets {
                // Only a tolerance below the model's finest goes unmet, and it says so.
                prop_assert!(need < finest, "{detail:?}");
                let why = detail.unmet.as_deref().unwrap_or_default();
                prop_assert!(why.contains("finest") && why.contains(name), "{why}");
                continue;
            }
            prop_assert!(detail.unmet.is_none());
            prop_assert!(detail.cut.error <= need * scale * (1.0 + 1e-12), "{detail:?}");
            prop_assert!(detail.spheres.meets && detail.cut.count <= detail.spheres.count);
            let count = check_cut(&model, detail.tree.index, need, &samples, seed);
            prop_assert_eq!(count, Ok(detail.cut.count), "{}", name);
        }
        prop_assert_eq!(report.all_meet, report.instances.iter().all(|d| d.cut.meets));
        // One tolerance tree at most per distinct need, and the finest need built once.
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
        .detail(None, Tolerance::Relative(0.08))
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
        .detail(None, Tolerance::Relative(0.08))
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
        .detail(None, Tolerance::Relative(0.2))
        .expect("detail");
    assert_eq!(coarser.trees_built, 0);
    // Finer than asked before, but what the tree built reaches: nothing to build.
    let reached = model.trees()[1].worst_error() / model.diagonal();
    assert!(reached <= 0.08);
    let met = scene
        .detail(None, Tolerance::Relative(reached))
        .expect("detail");
    assert_eq!((met.trees_built, model.trees().len()), (0, 2));
    // Finer than every tree: built, to the finer of the tolerance and half of 8 %.
    let finer = scene
        .detail(None, Tolerance::Relative(0.06_f64.min(0.99 * reached)))
        .expect("detail");
    assert_eq!(finer.trees_built, 1);
    let built = &model.trees()[2];
    assert_eq!(built.tolerance(), Some(0.04 * model.diagonal()));
    assert!(built.worst_error() <= 0.04 * model.diagonal());
    assert!(finer.all_meet && finer.instances.iter().all(|d| d.tree.index == 2));
    // Each request takes the smallest cut its trees offer: 20 % still takes the coarse tree's.
    let coarse_again = scene
        .detail(None, Tolerance::Relative(0.2))
        .expect("detail");
    assert_eq!(
        coarse_again.clone().without_times(),
        coarser.clone().without_times()
    );
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

/// A tolerance below a model's finest is refused for the instances that need it, with
/// the reason; the others get their trees.
#[test]
fn a_tolerance_below_the_finest_is_said_and_the_others_are_met() {
    let (name, mesh) = common::meshes().swap_remove(1);
    let model = Arc::new(ObjectModel::build(name, mesh, &options()).expect("a model"));
    let mut scene = Scene::new();
    scene.add("near", Arc::clone(&model), Similarity::IDENTITY);
    let small = Similarity::new(glam::DAffine3::from_scale(DVec3::splat(0.125))).expect("pose");
    scene.add("small", Arc::clone(&model), small);
    // 0.5 % of the diagonal for the first (below the 1 % finest), 4 % for the second.
    let report = scene
        .detail(None, Tolerance::World(0.005 * model.diagonal()))
        .expect("detail");
    let (near, far) = (&report.instances[0], &report.instances[1]);
    assert!(!near.cut.meets && !report.all_meet);
    let why = near.unmet.as_deref().expect("a reason");
    assert!(why.contains("finest") && why.contains(name), "{why}");
    assert!(
        far.cut.meets && far.unmet.is_none() && far.tree.built,
        "{far:?}"
    );
    // The unmet instance takes the finest spheres there are.
    assert_eq!(near.tree.index, model.collision_tree().index());
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

/// Tolerance trees need the minimax method: other options are said per instance.
#[test]
fn tolerance_trees_with_a_method_that_cannot_build_them_say_why() {
    let (name, mesh) = common::meshes().swap_remove(2);
    let options = options().with_tolerance_tree(
        SphereTreeOptions::default().with_method(sphaera_spheretree::Method::Combined),
    );
    let model = Arc::new(ObjectModel::build(name, mesh, &options).expect("a model"));
    let mut scene = Scene::new();
    scene.add("torus", model, Similarity::IDENTITY);
    let report = scene
        .detail(None, Tolerance::Relative(0.05))
        .expect("detail");
    let why = report.instances[0].unmet.as_deref().expect("a reason");
    assert!(
        why.contains("tolerance") && why.contains("minimax"),
        "{why}"
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
        .detail(None, Tolerance::Relative(0.03))
        .expect("detail");
    // The ball's root is within 3 % already; the others need trees.
    assert!(
        report.all_meet && report.trees_built >= models.len() - 1,
        "{report:?}"
    );
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
