//! The experiments, one module each: [`NAMES`] lists them in the order `cargo xtask
//! charts` runs them, [`run`] runs one. The docs at the top of each source file say what
//! the experiment measures, how, and which files it writes.
//!
//! - `load_topology_time`: `load_topology.rs`;
//! - `simplify_error_vs_time`: `simplify_error.rs` (the calls of [`crate::methods`]);
//! - `sweep_throughput`: `sweep_throughput.rs` (the points of [`crate::query_sets`], and
//!   [`crate::brute`]);
//! - `sweep_speedup_vs_step`: `sweep_coherence.rs` (coherent queries against the step
//!   length);
//! - `hausdorff_gap_vs_time`: `hausdorff_gap.rs` (the naive estimate of [`crate::brute`]);
//! - `medial_static_vs_adaptive`: `medial_static_vs_adaptive.rs`;
//! - `spheretree`: `spheretree/mod.rs`, its tables and charts in `spheretree/charts.rs`;
//! - `spheretree_similarity`: `spheretree/similarity.rs` (the default tree under random
//!   similarity transforms);
//! - `hal`: `hal/mod.rs` (three charts: widths, query speed, against strip and box trees;
//!   the peers in `hal/peers.rs`);
//! - `silhouette_error_vs_triangles`: `silhouette/mod.rs` (levels of detail guided by
//!   silhouette labels against unweighted ones, in image space and object space; the
//!   Fig. 3 picture in `silhouette/picture.rs`);
//! - `silhouette_time_vs_faces`: `silhouette/timing.rs` (the paper's Tables 1–2);
//! - `silhouette_vs_simplify`: `silhouette/plain.rs` (guided against the plain simplifier
//!   at equal triangle counts, on meshes nobody tuned it for; the paper's factor swept);
//! - `silhouette_temporal`: `silhouette/temporal.rs` (popping along an orbit, nearest
//!   camera against the mean of the 4 nearest);
//! - `scene_time_vs_error`: `scene/mod.rs` (200 bodies falling into a box in rapier with
//!   Sphaera's ball compounds, trimesh and convex-decomposition colliders; the simulation
//!   and the measurement on the true meshes in `scene/physics.rs`);
//! - `robot_protrusion_vs_spheres`: `robot/mod.rs` (the Franka Panda's and KUKA iiwa's
//!   links spherized by Sphaera and by the voxel k-means baseline planners ship, in
//!   [`voxel`] (`robot/voxel.rs`, public for the `robot_spheres` bench), both measured by
//!   the same certified evaluator);
//! - `robot_budgets`: `robot/budgets.rs` (the Panda and the KUKA spherized whole, by
//!   spheres per link, a total and a tolerance: spheres, worst protrusion, time);
//! - `spheres_vs_count`: `spheres_vs_count/mod.rs` (exactly N spheres, Sphaera's one-level
//!   minimax tree against morphit-rs raw and grown to cover, on the shared meshes, the
//!   Panda's links and the procedural animal; three charts, written in
//!   `spheres_vs_count/charts.rs`);
//! - `main_job`: `main_job.rs` (the default tree of the CLI's bunny, the 69k bunny and the
//!   dragon, built and certified level by level as `sphaera spheretree` does: seconds and
//!   certified worst error per level);
//! - `tolerance_trees`: `tolerance_trees.rs` (trees to 4, 2, 1 and 0.5 % of the diagonal
//!   on three meshes: leaves, nodes, levels, certified leaf error, build seconds).

// Experiments report each measurement on the terminal as they go.
#![allow(clippy::print_stderr)]

mod hal;
mod hausdorff_gap;
mod load_topology;
mod main_job;
mod medial_static_vs_adaptive;
mod robot;
mod scene;
mod silhouette;
mod simplify_error;
mod spheres_vs_count;
mod spheretree;
mod sweep_coherence;
mod sweep_throughput;
mod tolerance_trees;

pub use robot::voxel;

use std::path::Path;

use anyhow::{Context, Result, bail};
use sphaera::mesh::{TriMesh, io};

