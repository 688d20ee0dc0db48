//! SVG charts (plotters, SVG backend: no system fonts needed) and the CSV behind each.

mod grid;
mod log_log;
mod styled;
#[cfg(test)]
mod tests;

use std::path::Path;

use anyhow::{Context, Result};
/// Where a panel's legend goes.
pub use plotters::prelude::SeriesLabelPosition;
use plotters::prelude::*;

pub use grid::{GridLegend, GridLine, GridPanel, line_grid};
pub use log_log::{Panel, log_log_panels, log_log_scatter};
pub use styled::{
    LegendEntry, Marker, Note, Style, StyledPanel, StyledSeries, XAxis, styled_panels,
    titled_panels,
};

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
/// The drawing area of a whole SVG figure.
type SvgArea<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;
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
/// Height of the figure-wide title of [`titled_panels`], in pixels.
const TITLE_HEIGHT: u32 = 40;
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

/// Writes a CSV table (header + rows) atomically, one line per row, fields quoted as
/// RFC 4180 says ([`csv_text`]).
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> Result<()> {
    write_atomically(path, csv_text(header, rows).as_bytes())
}

/// The text [`write_csv`] writes: the header line, then one line per row, each ending in
/// `\n`; a field containing `,`, `"`, CR or LF is wrapped in double quotes with its
/// inner quotes doubled (RFC 4180), any other field is written as it is.
#[must_use]
pub fn csv_text(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut text = String::new();
    push_csv_line(&mut text, header.iter().copied());
    for row in rows {
        push_csv_line(&mut text, row.iter().map(String::as_str));
    }
    text
}

/// Appends `fields` to `text` as one CSV line ending in `\n`, quoted as [`csv_text`] says.
fn push_csv_line<'a>(text: &mut String, fields: impl Iterator<Item = &'a str>) {
    for (i, field) in fields.enumerate() {
        if i > 0 {
            text.push(',');
        }
        if field.contains([',', '"', '\r', '\n']) {
            text.push('"');
            text.push_str(&field.replace('"', "\"\""));
            text.push('"');
        } else {
            text.push_str(field);
        }
    }
    text.push('\n');
}

/// Writes `bytes` to `path` atomically (temporary file, then rename), creating the folder.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    sphaera::mesh::io::write_atomic(path, |w| std::io::Write::write_all(w, bytes))?;
    Ok(())
}
