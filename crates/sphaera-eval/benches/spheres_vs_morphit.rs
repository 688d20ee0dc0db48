//! Exactly N spheres around `bunny_lowres.obj`, N = 8, 64 and 512: Sphaera against
//! morphit-rs in the same run (issue 36; the `spheres_vs_count` experiment charts the
//! same calls over more meshes and counts, with their accuracy).
//!
//! - `sphaera_N`: [`one_level_minimax`], from the loaded mesh to the spheres:
//!   `Surface::solid_or_shell` and a one-level minimax tree of branching factor N, on
//!   both cores.
//! - `morphit_N`: the peer through its Python package, run by `peers/morphit_spheres.py`
//!   (its default preset `MorphIt-B`, seed 0, the package's default threads: both
//!   cores); criterion times the `pack` calls the script reports (loading the mesh and
//!   starting Python excluded). The interpreter is `$SPHAERA_MORPHIT_PYTHON`, else
//!   `python3`; without the package the bench says how to install it and skips the peer.
//!
//! Counts above [`CRITERION_MAX`] are timed once each, outside criterion, for both
//! libraries (ten samples of the peer at 512 take about a minute), and
//! printed. At the end the bench prints, per N, both mean times and Sphaera's over the
//! peer's.
//!
//! Run with `cargo bench -p sphaera-eval --bench spheres_vs_morphit`. Needs
//! `../shared/data` (or `$SPHAERA_DATA`); without it the bench says so and exits.

// The bench reports the spheres produced and the ratios on the terminal.
#![allow(clippy::print_stderr)]

use std::{
    collections::BTreeMap,
    hint::black_box,
    path::Path,
    sync::Mutex,
    time::{Duration, Instant},
};

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use sphaera::mesh::io;
use sphaera_eval::{
    peers::{morphit_python, run_morphit},
    sphere_sets::one_level_minimax,
};

/// The mesh, in `shared/data`.
const MESH: &str = "bunny_lowres.obj";

/// The sphere counts.
const COUNTS: [usize; 3] = [8, 64, 512];

/// The largest count timed by criterion; larger ones are timed once (see the top).
const CRITERION_MAX: usize = 64;

/// Per (library, N): total seconds and iterations timed.
type Totals = BTreeMap<(&'static str, usize), (f64, u64)>;

/// The times so far, for the ratios at the end.
static TOTALS: Mutex<Totals> = Mutex::new(BTreeMap::new());

fn record(library: &'static str, n: usize, elapsed: Duration, iterations: u64) {
    if let Ok(mut totals) = TOTALS.lock() {
        let entry = totals.entry((library, n)).or_insert((0.0, 0));
        entry.0 += elapsed.as_secs_f64();
        entry.1 += iterations;
    }
}

fn spheres(c: &mut Criterion) {
    let Some(data) = sphaera_tests::data_dir("spheres_vs_morphit bench") else {
        return;
    };
    let path = data.join(MESH);
    let Ok(mesh) = io::load(&path) else {
        eprintln!(
            "spheres_vs_morphit bench: skipped, needs {}",
            path.display()
        );
        return;
    };
    let python = morphit_python("spheres_vs_morphit bench");
    let mut group = c.benchmark_group("spheres_vs_morphit/bunny_lowres");
    group.sample_size(10);
    group.sampling_mode(SamplingMode::Flat);
    group.warm_up_time(Duration::from_secs(1));
    for n in COUNTS {
        if n > CRITERION_MAX {
            once(&mesh, &path, python.as_deref(), n);
            continue;
        }
        // Ten samples of a few seconds each at 64.
        group.measurement_time(Duration::from_secs(if n > 8 { 40 } else { 5 }));
        let produced = one_level_minimax(&mesh, n)
            .expect("the bunny builds")
            .spheres
            .len();
        eprintln!("spheres_vs_morphit bench: Sphaera gives {produced} spheres for {n}");
        group.bench_function(format!("sphaera_{n}"), |bench| {
            bench.iter_custom(|iterations| {
                let started = Instant::now();
                for _ in 0..iterations {
                    black_box(one_level_minimax(black_box(&mesh), n).expect("builds"));
                }
                let elapsed = started.elapsed();
                record("sphaera", n, elapsed, iterations);
                elapsed
            });
        });
        if let Some(python) = &python {
            group.bench_function(format!("morphit_{n}"), |bench| {
                bench.iter_custom(|iterations| {
                    let elapsed = morphit_seconds(python, &path, n, iterations);
                    record("morphit", n, elapsed, iterations);
                    elapsed
                });
            });
        }
    }
    group.finish();
    report();
}

/// One timed run of each library at `n` spheres, outside criterion.
fn once(mesh: &sphaera::mesh::TriMesh, path: &Path, python: Option<&Path>, n: usize) {
    let started = Instant::now();
    let produced = one_level_minimax(mesh, n)
        .expect("the bunny builds")
        .spheres
        .len();
    let elapsed = started.elapsed();
    record("sphaera", n, elapsed, 1);
    eprintln!(
        "spheres_vs_morphit bench: sphaera_{n} (one run): {:.3} s, {produced} spheres",
        elapsed.as_secs_f64()
    );
    if let Some(python) = python {
        let elapsed = morphit_seconds(python, path, n, 1);
        record("morphit", n, elapsed, 1);
        eprintln!(
            "spheres_vs_morphit bench: morphit_{n} (one run): {:.3} s",
            elapsed.as_secs_f64()
        );
    }
}

/// The peer's `pack` time over `runs` runs at `n` spheres, as the script reports it.
fn morphit_seconds(python: &Path, mesh: &Path, n: usize, runs: u64) -> Duration {
    let runs = usize::try_from(runs).expect("a count of runs fits");
    let reported = run_morphit(python, mesh, &[n], runs).expect("morphit_spheres.py runs");
    let total: f64 = reported.iter().flat_map(|r| &r.seconds_all).sum();
    Duration::from_secs_f64(total)
}

/// Mean times per N of both libraries and their ratio.
fn report() {
    let Ok(totals) = TOTALS.lock() else { return };
    let mean = |library, n| {
        totals
            .get(&(library, n))
            .filter(|t| t.1 > 0)
            .map(|&(seconds, iterations)| seconds / iterations as f64)
    };
    for n in COUNTS {
        match (mean("sphaera", n), mean("morphit", n)) {
            (Some(ours), Some(peer)) => eprintln!(
                "spheres_vs_morphit bench: N = {n}: Sphaera {ours:.3} s, morphit-rs {peer:.3} s, \
                 Sphaera / morphit-rs = {:.2}",
                ours / peer
            ),
            (Some(ours), None) => {
                eprintln!("spheres_vs_morphit bench: N = {n}: Sphaera {ours:.3} s (no peer)");
            }
            _ => {}
        }
    }
}

criterion_group!(benches, spheres);
criterion_main!(benches);
