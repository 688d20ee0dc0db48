//! `hal`: HAL trees (Veltkamp) on the real outlines of `shared/data/polygons`, three
//! charts from one run.
//!
//! - **`hal_width_vs_size`**: the covering error (eq. 1: the largest width of the
//!   bounding areas of an approximation's non-original edges, in % of the bounding-box
//!   diagonal) against the approximation's vertices, for every uniform level and for the
//!   adaptive approximation at tolerances `diagonal · 2⁻ᵏ`, `k = 1..=20` (the paper's
//!   Figs. 6, 13, 14), on the Netherlands, Norway and the Americas, and in 3D (triangles,
//!   Definition 6's widths) on the genus-0 meshes of [`MESHES_3D`].
//! - **`hal_query_speed`**: microseconds per point-in-polygon query against the vertex
//!   count, for the HAL tree (`HalTree2::contains`: its cell grid, then the hierarchy),
//!   the hierarchy alone (`contains_by_hierarchy`, the paper's method), Ballard's strip
//!   tree and an axis-aligned box tree over the edges ([`peers`]), the brute-force
//!   crossing test and `geo`'s `Contains`, on every
//!   outline and on the Americas refined to about a million vertices (every edge cut into
//!   16, each inserted point moved across the edge by up to 2 % of its length, seeded: a
//!   coastline-like outline, not necessarily simple, which the even–odd rule handles).
//!   [`QUERIES`] random points in the bounding box and as many within an edge's length of
//!   the outline (seed [`SEED`], `crate::query_sets`), one panel each; the linear-time
//!   methods answer a prefix of them (at most [`LINEAR_WORK`] vertex visits in all). Every
//!   structure's answers are checked against brute force on that prefix (geo's only off
//!   the boundary, where it says "not contained"), and against the HAL tree's on all.
//! - **`hal_vs_strip_tree`**: the total area of the bounding areas per depth (HAL lenses,
//!   strips, boxes), in % of the outline's bounding-box area, on the Netherlands and
//!   Norway: how tightly each structure localizes the outline, the comparison the paper
//!   leaves as future work. Depth 1 is the two halves of the outline in all three (HAL
//!   node level, strip depth + 1, box-tree depth); an unbounded HAL area (a half-plane on a
//!   vertex's side, which only a collinear back-track makes) is left out of the sum and
//!   counted in the CSV.
//! - **`hal_multipolygon_speed`** ([`multipolygon`]): point inclusion in countries with
//!   their islands and holes (kept in the repository), the HAL trees per ring against
//!   brute force and `geo`'s `MultiPolygon` `Contains`.
//! - **`hal_vs_simplify`** ([`quality`]): the certified Hausdorff distance of 3D HAL
//!   approximations to the original, against their largest width and against
//!   `sphaera-simplify` at equal triangle counts.
//!
//! Times are single-threaded (the structures have no parallel query path), the best of
//! [`RUNS`] runs.

mod multipolygon;
mod peers;
mod quality;

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use geo::{Contains, LineString, Point, Polygon};
use sphaera::hal::{Containment, HalTree2, HalTree3, Polyline2, contains_brute};
use sphaera::mesh::glam::DVec2;
use sphaera_tests::random::SplitMix64;

use crate::query_sets::{box_points, near_outline_points};

use crate::chart::{
    ChartSpec, LegendEntry, Marker, Series, Style, StyledPanel, StyledSeries, XAxis, palette,
    titled_panels, write_csv,
};
use peers::{EdgeBoxTree, StripTree};

/// The experiment's name (`--only hal`).
pub const NAME: &str = "hal";

/// The outlines, smallest first.
pub const OUTLINES: &[&str] = &[
    "luxembourg.txt",
    "netherlands.txt",
    "belgium.txt",
    "united-kingdom.txt",
    "norway.txt",
    "afro-eurasia.txt",
    "americas.txt",
];

/// Random query points per outline.
pub const QUERIES: usize = 10_000;

/// Seed of the query points and of the refinement.
pub const SEED: u64 = 17;

/// Vertex visits the linear-time methods (brute force, geo) may spend per outline.
pub const LINEAR_WORK: usize = 400_000_000;

/// The genus-0 meshes of `hal_width_vs_size`'s 3D panels (the paper's Figs. 13 and 14).
pub const MESHES_3D: &[&str] = &["spot.obj", "bunny_lowres.obj", "fandisk.obj"];

/// Timing runs per measurement (the best is kept).
pub const RUNS: usize = 3;