/// Names of the experiments, in the order `cargo xtask charts` runs them. Each writes
/// its charts as `CHART.svg` with the data in `CHART.csv` (`spheretree` writes two,
/// from one set of trees; `spheretree_similarity` writes its own name's).
pub const NAMES: &[&str] = &[
    load_topology::NAME,
    simplify_error::NAME,
    sweep_throughput::NAME,
    sweep_coherence::NAME,
    hausdorff_gap::NAME,
    medial_static_vs_adaptive::NAME,
    spheretree::NAME,
    spheretree::similarity::NAME,
    hal::NAME,
    silhouette::NAME,
    silhouette::timing::NAME,
    silhouette::plain::NAME,
    silhouette::temporal::NAME,
    scene::NAME,
    robot::NAME,
    robot::budgets::NAME,
    robot::morphit::NAME,
    spheres_vs_count::NAME,
    main_job::NAME,
    tolerance_trees::NAME,
];

/// Runs the experiment `name` on the meshes in `data`, writing its files into `out`.
pub fn run(name: &str, data: &Path, out: &Path) -> Result<()> {
    match name {
        load_topology::NAME => load_topology::run(data, out),
        simplify_error::NAME => simplify_error::run(data, out),
        sweep_throughput::NAME => sweep_throughput::run(data, out),
        sweep_coherence::NAME => sweep_coherence::run(data, out),
        hausdorff_gap::NAME => hausdorff_gap::run(data, out),
        medial_static_vs_adaptive::NAME => medial_static_vs_adaptive::run(data, out),
        spheretree::NAME => spheretree::run(data, out),
        spheretree::similarity::NAME => spheretree::similarity::run(data, out),
        hal::NAME => hal::run(data, out),
        silhouette::NAME => silhouette::run(data, out),
        silhouette::timing::NAME => silhouette::timing::run(data, out),
        silhouette::plain::NAME => silhouette::plain::run(data, out),
        silhouette::temporal::NAME => silhouette::temporal::run(data, out),
        scene::NAME => scene::run(data, out),
        robot::NAME => robot::run(data, out),
        robot::budgets::NAME => robot::budgets::run(data, out),
        robot::morphit::NAME => robot::morphit::run(data, out),
        spheres_vs_count::NAME => spheres_vs_count::run(data, out),
        main_job::NAME => main_job::run(data, out),
        tolerance_trees::NAME => tolerance_trees::run(data, out),
        other => bail!("no experiment named `{other}`"),
    }
}

/// The shortest of `runs` timings of `f`, in seconds, with the last result.
pub(crate) fn min_time<T>(runs: usize, mut f: impl FnMut() -> Result<T>) -> Result<(f64, T)> {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..runs.max(1) {
        let started = std::time::Instant::now();
        let value = f()?;
        best = best.min(started.elapsed().as_secs_f64());
        last = Some(value);
    }
    match last {
        Some(value) => Ok((best, value)),
        None => bail!("no run"),
    }
}

/// The meshes of `files` found in `data`, each with its file name; the missing ones
/// skipped with a message ([`load_or_skip`]).
pub(crate) fn load_all_or_skip(data: &Path, files: &[&str]) -> Result<Vec<(String, TriMesh)>> {
    let mut meshes = Vec::new();
    for file in files {
        if let Some(mesh) = load_or_skip(data, file)? {
            meshes.push(((*file).to_owned(), mesh));
        }
    }
    Ok(meshes)
}

/// Loads the mesh at `path`; the error names the file.
pub(crate) fn load_mesh(path: &Path) -> Result<TriMesh> {
    io::load(path).with_context(|| format!("cannot load {}", path.display()))
}

/// Loads `file` of the folder `data`, or says on the terminal that it is not there and
/// returns `None`: an experiment skips the meshes it cannot find.
pub(crate) fn load_or_skip(data: &Path, file: &str) -> Result<Option<TriMesh>> {
    let path = data.join(file);
    if !path.is_file() {
        eprintln!("{file}: not in {}, skipped", data.display());
        return Ok(None);
    }
    load_mesh(&path).map(Some)
}
