//! Closest-point queries: Sphaera's Meshsweeper sessions against parry3d-f64's `TriMesh`
//! point projection (its BVH), in the same run.
//!
//! Query sets (seeded; `src/query_sets.rs`, shared with the `sweep_throughput`
//! experiment), on the 69k-triangle bunny and the 871k-triangle dragon:
//! - `uniform`: points uniform in the bounding box scaled 1.5×;
//! - `near`: points within 1 % of the diagonal of the surface (a surface sample moved
//!   along a random direction);
//! - `path`: a smooth closed path of small steps (coherent queries).
//!
//! Each measurement answers a block of `QUERIES` queries with one session (Sphaera) or
//! one BVH (parry); criterion reports the time per block. Hierarchy and BVH builds are
//! benched beside. Run with `cargo bench -p sphaera-eval --bench sweep_vs_parry` (append
//! `-- bunny` for the bunny only). Needs `../shared/data`; without it the bench says so.

#![allow(clippy::print_stderr)]

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera::{
    mesh::io,
    sweep::{Sweeper, build_hierarchy},
};
use sphaera_tests::hausdorff::DistanceToMesh;

// Shared with the `sweep_throughput` experiment, which measures the same query sets.
#[allow(dead_code)]
#[path = "../src/query_sets.rs"]
mod query_sets;

use query_sets::query_sets;

/// Queries per measured block.
const QUERIES: usize = 2_000;

/// The meshes: bench name, file in `shared/data`.
const MESHES: &[(&str, &str)] = &[
    ("bunny_69k", "stanford-bunny.obj"),
    ("dragon_871k", "dragon_vrip.ply"),
];

fn sweep_vs_parry(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("sweep_vs_parry bench") else {
        return;
    };
    for &(name, file) in MESHES {
        let path = data.join(file);
        if !path.is_file() {
            eprintln!("sweep_vs_parry: skipped {name}, no {}", path.display());
            continue;
        }
        let mesh = io::load(&path).expect("the mesh loads");
        let mut group = c.benchmark_group(format!("sweep_build/{name}"));
        group.sample_size(10);
        group.measurement_time(Duration::from_secs(1));
        group.bench_function("sphaera_hierarchy", |b| {
            b.iter(|| build_hierarchy(black_box(&mesh)).expect("builds"));
        });
        group.bench_function("parry_bvh", |b| {
            b.iter(|| DistanceToMesh::new(black_box(&mesh)));
        });
        group.finish();
        let hierarchy = build_hierarchy(&mesh).expect("builds");
        let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
        let parry = DistanceToMesh::new(&mesh);
        for (set, points) in query_sets(&mesh, QUERIES).expect("the mesh has area") {
            let mut group = c.benchmark_group(format!("sweep/{name}/{set}_{QUERIES}"));
            group.sample_size(10);
            group.warm_up_time(Duration::from_millis(300));
            group.measurement_time(Duration::from_secs(2));
            group.bench_function("sphaera_session", |b| {
                b.iter(|| {
                    let mut session = sweeper.session();
                    points
                        .iter()
                        .map(|&p| session.closest(p).expect("finite").distance)
                        .sum::<f64>()
                });
            });
            group.bench_function("parry", |b| {
                b.iter(|| points.iter().map(|&p| parry.distance(p)).sum::<f64>());
            });
            group.finish();
        }
    }
}

criterion_group!(benches, sweep_vs_parry);
criterion_main!(benches);
