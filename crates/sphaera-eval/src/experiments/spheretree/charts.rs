//! The tables and charts of the sphere-tree experiment (see the parent module): one CSV
//! and one SVG per chart, from the measured trees and the toolkit's figures of the issue.

use std::path::Path;

use anyhow::Result;

use plotters::style::RGBColor;

use super::{
    ANIMAL, ANIMAL_LABEL, BRANCH, DEPTH, EFFORTS, ERROR_FRACTIONS, LEVEL_CHART, MESHES, METHODS,
    Measured, Method, SWEEP_METHOD, TARGET, TIME_CHART, TOOLKIT, TOOLKIT_MESH, Variant,
    method_index,
};
use crate::chart::{
    ChartSpec, LegendEntry, Marker, Series, Style, StyledPanel, StyledSeries, XAxis, palette,
    styled_panels, write_csv,
};

/// The colour of the library's default in the time chart (no method has it).
const DEFAULT_COLOR: RGBColor = RGBColor(0, 0, 0);

/// The colour of the legend's mesh markers in the time chart (no method has it).
const SHAPE_COLOR: RGBColor = RGBColor(70, 70, 70);

/// The method column of issue 36's target rows in the level CSV.
const TARGET_NAME: &str = "target";

/// One row per mesh, method and level; then the toolkit's rows and issue 36's target.
pub(super) fn write_level_table(out: &Path, measured: &[Measured]) -> Result<()> {
    let pct = |x: f64| format!("{:.4}", 100.0 * x);
    let mut table = Vec::new();
    for m in measured {
        for l in &m.levels {
            table.push(vec![
                m.file.to_owned(),
                m.method.name().to_owned(),
                "measured".to_owned(),
                l.level.to_string(),
                l.spheres.to_string(),
                pct(l.worst_lower),
                pct(l.worst_upper),
                pct(l.mean_error),
                pct(l.construction_error),
                format!("{:.4}", 100.0 * l.uncovered),
                l.converged.to_string(),
                format!("{:.4}", m.seconds),
                format!("{:.3}", l.evaluation_seconds),
            ]);
        }
    }
    let reference = TOOLKIT.iter().copied().chain([(TARGET_NAME, None, TARGET)]);
    for (name, seconds, errors) in reference {
        for (i, error) in errors.iter().enumerate() {
            table.push(vec![
                TOOLKIT_MESH.to_owned(),
                name.to_owned(),
                "issue".to_owned(),
                (i + 1).to_string(),
                String::new(),
                String::new(),
                format!("{error}"),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                seconds.map(|s| format!("{s}")).unwrap_or_default(),
                String::new(),
            ]);
        }
    }
    write_csv(
        &out.join(format!("{LEVEL_CHART}.csv")),
        &[
            "file",
            "method",
            "source",
            "level",
            "spheres",
            "worst_error_lower_pct_diag",
            "worst_error_upper_pct_diag",
            "mean_error_pct_diag",
            "construction_error_pct_diag",
            "uncovered_surface_pct",
            "converged",
            "build_seconds",
            "evaluation_seconds",
        ],
        &table,
    )
}

/// The `series` column of the time table for a measured tree.
fn series_name(variant: Variant) -> &'static str {
    match variant {
        Variant::Method => "method",
        Variant::ErrorFraction(_) => "error_fraction_sweep",
        Variant::Effort(_) => "effort_sweep",
        Variant::LibraryDefault => "default",
    }
}

