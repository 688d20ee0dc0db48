//! A grid of small base-2 log–log line plots with a legend cell ([`line_grid`]).

use std::path::Path;

use anyhow::Result;
use plotters::prelude::*;

use super::{ChartSpec, Series, TITLE_HEIGHT, is_positive, log_range, write_svg};
/// One line of a [`line_grid`] panel.
pub struct GridLine {
    /// The points, joined in the order given (non-positive values are dropped: log axes).
    pub series: Series,
    /// Its colour.
    pub color: RGBColor,
    /// Dashed with hollow markers, or solid with filled markers.
    pub dashed: bool,
}

/// One small plot of [`line_grid`]: log–log axes (base 2) over its own data.
pub struct GridPanel<'a> {
    /// Caption, axes.
    pub spec: ChartSpec<'a>,
    /// Its lines.
    pub lines: &'a [GridLine],
}

/// One entry of the legend cell of [`line_grid`].
pub struct GridLegend {
    /// The text.
    pub label: String,
    /// The colour of the line (`None`: text only, e.g. a note under the entries).
    pub color: Option<RGBColor>,
    /// Dashed or solid, as the lines it names.
    pub dashed: bool,
}

/// Draws `panels` as a grid of small log–log plots (420 × 320 each; base-2 axes, ticks
/// labelled at the powers of two), `columns` to a row,
/// with `title` above the figure and the legend in the cell after the last panel, into
/// `path` (SVG, written atomically).
pub fn line_grid(
    path: &Path,
    title: &str,
    columns: usize,
    panels: &[GridPanel<'_>],
    legend: &[GridLegend],
) -> Result<()> {
    let columns = columns.max(1);
    let rows = (panels.len() + 1).div_ceil(columns);
    let width = 420 * u32::try_from(columns).unwrap_or(1);
    let height = 320 * u32::try_from(rows).unwrap_or(1) + TITLE_HEIGHT;
    write_svg(path, (width, height), |root| {
        let (header, body) = root.split_vertically(TITLE_HEIGHT);
        header.draw(&Text::new(
            title.to_owned(),
            (16, 12),
            ("sans-serif", 20).into_font(),
        ))?;
        let cells = body.split_evenly((rows, columns));
        for (panel, area) in panels.iter().zip(&cells) {
            let all: Vec<(f64, f64)> = panel
                .lines
                .iter()
                .flat_map(|l| l.series.points.iter().copied())
                .filter(is_positive)
                .collect();
            let (x_range, y_range) = log_range(&all);
            // Base-2 axes: ticks at the powers of two (the sphere counts are 4, 8, …).
            let mut chart = ChartBuilder::on(area)
                .caption(panel.spec.title, ("sans-serif", 15))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(56)
                .build_cartesian_2d(x_range.log_scale().base(2.0), y_range.log_scale().base(2.0))?;
            let power_of_two = |v: &f64| {
                let exponent = v.log2().round();
                if (v / exponent.exp2() - 1.0).abs() < 1e-9 {
                    let text = format!("{v:.3}");
                    text.trim_end_matches('0').trim_end_matches('.').to_owned()
                } else {
                    String::new()
                }
            };
            chart
                .configure_mesh()
                .x_desc(panel.spec.x_label)
                .y_desc(panel.spec.y_label)
                .light_line_style(TRANSPARENT)
                .x_label_formatter(&power_of_two)
                .y_label_formatter(&power_of_two)
                .draw()?;
            for line in panel.lines {
                let points: Vec<(f64, f64)> = line
                    .series
                    .points
                    .iter()
                    .copied()
                    .filter(is_positive)
                    .collect();
                let style = line.color.stroke_width(2);
                if line.dashed {
                    chart.draw_series(DashedLineSeries::new(
                        points.iter().copied(),
                        7,
                        5,
                        style,
                    ))?;
                    chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, style)))?;
                } else {
                    chart.draw_series(LineSeries::new(points.iter().copied(), style))?;
                    chart.draw_series(
                        points
                            .iter()
                            .map(|&p| Circle::new(p, 3, line.color.filled())),
                    )?;
                }
            }
        }
        if let Some(area) = cells.get(panels.len()) {
            let mut y = 40;
            for entry in legend {
                if let Some(color) = entry.color {
                    let style = color.stroke_width(2);
                    if entry.dashed {
                        area.draw(&PathElement::new([(20, y), (32, y)], style))?;
                        area.draw(&PathElement::new([(40, y), (52, y)], style))?;
                        area.draw(&Circle::new((36, y), 3, style))?;
                    } else {
                        area.draw(&PathElement::new([(20, y), (52, y)], style))?;
                        area.draw(&Circle::new((36, y), 3, color.filled()))?;
                    }
                }
                area.draw(&Text::new(
                    entry.label.clone(),
                    (62, y - 7),
                    ("sans-serif", 14).into_font(),
                ))?;
                y += 24;
            }
        }
        Ok(())
    })
}
