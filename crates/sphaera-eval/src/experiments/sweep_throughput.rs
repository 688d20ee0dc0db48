//! Closest-point throughput against mesh size: Sphaera's Meshsweeper sessions, parry3d-f64
//! and brute force, in the same run, on a ladder of meshes from 3.7k to 871k triangles.
//!
//! For each mesh of [`MESHES`] and each query set of [`crate::query_sets`] (`uniform` in
//! the 1.5× box, `near` the surface, a smooth `path`), queries per second on one thread:
//!
//! - **triangle tree**: Sphaera's exact engine for independent queries
//!   ([`TriangleTree::closest`]); its build is not timed (its time is in the CSV);
//! - **tree cursor**: the same tree answering the points in order through one
//!   [`TriangleTree::cursor`] (coherent on the `path` set);
//! - **tree anytime 1 %**: a default session's certified intervals at most 1 % of the
//!   diagonal wide ([`Session::closest_within`](sphaera::sweep::Session::closest_within),
//!   the documented entry point: the tree through the session's cursor,
//!   [`TreeCursor::closest_approx`](sphaera::sweep::TreeCursor::closest_approx), seeded by
//!   the previous answer);
//! - **Meshsweeper session**: one session per query set answering the paper's way
//!   ([`SessionOptions::with_exact_by_tree`]`(false)`), the points in order (so the
//!   `path` set is coherent); the session's creation is timed, the hierarchy build
//!   ([`build_hierarchy`], which is parallel) is not (its time is in the CSV);
//! - **Meshsweeper anytime 1 %**: the same session's certified intervals at most 1 % of the
//!   diagonal wide ([`Session::closest_within`](sphaera::sweep::Session::closest_within),
//!   the paper's way);
//! - **parry3d-f64** 0.31: `TriMesh` point projection through [`DistanceToMesh`] (its BVH
//!   build is not timed; its time is in the CSV);
//! - **brute force** ([`BruteForce`]: every triangle for every query): timed on the first
//!   [`BRUTE_EVALUATIONS`]` / triangles` queries of each set only (at least 8), and
//!   reported per query (its cost hardly depends on the point); the CSV says how many
//!   queries were timed.
//!
//! Each timing is the minimum of the mesh's runs (at least [`PARRY_RUNS`] for parry). The number of queries per set shrinks
//! with the mesh so that the whole experiment stays within a few minutes.
//!
//! By design this chart covers only [`MESHES`]; `cargo xtask charts --check` checks it
//! covers exactly those.

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::{
    mesh::{DVec3, TriMesh, closest::TriangleTree},
    sweep::{SessionOptions, Sweeper, Tolerance, build_hierarchy},
};
use sphaera_tests::hausdorff::DistanceToMesh;

use super::{load_or_skip, min_time};
use crate::brute::BruteForce;
use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};
use crate::query_sets::{SET_NAMES, query_sets};

/// The experiment's name: its files are `sweep_throughput.{svg,csv}`.
pub const NAME: &str = "sweep_throughput";

/// The meshes, by triangle count: file in `shared/data`, queries per set, timing runs.
pub const MESHES: &[(&str, usize, usize)] = &[
    ("bunny_lowres.obj", 2_000, 3),
    ("dragon_vrip_res4.ply", 2_000, 3),
    ("dragon_vrip_res3.ply", 1_000, 2),
    ("stanford-bunny.obj", 1_000, 2),
    ("dragon_vrip_res2.ply", 500, 2),
    ("dragon_vrip.ply", 200, 1),
];

/// Point–triangle distances per brute-force timing (about half a second).
pub const BRUTE_EVALUATIONS: usize = 20_000_000;

/// parry answers a set in milliseconds: its timing is the minimum of at least this many
/// runs.
pub const PARRY_RUNS: usize = 5;

/// The methods, in chart order.
const METHODS: [&str; 7] = [
    "triangle_tree",
    "tree_cursor",
    "tree_anytime_1%",
    "meshsweeper_session",
    "meshsweeper_anytime_1%",
    "parry3d",
    "brute_force",
];

/// One measured point.
struct Row {
    file: &'static str,
    triangles: usize,
    set: &'static str,
    method: &'static str,
    queries: usize,
    seconds: f64,
    build_seconds: Option<f64>,
}

impl Row {
    fn queries_per_second(&self) -> f64 {
        self.queries as f64 / self.seconds
    }
}

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    for &(file, queries, runs) in MESHES {
        let Some(mesh) = load_or_skip(data, file)? else {
            continue;
        };
        measure_mesh(file, &mesh, (queries, runs), &mut rows)?;
    }
    write_table(out, &rows)?;
    draw(out, &rows)
}

