//! Simplification time: Sphaera (each placement) against meshopt, in the same run.
//!
//! The 69k-triangle bunny and the 871k-triangle dragon of `shared/data`, simplified to
//! 50 %, 10 % and 2 % of their triangles (the same `ceil(ratio × triangles)` target for
//! both libraries). The calls and options are those of `sphaera_eval::methods`, shared
//! with the `simplify_error_vs_time` experiment (which measures the error of the same
//! outputs): Sphaera with its defaults (boundary locked), meshopt's `simplify` with a
//! target index count, an unlimited target error and `LockBorder`; meshopt's `f32` input
//! is prepared once, outside the timing.
//!
//! Run with `cargo bench -p sphaera-eval --bench simplify_vs_meshopt` (append
//! `-- bunny` for the bunny only: the dragon's optimal placement takes about 30 s a run,
//! so its cases take minutes).
//! Needs `../shared/data` (or `$SPHAERA_DATA`); without it the bench says so and exits.

// A skipped case says why on the terminal.
#![allow(clippy::print_stderr)]

use std::{hint::black_box, time::Duration};

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera::{
    mesh::io,
    simplify::{Hierarchy, SimplifyOptions, simplify},
};
use sphaera_eval::methods::{MeshoptInput, PLACEMENTS, sphaera_simplify, target_triangles};

/// The meshes: bench name, file in `shared/data`, measurement time per group.
const MESHES: &[(&str, &str, Duration)] = &[
    ("bunny_69k", "stanford-bunny.obj", Duration::from_secs(5)),
    ("dragon_871k", "dragon_vrip.ply", Duration::from_secs(1)),
];

/// The targets, as fractions of the input's triangles.
const RATIOS: &[(&str, f64)] = &[("50pct", 0.5), ("10pct", 0.1), ("2pct", 0.02)];

fn simplify_vs_meshopt(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("simplify_vs_meshopt bench") else {
        return;
    };
    for &(name, file, measurement) in MESHES {
        let path = data.join(file);
        if !path.is_file() {
            eprintln!("simplify_vs_meshopt: skipped {name}, no {}", path.display());
            continue;
        }
        let mesh = io::load(&path).expect("the mesh loads");
        let meshopt = MeshoptInput::new(&mesh);
        for &(ratio_name, ratio) in RATIOS {
            let target = target_triangles(&mesh, ratio);
            let mut group = c.benchmark_group(format!("simplify/{name}/{ratio_name}"));
            group.sample_size(10);
            group.warm_up_time(Duration::from_millis(500));
            group.measurement_time(measurement);
            for &(placement_name, placement) in PLACEMENTS {
                group.bench_function(format!("sphaera_{placement_name}"), |b| {
                    b.iter(|| {
                        sphaera_simplify(black_box(&mesh), placement, target)
                            .expect("Sphaera simplifies the mesh")
                    });
                });
            }
            group.bench_function("meshopt", |b| {
                b.iter(|| {
                    meshopt
                        .simplify(black_box(target))
                        .expect("meshopt simplifies the mesh")
                });
            });
            group.finish();
        }
    }
}

/// Simplifying the bunny as far as it goes (no target, no bound): the cost of a full
/// hierarchy's worth of collapses.
fn full_depth(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("simplify_vs_meshopt bench") else {
        return;
    };
    let path = data.join("stanford-bunny.obj");
    if !path.is_file() {
        eprintln!(
            "simplify_vs_meshopt: skipped full_depth, no {}",
            path.display()
        );
        return;
    }
    let mesh = io::load(&path).expect("the mesh loads");
    let mut group = c.benchmark_group("full_depth/bunny_69k");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(5));
    for &(placement_name, placement) in PLACEMENTS {
        group.bench_function(format!("simplifier_{placement_name}"), |b| {
            b.iter(|| {
                simplify(
                    black_box(&mesh),
                    &SimplifyOptions::default().with_placement(placement),
                )
                .expect("Sphaera simplifies the mesh")
            });
        });
        group.bench_function(format!("hierarchy_{placement_name}"), |b| {
            b.iter(|| {
                Hierarchy::build(
                    black_box(&mesh),
                    &SimplifyOptions::default().with_placement(placement),
                )
                .expect("Sphaera records the hierarchy")
            });
        });
    }
    group.finish();
}

criterion_group!(benches, simplify_vs_meshopt, full_depth);
criterion_main!(benches);
