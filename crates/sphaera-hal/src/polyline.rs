//! The 2D input: a closed polygon or an open polyline, validated once.

use std::path::Path;

use glam::{DVec2, DVec3};

use crate::HalError;

/// A closed polygon (the last vertex connects to the first) or an open polyline.
///
/// Any vertex sequence of finite coordinates is accepted: collinear runs, repeated
/// vertices and self-touching or self-crossing outlines included. Point inclusion then
/// follows the even–odd rule of the outline as given.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline2 {
    points: Vec<DVec2>,
    closed: bool,
}

impl Polyline2 {
    /// A closed polygon through `points` (at least three).
    ///
    /// # Errors
    ///
    /// [`HalError::TooFewVertices`], [`HalError::NonFinite`],
    /// [`HalError::TooManyVertices`].
    pub fn polygon(points: Vec<DVec2>) -> Result<Self, HalError> {
        Self::new(points, true)
    }

    /// An open polyline through `points` (at least two).
    ///
    /// # Errors
    ///
    /// As [`Polyline2::polygon`].
    pub fn open(points: Vec<DVec2>) -> Result<Self, HalError> {
        Self::new(points, false)
    }

    fn new(points: Vec<DVec2>, closed: bool) -> Result<Self, HalError> {
        let (what, needed) = if closed {
            ("polygon", 3)
        } else {
            ("polyline", 2)
        };
        if points.len() < needed {
            return Err(HalError::TooFewVertices {
                shape: what,
                count: points.len(),
                needed,
            });
        }
        if points.len() >= u32::MAX as usize {
            return Err(HalError::TooManyVertices {
                count: points.len(),
            });
        }
        if let Some((vertex, p)) = points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(HalError::NonFinite {
                vertex,
                x: p.x,
                y: p.y,
            });
        }
        Ok(Self { points, closed })
    }

    /// Parses text: `#` comment lines and blank lines are skipped, every other line is
    /// `x y` (whitespace or a comma between). The result is a closed polygon if `closed`.
    ///
    /// # Errors
    ///
    /// [`HalError::Parse`] naming the first bad line, then as [`Polyline2::polygon`].
    pub fn parse(text: &str, closed: bool) -> Result<Self, HalError> {
        Self::new(parse_points(text)?, closed)
    }

    /// Reads a polygon file (as [`Polyline2::parse`], closed).
    ///
    /// # Errors
    ///
    /// [`HalError::Io`], then as [`Polyline2::parse`].
    pub fn read_polygon(path: impl AsRef<Path>) -> Result<Self, HalError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| HalError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, true)
    }

    /// The vertices.
    #[must_use]
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    /// Whether the last vertex connects to the first.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The bounding box of the vertices: `(min, max)` per axis.
    #[must_use]
    pub fn bounds(&self) -> (DVec2, DVec2) {
        self.points.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
    }

    /// The number of edges (vertices for a polygon, one fewer for a polyline).
    #[must_use]
    pub fn edge_count(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len() - 1
        }
    }

    /// Edge `i`: from vertex `i` to the next.
    ///
    /// # Panics
    ///
    /// If `i >= self.edge_count()`.
    #[must_use]
    pub fn edge(&self, i: usize) -> (DVec2, DVec2) {
        let n = self.points.len();
        (self.points[i], self.points[(i + 1) % n])
    }
}

/// The points of a text: `#` comment lines and blank lines are skipped, every other line is
/// `x y` (whitespace or a comma between). Any number of points, none included.
///
/// # Errors
///
/// [`HalError::Parse`] naming the first line that is not two finite numbers.
pub fn parse_points(text: &str) -> Result<Vec<DVec2>, HalError> {
    Ok(parse_rows::<2>(text)?
        .into_iter()
        .map(DVec2::from_array)
        .collect())
}

/// [`parse_points`] for 3D points: every line `x y z`.
///
/// # Errors
///
/// [`HalError::Parse`] naming the first line that is not three finite numbers.
pub fn parse_points3(text: &str) -> Result<Vec<DVec3>, HalError> {
    Ok(parse_rows::<3>(text)?
        .into_iter()
        .map(DVec3::from_array)
        .collect())
}

/// Rows of `N` finite numbers, as [`parse_points`] reads them.
fn parse_rows<const N: usize>(text: &str) -> Result<Vec<[f64; N]>, HalError> {
    let mut rows = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let bad = || HalError::Parse {
            line: number + 1,
            columns: N,
            text: trimmed.chars().take(80).collect(),
        };
        let fields: Vec<&str> = trimmed
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|f| !f.is_empty())
            .collect();
        if fields.len() != N {
            return Err(bad());
        }
        let mut row = [0.0; N];
        for (value, field) in row.iter_mut().zip(&fields) {
            *value = field
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(bad)?;
        }
        rows.push(row);
    }
    Ok(rows)
}
