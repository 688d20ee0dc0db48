//! `sphaera hal` on GIS outlines: countries with their islands and holes (GeoJSON, WKT),
//! point inclusion that says where, and intersection of two files (`--intersect`).

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::hal::{
    Containment, HalMultiPolygon2, HalTree2, MultiPolygon2, Polyline2, RingEdge, RingId,
    parse_points,
};
use sphaera::mesh::io::{ShapeFormat, read_shapes};

use crate::{
    cli::HalArgs,
    output::{print_json, thousands},
};

/// An outline read for `sphaera hal`: a region (polygons with holes), open lines, or both.
pub struct Shape {
    /// The polygons, if any.
    pub area: Option<HalMultiPolygon2>,
    /// The open lines, each its own tree.
    pub lines: Vec<HalTree2>,
    /// Rings that bound no area, dropped (in the file's numbering).
    pub dropped: Vec<RingId>,
    /// Points in the file, which bound nothing.
    pub ignored_points: usize,
    /// Vertices of everything kept.
    pub vertices: usize,
}

/// Reads an outline: GeoJSON or WKT (any polygons and lines), or a text file of `x y`
/// lines (one ring, or one open line with `open`).
pub fn read_shape(path: &Path, open: bool) -> Result<Shape> {
    if ShapeFormat::from_path(path).is_some() {
        let shapes = read_shapes(path, &crate::input::file_policy())?;
        let (area, dropped) = if shapes.polygons.is_empty() {
            (None, Vec::new())
        } else {
            let (multi, dropped) =
                MultiPolygon2::from_rings_dropping_degenerate(shapes.polygons)
                    .with_context(|| format!("{} holds no usable polygon", path.display()))?;
            (Some(multi), dropped)
        };
        let lines = shapes
            .lines
            .into_iter()
            .enumerate()
            .map(|(i, points)| {
                Polyline2::open(points)
                    .and_then(|line| HalTree2::build(&line))
                    .with_context(|| format!("line {i} of {}", path.display()))
            })
            .collect::<Result<Vec<_>>>()?;
        let vertices = area.as_ref().map_or(0, MultiPolygon2::vertex_count)
            + lines
                .iter()
                .map(|l| l.polyline().points().len())
                .sum::<usize>();
        if area.is_none() && lines.is_empty() {
            bail!("{} holds no polygon and no line", path.display());
        }
        return Ok(Shape {
            area: area.as_ref().map(HalMultiPolygon2::build).transpose()?,
            lines,
            dropped,
            ignored_points: shapes.ignored_points,
            vertices,
        });
    }
    let text = crate::input::read_text(path, "the outline")?;
    let points = parse_points(&text)
        .with_context(|| format!("{} is not a file of `x y` lines", path.display()))?;
    let vertices = points.len();
    if open {
        let line = Polyline2::open(points)
            .with_context(|| format!("{} is not a polyline", path.display()))?;
        return Ok(Shape {
            area: None,
            lines: vec![HalTree2::build(&line)?],
            dropped: Vec::new(),
            ignored_points: 0,
            vertices,
        });
    }
    let multi = MultiPolygon2::from_rings(vec![vec![points]])
        .with_context(|| format!("{} is not a polygon", path.display()))?;
    Ok(Shape {
        area: Some(HalMultiPolygon2::build(&multi)?),
        lines: Vec::new(),
        dropped: Vec::new(),
        ignored_points: 0,
        vertices,
    })
}

/// A ring in a report: its polygon, and 0 for the exterior or `k` for the hole `k − 1`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct RingAt {
    pub polygon: usize,
    pub ring: usize,
}

impl From<RingId> for RingAt {
    fn from(id: RingId) -> Self {
        Self {
            polygon: id.polygon,
            ring: id.ring,
        }
    }
}

/// An edge in a report: of a polygon's ring, or of a line.
#[derive(Debug, Serialize)]
#[serde(untagged)]
pub enum EdgeAt {
    /// An edge of a ring (ring 0 the exterior, `k` the hole `k − 1`).
    Ring {
        polygon: usize,
        ring: usize,
        edge: usize,
    },
    /// An edge of an open line.
    Line { line: usize, edge: usize },
}

impl EdgeAt {
    fn ring(at: RingEdge) -> Self {
        Self::Ring {
            polygon: at.ring.polygon,
            ring: at.ring.ring,
            edge: at.edge,
        }
    }
}

impl std::fmt::Display for EdgeAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Ring {
                polygon,
                ring: 0,
                edge,
            } => write!(f, "polygon {polygon} exterior edge {edge}"),
            Self::Ring {
                polygon,
                ring,
                edge,
            } => {
                write!(f, "polygon {polygon} hole {} edge {edge}", ring - 1)
            }
            Self::Line { line, edge } => write!(f, "line {line} edge {edge}"),
        }
    }
}