/// The deepest level charted in `hal_vs_strip_tree`.
pub const DEPTHS: u32 = 14;

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let folder = data.join("polygons");
    let mut outlines: Vec<(String, Polyline2)> = Vec::new();
    for file in OUTLINES {
        let path = folder.join(file);
        if !path.is_file() {
            eprintln!("{file}: not in {}, skipped", folder.display());
            continue;
        }
        outlines.push((format!("polygons/{file}"), Polyline2::read_polygon(&path)?));
    }
    if let Some((_, americas)) = outlines.iter().find(|(n, _)| n == "polygons/americas.txt") {
        let refined = refine(americas, 16)?;
        outlines.push(("polygons/americas.txt refined ×16".to_owned(), refined));
    }
    width_vs_size(data, &outlines, out)?;
    query_speed(&outlines, out)?;
    strip_tree(&outlines, out)?;
    multipolygon::multipolygon_speed(out)?;
    quality::versus_simplify(data, out)
}

/// `polygon` with every edge cut into `pieces`, each inserted point moved across the edge
/// by up to 2 % of its length (seeded).
fn refine(polygon: &Polyline2, pieces: u32) -> Result<Polyline2> {
    let mut rng = SplitMix64::new(SEED);
    let mut points = Vec::with_capacity(polygon.edge_count() * pieces as usize);
    for i in 0..polygon.edge_count() {
        let (a, b) = polygon.edge(i);
        points.push(a);
        let across = (b - a).perp();
        for k in 1..pieces {
            let t = f64::from(k) / f64::from(pieces);
            points.push(a.lerp(b, t) + across * rng.range(-0.02, 0.02));
        }
    }
    Ok(Polyline2::polygon(points)?)
}

fn style(i: usize, marker: Marker, line: bool) -> Style {
    Style {
        color: palette(i),
        marker,
        filled: true,
        line,
    }
}

/// One panel per `(title, series)`, with the same axes.
fn panels<'a>(
    data: &'a [(String, Vec<StyledSeries>)],
    x_label: &'a str,
    y_label: &'a str,
    x_axis: &XAxis,
) -> Vec<StyledPanel<'a>> {
    data.iter()
        .map(|(title, series)| StyledPanel {
            spec: ChartSpec {
                title,
                x_label,
                y_label,
            },
            x_axis: x_axis.clone(),
            series,
            notes: &[],
        })
        .collect()
}

