//! Certified Hausdorff distance: the gap `upper − lower` against time, over a ladder of
//! tolerances, with the paper's naive alternative beside it.
//!
//! Two pairs of meshes ([`PAIRS`]): the 69k-triangle bunny against its 15 % quadric
//! simplification made by `MeshLab` (`stanford-bunny-qem15.obj`), and the 3.7k-triangle
//! `bunny_lowres.obj` against Sphaera's own 15 % simplification of it
//! (`simplify(&m, &SimplifyOptions::default().with_target_ratio(0.15))`, defaults
//! otherwise).
//!
//! - **Sphaera** (`sphaera`): `hausdorff(&a, &b, &HausdorffOptions::default().with_tolerance(Length::RelativeToDiagonal(t)))`
//!   for each `t` of [`TOLERANCES`] (relative to the bounding-box diagonal of both meshes
//!   together), from the meshes: **all told**, the triangle trees built inside the
//!   timing, on both cores. Time: minimum of [`RUNS`] runs.
//! - **Meshsweeper** (`meshsweeper`): the paper's engine, `meshsweeper_hausdorff`, one
//!   thread; the hierarchies and sweepers are built once per pair, **outside** the timing
//!   (their build time, which is parallel, is in the CSV as `build_seconds`).
//! - **cascading-upper-bounds** (`cascading_upper_bounds`), the peer, through its Python
//!   package (`peers/cub_hausdorff.py`, both directions, loading excluded) at the
//!   tolerances of [`PEER_TOLERANCES`], when `$SPHAERA_CUB_PYTHON` (else `python3`) can
//!   import it; skipped with a message otherwise.
//! - **Naive** (paper section 6): every referenced vertex of each mesh against every
//!   triangle of the other, by brute force on one thread ([`naive_hausdorff`]), timed once.
//!   Its value is only a **lower bound** of the distance: it certifies nothing, so it has
//!   no gap and appears only on the right panel.
//!
//! Distances and gaps are relative to the joint diagonal. By design this chart covers only
//! the first meshes of [`PAIRS`]; `cargo xtask charts --check` checks them.

use std::path::Path;

use anyhow::{Context, Result, bail};
use sphaera::{
    mesh::{Length, TriMesh, io},
    simplify::{SimplifyOptions, simplify},
    sweep::{HausdorffOptions, Sweeper, build_hierarchy, hausdorff, meshsweeper_hausdorff},
};

use super::{load_mesh, load_or_skip, min_time};
use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};
use crate::{
    brute::naive_hausdorff,
    peers::{CubRun, cub_python, run_cub},
};

/// The experiment's name: its files are `hausdorff_gap_vs_time.{svg,csv}`.
pub const NAME: &str = "hausdorff_gap_vs_time";

/// The pairs: first mesh (file in `shared/data`), label, second mesh (a file in
/// `shared/data`, or `None` for Sphaera's 15 % simplification of the first).
pub const PAIRS: &[(&str, &str, Option<&str>)] = &[
    (
        "stanford-bunny.obj",
        "bunny 69k vs MeshLab 15 %",
        Some("stanford-bunny-qem15.obj"),
    ),
    ("bunny_lowres.obj", "bunny 3.7k vs Sphaera 15 %", None),
];

/// The tolerances, relative to the joint diagonal.
pub const TOLERANCES: &[f64] = &[1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6];

/// The tolerances the peer runs at (its time grows fast below 1e-5).
pub const PEER_TOLERANCES: &[f64] = &[1e-3, 1e-4, 1e-5];

/// Timing runs per tolerance (the minimum is kept).
pub const RUNS: usize = 3;

/// Name of Sphaera's simplification in the CSV's `other` column.
const SIMPLIFIED: &str = "sphaera_target_ratio_0.15";

