//! The files of `spheres_vs_count`: the CSV of every row and the three charts.

use std::path::Path;

use anyhow::Result;

use super::{MORPHIT_GROWN, MORPHIT_RAW, NAME, Row, SPHAERA, short_name};
use crate::chart::{
    ChartSpec, GridLegend, GridLine, GridPanel, LegendEntry, Marker, Series, Style, StyledPanel,
    StyledSeries, XAxis, line_grid, palette, titled_panels, write_csv,
};

/// The time chart's name.
const TIME: &str = "spheres_vs_count_time";

/// The uncovered-share chart's name.
const UNCOVERED: &str = "spheres_vs_count_uncovered";

/// The methods of the protrusion chart: CSV name, legend, colour, dashed.
const METHODS: [(&str, &str, usize, bool); 3] = [
    (SPHAERA, "Sphaera, one-level minimax tree", 0, false),
    (MORPHIT_GROWN, "morphit-rs grown to cover", 1, false),
    (MORPHIT_RAW, "morphit-rs raw (does not cover)", 3, true),
];

pub(super) fn write_outputs(out: &Path, rows: &[Row]) -> Result<()> {
    write_table(out, rows)?;
    let meshes = mesh_names(rows);
    protrusion_chart(out, rows, &meshes)?;
    time_chart(out, rows, &meshes)?;
    uncovered_chart(out, rows, &meshes)
}

/// The meshes in the order of the rows.
fn mesh_names(rows: &[Row]) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        if !names.contains(&r.mesh.as_str()) {
            names.push(&r.mesh);
        }
    }
    names
}

/// `spheres_vs_count.csv`: every row; the time and uncovered charts' CSVs: their columns.
fn write_table(out: &Path, rows: &[Row]) -> Result<()> {
    let header = [
        "mesh",
        "method",
        "requested",
        "spheres",
        "worst_lower_pct",
        "worst_upper_pct",
        "node_error_pct",
        "node_bound_pct",
        "uncovered_pct",
        "largest_gap_pct",
        "seconds",
        "runs",
        "uniform_growth_pct",
        "certify_growth_pct",
        "certify_grown_spheres",
        "protrusion_vs_grown",
        "time_vs_peer",
        "verdict",
        "diagonal",
    ];
    let optional =
        |v: Option<f64>, digits: usize| v.map_or_else(String::new, |v| format!("{v:.digits$}"));
    let lines: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            let pct = |v: f64| format!("{:.4}", 100.0 * v / r.diagonal);
            let pct_opt = |v: Option<f64>| v.map_or_else(String::new, pct);
            let verdict = r.verdict.as_ref();
            vec![
                r.mesh.clone(),
                r.method.to_owned(),
                r.requested.to_string(),
                r.fit.sphere_count.to_string(),
                pct(r.fit.worst_lower),
                pct(r.fit.worst_upper),
                pct_opt(r.node_bound.map(|b| b.0)),
                pct_opt(r.node_bound.map(|b| b.1)),
                format!("{:.3}", 100.0 * r.fit.coverage.uncovered_fraction),
                pct(r.fit.coverage.largest_gap),
                format!("{:.4}", r.seconds),
                r.runs.to_string(),
                pct_opt(r.growth.map(|g| g.0)),
                pct_opt(r.growth.map(|g| g.1.largest_growth)),
                r.growth
                    .map_or_else(String::new, |g| g.1.grown_spheres.to_string()),
                optional(verdict.and_then(|v| v.protrusion_ratio), 3),
                optional(verdict.and_then(|v| v.time_ratio), 3),
                verdict.map_or_else(String::new, super::Verdict::text),
                format!("{:.6}", r.diagonal),
            ]
        })
        .collect();
    write_csv(&out.join(format!("{NAME}.csv")), &header, &lines)?;

    let time: Vec<Vec<String>> = rows
        .iter()
        .filter(|r| r.method != MORPHIT_GROWN)
        .map(|r| {
            vec![
                r.mesh.clone(),
                r.method.to_owned(),
                r.requested.to_string(),
                r.fit.sphere_count.to_string(),
                format!("{:.4}", r.seconds),
                r.runs.to_string(),
            ]
        })
        .collect();
    write_csv(
        &out.join(format!("{TIME}.csv")),
        &["mesh", "method", "requested", "spheres", "seconds", "runs"],
        &time,
    )?;
    let uncovered: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.mesh.clone(),
                r.method.to_owned(),
                r.requested.to_string(),
                r.fit.sphere_count.to_string(),
                format!("{:.3}", 100.0 * r.fit.coverage.uncovered_fraction),
            ]
        })
        .collect();
    write_csv(
        &out.join(format!("{UNCOVERED}.csv")),
        &["mesh", "method", "requested", "spheres", "uncovered_pct"],
        &uncovered,
    )
}

/// The points `(requested, value)` of `method` on `mesh`.
fn points(rows: &[Row], mesh: &str, method: &str, value: impl Fn(&Row) -> f64) -> Vec<(f64, f64)> {
    rows.iter()
        .filter(|r| r.mesh == mesh && r.method == method)
        .map(|r| (r.requested as f64, value(r)))
        .collect()
}