/// What `--intersect` reports.
#[derive(Debug, Serialize)]
pub struct Intersect {
    /// The other file.
    pub file: String,
    /// Whether the two meet: outlines cross or touch, or one lies inside the other's
    /// polygons (GEOS's `intersects`).
    pub intersects: bool,
    /// Pairs of intersecting edges.
    pub pairs: usize,
    /// Every pair: an edge of the first file, one of the second.
    pub edge_pairs: Vec<[EdgeAt; 2]>,
    pub seconds: f64,
}

/// Intersection of `first` and `second` (read from `file`): regions and lines, each pair.
pub fn intersect(first: &Shape, second: &Shape, file: &Path) -> Intersect {
    let started = Instant::now();
    let mut meets = false;
    let mut pairs: Vec<[EdgeAt; 2]> = Vec::new();
    let line = |line: usize, edge: usize| EdgeAt::Line { line, edge };
    if let (Some(a), Some(b)) = (&first.area, &second.area) {
        meets |= a.intersects(b);
        pairs.extend(
            a.intersecting_edges(b)
                .into_iter()
                .map(|(p, q)| [EdgeAt::ring(p), EdgeAt::ring(q)]),
        );
    }
    if let Some(a) = &first.area {
        for (j, l) in second.lines.iter().enumerate() {
            meets |= a.intersects_outline(l);
            pairs.extend(
                a.intersecting_outline_edges(l)
                    .into_iter()
                    .map(|(p, e)| [EdgeAt::ring(p), line(j, e)]),
            );
        }
    }
    if let Some(b) = &second.area {
        for (i, l) in first.lines.iter().enumerate() {
            meets |= b.intersects_outline(l);
            pairs.extend(
                b.intersecting_outline_edges(l)
                    .into_iter()
                    .map(|(q, e)| [line(i, e), EdgeAt::ring(q)]),
            );
        }
    }
    for (i, a) in first.lines.iter().enumerate() {
        for (j, b) in second.lines.iter().enumerate() {
            meets |= a.intersects(b);
            pairs.extend(
                a.intersecting_edges(b)
                    .into_iter()
                    .map(|(p, q)| [line(i, p), line(j, q)]),
            );
        }
    }
    Intersect {
        file: file.display().to_string(),
        intersects: meets || !pairs.is_empty(),
        pairs: pairs.len(),
        edge_pairs: pairs,
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// Prints `--intersect`'s report: the answer and the first pairs.
pub fn print_intersect(report: &Intersect) {
    println!(
        "{} {} it: {} pairs of edges cross or touch, in {:.4} s",
        if report.intersects {
            "intersects"
        } else {
            "does not intersect"
        },
        report.file,
        thousands(report.pairs),
        report.seconds
    );
    const SHOWN: usize = 10;
    for [a, b] in report.edge_pairs.iter().take(SHOWN) {
        println!("  {a} meets {b}");
    }
    if report.pairs > SHOWN {
        println!("  … {} more (--json lists them all)", report.pairs - SHOWN);
    }
}

/// What `sphaera hal` reports for a GIS file; also its JSON schema.
#[derive(Debug, Serialize)]
struct ShapesReport {
    file: String,
    polygons: usize,
    /// Rings of every polygon (exteriors and holes).
    rings: usize,
    holes: usize,
    lines: usize,
    vertices: usize,
    /// Rings that bound no area (fewer than three distinct points), dropped.
    dropped_rings: Vec<RingAt>,
    /// Points and multipoints in the file, which bound nothing.
    ignored_points: usize,
    /// The deepest HAL tree among the rings.
    depth: usize,
    /// The adaptive approximation of every ring at `--tolerance`, if given.
    approximation: Option<ShapesApproximation>,
    contains: Option<Located>,
    intersect: Option<Intersect>,
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct ShapesApproximation {
    tolerance: f64,
    vertices: usize,
    width: f64,
}

/// Point inclusion that says where.
#[derive(Debug, Serialize)]
struct Located {
    file: String,
    points: usize,
    inside: usize,
    outside: usize,
    boundary: usize,
    /// Per point in file order.
    answers: Vec<Where>,
    seconds: f64,
}

/// Where one point lies.
#[derive(Debug, Serialize)]
struct Where {
    /// `inside`, `outside` or `boundary`.
    containment: &'static str,
    /// The innermost ring holding it: the exterior of the polygon it is in, the ring it
    /// lies on, the hole (lake) it is in; `null` outside every polygon.
    ring: Option<RingAt>,
    /// The nearest edge and the distance to it.
    nearest: EdgeAt,
    distance: f64,
}

/// `sphaera hal FILE.geojson|FILE.wkt`: trees over every ring, inclusion with where,
/// intersection.
pub fn run_shapes(args: &HalArgs) -> Result<()> {
    if args.output.is_some() || args.level.is_some() {
        bail!(
            "--output and --level apply to one ring (a text file of `x y` lines); for a GeoJSON or WKT file use --tolerance, --contains or --intersect"
        );
    }
    let started = Instant::now();
    let shape = read_shape(&args.polygon, args.open)?;
    let seconds = started.elapsed().as_secs_f64();
    let Some(area) = &shape.area else {
        bail!(
            "{} holds lines but no polygon: give it as --intersect to a polygon file",
            args.polygon.display()
        );
    };
    let (lo, hi) = area.bounding_box();
    let approximation = args.tolerance.map(|tolerance| {
        let tolerance = tolerance.resolve(lo.distance(hi));
        let (vertices, width) = area.rings().fold((0, 0.0_f64), |(v, w), (_, tree)| {
            let a = tree.approximate(tolerance);
            (v + a.vertices.len(), w.max(a.width))
        });
        ShapesApproximation {
            tolerance,
            vertices,
            width,
        }
    });
    let contains = match &args.contains {
        Some(path) => Some(locate(area, path)?),
        None => None,
    };
    let intersect = match &args.intersect {
        Some(path) => Some(intersect(&shape, &read_shape(path, false)?, path)),
        None => None,
    };
    let rings = area.rings().count();
    let report = ShapesReport {
        file: args.polygon.display().to_string(),
        polygons: area.polygon_count(),
        rings,
        holes: rings - area.polygon_count(),
        lines: shape.lines.len(),
        vertices: shape.vertices,
        dropped_rings: shape.dropped.iter().map(|&r| r.into()).collect(),
        ignored_points: shape.ignored_points,
        depth: area.rings().map(|(_, t)| t.depth()).max().unwrap_or(0),
        approximation,
        contains,
        intersect,
        seconds,
    };
    if args.print.json {
        return print_json(&report);
    }
    println!(
        "{}: {} polygon(s) with {} hole(s), {} vertices, {} line(s); trees built in {:.3} s, deepest {}",
        report.file,
        thousands(report.polygons),
        thousands(report.holes),
        thousands(report.vertices),
        report.lines,
        report.seconds,
        report.depth
    );
    if !report.dropped_rings.is_empty() {
        println!(
            "dropped {} ring(s) of fewer than three distinct points (no area): {}",
            report.dropped_rings.len(),
            report
                .dropped_rings
                .iter()
                .map(|r| format!("polygon {} ring {}", r.polygon, r.ring))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    if report.ignored_points > 0 {
        println!(
            "ignored {} point geometries (they bound nothing)",
            report.ignored_points
        );
    }
    if let Some(a) = &report.approximation {
        println!(
            "approximation (tolerance {}): {} vertices, width {}",
            a.tolerance,
            thousands(a.vertices),
            a.width
        );
    }
    if let Some(c) = &report.contains {
        println!(
            "{}",
            super::hal::contains_summary(
                &c.file,
                [c.points, c.inside, c.outside, c.boundary],
                c.seconds
            )
        );
        for w in &c.answers {
            let ring = match w.ring {
                Some(RingAt { polygon, ring: 0 }) => format!(" (polygon {polygon})"),
                Some(RingAt { polygon, ring }) => format!(" (polygon {polygon} hole {})", ring - 1),
                None => String::new(),
            };
            println!("{}{ring}, {} from {}", w.containment, w.distance, w.nearest);
        }
    }
    if let Some(i) = &report.intersect {
        print_intersect(i);
    }
    Ok(())
}

/// Inclusion with where for every point of `path`.
fn locate(area: &HalMultiPolygon2, path: &Path) -> Result<Located> {
    let text = crate::input::read_text(path, "the points")?;
    let points = parse_points(&text)
        .with_context(|| format!("{} is not a file of 2D points", path.display()))?;
    let started = Instant::now();
    let answers: Vec<Where> = points
        .iter()
        .map(|&x| {
            let location = area.locate(x);
            let nearest = area.nearest_edge(x);
            Where {
                containment: name(location.containment),
                ring: location.ring.map(RingAt::from),
                nearest: EdgeAt::ring(nearest.at),
                distance: nearest.distance,
            }
        })
        .collect();
    let count = |c: &str| answers.iter().filter(|w| w.containment == c).count();
    Ok(Located {
        file: path.display().to_string(),
        points: answers.len(),
        inside: count("inside"),
        outside: count("outside"),
        boundary: count("boundary"),
        answers,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The report's word for a containment.
pub fn name(containment: Containment) -> &'static str {
    match containment {
        Containment::Inside => "inside",
        Containment::Outside => "outside",
        Containment::Boundary => "boundary",
    }
}