/// `hal_width_vs_size`.
fn width_vs_size(data: &Path, outlines: &[(String, Polyline2)], out: &Path) -> Result<()> {
    let chosen = [
        "polygons/netherlands.txt",
        "polygons/norway.txt",
        "polygons/americas.txt",
    ];
    let mut rows = Vec::new();
    let mut panels_data = Vec::new();
    for (name, polygon) in outlines
        .iter()
        .filter(|(n, _)| chosen.contains(&n.as_str()))
    {
        let tree = HalTree2::build(polygon)?;
        let (lo, hi) = polygon.bounds();
        let diagonal = lo.distance(hi);
        let mut uniform = Series::new("uniform levels");
        for level in 0..=tree.depth() {
            let vertices = tree.level(level).len();
            let width = 100.0 * tree.level_width(level) / diagonal;
            uniform.points.push((vertices as f64, width));
            rows.push(vec![
                name.clone(),
                "uniform".into(),
                level.to_string(),
                vertices.to_string(),
                format!("{width:.6}"),
            ]);
        }
        let mut adaptive = Series::new("adaptive");
        for k in 1..=20 {
            let tolerance = diagonal * (-f64::from(k)).exp2();
            let approximation = tree.approximate(tolerance);
            let width = 100.0 * approximation.width / diagonal;
            adaptive
                .points
                .push((approximation.vertices.len() as f64, width));
            rows.push(vec![
                name.clone(),
                "adaptive".into(),
                format!("2^-{k}"),
                approximation.vertices.len().to_string(),
                format!("{width:.6}"),
            ]);
        }
        eprintln!(
            "{name}: depth {}, adaptive at 2^-10 of the diagonal: {} vertices",
            tree.depth(),
            tree.approximate(diagonal / 1024.0).vertices.len()
        );
        panels_data.push((
            format!("{name} ({} vertices)", polygon.points().len()),
            vec![
                StyledSeries::new(uniform, style(0, Marker::Circle, true)),
                StyledSeries::new(adaptive, style(1, Marker::Square, true)),
            ],
        ));
    }
    // 3D (the paper's Figs. 13 and 14): triangles instead of vertices.
    for file in MESHES_3D {
        let Some(mesh) = crate::experiments::load_or_skip(data, file)? else {
            continue;
        };
        let tree = HalTree3::build(&mesh).with_context(|| format!("no HAL tree for {file}"))?;
        let diagonal = mesh.bounding_box_diagonal();
        let mut uniform = Series::new("uniform levels");
        for level in 0..=tree.depth() {
            let triangles = tree.level(level)?.triangle_count();
            let width = 100.0 * tree.kept_width(|n| n.level < level) / diagonal;
            uniform.points.push((triangles as f64, width));
            rows.push(vec![
                (*file).to_owned(),
                "uniform".into(),
                level.to_string(),
                triangles.to_string(),
                format!("{width:.6}"),
            ]);
        }
        let mut adaptive = Series::new("adaptive");
        for k in 1..=20 {
            let tolerance = diagonal * (-f64::from(k)).exp2();
            let triangles = tree.approximate(tolerance)?.triangle_count();
            let width = 100.0 * tree.kept_width(|n| n.width > tolerance) / diagonal;
            adaptive.points.push((triangles as f64, width));
            rows.push(vec![
                (*file).to_owned(),
                "adaptive".into(),
                format!("2^-{k}"),
                triangles.to_string(),
                format!("{width:.6}"),
            ]);
        }
        panels_data.push((
            format!("{file} ({} triangles)", mesh.triangle_count()),
            vec![
                StyledSeries::new(uniform, style(0, Marker::Circle, true)),
                StyledSeries::new(adaptive, style(1, Marker::Square, true)),
            ],
        ));
    }
    if panels_data.is_empty() {
        bail!("no outline found for hal_width_vs_size");
    }
    write_csv(
        &out.join("hal_width_vs_size.csv"),
        &[
            "polygon",
            "approximation",
            "level_or_tolerance",
            "vertices",
            "width_pct_diagonal",
        ],
        &rows,
    )?;
    let panels = panels(
        &panels_data,
        "vertices (2D) or triangles (3D) of the approximation",
        "covering width, % of diagonal",
        &XAxis::Log,
    );
    let legend = [
        LegendEntry {
            label: "uniform level".into(),
            style: style(0, Marker::Circle, true),
        },
        LegendEntry {
            label: "adaptive (tolerance 2^-k diag)".into(),
            style: style(1, Marker::Square, true),
        },
    ];
    titled_panels(
        &out.join("hal_width_vs_size.svg"),
        "HAL trees: covering width (eq. 1) against size, uniform levels and adaptive refinement",
        &panels,
        &legend,
    )
}

/// The best of [`RUNS`] timings of `f` over `points`, in microseconds per point, with the
/// answers.
fn time_queries<T>(points: &[DVec2], mut f: impl FnMut(DVec2) -> T) -> (f64, Vec<T>) {
    let mut best = f64::INFINITY;
    let mut answers = Vec::new();
    for _ in 0..RUNS {
        let started = Instant::now();
        answers = points.iter().map(|&p| f(p)).collect();
        best = best.min(started.elapsed().as_secs_f64());
    }
    (1e6 * best / points.len().max(1) as f64, answers)
}

/// The methods of `hal_query_speed`, in its CSV's and chart's order.
const QUERY_METHODS: [&str; 6] = [
    "HAL tree",
    "HAL hierarchy",
    "strip tree",
    "box tree",
    "brute force",
    "geo contains",
];