/// One measured point.
struct Row {
    file: &'static str,
    other: String,
    method: &'static str,
    tolerance: Option<f64>,
    seconds: f64,
    build_seconds: Option<f64>,
    lower: f64,
    upper: Option<f64>,
    samples: usize,
    converged: bool,
}

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    let python = cub_python(NAME);
    for &(file, label, other) in PAIRS {
        let Some(a) = load_or_skip(data, file)? else {
            continue;
        };
        let (b, other) = match other {
            Some(name) => (load_mesh(&data.join(name))?, name.to_owned()),
            None => {
                let simplified = simplify(&a, &SimplifyOptions::default().with_target_ratio(0.15))
                    .context("cannot simplify")?;
                (simplified.mesh, SIMPLIFIED.to_owned())
            }
        };
        eprintln!(
            "{label}: {} vs {} triangles",
            a.triangle_count(),
            b.triangle_count()
        );
        measure_pair(file, &other, (&a, &b), &mut rows)?;
        if let Some(python) = &python {
            measure_peer(python, file, &other, (&a, &b), &mut rows)?;
        }
    }
    write_table(out, &rows)?;
    draw(out, &rows)
}

/// The tolerance ladder and the naive estimate on one pair.
fn measure_pair(
    file: &'static str,
    other: &str,
    (a, b): (&TriMesh, &TriMesh),
    rows: &mut Vec<Row>,
) -> Result<()> {
    let diagonal = a.bounding_box().union(b.bounding_box()).diagonal();
    let (build_seconds, (ha, hb)) = min_time(1, || {
        Ok((
            build_hierarchy(a).context("cannot build a hierarchy")?,
            build_hierarchy(b).context("cannot build a hierarchy")?,
        ))
    })?;
    let (sa, sb) = (Sweeper::new(&ha)?, Sweeper::new(&hb)?);
    for &tolerance in TOLERANCES {
        let options =
            HausdorffOptions::default().with_tolerance(Length::RelativeToDiagonal(tolerance));
        let (seconds, result) = min_time(RUNS, || Ok(hausdorff(a, b, &options)?))?;
        let samples = result.a_to_b.samples + result.b_to_a.as_ref().map_or(0, |s| s.samples);
        rows.push(Row {
            file,
            other: other.to_owned(),
            method: "sphaera",
            tolerance: Some(tolerance),
            seconds,
            build_seconds: None,
            lower: result.lower / diagonal,
            upper: Some(result.upper / diagonal),
            samples,
            converged: result.converged,
        });
        report(rows.last());
        let (seconds, result) = min_time(RUNS, || Ok(meshsweeper_hausdorff(&sa, &sb, &options)?))?;
        let samples = result.a_to_b.samples + result.b_to_a.as_ref().map_or(0, |s| s.samples);
        rows.push(Row {
            file,
            other: other.to_owned(),
            method: "meshsweeper",
            tolerance: Some(tolerance),
            seconds,
            build_seconds: Some(build_seconds),
            lower: result.lower / diagonal,
            upper: Some(result.upper / diagonal),
            samples,
            converged: result.converged,
        });
        report(rows.last());
    }
    let (seconds, naive) = min_time(1, || Ok(naive_hausdorff(a, b, 1)?))?;
    rows.push(Row {
        file,
        other: other.to_owned(),
        method: "naive",
        tolerance: None,
        seconds,
        build_seconds: None,
        lower: naive.value / diagonal,
        upper: None,
        samples: naive.samples,
        converged: false,
    });
    report(rows.last());
    Ok(())
}

/// The peer at [`PEER_TOLERANCES`] (meshes written to temporary OBJ files, without the
/// vertices no triangle uses).
fn measure_peer(
    python: &Path,
    file: &'static str,
    other: &str,
    (a, b): (&TriMesh, &TriMesh),
    rows: &mut Vec<Row>,
) -> Result<()> {
    let folder = std::env::temp_dir().join(format!("sphaera-cub-{}", std::process::id()));
    std::fs::create_dir_all(&folder)?;
    let (path_a, path_b) = (folder.join("a.obj"), folder.join("b.obj"));
    io::write_obj(&path_a, a)?;
    io::write_obj(&path_b, b)?;
    for &tolerance in PEER_TOLERANCES {
        let runs = run_cub(python, &path_a, &path_b, tolerance, RUNS as u64)?;
        let diagonal = a.bounding_box().union(b.bounding_box()).diagonal();
        let best = runs.iter().min_by(|x, y| x.seconds.total_cmp(&y.seconds));
        let Some(&CubRun {
            seconds,
            lower,
            upper,
        }) = best
        else {
            bail!("cub_hausdorff.py printed no run");
        };
        rows.push(Row {
            file,
            other: other.to_owned(),
            method: "cascading_upper_bounds",
            tolerance: Some(tolerance),
            seconds,
            build_seconds: None,
            lower: lower / diagonal,
            upper: Some(upper / diagonal),
            samples: 0,
            converged: true,
        });
        report(rows.last());
    }
    std::fs::remove_dir_all(&folder).ok();
    Ok(())
}