/// One row per mesh and tree (every method, expand's error-fraction sweep, the library's
/// effort sweep, the library's default): build time, worst error at levels 2 and 3, the
/// error fraction (medial methods only), the effort (minimax only) and the series; then
/// the toolkit's rows that have a time.
pub(super) fn write_time_table(out: &Path, measured: &[Measured]) -> Result<()> {
    let pct = |x: Option<f64>| x.map(|v| format!("{v:.4}")).unwrap_or_default();
    let mut table: Vec<Vec<String>> = measured
        .iter()
        .map(|m| {
            vec![
                m.file.to_owned(),
                m.method.name().to_owned(),
                "measured".to_owned(),
                format!("{:.4}", m.seconds),
                pct(m.upper_pct(2)),
                pct(m.upper_pct(3)),
                if m.method.is_medial() {
                    format!("{}", m.error_fraction)
                } else {
                    String::new()
                },
                if m.method.resolved() == Method::Minimax {
                    m.effort.name().to_owned()
                } else {
                    String::new()
                },
                series_name(m.variant).to_owned(),
            ]
        })
        .collect();
    for &(name, seconds, errors) in TOOLKIT {
        if let Some(s) = seconds {
            table.push(vec![
                TOOLKIT_MESH.to_owned(),
                name.to_owned(),
                "issue".to_owned(),
                format!("{s}"),
                format!("{}", errors[1]),
                format!("{}", errors[2]),
                String::new(),
                String::new(),
                "toolkit".to_owned(),
            ]);
        }
    }
    write_csv(
        &out.join(format!("{TIME_CHART}.csv")),
        &[
            "file",
            "method",
            "source",
            "build_seconds",
            "level2_worst_error_upper_pct_diag",
            "level3_worst_error_upper_pct_diag",
            "error_fraction",
            "effort",
            "series",
        ],
        &table,
    )
}

/// The style of a measured method: its colour, filled `marker`s, joined by a line if `line`.
fn method_style(method: Method, marker: Marker, line: bool) -> Style {
    Style {
        color: palette(method_index(method)),
        marker,
        filled: true,
        line,
    }
}

/// One legend line per method of [`METHODS`]: its name and [`method_style`] (circles,
/// joined by a line if `line`).
fn method_legend(line: bool) -> Vec<LegendEntry> {
    METHODS
        .iter()
        .map(|&m| LegendEntry {
            label: m.name().to_owned(),
            style: method_style(m, Marker::Circle, line),
        })
        .collect()
}

/// The method a toolkit entry (`toolkit-merge`, ...) stands for.
fn toolkit_method(name: &str) -> Method {
    METHODS
        .iter()
        .copied()
        .find(|m| name.strip_prefix("toolkit-") == Some(m.name()))
        .unwrap_or(Method::Hubbard)
}

/// The toolkit's entry `name` drawn in the colour of the method it stands for, hollow.
fn toolkit_style(name: &str, marker: Marker, line: bool) -> Style {
    Style {
        filled: false,
        ..method_style(toolkit_method(name), marker, line)
    }
}

/// The x of `level` for `method` in the level chart: shifted a little per method, so
/// that methods with equal errors (combined often equals expand) stay visible.
fn dodge(level: usize, method: Method) -> f64 {
    level as f64 + 0.035 * (method_index(method) as f64 - 3.0)
}

/// One panel per mesh: certified worst error against level, one line per method; the
/// toolkit's figures as hollow squares on the bunny.
pub(super) fn draw_levels(
    out: &Path,
    measured: &[Measured],
    labels: &[(&str, String)],
) -> Result<()> {
    let mut per_mesh = Vec::new();
    for (file, _) in labels {
        let mut series: Vec<StyledSeries> = measured
            .iter()
            .filter(|m| m.file == *file)
            .map(|m| {
                let mut s = Series::new(m.method.name());
                s.points = m
                    .levels
                    .iter()
                    .map(|l| (dodge(l.level, m.method), 100.0 * l.worst_upper))
                    .collect();
                StyledSeries::new(s, method_style(m.method, Marker::Circle, true))
            })
            .collect();
        if *file == TOOLKIT_MESH {
            for &(name, _, errors) in TOOLKIT {
                let mut s = Series::new(name);
                let method = toolkit_method(name);
                s.points = (1..=errors.len())
                    .map(|l| dodge(l, method))
                    .zip(errors.iter().copied())
                    .collect();
                series.push(StyledSeries::new(
                    s,
                    toolkit_style(name, Marker::Square, true),
                ));
            }
            let mut s = Series::new(TARGET_NAME);
            s.points = (1..=TARGET.len())
                .map(|l| l as f64)
                .zip(TARGET.iter().copied())
                .collect();
            series.push(StyledSeries::new(s, target_style()));
        }
        per_mesh.push(series);
    }
    let sizes: Vec<String> = (1..=DEPTH)
        .map(|l| BRANCH.pow(l as u32).to_string())
        .collect();
    let x_label = format!("tree level (at most {} spheres)", sizes.join(", "));
    let panels: Vec<StyledPanel<'_>> = labels
        .iter()
        .zip(&per_mesh)
        .map(|((_, label), series)| StyledPanel {
            spec: ChartSpec {
                title: label,
                x_label: &x_label,
                y_label: "certified worst error, % of diagonal",
            },
            x_axis: XAxis::Integers(0.75..DEPTH as f64 + 0.25),
            series,
            notes: &[],
        })
        .collect();
    let mut legend = method_legend(true);
    legend.extend(TOOLKIT.iter().map(|&(name, _, _)| LegendEntry {
        label: format!("{} (issue, bunny)", name.replace('-', " ")),
        style: toolkit_style(name, Marker::Square, true),
    }));
    legend.push(LegendEntry {
        label: "target: 0.9× toolkit's best".to_owned(),
        style: target_style(),
    });
    styled_panels(&out.join(format!("{LEVEL_CHART}.svg")), &panels, &legend)
}

