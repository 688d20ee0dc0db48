//! `hal_multipolygon_speed`: point inclusion in real multipolygons (countries with their
//! islands and holes, `tests/data/countries` in the repository), the HAL trees over every
//! ring against brute force over every edge and `geo`'s `Contains` of a `MultiPolygon`, in
//! the same run, one thread; every answer checked against brute force.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use geo::{Contains, LineString, MultiPolygon, Point, Polygon};
use sphaera::hal::{Containment, HalMultiPolygon2, MultiPolygon2};
use sphaera::mesh::glam::DVec2;
use sphaera::mesh::io::{FilePolicy, read_shapes};
use sphaera_tests::random::SplitMix64;

use super::{QUERIES, SEED, style, time_queries};
use crate::chart::{
    ChartSpec, LegendEntry, Marker, Series, StyledPanel, StyledSeries, XAxis, titled_panels,
    write_csv,
};

/// The countries, in `tests/data/countries`.
pub const COUNTRIES: &[&str] = &[
    "san-marino",
    "lesotho",
    "south-africa",
    "italy",
    "indonesia",
];

/// The folder of the country files.
fn folder() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/countries")
}

/// A country as HAL's multipolygon (degenerate rings dropped) and as geo's.
fn read(name: &str) -> Result<(MultiPolygon2, MultiPolygon<f64>)> {
    let path = folder().join(format!("{name}.geojson"));
    let shapes = read_shapes(&path, &FilePolicy::default())
        .with_context(|| format!("reading {}", path.display()))?;
    let (multi, _) = MultiPolygon2::from_rings_dropping_degenerate(shapes.polygons)?;
    let ring =
        |points: &[DVec2]| LineString::from(points.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>());
    let geo = MultiPolygon::new(
        multi
            .polygons()
            .iter()
            .map(|p| {
                Polygon::new(
                    ring(p.exterior().points()),
                    p.holes().iter().map(|h| ring(h.points())).collect(),
                )
            })
            .collect(),
    );
    Ok((multi, geo))
}

/// Runs the measurement and writes `hal_multipolygon_speed.{csv,svg}`.
pub fn multipolygon_speed(out: &Path) -> Result<()> {
    let methods = ["HAL multipolygon", "brute force", "geo contains"];
    let mut series: Vec<Series> = methods.iter().map(|m| Series::new(m)).collect();
    let mut rows = Vec::new();
    for name in COUNTRIES {
        let (multi, geo) = read(name)?;
        let (lo, hi) = multi.bounds();
        let mut rng = SplitMix64::new(SEED);
        let points: Vec<DVec2> = (0..QUERIES)
            .map(|_| DVec2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y)))
            .collect();
        let started = Instant::now();
        let tree = HalMultiPolygon2::build(&multi)?;
        let build = started.elapsed().as_secs_f64();
        let (hal_us, hal) = time_queries(&points, |p| tree.contains(p));
        let prefix = &points[..QUERIES.min(2_000)];
        let (brute_us, brute) = time_queries(prefix, |p| multi.contains_brute(p));
        let (geo_us, geo_answers) = time_queries(prefix, |p| geo.contains(&Point::new(p.x, p.y)));
        for (k, expected) in brute.iter().enumerate() {
            if hal[k] != *expected {
                bail!(
                    "{name}: HAL says {:?}, brute force {expected:?} at {}",
                    hal[k],
                    prefix[k]
                );
            }
            if *expected != Containment::Boundary
                && geo_answers[k] != (*expected == Containment::Inside)
            {
                bail!("{name}: geo disagrees with brute force at {}", prefix[k]);
            }
        }
        let vertices = multi.vertex_count();
        for (i, (us, queries, seconds)) in [
            (hal_us, points.len(), build),
            (brute_us, prefix.len(), 0.0),
            (geo_us, prefix.len(), 0.0),
        ]
        .into_iter()
        .enumerate()
        {
            series[i].points.push((vertices as f64, us));
            rows.push(vec![
                (*name).to_owned(),
                multi.polygons().len().to_string(),
                multi.ring_count().to_string(),
                vertices.to_string(),
                methods[i].to_owned(),
                format!("{seconds:.6}"),
                queries.to_string(),
                format!("{us:.4}"),
            ]);
        }
        eprintln!(
            "{name:<14} {:>4} rings {vertices:>7} vertices  µs/query: HAL {hal_us:.3} (build {:.1} ms), brute {brute_us:.2}, geo {geo_us:.2}",
            multi.ring_count(),
            1e3 * build
        );
    }
    write_csv(
        &out.join("hal_multipolygon_speed.csv"),
        &[
            "country",
            "polygons",
            "rings",
            "vertices",
            "method",
            "build_seconds",
            "queries",
            "microseconds_per_query",
        ],
        &rows,
    )?;
    let markers = [Marker::Circle, Marker::Square, Marker::Triangle];
    let styled: Vec<StyledSeries> = series
        .into_iter()
        .enumerate()
        .map(|(i, s)| StyledSeries::new(s, style(i, markers[i], true)))
        .collect();
    let legend: Vec<LegendEntry> = methods
        .iter()
        .enumerate()
        .map(|(i, m)| LegendEntry {
            label: (*m).to_owned(),
            style: style(i, markers[i], true),
        })
        .collect();
    let panel = StyledPanel {
        spec: ChartSpec {
            title: "countries with their islands and holes, random points in the bounding box",
            x_label: "vertices of every ring",
            y_label: "microseconds per query (one thread)",
        },
        x_axis: XAxis::Log,
        series: &styled,
        notes: &[],
    };
    titled_panels(
        &out.join("hal_multipolygon_speed.svg"),
        "Point inclusion in multipolygons: HAL trees per ring against brute force and geo (same run)",
        &[panel],
        &legend,
    )
}
