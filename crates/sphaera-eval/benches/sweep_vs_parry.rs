//! Closest-point queries: Sphaera's Meshsweeper sessions against parry3d-f64's `TriMesh`
//! point projection (its BVH), in the same run.
//!
//! Query sets (seeded), on the 69k-triangle bunny and the 871k-triangle dragon:
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
    mesh::{DVec3, TriMesh, io, sampling},
    sweep::{Sweeper, build_hierarchy},
};
use sphaera_tests::hausdorff::DistanceToMesh;

/// Queries per measured block.
const QUERIES: usize = 2_000;

/// The meshes: bench name, file in `shared/data`.
const MESHES: &[(&str, &str)] = &[
    ("bunny_69k", "stanford-bunny.obj"),
    ("dragon_871k", "dragon_vrip.ply"),
];

/// A small deterministic generator (uniform in `[0, 1)`).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1_u64 << 53) as f64
    }
}

/// The three query sets of the module docs.
fn query_sets(mesh: &TriMesh) -> Vec<(&'static str, Vec<DVec3>)> {
    let bounds = mesh.bounding_box();
    let center = 0.5 * (bounds.min + bounds.max);
    let half = 0.5 * (bounds.max - bounds.min);
    let diagonal = mesh.bounding_box_diagonal();
    let mut rng = Lcg(7);
    let uniform = (0..QUERIES)
        .map(|_| {
            let u = DVec3::new(rng.next(), rng.next(), rng.next());
            center + 1.5 * half * (2.0 * u - DVec3::ONE)
        })
        .collect();
    let samples = sampling::random(mesh, QUERIES, 11).expect("the mesh has area");
    let near = samples
        .iter()
        .map(|s| {
            let d = DVec3::new(rng.next(), rng.next(), rng.next()) * 2.0 - DVec3::ONE;
            s.position + d.normalize_or_zero() * (0.01 * diagonal * rng.next())
        })
        .collect();
    let path = (0..QUERIES)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / QUERIES as f64;
            center + 0.9 * half * DVec3::new(a.cos(), a.sin(), 0.5 * (3.0 * a).sin())
        })
        .collect();
    vec![("uniform", uniform), ("near", near), ("path", path)]
}

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
        for (set, points) in query_sets(&mesh) {
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