/// Issue 36's target on the bunny in the level chart: black hollow triangles, joined.
fn target_style() -> Style {
    Style {
        color: DEFAULT_COLOR,
        marker: Marker::Triangle,
        filled: false,
        line: true,
    }
}

/// Marker of a mesh in the time chart.
fn mesh_marker(file: &str) -> Marker {
    if file == ANIMAL {
        return Marker::Cross;
    }
    match MESHES.iter().position(|&(f, _)| f == file) {
        Some(1) => Marker::Square,
        Some(2) => Marker::Triangle,
        _ => Marker::Circle,
    }
}

/// The method of the effort sweep, and its legend.
const EFFORT_METHOD: Method = Method::Minimax;

/// Levels 2 and 3: certified worst error against build time, one point per mesh and
/// method (colour: method, marker: mesh); per mesh, expand's error-fraction sweep and
/// minimax's effort sweep as lines with each point labelled by its fraction or effort
/// (the default effort unlabelled: it is the library's default), and the library's
/// default as a black
/// hollow marker labelled "default"; the toolkit's timed figures (bunny only) hollow.
pub(super) fn draw_times(out: &Path, measured: &[Measured]) -> Result<()> {
    let per_level: Vec<Vec<StyledSeries>> = [2, 3]
        .iter()
        .map(|&level| time_series(measured, level))
        .collect();
    let titles = ["Level 2 (≤ 64 spheres)", "Level 3 (≤ 512 spheres)"];
    let panels: Vec<StyledPanel<'_>> = titles
        .iter()
        .zip(&per_level)
        .map(|(title, series)| StyledPanel {
            spec: ChartSpec {
                title,
                x_label: "build time, s (best of 2; toolkit: CPU s from the issue)",
                y_label: "certified worst error, % of diagonal",
            },
            x_axis: XAxis::Log,
            series,
            notes: &[],
        })
        .collect();
    let grey = SHAPE_COLOR;
    let mut legend = method_legend(false);
    legend.push(LegendEntry {
        label: format!("{} by error fraction", SWEEP_METHOD.name()),
        style: method_style(SWEEP_METHOD, Marker::Circle, true),
    });
    legend.push(LegendEntry {
        label: format!("{} by effort", EFFORT_METHOD.name()),
        style: method_style(EFFORT_METHOD, Marker::Circle, true),
    });
    legend.push(LegendEntry {
        label: format!("default ({})", Method::default().name()),
        style: default_style(Marker::Circle),
    });
    let meshes = MESHES.iter().copied().chain([(ANIMAL, ANIMAL_LABEL)]);
    legend.extend(meshes.map(|(file, label)| LegendEntry {
        label: label.to_owned(),
        style: Style {
            color: grey,
            marker: mesh_marker(file),
            filled: true,
            line: false,
        },
    }));
    legend.push(LegendEntry {
        label: "toolkit (issue), bunny only".to_owned(),
        style: Style {
            color: grey,
            marker: mesh_marker(TOOLKIT_MESH),
            filled: false,
            line: false,
        },
    });
    styled_panels(&out.join(format!("{TIME_CHART}.svg")), &panels, &legend)
}

/// The style of the library's default: black, hollow (the method it is drawn over
/// stays visible inside), never joined.
fn default_style(marker: Marker) -> Style {
    Style {
        color: DEFAULT_COLOR,
        marker,
        filled: false,
        line: false,
    }
}

