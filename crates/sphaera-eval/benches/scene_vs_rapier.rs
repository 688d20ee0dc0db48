//! Collision detection over a whole scene: `sphaera-scene`'s budgeted traversal against
//! rapier's collision pipeline (broad phase and narrow phase, on the same parry3d-f64), in
//! the same run; and the per-instance level choice of `Scene::detail`.
//!
//! The scene: 200 low-resolution bunnies (`bunny_lowres.obj` from `shared/data`, or the
//! procedural capsule when absent) scaled to a size of 1, on a jittered 6 × 6 × 6 grid
//! 0.75 apart, turned at random (seeded `SplitMix64`): every bunny touches a few
//! neighbours. The same poses for every method; each measured call starts from scratch
//! (Sphaera places its spheres; rapier gets a new world with the prebuilt shapes, so its
//! broad phase and contact manifolds are computed, not cached).
//!
//! - `sphaera/unlimited`: `Scene::collide` to the leaves (depth 3, branch 8: up to 512
//!   spheres per bunny);
//! - `sphaera/cost_20000`: the same under a budget of 20,000 (the paper's cost model);
//! - `rapier/balls_finest`: rapier's pipeline on compounds of the same finest-level balls;
//! - `rapier/trimesh`: rapier's pipeline on the bunnies' triangle meshes;
//! - `detail/pixels`: `Scene::detail` for 2 px on a 1280×720 camera (no peer);
//! - `detail/silhouettes`: `Scene::silhouette_detail` for outlines within 2 px and
//!   interiors within 8 px on the same camera (one view-dependent extraction per
//!   instance; no peer).
//!
//! Run with `cargo bench -p sphaera-eval --bench scene_vs_rapier`.

// A bench reports what it measured on the terminal.
#![allow(clippy::print_stderr)]

use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rapier3d_f64::prelude::*;
use sphaera::mesh::geometry::Similarity;
use sphaera::mesh::{DVec3, TriMesh, shapes};
use sphaera::scene::{
    Budget, Camera, ModelOptions, ObjectModel, Scene, SilhouetteDetailOptions, Tolerance,
};
use sphaera_eval::rapier_shapes::{ball_compound, unit_size};
use sphaera_tests::random::SplitMix64;

/// Bodies in the scene.
const BODIES: usize = 200;

/// The bunny scaled to a bounding-box diagonal of 1 and centred.
fn object() -> TriMesh {
    let mesh = sphaera_tests::data_dir("scene_vs_rapier")
        .and_then(|d| sphaera::mesh::io::load(d.join("bunny_lowres.obj")).ok())
        .unwrap_or_else(|| shapes::capsule(0.3, 1.0, 16).expect("a capsule"));
    unit_size(&mesh).expect("a mesh")
}

/// Jittered grid poses, turned at random.
fn poses() -> Vec<Pose> {
    let mut rng = SplitMix64::new(7);
    (0..BODIES)
        .map(|i| {
            let cell = DVec3::new((i % 6) as f64, ((i / 6) % 6) as f64, (i / 36) as f64);
            let jitter = DVec3::new(rng.unit(), rng.unit(), rng.unit()) - 0.5;
            let axis = (DVec3::new(rng.unit(), rng.unit(), rng.unit()) - 0.5)
                .try_normalize()
                .unwrap_or(DVec3::Y);
            Pose::new(
                (cell + jitter * 0.2) * 0.75,
                axis * rng.unit() * std::f64::consts::TAU,
            )
        })
        .collect()
}

/// Contact pairs found by a fresh rapier world holding `shape` at every pose.
fn rapier_contacts(shape: &SharedShape, poses: &[Pose]) -> usize {
    let mut world = PhysicsWorld::new();
    for &pose in poses {
        world.insert(
            RigidBodyBuilder::dynamic().pose(pose),
            ColliderBuilder::new(shape.clone()),
        );
    }
    world.detect_collisions(&(), &());
    world
        .narrow_phase
        .contact_pairs()
        .filter(|p| p.has_any_active_contact())
        .count()
}

fn bench(c: &mut Criterion) {
    let mesh = object();
    let model = Arc::new(
        ObjectModel::build("bunny", mesh.clone(), &ModelOptions::default()).expect("a model"),
    );
    let poses = poses();
    let mut scene = Scene::new();
    for (i, pose) in poses.iter().enumerate() {
        let similarity =
            Similarity::from_rotation_translation(pose.rotation, pose.translation).expect("a pose");
        scene.add(format!("bunny-{i}"), Arc::clone(&model), similarity);
    }
    let tree = model.tree();
    let finest = tree.level_count() - 1;
    let balls = ball_compound(&tree.level_spheres(finest));
    let trimesh = SharedShape::trimesh(mesh.positions().to_vec(), mesh.triangles().to_vec())
        .expect("a trimesh");
    let exact = scene.collide(&Budget::Unlimited).expect("collide");
    eprintln!(
        "scene: {} close pairs, {} in contact at the leaves, {} sphere contacts; rapier: {} pairs with balls, {} with trimeshes",
        exact.broad_phase_pairs,
        exact.pairs.len(),
        exact.summary().contacts,
        rapier_contacts(&balls, &poses),
        rapier_contacts(&trimesh, &poses)
    );

    let mut group = c.benchmark_group("scene_collide_200");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(5));
    group.bench_function("sphaera/unlimited", |b| {
        b.iter(|| black_box(scene.collide(&Budget::Unlimited).expect("collide")));
    });
    group.bench_function("sphaera/cost_20000", |b| {
        b.iter(|| black_box(scene.collide(&Budget::cost(20_000.0)).expect("collide")));
    });
    group.bench_function("rapier/balls_finest", |b| {
        b.iter(|| black_box(rapier_contacts(&balls, &poses)));
    });
    group.bench_function("rapier/trimesh", |b| {
        b.iter(|| black_box(rapier_contacts(&trimesh, &poses)));
    });
    group.finish();

    let camera = Camera::perspective(
        DVec3::new(2.0, 2.0, 10.0),
        DVec3::new(2.0, 2.0, 2.0),
        60.0,
        1280,
        720,
    )
    .expect("a camera");
    let mut group = c.benchmark_group("scene_detail_200");
    group.bench_function("detail/pixels", |b| {
        b.iter(|| {
            black_box(
                scene
                    .detail(Some(&camera), Tolerance::Pixels(2.0))
                    .expect("detail"),
            )
        });
    });
    group.sample_size(10);
    group.bench_function("detail/silhouettes", |b| {
        b.iter(|| {
            black_box(
                scene
                    .silhouette_detail(
                        &camera,
                        Tolerance::Pixels(2.0),
                        // The extraction alone, as before the outline check existed.
                        &SilhouetteDetailOptions::default().with_check_outline(false),
                    )
                    .expect("silhouettes"),
            )
        });
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
