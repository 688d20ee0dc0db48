//! Point inclusion in a closed genus-0 mesh: the 3D HAL tree against brute-force ray
//! parity, `sphaera-mesh`'s certified winding number and parry3d-f64's `contains_point`
//! (its BVH with angle-weighted pseudo-normals), in the same run; and the HAL tree's build.
//!
//! Meshes: `spot.obj` (5,856 triangles), `fandisk.obj` (12,946; coplanar-rich) from
//! `shared/data` (skipped with a message when absent), and a procedural sphere of about
//! 50,000 triangles (`shapes::sphere(1.0, 224)`). Queries: `QUERIES` points uniform in the mesh's bounding box grown by 20 %
//! (seeded `SplitMix64`); criterion reports the time per block. Brute force only on the
//! real meshes (it is linear in the triangles). Run with
//! `cargo bench -p sphaera-eval --bench hal3_vs_parry`.

use std::{hint::black_box, time::Duration};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{TriMesh as ParryTriMesh, TriMeshFlags};
use sphaera::hal::{Containment, HalTree3, contains3_brute};
use sphaera::mesh::{DVec3, Surface, TriMesh, shapes};
use sphaera_tests::random::SplitMix64;

/// Queries per measured block.
const QUERIES: usize = 200;

fn queries(mesh: &TriMesh, seed: u64) -> Vec<DVec3> {
    let bounds = mesh.bounding_box();
    let (lo, hi) = (bounds.min, bounds.max);
    let grow = (hi - lo) * 0.1;
    let mut rng = SplitMix64::new(seed);
    (0..QUERIES)
        .map(|_| {
            let t = DVec3::new(rng.unit(), rng.unit(), rng.unit());
            lo - grow + (hi - lo + 2.0 * grow) * t
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut meshes: Vec<(String, TriMesh, bool)> = Vec::new();
    if let Some(data) = sphaera_tests::data_dir("hal3_vs_parry") {
        for name in ["spot.obj", "fandisk.obj"] {
            let mesh = sphaera::mesh::io::load(data.join(name)).expect("a shared mesh");
            meshes.push((name.trim_end_matches(".obj").to_owned(), mesh, true));
        }
    }
    let sphere = shapes::sphere(1.0, 224).expect("a sphere");
    meshes.push((
        format!("sphere_{}k", sphere.triangle_count() / 1000),
        sphere,
        false,
    ));

    let mut group = c.benchmark_group("point_in_mesh");
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    for (name, mesh, brute) in &meshes {
        let points = queries(mesh, 23);
        let tree = HalTree3::build(mesh).expect("genus 0");
        let surface = Surface::new(mesh).expect("closed");
        let parry = ParryTriMesh::with_flags(
            mesh.positions().to_vec(),
            mesh.triangles().to_vec(),
            TriMeshFlags::ORIENTED,
        )
        .expect("an oriented mesh");
        group.bench_with_input(BenchmarkId::new("hal", name), &points, |b, points| {
            b.iter(|| {
                points
                    .iter()
                    .filter(|&&p| tree.contains(p) == Containment::Inside)
                    .count()
            });
        });
        group.bench_with_input(BenchmarkId::new("winding", name), &points, |b, points| {
            b.iter(|| {
                points
                    .iter()
                    .filter(|&&p| surface.is_inside_certified(p))
                    .count()
            });
        });
        group.bench_with_input(BenchmarkId::new("parry", name), &points, |b, points| {
            b.iter(|| {
                points
                    .iter()
                    .filter(|&&p| parry.contains_local_point(p))
                    .count()
            });
        });
        if *brute {
            group.bench_with_input(
                BenchmarkId::new("brute_force", name),
                &points,
                |b, points| {
                    b.iter(|| {
                        points
                            .iter()
                            .filter(|&&p| contains3_brute(mesh, p) == Containment::Inside)
                            .count()
                    });
                },
            );
        }
    }
    group.finish();

    let mut group = c.benchmark_group("hal3_build");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(5));
    for (name, mesh, _) in &meshes {
        group.bench_with_input(BenchmarkId::from_parameter(name), mesh, |b, mesh| {
            b.iter(|| black_box(HalTree3::build(mesh).expect("genus 0")));
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