/// `hal_query_speed`: both point sets, one panel each.
fn query_speed(outlines: &[(String, Polyline2)], out: &Path) -> Result<()> {
    let sets = [
        ("box", "random points in the bounding box"),
        (
            "near",
            "random points within an edge's length of the outline",
        ),
    ];
    let mut rows = Vec::new();
    let mut all_series = Vec::new();
    for (set, _) in sets {
        let mut series: Vec<Series> = QUERY_METHODS.iter().map(|m| Series::new(m)).collect();
        for (name, polygon) in outlines {
            let points = match set {
                "box" => box_points(polygon, QUERIES, SEED),
                _ => near_outline_points(polygon, QUERIES, SEED),
            };
            let measured = query_speed_of(name, polygon, &points)?;
            let n = polygon.points().len();
            for (i, &(us, queries, build)) in measured.iter().enumerate() {
                series[i].points.push((n as f64, us));
                rows.push(vec![
                    name.clone(),
                    n.to_string(),
                    set.to_owned(),
                    QUERY_METHODS[i].into(),
                    format!("{build:.6}"),
                    queries.to_string(),
                    format!("{us:.4}"),
                ]);
            }
            eprintln!(
                "{name:<28} {n:>9} vertices, {set:<4} µs/query: HAL {:.3} (build {:.3} s), hierarchy {:.3}, strip {:.3}, box {:.3}, brute {:.2}, geo {:.2}; brute/HAL {:.0}×",
                measured[0].0,
                measured[0].2,
                measured[1].0,
                measured[2].0,
                measured[3].0,
                measured[4].0,
                measured[5].0,
                measured[4].0 / measured[0].0
            );
        }
        all_series.push(series);
    }
    write_csv(
        &out.join("hal_query_speed.csv"),
        &[
            "polygon",
            "vertices",
            "points",
            "method",
            "build_seconds",
            "queries",
            "microseconds_per_query",
        ],
        &rows,
    )?;
    let markers = [
        Marker::Circle,
        Marker::Triangle,
        Marker::Square,
        Marker::Triangle,
        Marker::Circle,
        Marker::Square,
    ];
    let styled: Vec<Vec<StyledSeries>> = all_series
        .into_iter()
        .map(|series| {
            series
                .into_iter()
                .enumerate()
                .map(|(i, s)| StyledSeries::new(s, style(i, markers[i], true)))
                .collect()
        })
        .collect();
    let legend: Vec<LegendEntry> = QUERY_METHODS
        .iter()
        .enumerate()
        .map(|(i, m)| LegendEntry {
            label: (*m).to_owned(),
            style: style(i, markers[i], true),
        })
        .collect();
    let panels: Vec<StyledPanel<'_>> = sets
        .iter()
        .zip(&styled)
        .map(|(&(_, title), series)| StyledPanel {
            spec: ChartSpec {
                title,
                x_label: "polygon vertices",
                y_label: "microseconds per query (one thread)",
            },
            x_axis: XAxis::Log,
            series,
            notes: &[],
        })
        .collect();
    titled_panels(
        &out.join("hal_query_speed.svg"),
        "Point inclusion: the HAL tree (cell grid, then hierarchy) and its hierarchy alone against a strip tree, a box tree, brute force and geo (same run)",
        &panels,
        &legend,
    )
}

/// Each of [`QUERY_METHODS`] on `points`: microseconds per query, the queries answered
/// and the build's seconds; every answer checked (see the module docs).
fn query_speed_of(
    name: &str,
    polygon: &Polyline2,
    points: &[DVec2],
) -> Result<[(f64, usize, f64); 6]> {
    let n = polygon.points().len();
    let linear = (LINEAR_WORK / n).clamp(50, points.len());
    let started = Instant::now();
    let hal = HalTree2::build(polygon)?;
    let hal_build = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let strip = StripTree::build(&hal);
    let strip_build = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let boxes = EdgeBoxTree::build(polygon)?;
    let box_build = started.elapsed().as_secs_f64();
    let geo_polygon = Polygon::new(
        LineString::from(
            polygon
                .points()
                .iter()
                .map(|p| (p.x, p.y))
                .collect::<Vec<_>>(),
        ),
        vec![],
    );

    let (hal_us, hal_answers) = time_queries(points, |p| hal.contains(p));
    let hal_answers: Vec<Containment> = hal_answers.into_iter().collect::<Result<_, _>>()?;
    let (walk_us, walk_answers) = time_queries(points, |p| hal.contains_by_hierarchy(p));
    let as_option = |l: &Containment| match l {
        Containment::Inside => Some(true),
        Containment::Outside => Some(false),
        Containment::Boundary => None,
    };
    let (strip_us, strip_answers) = time_queries(points, |p| strip.contains(p));
    let (box_us, box_answers) = time_queries(points, |p| boxes.contains(p));
    let prefix = &points[..linear];
    let (brute_us, brute_answers) = time_queries(prefix, |p| contains_brute(polygon, p));
    let (geo_us, geo_answers) =
        time_queries(prefix, |p| geo_polygon.contains(&Point::new(p.x, p.y)));
    for (k, brute) in brute_answers.iter().enumerate() {
        let brute = brute.as_ref().map_err(|e| anyhow::anyhow!("{e}"))?;
        if *brute != hal_answers[k] {
            bail!(
                "{name}: HAL says {:?}, brute force {brute:?} at {}",
                hal_answers[k],
                points[k]
            );
        }
        if *brute != Containment::Boundary && geo_answers[k] != (*brute == Containment::Inside) {
            bail!("{name}: geo disagrees with brute force at {}", points[k]);
        }
    }
    for (k, hal_answer) in hal_answers.iter().enumerate() {
        let expected = as_option(hal_answer);
        let walk = walk_answers[k]
            .as_ref()
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        if walk != hal_answer || strip_answers[k] != expected || box_answers[k] != expected {
            bail!(
                "{name}: the hierarchy, strip or box tree disagrees with HAL at {}",
                points[k]
            );
        }
    }
    Ok([
        (hal_us, points.len(), hal_build),
        (walk_us, points.len(), hal_build),
        (strip_us, points.len(), strip_build),
        (box_us, points.len(), box_build),
        (brute_us, linear, 0.0),
        (geo_us, linear, 0.0),
    ])
}

