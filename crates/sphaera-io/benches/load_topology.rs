//! Load + topology of the real meshes: the 871k-triangle Stanford dragon (target: under
//! 1.5 s for both together on the 2-core reference machine) and the 69k-triangle bunny.
//!
//! Run with `cargo xtask bench -p sphaera-mesh` or `cargo bench -p sphaera-mesh`.
//! Needs `../shared/data` (or `$SPHAERA_DATA`); without it the bench says so and exits.

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera_io as io;
use sphaera_mesh::topology::{self, HalfEdgeMesh};

fn load_and_topology(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("load_topology bench") else {
        return;
    };
    for (name, file) in [
        ("dragon_871k", "dragon_vrip.ply"),
        ("bunny_69k", "stanford-bunny.obj"),
    ] {
        let path = data.join(file);
        let mut group = c.benchmark_group(format!("load_topology/{name}"));
        group.sample_size(10);
        group.measurement_time(Duration::from_secs(8));
        group.bench_function("load", |b| {
            b.iter(|| io::load(black_box(&path)).expect("the mesh loads"));
        });
        let mesh = io::load(&path).expect("the mesh loads");
        group.bench_function("analyze", |b| {
            b.iter(|| topology::analyze(black_box(&mesh)));
        });
        group.bench_function("half_edge_build", |b| {
            b.iter(|| HalfEdgeMesh::from_trimesh(black_box(&mesh)));
        });
        group.bench_function("load_and_analyze", |b| {
            b.iter(|| {
                let mesh = io::load(black_box(&path)).expect("the mesh loads");
                topology::analyze(&mesh)
            });
        });
        group.finish();
    }
}

criterion_group!(benches, load_and_topology);
criterion_main!(benches);
