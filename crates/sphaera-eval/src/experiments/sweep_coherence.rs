//! `sweep_speedup_vs_step`: how coherence pays as the query point's step shrinks.
//!
//! For each mesh of [`MESHES`] and each step length of [`STEPS`] (relative to the
//! diagonal), [`QUERIES`] points walk the `path` curve of [`crate::query_sets`] (a wavy
//! ellipse at 0.9× the half-extents, inside and outside the surface) with every step that
//! long, in [`SEGMENTS`] pieces starting at evenly spaced places of the curve (so that
//! every step length samples the same places, not one spot for the small steps). Timed on one thread, the minimum of [`RUNS`] runs:
//!
//! - **tree cursor**: one [`TriangleTree::cursor`] answering the points in order (the
//!   fan of the previous answer first, then a descent seeded by it);
//! - **triangle tree**: independent [`TriangleTree::closest`] queries;
//! - **Meshsweeper session**: one session answering the paper's way
//!   ([`SessionOptions::with_exact_by_tree`]`(false)`), the paper's coherent method;
//! - **parry3d-f64**: independent point projections ([`DistanceToMesh`]).
//!
//! The chart plots each method's speed relative to parry's against the step; the CSV has
//! the cursor's share of constant-time answers.

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::{
    mesh::{DVec3, TriMesh, closest::TriangleTree},
    sweep::{SessionOptions, Sweeper, build_hierarchy},
};
use sphaera_tests::hausdorff::DistanceToMesh;

use super::{load_or_skip, min_time};
use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};

/// The experiment's name.
pub const NAME: &str = "sweep_speedup_vs_step";

/// The meshes.
pub const MESHES: &[&str] = &["stanford-bunny.obj", "dragon_vrip_res2.ply"];

/// Step lengths, relative to the bounding-box diagonal.
pub const STEPS: &[f64] = &[1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1];

/// Points per path.
pub const QUERIES: usize = 2_000;

/// Pieces of each path.
pub const SEGMENTS: usize = 20;

/// Timing runs (the minimum is kept).
pub const RUNS: usize = 5;

/// The methods, in chart order.
const METHODS: [&str; 3] = ["tree_cursor", "triangle_tree", "meshsweeper_session"];

/// Runs the experiment.
pub fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    let mut panels_data = Vec::new();
    for file in MESHES {
        let Some(mesh) = load_or_skip(data, file)? else {
            continue;
        };
        let tree = TriangleTree::new(&mesh)?;
        let hierarchy = build_hierarchy(&mesh).context("cannot build the hierarchy")?;
        let sweeper = Sweeper::new(&hierarchy)?;
        let parry = DistanceToMesh::new(&mesh);
        let mut series: Vec<Series> = METHODS
            .iter()
            .map(|m| Series::new(&m.replace('_', " ")))
            .collect();
        for &step in STEPS {
            let points = path(&mesh, step, QUERIES);
            let (parry_s, parry_sum) = min_time(RUNS, || {
                Ok(points.iter().map(|&p| parry.distance(p)).sum::<f64>())
            })?;
            let (cursor_s, (cursor_sum, shortcuts)) = min_time(RUNS, || {
                let mut cursor = tree.cursor();
                let sum = points.iter().try_fold(0.0, |sum, &p| {
                    Ok::<f64, anyhow::Error>(sum + cursor.closest(p)?.distance)
                })?;
                Ok((sum, cursor.shortcuts()))
            })?;
            let (tree_s, tree_sum) = min_time(RUNS, || {
                points.iter().try_fold(0.0, |sum, &p| {
                    Ok::<f64, anyhow::Error>(sum + tree.closest(p)?.distance)
                })
            })?;
            let (session_s, session_sum) = min_time(RUNS.min(2), || {
                let mut session =
                    sweeper.session_with(&SessionOptions::default().with_exact_by_tree(false));
                points.iter().try_fold(0.0, |sum, &p| {
                    Ok::<f64, anyhow::Error>(sum + session.closest(p)?.distance)
                })
            })?;
            for ours in [cursor_sum, tree_sum, session_sum] {
                let relative = (ours - parry_sum).abs() / parry_sum.max(f64::MIN_POSITIVE);
                anyhow::ensure!(relative < 1e-9, "{file}, step {step}: answers disagree");
            }
            let shortcut_share = shortcuts as f64 / points.len() as f64;
            eprintln!(
                "{file}, step {step:.0e}: cursor {:.2}× parry ({:.0} % constant time), tree {:.2}×, session {:.2}×",
                parry_s / cursor_s,
                100.0 * shortcut_share,
                parry_s / tree_s,
                parry_s / session_s
            );
            for (s, seconds) in series.iter_mut().zip([cursor_s, tree_s, session_s]) {
                s.points.push((step, parry_s / seconds));
            }
            for (method, seconds) in METHODS.iter().zip([cursor_s, tree_s, session_s]) {
                rows.push(vec![
                    (*file).to_owned(),
                    format!("{step:e}"),
                    (*method).to_owned(),
                    points.len().to_string(),
                    format!("{seconds:.6}"),
                    format!("{:.4}", parry_s / seconds),
                    if *method == "tree_cursor" {
                        format!("{shortcut_share:.4}")
                    } else {
                        String::new()
                    },
                ]);
            }
        }
        panels_data.push(((*file).to_owned(), series));
    }
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "mesh",
            "step_rel_diagonal",
            "method",
            "queries",
            "seconds",
            "speed_relative_to_parry",
            "constant_time_share",
        ],
        &rows,
    )?;
    let panels: Vec<Panel<'_>> = panels_data
        .iter()
        .map(|(title, series)| Panel {
            spec: ChartSpec {
                title,
                x_label: "step of the query point (fraction of the diagonal)",
                y_label: "speed relative to parry3d (one thread)",
            },
            series,
            diagonal: false,
            legend: SeriesLabelPosition::LowerLeft,
        })
        .collect();
    log_log_panels(&out.join(format!("{NAME}.svg")), &panels)
}

/// `n` points on the wavy ellipse of the `path` query set in [`SEGMENTS`] pieces, each
/// point `step` diagonals from the last of its piece (the angle advanced by the step over
/// the curve's local speed).
fn path(mesh: &TriMesh, step: f64, n: usize) -> Vec<DVec3> {
    let bounds = mesh.bounding_box();
    let center = 0.5 * (bounds.min + bounds.max);
    let half = 0.9 * 0.5 * (bounds.max - bounds.min);
    let length = step * mesh.bounding_box_diagonal();
    let at = |a: f64| center + half * DVec3::new(a.cos(), a.sin(), 0.5 * (3.0 * a).sin());
    let speed = |a: f64| (half * DVec3::new(-a.sin(), a.cos(), 1.5 * (3.0 * a).cos())).length();
    let per_piece = n.div_ceil(SEGMENTS);
    let mut points = Vec::with_capacity(n);
    for piece in 0..SEGMENTS {
        let mut a = std::f64::consts::TAU * piece as f64 / SEGMENTS as f64;
        for _ in 0..per_piece.min(n - points.len()) {
            points.push(at(a));
            a += length / speed(a).max(f64::MIN_POSITIVE);
        }
    }
    points
}