/// `hal_vs_strip_tree`.
fn strip_tree(outlines: &[(String, Polyline2)], out: &Path) -> Result<()> {
    let chosen = ["polygons/netherlands.txt", "polygons/norway.txt"];
    let names = ["HAL lenses", "strips (Ballard)", "boxes"];
    let mut rows = Vec::new();
    let mut panels_data = Vec::new();
    for (name, polygon) in outlines
        .iter()
        .filter(|(n, _)| chosen.contains(&n.as_str()))
    {
        let hal = HalTree2::build(polygon)?;
        let strip = StripTree::build(&hal);
        let boxes = EdgeBoxTree::build(polygon).context("box tree")?;
        let (lo, hi) = polygon.bounds();
        let box_area = (hi - lo).x * (hi - lo).y;
        let mut series: Vec<Series> = names.iter().map(|n| Series::new(n)).collect();
        for depth in 1..=DEPTHS {
            let mut hal_area = 0.0;
            let mut unbounded = 0;
            let mut hal_count = 0;
            for node in hal.nodes().iter().filter(|n| n.level == depth) {
                hal_count += 1;
                match node
                    .lens
                    .area(hal.point_at(node.first), hal.point_at(node.last))
                {
                    Some(a) if a.is_finite() => hal_area += a,
                    _ => unbounded += 1,
                }
            }
            let strips: Vec<_> = strip
                .strips()
                .iter()
                .filter(|s| s.depth + 1 == depth)
                .collect();
            let strip_area: f64 = strips.iter().map(|s| StripTree::area(s)).sum();
            let level_boxes = boxes.boxes_at(depth as usize);
            let boxes_area: f64 = level_boxes
                .iter()
                .map(|b| (b.max.x - b.min.x) * (b.max.y - b.min.y))
                .sum();
            let values = [
                (hal_area, hal_count),
                (strip_area, strips.len()),
                (boxes_area, level_boxes.len()),
            ];
            for (i, &(area, count)) in values.iter().enumerate() {
                if count == 0 {
                    continue;
                }
                let pct = 100.0 * area / box_area;
                series[i].points.push((f64::from(depth), pct));
                rows.push(vec![
                    name.clone(),
                    names[i].into(),
                    depth.to_string(),
                    count.to_string(),
                    format!("{pct:.6}"),
                    if i == 0 {
                        unbounded.to_string()
                    } else {
                        "0".into()
                    },
                ]);
            }
        }
        panels_data.push((
            format!("{name} ({} vertices)", polygon.points().len()),
            series
                .into_iter()
                .enumerate()
                .map(|(i, s)| StyledSeries::new(s, style(i, Marker::Circle, true)))
                .collect::<Vec<_>>(),
        ));
    }
    if panels_data.is_empty() {
        bail!("no outline found for hal_vs_strip_tree");
    }
    write_csv(
        &out.join("hal_vs_strip_tree.csv"),
        &[
            "polygon",
            "structure",
            "depth",
            "volumes",
            "area_pct_bbox",
            "unbounded",
        ],
        &rows,
    )?;
    let panels = panels(
        &panels_data,
        "depth",
        "total area of the bounding volumes, % of the bounding box",
        &XAxis::Integers(0.5..f64::from(DEPTHS) + 0.5),
    );
    let legend: Vec<LegendEntry> = names
        .iter()
        .enumerate()
        .map(|(i, n)| LegendEntry {
            label: (*n).to_owned(),
            style: style(i, Marker::Circle, true),
        })
        .collect();
    titled_panels(
        &out.join("hal_vs_strip_tree.svg"),
        "Localization per depth: HAL lenses against Ballard's strips and axis-aligned boxes",
        &panels,
        &legend,
    )
}
