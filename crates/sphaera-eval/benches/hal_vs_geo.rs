//! Point-in-polygon on a real outline: the HAL tree against the brute-force crossing test
//! and `geo`'s `Contains`, in the same run; and the HAL tree's build on that outline and on
//! its worst case.
//!
//! The outline: `shared/data/polygons/americas.txt` (66,354 vertices; the bench skips
//! with a message when the data is absent). Queries: `QUERIES` points uniform in its
//! bounding box (seeded `SplitMix64`); criterion reports the time per block. The worst
//! case of Algorithm 1 (Theorem 2's `Θ(N²)`): an open half-circle arc whose radius shrinks
//! slightly (by 10⁻³) from its start to its end, so that the vertex after a part's first
//! always lies farthest outside the part's chord circle and each split peels one vertex.
//! Run with `cargo bench -p sphaera-eval --bench hal_vs_geo`.

use std::{hint::black_box, time::Duration};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use geo::{Contains, LineString, Point, Polygon};
use sphaera::hal::{HalTree2, Polyline2, contains_brute};
use sphaera::mesh::glam::DVec2;
use sphaera_tests::random::SplitMix64;

/// Queries per measured block.
const QUERIES: usize = 200;

/// The worst case of the module docs, `n` vertices.
fn worst_case(n: usize) -> Polyline2 {
    let last = (n - 1) as f64;
    let points = (0..n)
        .map(|i| {
            let t = i as f64 / last;
            DVec2::from_angle(std::f64::consts::PI * t) * (1.0 + 1e-3 * (1.0 - t))
        })
        .collect();
    Polyline2::open(points).expect("an arc")
}

fn bench(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("hal_vs_geo") else {
        return;
    };
    let americas =
        Polyline2::read_polygon(data.join("polygons/americas.txt")).expect("the Americas");
    let (lo, hi) = americas.bounds();
    let mut rng = SplitMix64::new(17);
    let queries: Vec<DVec2> = (0..QUERIES)
        .map(|_| DVec2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y)))
        .collect();
    let tree = HalTree2::build(&americas).expect("builds");
    let geo_polygon = Polygon::new(
        LineString::from(
            americas
                .points()
                .iter()
                .map(|p| (p.x, p.y))
                .collect::<Vec<_>>(),
        ),
        vec![],
    );

    let mut group = c.benchmark_group("point_in_polygon_americas");
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    group.bench_function("hal", |b| {
        b.iter(|| {
            for &q in &queries {
                black_box(tree.contains(q).expect("closed"));
            }
        });
    });
    group.bench_function("brute_force", |b| {
        b.iter(|| {
            for &q in &queries {
                black_box(contains_brute(&americas, q).expect("closed"));
            }
        });
    });
    group.bench_function("geo", |b| {
        b.iter(|| {
            for &q in &queries {
                black_box(geo_polygon.contains(&Point::new(q.x, q.y)));
            }
        });
    });
    group.finish();

    let mut group = c.benchmark_group("hal_build");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    group.bench_function("americas_66k", |b| {
        b.iter(|| black_box(HalTree2::build(&americas).expect("builds")));
    });
    for n in [2_000, 4_000, 8_000] {
        let polygon = worst_case(n);
        group.bench_with_input(BenchmarkId::new("worst_case_arc", n), &polygon, |b, p| {
            b.iter(|| black_box(HalTree2::build(p).expect("builds")));
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