/// A figure of [`grid`]: its file, title, y axis and the notes under its legend.
struct Figure<'a> {
    path: &'a Path,
    title: &'a str,
    y_label: &'a str,
    notes: &'a [&'a str],
}

/// A line-grid figure: one panel per mesh with a line per method of `methods`.
fn grid(
    figure: &Figure<'_>,
    rows: &[Row],
    meshes: &[&str],
    methods: &[(&str, &str, usize, bool)],
    value: impl Fn(&Row) -> f64 + Copy,
) -> Result<()> {
    let Figure {
        path,
        title,
        y_label,
        notes,
    } = *figure;
    let titles: Vec<String> = meshes.iter().map(|m| short_name(m)).collect();
    let lines: Vec<Vec<GridLine>> = meshes
        .iter()
        .map(|mesh| {
            methods
                .iter()
                .map(|&(method, label, color, dashed)| {
                    let mut series = Series::new(label);
                    series.points = points(rows, mesh, method, value);
                    GridLine {
                        series,
                        color: palette(color),
                        dashed,
                    }
                })
                .collect()
        })
        .collect();
    let panels: Vec<GridPanel<'_>> = titles
        .iter()
        .zip(&lines)
        .map(|(title, lines)| GridPanel {
            spec: ChartSpec {
                title,
                x_label: "spheres asked for (N)",
                y_label,
            },
            lines,
        })
        .collect();
    let legend: Vec<GridLegend> = methods
        .iter()
        .map(|&(_, label, color, dashed)| GridLegend {
            label: label.to_owned(),
            color: Some(palette(color)),
            dashed,
        })
        .chain(notes.iter().map(|text| GridLegend {
            label: (*text).to_owned(),
            color: None,
            dashed: false,
        }))
        .collect();
    line_grid(path, title, 4, &panels, &legend)
}

fn protrusion_chart(out: &Path, rows: &[Row], meshes: &[&str]) -> Result<()> {
    let figure = Figure {
        path: &out.join(format!("{NAME}.svg")),
        title: "Exactly N spheres: certified worst protrusion, Sphaera against morphit-rs (issue 36)",
        y_label: "worst protrusion (% of diagonal)",
        notes: &[
            "all measured by evaluate_set:",
            "certified upper bound of the",
            "farthest reach beyond the mesh;",
            "grown: every radius by the largest",
            "gap, then certify_coverage;",
            "links: N = 8 to 64",
        ],
    };
    grid(&figure, rows, meshes, &METHODS, |r| {
        100.0 * r.fit.worst_upper / r.diagonal
    })
}

fn time_chart(out: &Path, rows: &[Row], meshes: &[&str]) -> Result<()> {
    let methods = [
        (SPHAERA, "Sphaera: surface + one-level tree", 0, false),
        (MORPHIT_RAW, "morphit-rs: pack() alone", 1, true),
    ];
    let figure = Figure {
        path: &out.join(format!("{TIME}.svg")),
        title: "Exactly N spheres: time, Sphaera against morphit-rs (2 cores, same run)",
        y_label: "seconds",
        notes: &[
            "shortest of 2 runs for N <= 64,",
            "1 run above; both on 2 threads",
        ],
    };
    grid(&figure, rows, meshes, &methods, |r| r.seconds)
}

fn uncovered_chart(out: &Path, rows: &[Row], meshes: &[&str]) -> Result<()> {
    let markers = [Marker::Circle, Marker::Square, Marker::Triangle];
    let style = |i: usize| Style {
        color: palette(i),
        marker: markers[(i / 10 + i) % markers.len()],
        filled: i < 10,
        line: true,
    };
    let series: Vec<StyledSeries> = meshes
        .iter()
        .enumerate()
        .map(|(i, mesh)| {
            let mut s = Series::new(mesh);
            s.points = points(rows, mesh, MORPHIT_RAW, |r| {
                100.0 * r.fit.coverage.uncovered_fraction
            });
            StyledSeries::new(s, style(i))
        })
        .collect();
    let panels = [StyledPanel {
        spec: ChartSpec {
            title: "morphit-rs raw: surface outside every sphere",
            x_label: "spheres asked for (N)",
            y_label: "uncovered share of 100,000 samples (%)",
        },
        x_axis: XAxis::Log,
        series: &series,
        notes: &[],
    }];
    let legend: Vec<LegendEntry> = meshes
        .iter()
        .enumerate()
        .map(|(i, mesh)| LegendEntry {
            label: short_name(mesh),
            style: style(i),
        })
        .collect();
    let covering = rows
        .iter()
        .filter(|r| r.method != MORPHIT_RAW)
        .all(|r| r.fit.coverage.uncovered == 0);
    let title = if covering {
        "Uncovered share (Sphaera and morphit-rs grown: 0 % on every mesh and N)"
    } else {
        "Uncovered share (Sphaera and morphit-rs grown: not drawn, see the CSV)"
    };
    titled_panels(
        &out.join(format!("{UNCOVERED}.svg")),
        title,
        &panels,
        &legend,
    )
}
