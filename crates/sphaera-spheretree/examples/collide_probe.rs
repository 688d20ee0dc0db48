//! Times tree-against-tree traversals of two copies of a sphere-tree in contact (the
//! second translated by a fraction of the diagonal), unlimited and under cost budgets:
//! `cargo run --release -p sphaera-spheretree --example collide_probe -- [MESH] [SHIFT]`
//! (default: the shared `bunny_lowres.obj`, shift 0.3 of the diagonal along x).

#![allow(clippy::print_stdout)]

use std::time::{Duration, Instant};

use sphaera_io as io;
use sphaera_query::Surface;
use sphaera_spheretree::collide::{Budget, CostModel, Similarity, collide, overlaps};
use sphaera_spheretree::{DVec3, SphereTreeOptions, build};

/// Median seconds per call of `f` over `rounds` rounds of `reps` calls.
fn time_per_call(rounds: usize, reps: usize, mut f: impl FnMut()) -> f64 {
    let mut samples: Vec<f64> = (0..rounds)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                f();
            }
            start.elapsed().as_secs_f64() / reps as f64
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or_else(
        || sphaera_tests::data_root().join("bunny_lowres.obj"),
        std::path::PathBuf::from,
    );
    let shift: f64 = args.get(2).map_or(Ok(0.3), |s| s.parse())?;
    let mesh = io::load(&path)?;
    let diagonal = mesh.bounding_box_diagonal();
    let started = Instant::now();
    let tree = build(
        &Surface::new(&mesh)?,
        &SphereTreeOptions::default().with_depth(3),
    )?;
    println!(
        "{}: depth-3 tree, {} nodes per level {:?}, built in {:.2} s",
        path.display(),
        tree.nodes().len(),
        (0..tree.level_count())
            .map(|k| tree.level(k).len())
            .collect::<Vec<_>>(),
        started.elapsed().as_secs_f64()
    );
    let here = Similarity::IDENTITY;
    let there = Similarity::from_translation(DVec3::X * (shift * diagonal))?;
    let full = collide(&tree, &here, &tree, &there, &Budget::Unlimited)?;
    let model = CostModel::default();
    let seconds = time_per_call(15, 200, || {
        let c = collide(&tree, &here, &tree, &there, &Budget::Unlimited);
        std::hint::black_box(c).ok();
    });
    println!(
        "shift {shift} × diagonal: full traversal {:.1} µs (median of 15 × 200), level {}, \
         {} contacts, {} updates, {} tests, cost {}, worst error bound {:.2} % of the diagonal",
        seconds * 1e6,
        full.level,
        full.contacts.len(),
        full.stats.updates,
        full.stats.tests,
        full.stats.cost(&model),
        100.0 * full.max_error_bound().unwrap_or(0.0) / diagonal
    );
    let seconds = time_per_call(15, 200, || {
        std::hint::black_box(overlaps(&tree, &here, &tree, &there));
    });
    println!(
        "overlaps (early exit): {:.2} µs, {}",
        seconds * 1e6,
        overlaps(&tree, &here, &tree, &there)
    );
    let full_cost = full.stats.cost(&model);
    for fraction in [0.01, 0.05, 0.2, 0.5, 1.0] {
        let c = collide(
            &tree,
            &here,
            &tree,
            &there,
            &Budget::cost(fraction * full_cost),
        )?;
        println!(
            "cost budget {:>5.0} ({fraction:>4} of full): level {}, {} contacts, cost spent {}, \
             worst error bound {:.2} %",
            fraction * full_cost,
            c.level,
            c.contacts.len(),
            c.stats.cost(&model),
            100.0 * c.max_error_bound().unwrap_or(0.0) / diagonal
        );
    }
    for micros in [1, 5, 20, 100] {
        let c = collide(
            &tree,
            &here,
            &tree,
            &there,
            &Budget::Time(Duration::from_micros(micros)),
        )?;
        println!(
            "time budget {micros:>3} µs: level {}, completed {}, {} contacts",
            c.level,
            c.completed,
            c.contacts.len()
        );
    }
    Ok(())
}
