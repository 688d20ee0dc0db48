//! Simplification: measured error against time, Sphaera (each placement) and meshopt in the
//! same run, on the 69k-triangle bunny and the 871k-triangle dragon; and Sphaera's reported
//! bound against the measured error.
//!
//! For each mesh, ratio and method: the triangles reached, the time (minimum of a few runs;
//! the input conversion for meshopt is not timed), the symmetric Hausdorff distance between
//! input and output measured by [`reference_hausdorff`] (parry3d-f64 projections from every
//! vertex, every edge midpoint and [`HAUSDORFF_SAMPLES`] random points per mesh, then a
//! local refinement; a lower bound of the true distance), and for Sphaera its certified
//! bound. Distances are relative to the input's bounding-box diagonal. The methods and
//! their options are in [`crate::methods`].
//!
//! `MeshLab`'s quadric edge collapse is there too, from its own output: `shared/data` holds
//! the bunny simplified by `MeshLab` to 15 % ([`MESHLAB`]), measured the same way. Its time
//! is unknown (it was not run here), so it appears only in the third panel, measured error
//! against triangles kept, where every method is.
//!
//! By design this chart covers only [`MESHES`], not every mesh of `shared/data`; `cargo
//! xtask charts --check` checks it covers exactly those.

use std::path::Path;

use anyhow::Result;
use sphaera::mesh::TriMesh;
use sphaera_tests::reference_hausdorff;

use super::{load_or_skip, min_time};
use crate::chart::{ChartSpec, Panel, Series, SeriesLabelPosition, log_log_panels, write_csv};
use crate::methods::{
    MeshoptInput, PLACEMENTS, meshopt_surface, sphaera_simplify, target_triangles,
};

/// The experiment's name: its files are `simplify_error_vs_time.{svg,csv}`.
pub const NAME: &str = "simplify_error_vs_time";

/// The meshes: file in `shared/data`, label, timing runs and target triangle counts as
/// fractions of the input's (fewer runs and ratios for the dragon, whose simplification
/// takes minutes while Sphaera is slow; the generation stays under about 10 minutes).
pub const MESHES: &[(&str, &str, usize, &[f64])] = &[
    (
        "stanford-bunny.obj",
        "bunny 69k",
        3,
        &[0.5, 0.2, 0.1, 0.05, 0.02],
    ),
    ("dragon_vrip.ply", "dragon 871k", 1, &[0.5, 0.1, 0.02]),
];

/// `MeshLab`'s quadric edge collapse of a mesh of [`MESHES`]: the input, and `MeshLab`'s
/// output in `shared/data`.
pub const MESHLAB: (&str, &str) = ("stanford-bunny.obj", "stanford-bunny-qem15.obj");

/// The method name of [`MESHLAB`]'s rows.
const MESHLAB_METHOD: &str = "meshlab quadric";

/// Random points per mesh for the measured distance (on top of every vertex and edge
/// midpoint): enough for the value to be stable to about 1 % (the refinement around the
/// best samples does the rest).
pub const HAUSDORFF_SAMPLES: usize = 50_000;

/// One measured point.
struct Row {
    file: &'static str,
    method: String,
    ratio: f64,
    triangles_in: usize,
    target: usize,
    triangles_out: usize,
    /// `None` for an output made elsewhere ([`MESHLAB`]).
    seconds: Option<f64>,
    measured: f64,
    bound: Option<f64>,
}

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    for &(file, label, runs, ratios) in MESHES {
        let Some(mesh) = load_or_skip(data, file)? else {
            continue;
        };
        measure_mesh(file, label, (runs, ratios), &mesh, &mut rows)?;
        if file == MESHLAB.0
            && let Some(meshlab) = load_or_skip(data, MESHLAB.1)?
        {
            let measured = reference_hausdorff(&mesh, &meshlab, HAUSDORFF_SAMPLES, 0).symmetric();
            rows.push(Row {
                file,
                method: MESHLAB_METHOD.to_owned(),
                ratio: meshlab.triangle_count() as f64 / mesh.triangle_count() as f64,
                triangles_in: mesh.triangle_count(),
                target: meshlab.triangle_count(),
                triangles_out: meshlab.triangle_count(),
                seconds: None,
                measured: measured / mesh.bounding_box_diagonal(),
                bound: None,
            });
            report(label, rows.last());
        }
    }
    write_table(out, &rows)?;
    draw(out, &rows)
}

