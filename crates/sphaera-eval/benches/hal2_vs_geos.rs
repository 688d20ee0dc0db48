//! 2D point inclusion on the real outlines: the HAL tree against GEOS prepared geometry
//! (what shapely and `PostGIS` run), in the same run, on one thread.
//!
//! The outlines: every `shared/data/polygons/*.txt` (194 to 66,354 vertices; the bench
//! skips with a message when the data is absent). Queries: `QUERIES` points uniform in
//! each outline's bounding box (seeded `SplitMix64`, `sphaera_eval::geos_peer`), the same
//! points for both libraries. Three calls per outline: `hal` is `HalTree2::contains`,
//! `geos_contains` and `geos_intersects` are GEOS's prepared predicates; HAL's `Inside`
//! is GEOS's `contains`, `Inside | Boundary` its `intersects`, so HAL's one call answers
//! both. The tree and the prepared polygon are built once and GEOS's point geometries
//! made once, outside the timing (GEOS 3.11 has no predicate on bare coordinates), so
//! GEOS is timed on its predicate alone. Before timing, every answer is checked against
//! GEOS's on those points. Criterion reports points per second.
//!
//! Needs GEOS (Debian: `apt-get install libgeos-dev`). Run with
//! `cargo bench -p sphaera-eval --features geos --bench hal2_vs_geos`, on one core with
//! `taskset -c 0` in front.

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use geos::Geom;
use sphaera::hal::HalTree2;
use sphaera_eval::geos_peer::{
    QUERY_SEED, box_queries, geos_containment, geos_points, geos_polygon, outlines,
};

/// Queries per measured block.
const QUERIES: usize = 1_000;

fn bench(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("hal2_vs_geos") else {
        return;
    };
    for (name, outline) in outlines(&data).expect("the shared outlines") {
        let queries = box_queries(&outline, QUERIES, QUERY_SEED);
        let tree = HalTree2::build(&outline).expect("builds");
        let polygon = geos_polygon(&outline).expect("a GEOS polygon");
        let prepared = polygon.to_prepared_geom().expect("GEOS prepares it");
        let points = geos_points(&queries).expect("GEOS points");
        for (&q, point) in queries.iter().zip(&points) {
            let hal = tree.contains(q).expect("closed");
            let geos = geos_containment(&prepared, point).expect("GEOS answers");
            assert_eq!(
                hal, geos,
                "{name}: HAL and GEOS differ at ({}, {})",
                q.x, q.y
            );
        }

        let mut group = c.benchmark_group(format!("hal2_vs_geos_{name}"));
        group.throughput(Throughput::Elements(QUERIES as u64));
        group.sample_size(10);
        group.warm_up_time(Duration::from_secs(1));
        group.measurement_time(Duration::from_secs(2));
        group.bench_function("hal", |b| {
            b.iter(|| {
                for &q in &queries {
                    black_box(tree.contains(black_box(q)).expect("closed"));
                }
            });
        });
        group.bench_function("geos_contains", |b| {
            b.iter(|| {
                for point in &points {
                    black_box(prepared.contains(black_box(point)).expect("GEOS contains"));
                }
            });
        });
        group.bench_function("geos_intersects", |b| {
            b.iter(|| {
                for point in &points {
                    black_box(
                        prepared
                            .intersects(black_box(point))
                            .expect("GEOS intersects"),
                    );
                }
            });
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
