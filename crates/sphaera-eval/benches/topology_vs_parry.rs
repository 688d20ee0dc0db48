//! Half-edge topology: Sphaera against parry3d-f64, in the same run.
//!
//! parry builds a BVH with every `TriMesh`, so it is measured twice: without flags (BVH
//! only) and with `HALF_EDGE_TOPOLOGY`; the difference is its topology cost. Sphaera's
//! `HalfEdgeMesh::from_trimesh` builds topology only, and also accepts non-manifold input
//! (which parry rejects).
//!
//! Run with `cargo bench -p sphaera-eval --bench topology_vs_parry`.

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use parry3d_f64::shape::{TriMesh as ParryTriMesh, TriMeshFlags};
use sphaera::mesh::{io, topology};

fn topology_vs_parry(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("topology_vs_parry bench") else {
        return;
    };
    for (name, file) in [
        ("bunny_69k", "stanford-bunny.obj"),
        ("rocker_arm_20k", "rocker-arm.obj"),
    ] {
        let mesh = io::load(data.join(file)).expect("the mesh loads");
        let vertices = mesh.positions().to_vec();
        let triangles = mesh.triangles().to_vec();
        let mut group = c.benchmark_group(format!("half_edge_topology/{name}"));
        group.sample_size(20);
        group.measurement_time(Duration::from_secs(4));
        group.bench_function("sphaera_half_edge", |b| {
            b.iter(|| topology::HalfEdgeMesh::from_trimesh(black_box(&mesh)));
        });
        group.bench_function("sphaera_report", |b| {
            b.iter(|| topology::analyze(black_box(&mesh)));
        });
        group.bench_function("parry_bvh_only", |b| {
            b.iter(|| {
                ParryTriMesh::with_flags(
                    black_box(vertices.clone()),
                    triangles.clone(),
                    TriMeshFlags::empty(),
                )
                .expect("parry accepts the mesh")
            });
        });
        group.bench_function("parry_bvh_and_half_edge", |b| {
            b.iter(|| {
                ParryTriMesh::with_flags(
                    black_box(vertices.clone()),
                    triangles.clone(),
                    TriMeshFlags::HALF_EDGE_TOPOLOGY,
                )
                .expect("parry accepts the mesh")
            });
        });
        group.finish();
    }
}

criterion_group!(benches, topology_vs_parry);
criterion_main!(benches);
