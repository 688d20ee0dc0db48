//! 2D outlines from GIS files: GeoJSON and WKT polygons, multipolygons and line strings,
//! read through the `geojson` and `wkt` crates into plain rings of points.

use std::path::{Path, PathBuf};

use glam::DVec2;

use crate::{FilePolicy, IoError};

/// A format of 2D shapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShapeFormat {
    /// GeoJSON (RFC 7946): a geometry, a feature or a feature collection.
    GeoJson,
    /// Well-known text: one geometry (`POLYGON`, `MULTIPOLYGON`, `LINESTRING`, …).
    Wkt,
}

impl ShapeFormat {
    /// The format a file's extension names: `.geojson` and `.json` are GeoJSON, `.wkt`
    /// is WKT (in any case); `None` otherwise.
    #[must_use]
    pub fn from_path(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "geojson" | "json" => Some(Self::GeoJson),
            "wkt" => Some(Self::Wkt),
            _ => None,
        }
    }
}

impl std::fmt::Display for ShapeFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::GeoJson => "GeoJSON",
            Self::Wkt => "WKT",
        })
    }
}

/// The outlines of a GIS file: polygons as rings (per polygon its exterior, then its
/// holes; each ring's points in file order, a repeated closing point kept as written),
/// open line strings, and a count of what was not an outline.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Shapes2 {
    /// Per polygon, its rings: the exterior first, then the holes.
    pub polygons: Vec<Vec<Vec<DVec2>>>,
    /// Line strings (open polylines).
    pub lines: Vec<Vec<DVec2>>,
    /// Points and multipoints, which bound nothing and are not kept.
    pub ignored_points: usize,
}

impl Shapes2 {
    /// Every polygon's and line's points.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.polygons.iter().flatten().map(Vec::len).sum::<usize>()
            + self.lines.iter().map(Vec::len).sum::<usize>()
    }
}

/// Reads a GeoJSON or WKT file (the format from its extension, see
/// [`ShapeFormat::from_path`]) through `policy`.
///
/// # Errors
///
/// [`IoError::Io`] or [`IoError::Refused`] for a file that cannot or may not be read,
/// [`IoError::UnknownShapeFormat`] for another extension, [`IoError::MalformedShapes`]
/// naming the problem (the JSON line and column, the WKT error, a position with fewer than
/// two coordinates).
///
/// # Examples
///
/// ```
/// use sphaera_io::{FilePolicy, read_shapes};
///
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("lake.wkt");
/// std::fs::write(&path, "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0), (4 4, 6 4, 6 6, 4 4))")?;
/// let shapes = read_shapes(&path, &FilePolicy::default())?;
/// assert_eq!(shapes.polygons.len(), 1);
/// assert_eq!(shapes.polygons[0].len(), 2); // the exterior and one hole
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_shapes(path: impl AsRef<Path>, policy: &FilePolicy) -> Result<Shapes2, IoError> {
    let path = path.as_ref();
    let format = ShapeFormat::from_path(path).ok_or_else(|| IoError::UnknownShapeFormat {
        path: path.to_path_buf(),
    })?;
    let text = policy.read_to_string(path)?;
    parse_shapes(&text, format).map_err(|error| match error {
        IoError::MalformedShapes {
            path: None,
            format,
            message,
        } => IoError::MalformedShapes {
            path: Some(path.to_path_buf()),
            format,
            message,
        },
        other => other,
    })
}

