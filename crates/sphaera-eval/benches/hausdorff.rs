//! Certified symmetric Hausdorff distance: the 69k-triangle bunny against its 15 % quadric
//! simplification (`stanford-bunny-qem15.obj`, made by `MeshLab`), to a gap of 1e-5 of the
//! joint diagonal (the target: under 0.5 s on one thread), and the paper's naive
//! alternative in the same run.
//!
//! - `sphaera_symmetric_1e-5`: `hausdorff(&a, &b, &HausdorffOptions::default()
//!   .with_tolerance(Length::RelativeToDiagonal(1e-5)))`. The two hierarchies and sweepers are built once, **outside** the timed
//!   loop (their build, which is parallel, is benched beside as `hierarchies`); the
//!   computation itself runs on one thread.
//! - `naive_1_in_N`: every `N`-th referenced vertex of each mesh against every triangle of
//!   the other, by brute force on one thread (`sphaera_eval::brute`, shared with the
//!   `hausdorff_gap_vs_time` experiment). The bench prints the factor that extrapolates its
//!   time to every vertex (the ratio of point–triangle distances evaluated); the full
//!   naive run certifies nothing anyway (its value is only a lower bound).
//!
//! Run with `cargo bench -p sphaera-eval --bench hausdorff`. Needs `../shared/data` (or
//! `$SPHAERA_DATA`); without it the bench says so and exits.

// The bench reports the bracket and the extrapolation factor on the terminal.
#![allow(clippy::print_stderr)]

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera::{
    mesh::{Length, TriMesh, io},
    sweep::{HausdorffOptions, Sweeper, build_hierarchy, hausdorff},
};
use sphaera_eval::brute::{naive_hausdorff, referenced_vertices};

/// The pair measured, in `shared/data`.
const PAIR: (&str, &str) = ("stanford-bunny.obj", "stanford-bunny-qem15.obj");

/// The naive baseline measures one vertex in this many.
const NAIVE_STRIDE: usize = 32;

fn hausdorff_bench(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("hausdorff bench") else {
        return;
    };
    let (path_a, path_b) = (data.join(PAIR.0), data.join(PAIR.1));
    if !path_a.is_file() || !path_b.is_file() {
        eprintln!(
            "hausdorff bench: skipped, needs {} and {}",
            path_a.display(),
            path_b.display()
        );
        return;
    }
    let a = io::load(&path_a).expect("the bunny loads");
    let b = io::load(&path_b).expect("the simplified bunny loads");
    let mut group = c.benchmark_group("hausdorff/bunny_69k_vs_qem15");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(5));
    group.bench_function("hierarchies", |bench| {
        bench.iter(|| {
            (
                build_hierarchy(black_box(&a)).expect("builds"),
                build_hierarchy(black_box(&b)).expect("builds"),
            )
        });
    });
    let (ha, hb) = (
        build_hierarchy(&a).expect("builds"),
        build_hierarchy(&b).expect("builds"),
    );
    let (sa, sb) = (
        Sweeper::new(&ha).expect("non-empty"),
        Sweeper::new(&hb).expect("non-empty"),
    );
    let certified = hausdorff(
        &sa,
        &sb,
        &HausdorffOptions::default().with_tolerance(Length::RelativeToDiagonal(1e-5)),
    )
    .expect("a valid tolerance");
    eprintln!(
        "hausdorff bench: H(bunny, qem15) in [{:.8}, {:.8}], gap {:.3e}, converged {}",
        certified.lower,
        certified.upper,
        certified.gap(),
        certified.converged
    );
    group.bench_function("sphaera_symmetric_1e-5", |bench| {
        bench.iter(|| {
            hausdorff(
                black_box(&sa),
                black_box(&sb),
                &HausdorffOptions::default().with_tolerance(Length::RelativeToDiagonal(1e-5)),
            )
            .expect("a valid tolerance")
        });
    });
    let subset = naive_hausdorff(&a, &b, NAIVE_STRIDE).expect("both meshes have triangles");
    let every = naive_count(&a, &b);
    eprintln!(
        "hausdorff bench: naive_1_in_{NAIVE_STRIDE} evaluates {} of {every} point-triangle \
         distances: multiply its time by {:.2} for every vertex (value on the subset {:.8}; \
         a lower bound only)",
        subset.evaluations,
        every as f64 / subset.evaluations.max(1) as f64,
        subset.value,
    );
    group.bench_function(format!("naive_1_in_{NAIVE_STRIDE}"), |bench| {
        bench.iter(|| {
            naive_hausdorff(black_box(&a), black_box(&b), NAIVE_STRIDE)
                .expect("both meshes have triangles")
                .value
        });
    });
    group.finish();
}

/// Point–triangle distances of the full naive run (every referenced vertex of each mesh
/// against every triangle of the other), counted without evaluating them.
fn naive_count(a: &TriMesh, b: &TriMesh) -> usize {
    referenced_vertices(a).len() * b.triangle_count()
        + referenced_vertices(b).len() * a.triangle_count()
}

criterion_group!(benches, hausdorff_bench);
criterion_main!(benches);