/// Every method on every query set of one mesh.
fn measure_mesh(
    file: &'static str,
    mesh: &TriMesh,
    (queries, runs): (usize, usize),
    rows: &mut Vec<Row>,
) -> Result<()> {
    let (hierarchy_s, hierarchy) = min_time(1, || {
        build_hierarchy(mesh).context("cannot build the hierarchy")
    })?;
    let sweeper = Sweeper::new(&hierarchy)?;
    let (tree_s, tree) = min_time(1, || Ok(TriangleTree::new(mesh)?))?;
    let gap = 0.01 * mesh.bounding_box_diagonal();
    let tolerance = Tolerance::Absolute(gap);
    let paper = SessionOptions::default().with_exact_by_tree(false);
    let (bvh_s, parry) = min_time(1, || Ok(DistanceToMesh::new(mesh)))?;
    let brute = BruteForce::new(mesh);
    let brute_queries = (BRUTE_EVALUATIONS / mesh.triangle_count().max(1)).clamp(8, queries);
    let triangles = mesh.triangle_count();
    for (set, points) in query_sets(mesh, queries)? {
        let (sphaera_s, sphaera_sum) = min_time(runs, || {
            let mut session = sweeper.session_with(&paper);
            points.iter().try_fold(0.0, |sum, &p| {
                Ok::<f64, anyhow::Error>(sum + session.closest(p)?.distance)
            })
        })?;
        let (anytime_s, _) = min_time(runs, || {
            let mut session = sweeper.session_with(&paper);
            points.iter().try_fold(0.0, |sum, &p| {
                Ok::<f64, anyhow::Error>(sum + session.closest_within(p, tolerance)?.upper)
            })
        })?;
        let (tree_q, tree_sum) = min_time(runs.max(PARRY_RUNS), || {
            points.iter().try_fold(0.0, |sum, &p| {
                Ok::<f64, anyhow::Error>(sum + tree.closest(p)?.distance)
            })
        })?;
        let (tree_anytime_s, _) = min_time(runs.max(PARRY_RUNS), || {
            let mut session = sweeper.session();
            points.iter().try_fold(0.0, |sum, &p| {
                Ok::<f64, anyhow::Error>(sum + session.closest_within(p, tolerance)?.upper)
            })
        })?;
        let (cursor_s, cursor_sum) = min_time(runs.max(PARRY_RUNS), || {
            let mut cursor = tree.cursor();
            points.iter().try_fold(0.0, |sum, &p| {
                Ok::<f64, anyhow::Error>(sum + cursor.closest(p)?.distance)
            })
        })?;
        let (parry_s, parry_sum) = min_time(runs.max(PARRY_RUNS), || {
            Ok(sum_of(&points, |p| parry.distance(p)))
        })?;
        let subset = &points[..brute_queries.min(points.len())];
        let (brute_s, _) = min_time(runs, || Ok(sum_of(subset, |p| brute.distance(p))))?;
        // Both answer exact distances: a mismatch would make the comparison meaningless.
        for ours in [sphaera_sum, tree_sum, cursor_sum] {
            let relative = (ours - parry_sum).abs() / parry_sum.max(f64::MIN_POSITIVE);
            anyhow::ensure!(
                relative < 1e-6,
                "{file} {set}: Sphaera and parry disagree ({ours} vs {parry_sum})"
            );
        }
        for (method, queries, seconds, build_seconds) in [
            ("triangle_tree", points.len(), tree_q, Some(tree_s)),
            ("tree_cursor", points.len(), cursor_s, Some(tree_s)),
            (
                "tree_anytime_1%",
                points.len(),
                tree_anytime_s,
                Some(tree_s),
            ),
            (
                "meshsweeper_session",
                points.len(),
                sphaera_s,
                Some(hierarchy_s),
            ),
            (
                "meshsweeper_anytime_1%",
                points.len(),
                anytime_s,
                Some(hierarchy_s),
            ),
            ("parry3d", points.len(), parry_s, Some(bvh_s)),
            ("brute_force", subset.len(), brute_s, None),
        ] {
            rows.push(Row {
                file,
                triangles,
                set,
                method,
                queries,
                seconds,
                build_seconds,
            });
            report(rows.last());
        }
    }
    Ok(())
}

fn sum_of(points: &[DVec3], distance: impl Fn(DVec3) -> f64) -> f64 {
    points.iter().map(|&p| distance(p)).sum()
}

fn report(row: Option<&Row>) {
    if let Some(r) = row {
        eprintln!(
            "{:<22} {:>7} triangles  {:<8} {:<12} {:>5} queries  {:>9.4} s  {:>10.0} q/s",
            r.file,
            r.triangles,
            r.set,
            r.method,
            r.queries,
            r.seconds,
            r.queries_per_second()
        );
    }
}

fn write_table(out: &Path, rows: &[Row]) -> Result<()> {
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.file.to_owned(),
                r.triangles.to_string(),
                r.set.to_owned(),
                r.method.to_owned(),
                r.queries.to_string(),
                format!("{:.6}", r.seconds),
                format!("{:.1}", r.queries_per_second()),
                r.build_seconds
                    .map_or_else(String::new, |s| format!("{s:.6}")),
            ]
        })
        .collect();
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "file",
            "triangles",
            "query_set",
            "method",
            "queries_timed",
            "seconds",
            "queries_per_second",
            "build_seconds",
        ],
        &table,
    )
}

/// One panel per query set: queries per second against triangles, one series per method.
fn draw(out: &Path, rows: &[Row]) -> Result<()> {
    let series: Vec<Vec<Series>> = SET_NAMES
        .iter()
        .map(|&set| {
            METHODS
                .iter()
                .map(|&method| {
                    let mut s = Series::new(&method.replace('_', " "));
                    s.points = rows
                        .iter()
                        .filter(|r| r.set == set && r.method == method)
                        .map(|r| (r.triangles as f64, r.queries_per_second()))
                        .collect();
                    s
                })
                .collect()
        })
        .collect();
    let titles = [
        "uniform in the 1.5× box",
        "near the surface (≤ 1 % of the diagonal)",
        "smooth path (coherent)",
    ];
    let panels: Vec<Panel<'_>> = series
        .iter()
        .zip(titles)
        .map(|(series, title)| Panel {
            spec: ChartSpec {
                title,
                x_label: "triangles",
                y_label: "queries per second (one thread)",
            },
            series,
            diagonal: false,
            legend: SeriesLabelPosition::LowerLeft,
        })
        .collect();
    log_log_panels(&out.join(format!("{NAME}.svg")), &panels)
}
