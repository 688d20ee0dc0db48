//! Whole-robot sphere models: `sphaera::robot::spherize_geometry` on the Franka Panda's
//! eleven collision meshes and the KUKA iiwa's eight collision STLs, at 40 spheres per
//! link, and the voxel k-means baseline planners ship (`sphaera_eval::experiments::voxel`,
//! the peer) on the Panda in the same run.
//!
//! - `panda_40/sphaera_1_thread`: every Panda link spherized and certified (coverage of
//!   every point of the surface, worst protrusion) on a one-thread rayon pool;
//! - `panda_40/sphaera_2_threads`: the same on two threads (links in parallel);
//! - `panda_40/voxel_kmeans_1_thread`: the baseline on every Panda link (64 cells along
//!   the longest side, 40 k-means clusters, 20 Lloyd iterations, one enclosing sphere per
//!   cluster; no certification), one thread;
//! - `kuka_40/sphaera_1_thread` and `kuka_40/sphaera_2_threads`: the KUKA likewise.
//!
//! The geometry is loaded once, outside the measurement. Skipped, with a message, when
//! the shared data folder (`SPHAERA_DATA`, or `../shared/data`) is absent.
//!
//! Run with `cargo bench -p sphaera-eval --bench robot_spheres` (about five minutes:
//! every iteration takes seconds, and criterion takes at least ten samples). On the
//! 2-core reference machine, otherwise idle (2026-11-28), medians: Panda 2.87 s on one
//! thread, 1.64 s on two; KUKA 4.39 s and 2.53 s; the voxel k-means baseline on the Panda
//! 4.15 s on one thread, most of it the winding-number inside test of every voxel centre.
//! Figures and history: `docs/benchmarks.md`, "Time for a whole robot".

// A bench reports what it measured on the terminal.
#![allow(clippy::print_stderr)]

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera::robot::{
    GeometrySource, LinkGeometry, MeshResolver, SphereBudget, SpherizeOptions, Urdf,
    spherize_geometry,
};
use sphaera_eval::experiments::voxel::{VoxelOptions, robot_spheres};

/// Spheres per link.
const PER_LINK: usize = 40;

/// The robot's name and its links' collision geometry.
fn load(data: &Path, file: &str) -> (String, Vec<LinkGeometry>) {
    let urdf = Urdf::read(data.join(file)).expect("a URDF");
    let geometry = LinkGeometry::load_all(
        &urdf,
        GeometrySource::Collision,
        &MeshResolver::new(urdf.folder()),
    )
    .expect("the links' meshes");
    (urdf.name, geometry)
}

/// A rayon pool of `threads` threads.
fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

fn bench(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("robot_spheres") else {
        eprintln!("robot_spheres: no shared data folder, nothing measured");
        return;
    };
    let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(PER_LINK));
    let robots = [
        ("panda_40", "robots/urdf/franka_panda/panda.urdf"),
        ("kuka_40", "robots/urdf/kuka_iiwa/model.urdf"),
    ];
    for (group_name, file) in robots {
        let (name, geometry) = load(&data, file);
        let spherize =
            || spherize_geometry(&name, geometry.clone(), &options, &|_| {}).expect("spherize");
        let robot = spherize();
        let worst = robot
            .links
            .iter()
            .map(|l| l.report.worst_protrusion)
            .fold(0.0, f64::max);
        eprintln!(
            "{file}: {} links, {} spheres, worst certified protrusion {:.1} mm",
            robot.links.len(),
            robot.sphere_count(),
            1e3 * worst
        );
        let mut group = c.benchmark_group(group_name);
        group.sample_size(10);
        group.measurement_time(Duration::from_secs(10));
        for threads in [1, 2] {
            let pool = pool(threads);
            let id = if threads == 1 {
                "sphaera_1_thread".to_owned()
            } else {
                format!("sphaera_{threads}_threads")
            };
            group.bench_function(id, |b| {
                b.iter(|| pool.install(|| black_box(spherize())));
            });
        }
        if group_name == "panda_40" {
            let voxel = VoxelOptions::default();
            let baseline = robot_spheres(&geometry, PER_LINK, &voxel).expect("the baseline");
            eprintln!(
                "{file}: voxel k-means, {} spheres",
                baseline.iter().map(|(_, s)| s.len()).sum::<usize>()
            );
            group.bench_function("voxel_kmeans_1_thread", |b| {
                b.iter(|| black_box(robot_spheres(&geometry, PER_LINK, &voxel).expect("baseline")));
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
