//! Delaunay tetrahedralization: `sphaera-medial` against `delaunay` (the maintained
//! pure-Rust crate, BSD-3-Clause, pinned in the root `Cargo.toml`), in the same run.
//!
//! The peer is used as its documentation's convenience constructor gives it
//! (`DelaunayTriangulation::new_with_construction_statistics`: adaptive exact kernel,
//! default options); its vertices are prepared outside the timing. The peer takes
//! seconds per thousand points (about n²), so the cases are small: 1,000 random points in
//! the unit cube and the 1,016 integer points on the surface of the cube `[0, 13]³`
//! (`point_sets::cube_surface_grid(1_000)`, cocircular everywhere).
//!
//! Before criterion runs, each case is built once by both and a line reports the times,
//! their ratio and what the peer built: how many of the distinct input points ended up as
//! vertices (it skips points it cannot insert), or its error, or its panic (caught, as a
//! finding). Set `SPHAERA_PEER_10K=1` to add a one-shot comparison on 10,000 random
//! points (about five minutes for the peer on the 2-core reference machine).
//!
//! Run with `cargo bench -p sphaera-eval --bench delaunay_vs_peer` (about two minutes).

// The one-shot comparison reports on the terminal.
#![allow(clippy::print_stderr)]

use std::{
    hint::black_box,
    panic::{AssertUnwindSafe, catch_unwind},
    time::{Duration, Instant},
};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use delaunay::prelude::construction::{DelaunayTriangulation, vertex};
use sphaera::medial::{DVec3, Delaunay};
use sphaera_tests::point_sets;

/// The peer's input type for 3D points without attached data.
type PeerVertex = delaunay::prelude::construction::Vertex<f64, (), 3>;

/// The criterion cases: bench name and points.
fn cases() -> Vec<(&'static str, Vec<DVec3>)> {
    vec![
        ("random_1k", point_sets::random_in_cube(1_000, 1)),
        ("cube_surface_1k", point_sets::cube_surface_grid(1_000)),
    ]
}

/// The peer's vertices for `points`.
fn peer_vertices(points: &[DVec3]) -> Vec<PeerVertex> {
    points.iter().map(|p| vertex!([p.x, p.y, p.z])).collect()
}

/// The number of distinct points: what a complete tetrahedralization has as vertices.
fn distinct(points: &[DVec3]) -> usize {
    let mut keys: Vec<[u64; 3]> = points
        .iter()
        .map(|p| p.to_array().map(|c| (c + 0.0).to_bits()))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys.len()
}

/// What the peer made of one input.
fn peer_outcome(vertices: &[PeerVertex]) -> String {
    let built = catch_unwind(AssertUnwindSafe(|| {
        match DelaunayTriangulation::new_with_construction_statistics(vertices) {
            Ok((triangulation, statistics)) => format!(
                "{} vertices, {} tetrahedra ({} skipped as degenerate, {} as duplicates)",
                triangulation.number_of_vertices(),
                triangulation.number_of_simplices(),
                statistics.skipped_degeneracy,
                statistics.skipped_duplicate,
            ),
            Err(error) => format!("error: {error}"),
        }
    }));
    match built {
        Ok(outcome) => outcome,
        Err(panic) => {
            let message = panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("(no message)");
            format!("PANIC: {message}")
        }
    }
}

/// Builds `points` once with each library and reports times, ratio and outcomes.
fn one_shot(name: &str, points: &[DVec3]) {
    let start = Instant::now();
    let ours = Delaunay::new(points).expect("the point set tetrahedralizes");
    let ours_time = start.elapsed().as_secs_f64();
    let ours_vertices = (0..ours.vertex_count())
        .filter(|&v| ours.duplicate_of(v as u32).is_none())
        .count();
    let vertices = peer_vertices(points);
    let start = Instant::now();
    let peer = peer_outcome(&vertices);
    let peer_time = start.elapsed().as_secs_f64();
    eprintln!(
        "delaunay_vs_peer {name}: {} points ({} distinct); sphaera-medial {ours_time:.4} s \
         ({ours_vertices} vertices, {} tetrahedra), peer {peer_time:.3} s ({peer}); \
         peer / sphaera = {:.0}",
        points.len(),
        distinct(points),
        ours.tetrahedron_count(),
        peer_time / ours_time,
    );
}

fn delaunay_vs_peer(c: &mut Criterion) {
    for (name, points) in cases() {
        one_shot(name, &points);
    }
    if std::env::var_os("SPHAERA_PEER_10K").is_some_and(|v| v == "1") {
        one_shot("random_10k", &point_sets::random_in_cube(10_000, 1));
    }
    for (name, points) in cases() {
        let vertices = peer_vertices(&points);
        let mut group = c.benchmark_group(format!("delaunay_vs_peer/{name}"));
        group.sample_size(10);
        group.warm_up_time(Duration::from_millis(500));
        group.measurement_time(Duration::from_secs(3));
        group.throughput(Throughput::Elements(points.len() as u64));
        group.bench_function("sphaera_medial", |b| {
            b.iter(|| Delaunay::new(black_box(&points)).expect("the point set tetrahedralizes"));
        });
        group.bench_function("peer_delaunay", |b| {
            b.iter(|| {
                catch_unwind(AssertUnwindSafe(|| {
                    DelaunayTriangulation::new_with_construction_statistics(black_box(&vertices))
                        .map(|(triangulation, _)| triangulation.number_of_simplices())
                        .ok()
                }))
                .ok()
            });
        });
        group.finish();
    }
}

criterion_group!(benches, delaunay_vs_peer);
criterion_main!(benches);