/// The series of one panel of the time chart (`level`): see [`draw_times`].
fn time_series(measured: &[Measured], level: usize) -> Vec<StyledSeries> {
    let point = |m: &Measured| m.upper_pct(level).map(|e| (m.seconds, e));
    let mut series: Vec<StyledSeries> = measured
        .iter()
        .filter(|m| m.variant == Variant::Method)
        .map(|m| {
            let mut s = Series::new(m.method.name());
            s.points = point(m).into_iter().collect();
            StyledSeries::new(s, method_style(m.method, mesh_marker(m.file), false))
        })
        .collect();
    let mut files: Vec<&str> = measured.iter().map(|m| m.file).collect();
    files.dedup();
    for file in files {
        // The sweep, largest fraction first (the order of ERROR_FRACTIONS).
        let mut sweep: Vec<(usize, &Measured)> = measured
            .iter()
            .filter(|m| m.file == file)
            .filter_map(|m| match m.variant {
                Variant::ErrorFraction(i) => Some((i, m)),
                _ => None,
            })
            .collect();
        sweep.sort_by_key(|&(i, _)| i);
        let mut s = Series::new(&format!("{} by error fraction", SWEEP_METHOD.name()));
        let mut labels = Vec::new();
        for (i, m) in sweep {
            if let (Some(p), Some(&(_, label))) = (point(m), ERROR_FRACTIONS.get(i)) {
                s.points.push(p);
                labels.push(label.to_owned());
            }
        }
        series.push(
            StyledSeries::new(s, method_style(SWEEP_METHOD, mesh_marker(file), true))
                .with_labels(labels),
        );
        // The effort sweep, quickest first; the default effort is the library's default,
        // labelled as such below.
        let mut efforts: Vec<(usize, &Measured)> = measured
            .iter()
            .filter(|m| m.file == file)
            .filter_map(|m| match m.variant {
                Variant::Effort(i) => Some((i, m)),
                _ => None,
            })
            .collect();
        efforts.sort_by_key(|&(i, _)| i);
        let mut s = Series::new(&format!("{} by effort", EFFORT_METHOD.name()));
        let mut labels = Vec::new();
        for (i, m) in efforts {
            if let (Some(p), Some(&effort)) = (point(m), EFFORTS.get(i)) {
                s.points.push(p);
                labels.push(if effort == sphaera::spheretree::Effort::Default {
                    String::new()
                } else {
                    effort.name().to_owned()
                });
            }
        }
        series.push(
            StyledSeries::new(s, method_style(EFFORT_METHOD, mesh_marker(file), true))
                .with_labels(labels),
        );
        for m in measured
            .iter()
            .filter(|m| m.file == file && m.variant == Variant::LibraryDefault)
        {
            let mut s = Series::new("default");
            s.points = point(m).into_iter().collect();
            series.push(
                StyledSeries::new(s, default_style(mesh_marker(file)))
                    .with_labels(vec!["default".to_owned()]),
            );
        }
    }
    for &(name, seconds, errors) in TOOLKIT {
        if let Some(s) = seconds {
            let mut t = Series::new(name);
            t.points = vec![(s, errors[level - 1])];
            series.push(StyledSeries::new(
                t,
                toolkit_style(name, mesh_marker(TOOLKIT_MESH), false),
            ));
        }
    }
    series
}

#[cfg(test)]
mod tests {
    use super::super::tests::{measured, scratch};
    use super::*;