/// Every method at every ratio on one mesh.
fn measure_mesh(
    file: &'static str,
    label: &str,
    (runs, ratios): (usize, &[f64]),
    mesh: &TriMesh,
    rows: &mut Vec<Row>,
) -> Result<()> {
    let diagonal = mesh.bounding_box_diagonal();
    let meshopt = MeshoptInput::new(mesh);
    for &ratio in ratios {
        let target = target_triangles(mesh, ratio);
        for &(name, placement) in PLACEMENTS {
            let (seconds, out) = min_time(runs, || sphaera_simplify(mesh, placement, target))?;
            let measured = reference_hausdorff(mesh, &out.mesh, HAUSDORFF_SAMPLES, 0).symmetric();
            rows.push(Row {
                file,
                method: format!("sphaera {name}"),
                ratio,
                triangles_in: mesh.triangle_count(),
                target,
                triangles_out: out.mesh.triangle_count(),
                seconds: Some(seconds),
                measured: measured / diagonal,
                bound: Some(out.error_bound / diagonal),
            });
            report(label, rows.last());
        }
        let (seconds, indices) = min_time(runs, || meshopt.simplify(target))?;
        let surface = meshopt_surface(mesh, &indices)?;
        let measured = reference_hausdorff(mesh, &surface, HAUSDORFF_SAMPLES, 0).symmetric();
        rows.push(Row {
            file,
            method: "meshopt".to_owned(),
            ratio,
            triangles_in: mesh.triangle_count(),
            target,
            triangles_out: surface.triangle_count(),
            seconds: Some(seconds),
            measured: measured / diagonal,
            bound: None,
        });
        report(label, rows.last());
    }
    Ok(())
}

fn report(label: &str, row: Option<&Row>) {
    if let Some(r) = row {
        eprintln!(
            "{label:<12} {:<16} ratio {:<5.3} {:>7} triangles  {:>8} s  measured {:.4} %  bound {}",
            r.method,
            r.ratio,
            r.triangles_out,
            r.seconds
                .map_or_else(|| "-".to_owned(), |t| format!("{t:.4}")),
            100.0 * r.measured,
            r.bound
                .map_or_else(|| "-".to_owned(), |b| format!("{:.4} %", 100.0 * b))
        );
    }
}

fn write_table(out: &Path, rows: &[Row]) -> Result<()> {
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.file.to_owned(),
                r.method.replace(' ', "_"),
                format!("{}", r.ratio),
                r.triangles_in.to_string(),
                r.target.to_string(),
                r.triangles_out.to_string(),
                r.seconds.map_or_else(String::new, |t| format!("{t:.6}")),
                format!("{:.6e}", r.measured),
                r.bound.map_or_else(String::new, |b| format!("{b:.6e}")),
            ]
        })
        .collect();
    write_csv(
        &out.join(format!("{NAME}.csv")),
        &[
            "file",
            "method",
            "ratio",
            "triangles_in",
            "target_triangles",
            "triangles_out",
            "seconds",
            "measured_hausdorff_relative",
            "bound_relative",
        ],
        &table,
    )
}

/// Left: measured error against time, one series per method and mesh. Middle: Sphaera's
/// bound against the measured error, with `y = x` (every point must lie above it). Right:
/// measured error against triangles kept, `MeshLab`'s output included.
fn draw(out: &Path, rows: &[Row]) -> Result<()> {
    let mut methods: Vec<String> = PLACEMENTS
        .iter()
        .map(|(name, _)| format!("sphaera {name}"))
        .collect();
    methods.push("meshopt".to_owned());
    methods.push(MESHLAB_METHOD.to_owned());
    let mut time_series = Vec::new();
    let mut bound_series = Vec::new();
    let mut size_series = Vec::new();
    for &(file, label, _, _) in MESHES {
        for method in &methods {
            let of = || {
                rows.iter()
                    .filter(|r| r.file == file && &r.method == method)
            };
            if !of().any(|_| true) {
                continue;
            }
            let mut time = Series::new(&format!("{method}, {label}"));
            time.points = of()
                .filter_map(|r| r.seconds.map(|t| (t, r.measured)))
                .collect();
            let mut size = Series::new(&format!("{method}, {label}"));
            size.points = of().map(|r| (r.triangles_out as f64, r.measured)).collect();
            let mut bound = Series::new(&format!("{method}, {label}"));
            bound.points = of()
                .filter_map(|r| r.bound.map(|b| (r.measured, b)))
                .collect();
            // meshopt and `MeshLab` have no bound (and `MeshLab` no time): their series stay
            // in the lists, empty (not drawn), so that every series keeps its colour in
            // every panel.
            time_series.push(time);
            bound_series.push(bound);
            size_series.push(size);
        }
    }
    let runs = MESHES
        .iter()
        .map(|(_, label, runs, _)| format!("{runs} for the {label}"))
        .collect::<Vec<_>>()
        .join(", ");
    let time_label = format!("seconds (best of {runs} runs)");
    log_log_panels(
        &out.join(format!("{NAME}.svg")),
        &[
            Panel {
                spec: ChartSpec {
                    title: "Simplification: measured error against time",
                    x_label: &time_label,
                    y_label: "measured Hausdorff distance / diagonal",
                },
                series: &time_series,
                diagonal: false,
                legend: SeriesLabelPosition::LowerLeft,
            },
            Panel {
                spec: ChartSpec {
                    title: "Sphaera: certified bound against measured error",
                    x_label: "measured Hausdorff distance / diagonal",
                    y_label: "reported bound / diagonal",
                },
                series: &bound_series,
                diagonal: true,
                legend: SeriesLabelPosition::LowerRight,
            },
            Panel {
                spec: ChartSpec {
                    title: "Measured error against triangles kept",
                    x_label: "triangles",
                    y_label: "measured Hausdorff distance / diagonal",
                },
                series: &size_series,
                diagonal: false,
                legend: SeriesLabelPosition::LowerLeft,
            },
        ],
    )
}
