//! Panels of individually styled series (markers, fills, lines, labels, notes) with a
//! figure-wide legend column ([`styled_panels`], [`titled_panels`]).

use std::path::Path;

use anyhow::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{ChartSpec, Series, SvgArea, TITLE_HEIGHT, log_range, tick_label, write_svg};
/// The shape of a point marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// A circle.
    Circle,
    /// An axis-aligned square.
    Square,
    /// An upward triangle.
    Triangle,
    /// A diagonal cross (the same filled or hollow).
    Cross,
}

/// How a series of a [`StyledPanel`] (or an entry of a [`LegendEntry`] list) is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Style {
    /// Colour of the markers and the line.
    pub color: RGBColor,
    /// Marker shape.
    pub marker: Marker,
    /// Filled markers, or hollow outlines (e.g. reference values from elsewhere).
    pub filled: bool,
    /// Join the points by a line, in the order given.
    pub line: bool,
}
/// A series with its own style.
pub struct StyledSeries {
    /// The points (the name is for the caller's bookkeeping: the legend is figure-wide).
    pub series: Series,
    /// How it is drawn.
    pub style: Style,
    /// Text written beside each point, in the order of the points (fewer labels than
    /// points leave the last points unlabelled; an empty label writes nothing).
    pub labels: Vec<String>,
}

impl StyledSeries {
    /// `series` drawn in `style`, without labels.
    pub fn new(series: Series, style: Style) -> Self {
        Self {
            series,
            style,
            labels: Vec::new(),
        }
    }

    /// With `labels` written beside the points (see [`StyledSeries::labels`]).
    #[must_use]
    pub fn with_labels(mut self, labels: Vec<String>) -> Self {
        self.labels = labels;
        self
    }
}

/// A text of a [`StyledPanel`] placed in data coordinates: centred above `(x, y)`.
pub struct Note {
    /// Where the text's bottom centre goes.
    pub at: (f64, f64),
    /// The text.
    pub text: String,
    /// Its colour.
    pub color: RGBColor,
}

/// The x axis of a [`StyledPanel`].
#[derive(Debug, Clone, PartialEq)]
pub enum XAxis {
    /// Linear over the range, with a tick at every integer (e.g. tree levels).
    Integers(std::ops::Range<f64>),
    /// Logarithmic, over the data's range.
    Log,
}

/// One plot of [`styled_panels`]: a log y axis, a linear or log x axis.
pub struct StyledPanel<'a> {
    /// Caption, axes.
    pub spec: ChartSpec<'a>,
    /// The x axis.
    pub x_axis: XAxis,
    /// The series.
    pub series: &'a [StyledSeries],
    /// Texts in data coordinates (e.g. a statistic written above each group of points);
    /// the y axis's range includes them.
    pub notes: &'a [Note],
}

/// One line of the figure-wide legend of [`styled_panels`].
pub struct LegendEntry {
    /// The text.
    pub label: String,
    /// The marker (and line) drawn before it.
    pub style: Style,
}

