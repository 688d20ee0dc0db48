//! Log–log scatter plots and side-by-side log–log panels, coloured by series position.

use std::path::Path;

use anyhow::Result;
use plotters::prelude::*;

use super::{
    ChartSpec, PALETTE, Series, SvgArea, is_positive, log_range, palette, tick_label, write_svg,
};
/// The older charts cycle through the first six colours of [`PALETTE`].
const CLASSIC_COLORS: usize = 6;

/// Draws the series as points on log–log axes, into `path` (SVG, written atomically).
pub fn log_log_scatter(path: &Path, spec: &ChartSpec<'_>, series: &[Series]) -> Result<()> {
    let (x_range, y_range) = log_range(&positive_points(series));
    write_svg(path, (800, 520), |root| {
        let mut chart = log_log_chart(root, spec, 20, x_range, y_range)?;
        for (i, s) in series.iter().enumerate() {
            let points = s.points.iter().copied().filter(is_positive).collect();
            draw_points(&mut chart, &s.name, points, PALETTE[i % CLASSIC_COLORS])?;
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)
    })
}

/// One plot of a multi-panel chart: log–log axes, each series as points joined by a line.
pub struct Panel<'a> {
    /// Caption, axes.
    pub spec: ChartSpec<'a>,
    /// The series; colours are given by the position in this list, the same in every panel.
    pub series: &'a [Series],
    /// Draw the line `y = x` (dashed grey), e.g. to show a bound is never below a value.
    pub diagonal: bool,
    /// Where the legend goes (a corner the data leaves empty).
    pub legend: SeriesLabelPosition,
}

/// Draws `panels` side by side (each 640 × 520) into `path` (SVG, written atomically).
/// A series with the same index has the same colour in every panel.
pub fn log_log_panels(path: &Path, panels: &[Panel<'_>]) -> Result<()> {
    let width = 640 * u32::try_from(panels.len().max(1)).unwrap_or(1);
    write_svg(path, (width, 520), |root| {
        let areas = root.split_evenly((1, panels.len().max(1)));
        for (panel, area) in panels.iter().zip(&areas) {
            let (mut x_range, mut y_range) = log_range(&positive_points(panel.series));
            if panel.diagonal {
                // One range for both axes, so that y = x is the square's diagonal.
                let lo = x_range.start.min(y_range.start);
                let hi = x_range.end.max(y_range.end);
                (x_range, y_range) = (lo..hi, lo..hi);
            }
            let mut chart = log_log_chart(area, &panel.spec, 18, x_range.clone(), y_range)?;
            if panel.diagonal {
                let grey = RGBColor(128, 128, 128);
                chart
                    .draw_series(DashedLineSeries::new(
                        [(x_range.start, x_range.start), (x_range.end, x_range.end)],
                        6,
                        4,
                        grey.stroke_width(1),
                    ))?
                    .label("y = x")
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], grey));
            }
            for (i, s) in panel.series.iter().enumerate() {
                // The first six as the older charts have them; more series take the rest
                // of the palette rather than repeat a colour.
                let color = if panel.series.len() <= CLASSIC_COLORS {
                    PALETTE[i % CLASSIC_COLORS]
                } else {
                    palette(i)
                };
                let points: Vec<(f64, f64)> =
                    s.points.iter().copied().filter(is_positive).collect();
                if points.is_empty() {
                    continue;
                }
                chart.draw_series(LineSeries::new(points.iter().copied(), color.mix(0.5)))?;
                draw_points(&mut chart, &s.name, points, color)?;
            }
            draw_legend(&mut chart, panel.legend.clone())?;
        }
        Ok(())
    })
}
/// A chart with log–log axes on an SVG figure.
type LogLogChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;
/// Every drawable point of `series` (see [`is_positive`]).
fn positive_points(series: &[Series]) -> Vec<(f64, f64)> {
    series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(is_positive)
        .collect()
}

/// A log–log chart over `x_range` × `y_range` on `area`: the title of `spec` (at
/// `title_size` points) above, its axis labels, ticks labelled by [`tick_label`].
fn log_log_chart<'a, 'b>(
    area: &'a SvgArea<'b>,
    spec: &ChartSpec<'_>,
    title_size: u32,
    x_range: std::ops::Range<f64>,
    y_range: std::ops::Range<f64>,
) -> Result<LogLogChart<'a, 'b>> {
    let mut chart = ChartBuilder::on(area)
        .caption(spec.title, ("sans-serif", title_size))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
    chart
        .configure_mesh()
        .x_desc(spec.x_label)
        .y_desc(spec.y_label)
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(&|v| tick_label(*v))
        .draw()?;
    Ok(chart)
}

/// Draws `points` as filled circles of `color`, with a legend entry `name`.
fn draw_points(
    chart: &mut LogLogChart<'_, '_>,
    name: &str,
    points: Vec<(f64, f64)>,
    color: RGBColor,
) -> Result<()> {
    chart
        .draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p, 3, color.filled())),
        )?
        .label(name)
        .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
    Ok(())
}

/// Draws the legend of the labelled series of `chart` at `position`, on a light box.
fn draw_legend<'a, 'b: 'a>(
    chart: &mut LogLogChart<'a, 'b>,
    position: SeriesLabelPosition,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}