    #[test]
    fn tables_and_charts_list_the_mesh_first() -> Result<()> {
        let dir = scratch("spheretree");
        let rows = [
            measured(Method::Merge, [0.10, 0.05, 0.02]),
            measured(Method::Octree, [0.40, 0.25, 0.13]),
        ];
        let sweep = |i: usize, uppers| Measured {
            variant: Variant::ErrorFraction(i),
            error_fraction: ERROR_FRACTIONS[i].0,
            seconds: 1.0 + i as f64,
            ..measured(SWEEP_METHOD, uppers)
        };
        let default = Measured {
            variant: Variant::LibraryDefault,
            ..measured(Method::default(), [0.09, 0.045, 0.021])
        };
        let effort = |i: usize, uppers| Measured {
            variant: Variant::Effort(i),
            effort: EFFORTS[i],
            seconds: 0.5 + i as f64,
            ..measured(Method::Minimax, uppers)
        };
        let mut trees = rows.to_vec();
        trees.extend([
            sweep(0, [0.10, 0.05, 0.03]),
            sweep(1, [0.10, 0.04, 0.02]),
            effort(0, [0.10, 0.05, 0.025]),
            effort(2, [0.08, 0.04, 0.018]),
            default,
        ]);
        write_level_table(&dir, &rows)?;
        write_time_table(&dir, &trees)?;
        let labels = [(TOOLKIT_MESH, "bunny".to_owned())];
        draw_levels(&dir, &rows, &labels)?;
        draw_times(&dir, &trees)?;
        let levels = std::fs::read_to_string(dir.join(format!("{LEVEL_CHART}.csv")))?;
        let times = std::fs::read_to_string(dir.join(format!("{TIME_CHART}.csv")))?;
        // 2 trees × 3 levels measured, 4 × 3 from the issue and the 3 levels of the target;
        // 7 trees, 2 timed from the issue.
        assert_eq!(levels.lines().count(), 1 + 6 + 12 + 3);
        assert_eq!(times.lines().count(), 1 + 7 + 2);
        for table in [&levels, &times] {
            let columns = table.lines().next().map(|h| h.split(',').count());
            for line in table.lines().skip(1) {
                assert!(line.starts_with("bunny_lowres.obj,"), "{line}");
                assert_eq!(Some(line.split(',').count()), columns, "{line}");
            }
        }
        assert!(levels.contains("toolkit-merge,issue,3,,,2.13,"));
        assert!(levels.contains("target,issue,2,,,3.36,"));
        assert!(levels.contains("merge,measured,3,512,1.9000,2.0000,"));
        assert!(times.contains("toolkit-expand,issue,103,3.73,2.09,,,toolkit"));
        assert!(times.contains("merge,measured,1.0000,5.0000,2.0000,0.5,,method"));
        assert!(times.contains("octree,measured,1.0000,25.0000,13.0000,,,method"));
        assert!(times.contains("expand,measured,2.0000,4.0000,2.0000,0.25,,error_fraction_sweep"));
        assert!(times.contains("minimax,measured,2.5000,4.0000,1.8000,,thorough,effort_sweep"));
        let default_row = format!(
            "{},measured,1.0000,4.5000,2.1000,",
            Method::default().name()
        );
        assert!(times.contains(&default_row), "{times}");
        assert!(times.contains(",default\n"));
        let svg = std::fs::read_to_string(dir.join(format!("{LEVEL_CHART}.svg")))?;
        assert!(svg.contains("toolkit merge (issue, bunny)"));
        assert!(svg.contains("target: 0.9× toolkit"));
        assert!(svg.contains("certified worst error, % of diagonal"));
        let svg = std::fs::read_to_string(dir.join(format!("{TIME_CHART}.svg")))?;
        for text in [
            "½",
            "¼",
            "\ndefault\n",
            "expand by error fraction",
            "minimax by effort",
            "thorough",
            "bunny only",
        ] {
            assert!(svg.contains(text), "{text}");
        }
        std::fs::remove_dir_all(&dir)?;
        Ok(())
    }

    #[test]
    fn toolkit_entries_stand_for_a_method() {
        for &(name, seconds, errors) in TOOLKIT {
            let method = toolkit_method(name);
            assert_eq!(format!("toolkit-{}", method.name()), name);
            assert!(seconds.is_none_or(|s| s > 0.0));
            // The errors shrink from level 1 to 2 (level 3 of Hubbard does not).
            assert!(errors[1] < errors[0], "{name}");
        }
        // One colour per method, none of them the default's or the mesh legend's.
        assert!(METHODS.len() <= 10);
        for (i, &m) in METHODS.iter().enumerate() {
            assert_eq!(method_index(m), i);
            let color = method_style(m, Marker::Circle, false).color;
            assert!(
                color != DEFAULT_COLOR && color != SHAPE_COLOR,
                "{}",
                m.name()
            );
        }
    }

    #[test]
    fn dodged_levels_stay_apart() {
        for &m in METHODS {
            for l in 1..=DEPTH {
                assert!((dodge(l, m) - l as f64).abs() < 0.25);
            }
        }
        let merge = Method::Merge;
        let expand = Method::Expand;
        assert!(dodge(2, merge) < dodge(2, expand));
    }
}
