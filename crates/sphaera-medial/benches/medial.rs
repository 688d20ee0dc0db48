//! The adaptive medial approximation, the cases: the 69k-triangle Stanford bunny
//! with 10,000 surface samples improved to 500 and to 1,000 spheres, and every collision
//! mesh of the Franka Panda arm (5,000 samples, 200 spheres). Preparation (the inside
//! test's and the closest-point tree's builds, and the sampling) is timed apart. The worst
//! error of each built set is printed once (stderr), as a percentage of the mesh's
//! bounding-box diagonal, since criterion reports only times.
//!
//! Run with `cargo bench -p sphaera-medial --bench medial` (about two minutes on the
//! 2-core reference machine); needs `../shared/data` (skipped with a message without it).

#![allow(clippy::print_stderr)]

use std::{hint::black_box, path::Path, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera_io as io;
use sphaera_medial::{DVec3, MedialApproximation, MedialOptions, Surface};
use sphaera_mesh::TriMesh;
use sphaera_query::sampling;

fn samples(mesh: &TriMesh, n: usize) -> Vec<DVec3> {
    sampling::poisson_disk(mesh, n, 1)
        .expect("the mesh samples")
        .samples
        .iter()
        .map(|s| s.position)
        .collect()
}

/// Builds once to print the set's size and worst error, then times the build.
fn bench_build(
    c: &mut Criterion,
    group_name: &str,
    case: &str,
    mesh: &TriMesh,
    sample_count: usize,
    spheres: usize,
) {
    let surface = Surface::new(mesh).expect("the mesh has an inside");
    let points = samples(mesh, sample_count);
    let params = MedialOptions::default().with_target_spheres(spheres);
    let medial = MedialApproximation::build(&surface, &points, &params).expect("builds");
    eprintln!(
        "{group_name}/{case}: {} spheres, worst error {:.2} % of the diagonal, {} uncovered samples",
        medial.sphere_count(),
        100.0 * medial.worst_error() / surface.diagonal(),
        medial.uncovered_samples().len()
    );
    let mut group = c.benchmark_group(group_name);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(4));
    group.bench_function(case, |b| {
        b.iter(|| {
            MedialApproximation::build(&surface, black_box(&points), &params).expect("builds")
        });
    });
    group.finish();
}

fn load(data: &Path, file: &str) -> Option<TriMesh> {
    let path = data.join(file);
    if !path.is_file() {
        eprintln!("{file}: absent, skipped");
        return None;
    }
    Some(io::load(&path).expect("the shared mesh loads"))
}

fn bunny(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("bench medial/bunny_69k") else {
        return;
    };
    let Some(mesh) = load(&data, "stanford-bunny.obj") else {
        return;
    };
    let mut group = c.benchmark_group("medial/bunny_69k");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(4));
    group.bench_function("prepare_surface", |b| {
        b.iter(|| Surface::new(black_box(&mesh)).expect("the mesh has an inside"));
    });
    group.bench_function("sample_10k", |b| {
        b.iter(|| samples(black_box(&mesh), 10_000));
    });
    group.finish();
    for spheres in [500, 1_000] {
        bench_build(
            c,
            "medial/bunny_69k",
            &format!("10k_samples_to_{spheres}_spheres"),
            &mesh,
            10_000,
            spheres,
        );
    }
}

fn franka(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("bench medial/franka") else {
        return;
    };
    for link in [
        "link0", "link1", "link2", "link3", "link4", "link5", "link6", "link7", "hand", "finger",
    ] {
        let file = format!("robots/franka_panda/collision/{link}.obj");
        let Some(mesh) = load(&data, &file) else {
            continue;
        };
        bench_build(
            c,
            "medial/franka",
            &format!("{link}_5k_samples_to_200"),
            &mesh,
            5_000,
            200,
        );
    }
}

criterion_group!(benches, bunny, franka);
criterion_main!(benches);
