//! 2D point inclusion on the real outlines: the HAL tree against GEOS prepared geometry
//! (what shapely and `PostGIS` run), in the same run, on one thread.
//!
//! The outlines: every `shared/data/polygons/*.txt` (194 to 66,354 vertices; the bench
//! skips with a message when the data is absent). Two sets of `QUERIES` points per
//! outline (seeded, `sphaera_eval::query_sets`), the same points for both libraries:
//! `box`, uniform in the outline's bounding box, and `near`, within an edge's length of
//! the outline (where the cell grid must count crossings and GEOS's interval tree is
//! busiest). Four calls per set: `hal` is `HalTree2::contains` (the cell grid, then the
//! hierarchy where the grid cannot decide), `hal_hierarchy` the paper's walk alone
//! (`HalTree2::contains_by_hierarchy`), `geos_contains` and `geos_intersects` GEOS's
//! prepared predicates; HAL's `Inside` is GEOS's `contains`, `Inside | Boundary` its
//! `intersects`, so HAL's one call answers both. The tree and the prepared polygon are built once and GEOS's point geometries
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
use sphaera_eval::geos_peer::{QUERY_SEED, geos_containment, geos_points, geos_polygon, outlines};
use sphaera_eval::query_sets::{box_points, near_outline_points};

/// Queries per measured block.
const QUERIES: usize = 1_000;

fn bench(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("hal2_vs_geos") else {
        return;
    };
    for (name, outline) in outlines(&data).expect("the shared outlines") {
        let tree = HalTree2::build(&outline).expect("builds");
        let polygon = geos_polygon(&outline).expect("a GEOS polygon");
        let prepared = polygon.to_prepared_geom().expect("GEOS prepares it");
        for (set, queries) in [
            ("box", box_points(&outline, QUERIES, QUERY_SEED)),
            ("near", near_outline_points(&outline, QUERIES, QUERY_SEED)),
        ] {
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

            let mut group = c.benchmark_group(format!("hal2_vs_geos_{name}_{set}"));
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
            group.bench_function("hal_hierarchy", |b| {
                b.iter(|| {
                    for &q in &queries {
                        black_box(tree.contains_by_hierarchy(black_box(q)).expect("closed"));
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
}

criterion_group!(benches, bench);
criterion_main!(benches);