fn report(row: Option<&Row>) {
    if let Some(r) = row {
        eprintln!(
            "  {:<8} tolerance {:<6} {:>9.4} s  lower {:.6} %  upper {}  gap {}  {} samples{}",
            r.method,
            r.tolerance
                .map_or_else(|| "-".to_owned(), |t| format!("{t:e}")),
            r.seconds,
            100.0 * r.lower,
            r.upper
                .map_or_else(|| "-".to_owned(), |u| format!("{:.6} %", 100.0 * u)),
            r.upper
                .map_or_else(|| "-".to_owned(), |u| format!("{:.2e}", u - r.lower)),
            r.samples,
            if r.converged || r.upper.is_none() {
                ""
            } else {
                " (sample budget ran out)"
            },
        );
    }
}

fn write_table(out: &Path, rows: &[Row]) -> Result<()> {
    let optional = |v: Option<f64>| v.map_or_else(String::new, |v| format!("{v:.6e}"));
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.file.to_owned(),
                r.other.clone(),
                r.method.to_owned(),
                optional(r.tolerance),
                format!("{:.6}", r.seconds),
                r.build_seconds
                    .map_or_else(String::new, |s| format!("{s:.6}")),
                format!("{:.8e}", r.lower),
                r.upper.map_or_else(String::new, |u| format!("{u:.8e}")),
                optional(r.upper.map(|u| u - r.lower)),
                r.samples.to_string(),
                r.converged.to_string(),
            ]
        })
        .collect();
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "file",
            "other",
            "method",
            "tolerance_relative",
            "seconds",
            "build_seconds",
            "lower_relative",
            "upper_relative",
            "gap_relative",
            "samples",
            "converged",
        ],
        &table,
    )
}

/// Left: the certified gap against time, one series per pair. Right: the bounds against
/// time, and the naive value (a lower bound only). A pair keeps its colours in both panels.
fn draw(out: &Path, rows: &[Row]) -> Result<()> {
    let mut gaps = Vec::new();
    let mut bounds = Vec::new();
    for &(file, label, _) in PAIRS {
        let method = |m: &'static str| rows.iter().filter(move |r| r.file == file && r.method == m);
        let gap_of = |m: &'static str, name: &str| {
            let mut series = Series::new(&format!("{name}, {label}"));
            series.points = method(m)
                .filter_map(|r| r.upper.map(|u| (r.seconds, u - r.lower)))
                .collect();
            series
        };
        let mut upper = Series::new(&format!("Sphaera upper, {label}"));
        upper.points = method("sphaera")
            .filter_map(|r| r.upper.map(|u| (r.seconds, u)))
            .collect();
        let mut lower = Series::new(&format!("Sphaera lower, {label}"));
        lower.points = method("sphaera").map(|r| (r.seconds, r.lower)).collect();
        let mut naive = Series::new(&format!("naive (lower bound only), {label}"));
        naive.points = method("naive").map(|r| (r.seconds, r.lower)).collect();
        gaps.extend([
            gap_of("sphaera", "Sphaera"),
            gap_of("meshsweeper", "Meshsweeper (paper)"),
            gap_of("cascading_upper_bounds", "cascading-upper-bounds"),
        ]);
        bounds.extend([upper, lower, naive]);
    }
    log_log_panels(
        &out.join(format!("{NAME}.svg")),
        &[
            Panel {
                spec: ChartSpec {
                    title: "Certified Hausdorff gap against time",
                    x_label: &format!(
                        "seconds (best of {RUNS}; Sphaera all told on 2 cores, Meshsweeper's hierarchies not timed)"
                    ),
                    y_label: "upper − lower, / joint diagonal",
                },
                series: &gaps,
                diagonal: false,
                legend: SeriesLabelPosition::UpperRight,
            },
            Panel {
                spec: ChartSpec {
                    title: "Bounds against time, and the naive all-pairs estimate",
                    x_label: "seconds (Sphaera all told on 2 cores; naive one thread)",
                    y_label: "symmetric Hausdorff distance / joint diagonal",
                },
                series: &bounds,
                diagonal: false,
                legend: SeriesLabelPosition::UpperRight,
            },
        ],
    )
}
