//! SVG charts (plotters, SVG backend: no system fonts needed) and the CSV behind each.

use std::{fmt::Write as _, path::Path};

use anyhow::{Context, Result};
/// Where a panel's legend goes.
pub use plotters::prelude::SeriesLabelPosition;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One named set of `(x, y)` points.
pub struct Series {
    /// Legend label.
    pub name: String,
    /// The points; non-positive values are dropped on log axes.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// An empty series named `name`.
    pub fn new(name: &str) -> Self {
        Self {
            name: name.to_owned(),
            points: Vec::new(),
        }
    }
}

/// Titles and axes of a chart.
pub struct ChartSpec<'a> {
    /// Caption above the plot.
    pub title: &'a str,
    /// Label of the x axis.
    pub x_label: &'a str,
    /// Label of the y axis.
    pub y_label: &'a str,
}

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

/// The drawing area of a whole SVG figure.
type SvgArea<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// A chart with log–log axes on an SVG figure.
type LogLogChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// Draws a figure of `size` pixels on a white background with `draw`, and writes it to
/// `path` (SVG, written atomically).
fn write_svg(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&SvgArea<'_>) -> Result<()>,
) -> Result<()> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE)?;
        draw(&root)?;
        root.present()?;
    }
    write_atomically(path, svg.as_bytes())
}

/// A finite point in the positive quadrant: drawable on log–log axes.
fn is_positive(&(x, y): &(f64, f64)) -> bool {
    x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite()
}

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

/// The colours of [`palette`]: distinguishable, enough for ten series.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The `i`-th colour of a ten-colour palette (repeating after ten).
pub fn palette(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
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

/// Height of the figure-wide title of [`titled_panels`], in pixels.
const TITLE_HEIGHT: u32 = 40;

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

/// A short label for a tick on a log axis: powers of ten as `0.001`, `100`, `1e-6`.
fn tick_label(v: f64) -> String {
    if v <= 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let exponent = v.log10().round();
    let is_power_of_ten = (v / 10f64.powf(exponent) - 1.0).abs() < 1e-9;
    if is_power_of_ten {
        // The exponent of a finite positive f64 is within ±324.
        let e = exponent as i32;
        match e {
            -3..=-1 => format!("{:.*}", e.unsigned_abs() as usize, v),
            0..=6 => format!("{}", 10i64.pow(e.unsigned_abs())),
            _ => format!("1e{e}"),
        }
    } else {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    }
}

/// A range covering `values` on a log axis, padded by a factor of 1.5 each side.
fn log_range(points: &[(f64, f64)]) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
    let bounds = |get: fn(&(f64, f64)) -> f64| {
        let lo = points.iter().map(get).fold(f64::INFINITY, f64::min);
        let hi = points.iter().map(get).fold(f64::NEG_INFINITY, f64::max);
        if lo.is_finite() && hi.is_finite() {
            (lo / 1.5)..(hi * 1.5)
        } else {
            1.0..10.0
        }
    };
    (bounds(|p| p.0), bounds(|p| p.1))
}

/// Writes a CSV table (header + rows; fields must not contain commas) atomically.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> Result<()> {
    let mut text = header.join(",");
    text.push('\n');
    for row in rows {
        let _ = writeln!(text, "{}", row.join(","));
    }
    write_atomically(path, text.as_bytes())
}

/// Writes `bytes` to `path` atomically (temporary file, then rename), creating the folder.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    sphaera::mesh::io::write_atomic(path, |w| std::io::Write::write_all(w, bytes))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(0.001), "0.001");
        assert_eq!(tick_label(0.1), "0.1");
        assert_eq!(tick_label(1.0), "1");
        assert_eq!(tick_label(1e6), "1000000");
        assert_eq!(tick_label(1e-6), "1e-6");
        assert_eq!(tick_label(99.999_999_999_9e-6), "1e-4");
        assert_eq!(tick_label(2.5), "2.5");
    }

    #[test]
    fn styled_panels_draw_both_axes_and_the_legend() -> Result<()> {
        let path =
            std::env::temp_dir().join(format!("sphaera-eval-styled-{}.svg", std::process::id()));
        let style = |marker, filled| Style {
            color: palette(1),
            marker,
            filled,
            line: true,
        };
        let mut a = Series::new("a");
        a.points = vec![
            (1.0, 20.0),
            (2.0, 5.0),
            (3.0, 2.0),
            (2.0, 0.0),
            (f64::NAN, 1.0),
        ];
        let mut b = Series::new("b");
        b.points = vec![(0.01, 3.0), (10.0, 1.5), (-1.0, 2.0)];
        let levels = [StyledSeries::new(a, style(Marker::Circle, true))];
        // Labels stay with their points when points are dropped (the third is not drawn).
        let times = [
            StyledSeries::new(b, style(Marker::Triangle, false)).with_labels(vec![
                "first label".to_owned(),
                String::new(),
                "dropped label".to_owned(),
            ]),
        ];
        let notes = [Note {
            at: (2.0, 30.0),
            text: "a note".to_owned(),
            color: palette(0),
        }];
        let spec = |title| ChartSpec {
            title,
            x_label: "x units",
            y_label: "y units",
        };
        let panels = [
            StyledPanel {
                spec: spec("levels"),
                x_axis: XAxis::Integers(0.5..3.5),
                series: &levels,
                notes: &notes,
            },
            StyledPanel {
                spec: spec("times"),
                x_axis: XAxis::Log,
                series: &times,
                notes: &[],
            },
        ];
        let legend = [LegendEntry {
            label: "square entry".to_owned(),
            style: style(Marker::Square, false),
        }];
        styled_panels(&path, &panels, &legend)?;
        let svg = std::fs::read_to_string(&path)?;
        for text in [
            "levels",
            "times",
            "x units",
            "y units",
            "square entry",
            "first label",
            "a note",
        ] {
            assert!(svg.contains(text), "{text}");
        }
        assert!(!svg.contains("dropped label"));
        assert!(!svg.contains("figure title"));
        titled_panels(&path, "figure title", &panels, &legend)?;
        let titled = std::fs::read_to_string(&path)?;
        std::fs::remove_file(&path)?;
        assert!(titled.contains("figure title"));
        Ok(())
    }
}
