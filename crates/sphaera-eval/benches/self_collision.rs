//! The self-collision matrix (`sphaera::robot::self_collision_matrix`) of the Franka Panda
//! and the KUKA iiwa, spherized at 16 spheres per link (the CLI's default), over MoveIt's
//! default of 10,000 random configurations, on one and two threads.
//!
//! No peer runs in the same run: MoveIt's setup assistant, which computes the same matrix
//! on the meshes with FCL, needs a ROS installation this project cannot install from
//! PyPI or crates.io; cuRobo's `RobotBuilder` needs a CUDA device. The figures stand
//! alone, beside the time of spherizing (`robot_spheres`).
//!
//! Run with `cargo bench -p sphaera-eval --bench self_collision`. Skipped, with a
//! message, when the shared data folder is absent. Figures: `docs/benchmarks.md`,
//! "Self-collision matrix".

// A bench reports what it measured on the terminal.
#![allow(clippy::print_stderr)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera::robot::{
    MeshResolver, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf, self_collision_matrix,
    spherize,
};

fn bench(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("self_collision") else {
        eprintln!("self_collision: no shared data folder, nothing measured");
        return;
    };
    let options = SelfCollisionOptions::default();
    for (name, file) in [
        ("panda", "robots/urdf/franka_panda/panda.urdf"),
        ("kuka", "robots/urdf/kuka_iiwa/model.urdf"),
    ] {
        let urdf = Urdf::read(data.join(file)).expect("a URDF");
        let robot = spherize(
            &urdf,
            &MeshResolver::new(urdf.folder()),
            &SpherizeOptions::default().with_budget(SphereBudget::PerLink(16)),
        )
        .expect("spherize");
        let mut group = c.benchmark_group(format!("self_collision_{name}"));
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool");
            group.bench_function(format!("10000_samples_{threads}_threads"), |b| {
                b.iter(|| {
                    pool.install(|| {
                        black_box(
                            self_collision_matrix(&urdf, &robot, &options).expect("the matrix"),
                        )
                    })
                });
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
