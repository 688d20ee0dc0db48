//! Certified symmetric Hausdorff distance, to a gap of 1e-5 of the joint diagonal:
//! the 69k-triangle bunny against its 15 % quadric simplification
//! (`stanford-bunny-qem15.obj`, made by `MeshLab`), and the 871k-triangle dragon against its
//! own 2 % simplification (made here by `sphaera-simplify`, outside the timed loop).
//!
//! - `sphaera_1e-5`: `hausdorff(&a, &b, &options)` from the two meshes, **all told**: the
//!   triangle trees are built inside the timed loop; both cores.
//! - `meshsweeper_1e-5`: the paper's engine, `meshsweeper_hausdorff`, on one thread, its
//!   hierarchies and sweepers built **outside** the timed loop (their build is benched
//!   beside as `hierarchies`).
//! - `cascading_upper_bounds`: the peer (Sacht & Jacobson, SGP 2024) through its Python
//!   package, run by `peers/cub_hausdorff.py` in the same run; criterion times the two
//!   one-sided calls the script reports (loading excluded). The Python interpreter is
//!   `$SPHAERA_CUB_PYTHON`, else `python3`; without the package the bench says how to
//!   install it and skips the peer.
//! - `naive_1_in_N`: every `N`-th referenced vertex of each mesh against every triangle of
//!   the other, by brute force on one thread (`sphaera_eval::brute`, shared with the
//!   `hausdorff_gap_vs_time` experiment). The bench prints the factor that extrapolates its
//!   time to every vertex; the naive value is only a lower bound.
//!
//! Run with `cargo bench -p sphaera-eval --bench hausdorff` (append `-- bunny` for the
//! bunny only). Needs `../shared/data` (or `$SPHAERA_DATA`); without it the bench says so
//! and exits.

// The bench reports the brackets, the peer's and the extrapolation factor on the terminal.
#![allow(clippy::print_stderr)]

use std::{hint::black_box, path::Path, time::Duration};

use std::sync::atomic::{AtomicBool, Ordering};

use criterion::{Criterion, criterion_group, criterion_main};
use sphaera::{
    mesh::{Length, TriMesh, io},
    simplify::{SimplifyOptions, simplify},
    sweep::{
        HausdorffDistance, HausdorffOptions, Sweeper, build_hierarchy, hausdorff,
        meshsweeper_hausdorff,
    },
};
use sphaera_eval::{
    brute::{naive_hausdorff, referenced_vertices},
    peers::{cub_python, run_cub},
};

/// The bunny pair, in `shared/data`.
const PAIR: (&str, &str) = ("stanford-bunny.obj", "stanford-bunny-qem15.obj");

/// The dragon, simplified to this fraction of its triangles for the other side.
const DRAGON: (&str, f64) = ("dragon_vrip.ply", 0.02);

/// The relative tolerance of every run.
const TOLERANCE: f64 = 1e-5;

/// Whether the peer's bracket was printed.
static PEER_REPORTED: AtomicBool = AtomicBool::new(false);

/// The naive baseline measures one vertex in this many.
const NAIVE_STRIDE: usize = 32;

fn options() -> HausdorffOptions {
    HausdorffOptions::default().with_tolerance(Length::RelativeToDiagonal(TOLERANCE))
}

fn report(name: &str, h: &HausdorffDistance) {
    eprintln!(
        "hausdorff bench: {name}: H in [{:.8e}, {:.8e}], gap {:.3e}, converged {}",
        h.lower,
        h.upper,
        h.gap(),
        h.converged
    );
}

fn bunny(c: &mut Criterion) {
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

    report("sphaera", &hausdorff(&a, &b, &options()).expect("valid"));
    group.bench_function("sphaera_1e-5", |bench| {
        bench.iter(|| hausdorff(black_box(&a), black_box(&b), &options()).expect("valid"));
    });

    if let Some(python) = cub_python("hausdorff bench") {
        group.bench_function("cascading_upper_bounds", |bench| {
            bench.iter_custom(|iters| cub_seconds(&python, &path_a, &path_b, iters));
        });
    }

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
    report(
        "meshsweeper",
        &meshsweeper_hausdorff(&sa, &sb, &options()).expect("valid"),
    );
    group.bench_function("meshsweeper_1e-5", |bench| {
        bench.iter(|| {
            meshsweeper_hausdorff(black_box(&sa), black_box(&sb), &options()).expect("valid")
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

fn dragon(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("hausdorff bench") else {
        return;
    };
    let path = data.join(DRAGON.0);
    let Ok(a) = io::load(&path) else {
        eprintln!(
            "hausdorff bench: skipped the dragon, needs {}",
            path.display()
        );
        return;
    };
    let b = simplify(&a, &SimplifyOptions::default().with_target_ratio(DRAGON.1))
        .expect("the dragon simplifies")
        .mesh;
    let mut group = c.benchmark_group("hausdorff/dragon_871k_vs_2pct");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(30));
    report("dragon", &hausdorff(&a, &b, &options()).expect("valid"));
    group.bench_function("sphaera_1e-5", |bench| {
        bench.iter(|| hausdorff(black_box(&a), black_box(&b), &options()).expect("valid"));
    });
    group.finish();
}

/// The peer's seconds over `runs` runs of both directions, as the script reports them.
fn cub_seconds(python: &Path, a: &Path, b: &Path, runs: u64) -> Duration {
    let mut total = 0.0;
    for run in run_cub(python, a, b, TOLERANCE, runs).expect("cub_hausdorff.py runs") {
        total += run.seconds;
        if !PEER_REPORTED.swap(true, Ordering::Relaxed) {
            eprintln!(
                "hausdorff bench: cascading_upper_bounds: H in [{:.8e}, {:.8e}]",
                run.lower, run.upper
            );
        }
    }
    Duration::from_secs_f64(total)
}

/// Point–triangle distances of the full naive run (every referenced vertex of each mesh
/// against every triangle of the other), counted without evaluating them.
fn naive_count(a: &TriMesh, b: &TriMesh) -> usize {
    referenced_vertices(a).len() * b.triangle_count()
        + referenced_vertices(b).len() * a.triangle_count()
}

criterion_group!(benches, bunny, dragon);
criterion_main!(benches);
