//! Delaunay tetrahedralization speed: the two cases (100,000 random points in the
//! unit cube and about 100,000 samples of a cube's surface grid, the worst case for ties),
//! reported as insertions per second, and the adaptive medial algorithm's use: inserting
//! 10,000 points one at a time into an existing 100k tetrahedralization, in random order
//! (as the adaptive algorithm inserts them) and sorted along a Morton curve (short walks).
//!
//! Run with `cargo bench -p sphaera-medial --bench delaunay` (about two minutes on the
//! 2-core reference machine). The comparison with a peer crate is in `sphaera-eval`
//! (`cargo bench -p sphaera-eval --bench delaunay_vs_peer`).

use std::{hint::black_box, time::Duration};

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use sphaera_medial::{DVec3, Delaunay};
use sphaera_tests::point_sets;

/// `Delaunay::new` on the whole point set; throughput in inserted points.
fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("delaunay/new");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(8));
    for (name, points) in [
        ("random_100k", point_sets::random_in_cube(100_000, 1)),
        ("cube_surface_100k", point_sets::cube_surface_grid(100_000)),
    ] {
        group.throughput(Throughput::Elements(points.len() as u64));
        group.bench_function(name, |b| {
            b.iter(|| Delaunay::new(black_box(&points)).expect("the point set tetrahedralizes"));
        });
    }
    group.finish();
}

/// `insert` of 10,000 random points, one at a time, into a tetrahedralization of 100,000
/// random points (rebuilt outside the timing for every sample): the point order is the
/// caller's, so the walks are long, unlike in `new`'s Hilbert order.
fn insert_one_at_a_time(c: &mut Criterion) {
    let base = Delaunay::new(&point_sets::random_in_cube(100_000, 1))
        .expect("the point set tetrahedralizes");
    let extra = point_sets::random_in_cube(10_000, 2);
    let mut group = c.benchmark_group("delaunay/insert");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(5));
    group.throughput(Throughput::Elements(extra.len() as u64));
    group.bench_function("10k_into_random_100k", |b| {
        b.iter_batched(
            || base.clone(),
            |mut delaunay| {
                for &p in &extra {
                    black_box(delaunay.insert(p).expect("a finite point inserts"));
                }
                delaunay
            },
            BatchSize::LargeInput,
        );
    });
    // The same points in Morton order: the walks become short, so the difference from
    // the case above is the cost of locating a point far from the previous one.
    let mut sorted = extra.clone();
    sorted.sort_by_key(|p| morton(*p));
    group.bench_function("10k_morton_sorted_into_random_100k", |b| {
        b.iter_batched(
            || base.clone(),
            |mut delaunay| {
                for &p in &sorted {
                    black_box(delaunay.insert(p).expect("a finite point inserts"));
                }
                delaunay
            },
            BatchSize::LargeInput,
        );
    });
    group.finish();
}

/// The Morton (Z-order) key of a point of the unit cube on a 2¹⁰ grid.
fn morton(p: DVec3) -> u32 {
    let cell = |c: f64| (c.clamp(0.0, 1.0) * 1023.0) as u32;
    let [x, y, z] = [cell(p.x), cell(p.y), cell(p.z)];
    (0..10).fold(0, |key, bit| {
        key | ((x >> bit) & 1) << (3 * bit)
            | ((y >> bit) & 1) << (3 * bit + 1)
            | ((z >> bit) & 1) << (3 * bit + 2)
    })
}

criterion_group!(benches, build, insert_one_at_a_time);
criterion_main!(benches);