/// Parses GeoJSON or WKT text (see [`read_shapes`]). GeoJSON's third coordinate
/// (elevation), and WKT's `Z` and `M`, are dropped.
///
/// # Errors
///
/// [`IoError::MalformedShapes`], as [`read_shapes`].
pub fn parse_shapes(text: &str, format: ShapeFormat) -> Result<Shapes2, IoError> {
    let malformed = |message: String| IoError::MalformedShapes {
        path: None::<PathBuf>,
        format,
        message,
    };
    let mut shapes = Shapes2::default();
    match format {
        ShapeFormat::GeoJson => {
            let document: geojson::GeoJson = text
                .parse()
                .map_err(|e: geojson::Error| malformed(e.to_string()))?;
            let geometries: Vec<(String, &geojson::Geometry)> = match &document {
                geojson::GeoJson::Geometry(g) => vec![("the geometry".to_owned(), g)],
                geojson::GeoJson::Feature(f) => f
                    .geometry
                    .iter()
                    .map(|g| ("the feature".to_owned(), g))
                    .collect(),
                geojson::GeoJson::FeatureCollection(c) => c
                    .features
                    .iter()
                    .enumerate()
                    .filter_map(|(i, f)| f.geometry.as_ref().map(|g| (format!("feature {i}"), g)))
                    .collect(),
            };
            for (name, geometry) in geometries {
                add_geojson(&geometry.value, &mut shapes)
                    .map_err(|e| malformed(format!("{name}: {e}")))?;
            }
        }
        ShapeFormat::Wkt => {
            let geometry: wkt::Wkt<f64> = text
                .trim()
                .parse()
                .map_err(|e: &str| malformed(e.to_owned()))?;
            add_wkt(&geometry, &mut shapes);
        }
    }
    Ok(shapes)
}

/// Adds a GeoJSON geometry's outlines.
fn add_geojson(value: &geojson::GeometryValue, shapes: &mut Shapes2) -> Result<(), String> {
    use geojson::GeometryValue as V;
    let ring = |positions: &[geojson::Position]| -> Result<Vec<DVec2>, String> {
        positions
            .iter()
            .enumerate()
            .map(|(i, p)| match p.as_slice() {
                [x, y, ..] => Ok(DVec2::new(*x, *y)),
                _ => Err(format!("position {i} has fewer than two coordinates")),
            })
            .collect()
    };
    let polygon = |rings: &[Vec<geojson::Position>]| -> Result<Vec<Vec<DVec2>>, String> {
        rings.iter().map(|r| ring(r)).collect()
    };
    match value {
        V::Point { .. } | V::MultiPoint { .. } => shapes.ignored_points += 1,
        V::LineString { coordinates } => shapes.lines.push(ring(coordinates)?),
        V::MultiLineString { coordinates } => {
            for line in coordinates {
                shapes.lines.push(ring(line)?);
            }
        }
        V::Polygon { coordinates } => shapes.polygons.push(polygon(coordinates)?),
        V::MultiPolygon { coordinates } => {
            for (i, p) in coordinates.iter().enumerate() {
                shapes
                    .polygons
                    .push(polygon(p).map_err(|e| format!("polygon {i}: {e}"))?);
            }
        }
        V::GeometryCollection { geometries } => {
            for g in geometries {
                add_geojson(&g.value, shapes)?;
            }
        }
    }
    Ok(())
}

/// Adds a WKT geometry's outlines.
fn add_wkt(geometry: &wkt::Wkt<f64>, shapes: &mut Shapes2) {
    let points = |line: &wkt::types::LineString<f64>| -> Vec<DVec2> {
        line.coords().iter().map(|c| DVec2::new(c.x, c.y)).collect()
    };
    let polygon = |p: &wkt::types::Polygon<f64>| -> Vec<Vec<DVec2>> {
        p.rings().iter().map(points).collect()
    };
    match geometry {
        wkt::Wkt::Point(_) | wkt::Wkt::MultiPoint(_) => shapes.ignored_points += 1,
        wkt::Wkt::LineString(line) => shapes.lines.push(points(line)),
        wkt::Wkt::MultiLineString(lines) => {
            shapes.lines.extend(lines.line_strings().iter().map(points));
        }
        wkt::Wkt::Polygon(p) => {
            if !p.rings().is_empty() {
                shapes.polygons.push(polygon(p));
            }
        }
        wkt::Wkt::MultiPolygon(m) => shapes.polygons.extend(
            m.polygons()
                .iter()
                .filter(|p| !p.rings().is_empty())
                .map(polygon),
        ),
        wkt::Wkt::GeometryCollection(c) => {
            for g in c.geometries() {
                add_wkt(g, shapes);
            }
        }
    }
}