/// Width of the legend column of [`styled_panels`], in pixels.
const LEGEND_WIDTH: u32 = 230;
/// Draws `panels` side by side (each 600 × 520, log y axis) with one legend in a column
/// to their right, never over the data, into `path` (SVG, written atomically).
/// Non-positive or non-finite values are dropped (log axes).
pub fn styled_panels(
    path: &Path,
    panels: &[StyledPanel<'_>],
    legend: &[LegendEntry],
) -> Result<()> {
    titled_panels(path, "", panels, legend)
}

/// [`styled_panels`] with `title` written above the whole figure (none if empty).
pub fn titled_panels(
    path: &Path,
    title: &str,
    panels: &[StyledPanel<'_>],
    legend: &[LegendEntry],
) -> Result<()> {
    let count = u32::try_from(panels.len().max(1)).unwrap_or(1);
    let title_height = if title.is_empty() { 0 } else { TITLE_HEIGHT };
    write_svg(
        path,
        (600 * count + LEGEND_WIDTH, 520 + title_height),
        |root| {
            let (header, body) = root.split_vertically(title_height);
            if !title.is_empty() {
                header.draw(&Text::new(
                    title.to_owned(),
                    (16, 12),
                    ("sans-serif", 20).into_font(),
                ))?;
            }
            let (plots, legend_area) = body.split_horizontally(600 * count);
            let areas = plots.split_evenly((1, panels.len().max(1)));
            for (panel, area) in panels.iter().zip(&areas) {
                let all: Vec<(f64, f64)> = panel
                    .series
                    .iter()
                    .flat_map(|s| s.series.points.iter().copied())
                    .chain(panel.notes.iter().map(|n| n.at))
                    .filter(|&(x, y)| x.is_finite() && y > 0.0 && y.is_finite())
                    .collect();
                let (_, y_range) = log_range(&all);
                // From a power of ten: plotters labels a log axis from the first power of ten
                // in range, so a range starting at 1.5 would have no labels below 10.
                let y_range = 10f64.powf(y_range.start.log10().floor())..y_range.end;
                match &panel.x_axis {
                    XAxis::Integers(range) => {
                        let x = plotters::coord::types::RangedCoordf64::from(range.clone());
                        // One tick per integer of the range.
                        let ticks = (range.end.floor() - range.start.ceil()).max(0.0) as usize + 1;
                        draw_styled(area, panel, x, y_range.log_scale().into(), ticks)?;
                    }
                    XAxis::Log => {
                        let positive: Vec<(f64, f64)> =
                            all.into_iter().filter(|&(x, _)| x > 0.0).collect();
                        let (x_range, _) = log_range(&positive);
                        draw_styled(
                            area,
                            panel,
                            LogCoord::from(x_range.log_scale()),
                            y_range.log_scale().into(),
                            10,
                        )?;
                    }
                }
            }
            let mut y = 40;
            for entry in legend {
                if entry.style.line {
                    legend_area.draw(&PathElement::new(
                        [(6, y), (30, y)],
                        entry.style.color.mix(0.5),
                    ))?;
                }
                let shape = shape_style(entry.style);
                let at = EmptyElement::at((18, y));
                match entry.style.marker {
                    Marker::Circle => legend_area.draw(&(at + Circle::new((0, 0), 4, shape)))?,
                    Marker::Square => {
                        legend_area.draw(&(at + Rectangle::new([(-4, -4), (4, 4)], shape)))?;
                    }
                    Marker::Triangle => {
                        legend_area.draw(&(at + TriangleMarker::new((0, 0), 5, shape)))?;
                    }
                    Marker::Cross => {
                        legend_area
                            .draw(&(at + Cross::new((0, 0), 4, cross_style(entry.style))))?;
                    }
                }
                legend_area.draw(&Text::new(
                    entry.label.clone(),
                    (38, y - 7),
                    ("sans-serif", 14).into_font(),
                ))?;
                y += 22;
            }
            Ok(())
        },
    )
}

/// Draws one [`StyledPanel`] on `area` with the x coordinate `x` and log y `y`.
fn draw_styled<X>(
    area: &SvgArea<'_>,
    panel: &StyledPanel<'_>,
    x: X,
    y: LogCoord<f64>,
    x_ticks: usize,
) -> Result<()>
where
    X: Ranged<ValueType = f64> + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let integers = matches!(panel.x_axis, XAxis::Integers(_));
    let mut chart = ChartBuilder::on(area)
        .caption(panel.spec.title, ("sans-serif", 18))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .x_desc(panel.spec.x_label)
        .y_desc(panel.spec.y_label)
        .x_labels(x_ticks)
        // Every 1..9 multiple is already a labelled line on the log axis: lines between
        // them only darken the upper part of each decade.
        .light_line_style(TRANSPARENT)
        .x_label_formatter(&|v| {
            if integers {
                format!("{v:.0}")
            } else {
                tick_label(*v)
            }
        })
        .y_label_formatter(&|v| tick_label(*v))
        .draw()?;
    let drawable =
        |&(x, y): &(f64, f64)| x.is_finite() && y > 0.0 && y.is_finite() && (integers || x > 0.0);
    for s in panel.series {
        let points: Vec<(f64, f64)> = s.series.points.iter().copied().filter(drawable).collect();
        let labelled = s
            .series
            .points
            .iter()
            .zip(&s.labels)
            .filter(|(p, text)| drawable(p) && !text.is_empty());
        chart.draw_series(labelled.map(|(&p, text)| {
            EmptyElement::at(p)
                + Text::new(
                    text.clone(),
                    (7, -18),
                    ("sans-serif", 13).into_font().color(&s.style.color),
                )
        }))?;
        if s.style.line && points.len() > 1 {
            chart.draw_series(LineSeries::new(
                points.iter().copied(),
                s.style.color.mix(0.5),
            ))?;
        }
        let shape = shape_style(s.style);
        let at = points.into_iter().map(EmptyElement::at);
        match s.style.marker {
            Marker::Circle => chart.draw_series(at.map(|e| e + Circle::new((0, 0), 4, shape)))?,
            Marker::Square => {
                chart.draw_series(at.map(|e| e + Rectangle::new([(-4, -4), (4, 4)], shape)))?
            }
            Marker::Triangle => {
                chart.draw_series(at.map(|e| e + TriangleMarker::new((0, 0), 5, shape)))?
            }
            Marker::Cross => {
                let style = cross_style(s.style);
                chart.draw_series(at.map(|e| e + Cross::new((0, 0), 4, style)))?
            }
        };
    }
    let centred = Pos::new(HPos::Center, VPos::Bottom);
    chart.draw_series(panel.notes.iter().filter(|n| drawable(&n.at)).map(|n| {
        Text::new(
            n.text.clone(),
            n.at,
            ("sans-serif", 13).into_font().color(&n.color).pos(centred),
        )
    }))?;
    Ok(())
}

/// The outline or fill of a marker of `style`.
fn shape_style(style: Style) -> ShapeStyle {
    if style.filled {
        style.color.filled()
    } else {
        style.color.stroke_width(2)
    }
}

/// The stroke of a [`Marker::Cross`]: a line has no inside, so filled and hollow crosses
/// are the same two strokes.
fn cross_style(style: Style) -> ShapeStyle {
    style.color.stroke_width(2)
}
