//! `sphaera distance`: exact (or certified approximate) closest points on a mesh.
//!
//! Both come from the triangle tree (the fastest engine we have, and no hierarchy to
//! build): exact answers on every core, certified intervals to a `--tolerance` from a
//! descent that skips what cannot bring the distance down by more than the tolerance.

use std::{path::Path, time::Instant};

use anyhow::{Context, Result, bail};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use sphaera::{
    mesh::{DVec3, TriMesh, closest::TriangleTree},
    sweep::Feature,
};

use crate::{
    cli::DistanceArgs,
    input::read_mesh,
    output::{print_report, thousands},
    progress,
};

/// Points queried when neither `--points` nor `--random` is given.
const DEFAULT_RANDOM: usize = 1000;

/// Answers listed in the text output (JSON lists them all).
const TEXT_ANSWERS: usize = 10;

/// Everything `sphaera distance` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    /// The mesh file, or `<embedded bunny_lowres.obj>`.
    source: String,
    /// `--points FILE`, or `random N (seed S)`.
    queries_from: String,
    triangles: usize,
    /// `triangle tree` (exact answers) or `triangle tree, approximate` (certified
    /// intervals at most `--tolerance` wide), both on every core.
    engine: &'static str,
    /// The `--tolerance` in mesh units (`null`: exact answers).
    tolerance: Option<f64>,
    /// One answer per query point, in input order.
    answers: Vec<Answer>,
    /// The smallest, largest and mean distance (interval midpoints when approximate).
    min_distance: f64,
    max_distance: f64,
    mean_distance: f64,
    queries_per_second: f64,
    seconds: Seconds,
}

/// One query's answer.
#[derive(Debug, Serialize)]
struct Answer {
    query: [f64; 3],
    /// The certified interval (equal ends when exact).
    lower: f64,
    upper: f64,
    /// The point of the mesh at distance `upper` (the closest point when exact), its
    /// input triangle and feature.
    point: Option<[f64; 3]>,
    triangle: Option<u32>,
    /// `vertex V`, `edge A B` or `face`.
    feature: Option<String>,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    /// Building the triangle tree, once per mesh.
    build: f64,
    queries: f64,
}

pub fn run(args: &DistanceArgs, quiet: bool) -> Result<()> {
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = &input.loaded.mesh;
    let (points, queries_from) = match &args.points {
        Some(path) => (read_points(path)?, format!("{}", path.display())),
        None => {
            let n = args.random.unwrap_or(DEFAULT_RANDOM);
            (
                random_points(mesh, n, args.seed),
                format!("random {n} (seed {})", args.seed),
            )
        }
    };
    let diagonal = mesh.bounding_box_diagonal();
    let tolerance = args.tolerance.map(|t| t.resolve(diagonal));

    let built = answer(mesh, &points, tolerance, quiet)?;
    let middles: Vec<f64> = built
        .answers
        .iter()
        .map(|a| 0.5 * (a.lower + a.upper))
        .collect();
    let answers = built.answers;
    let report = Report {
        source: input.source,
        queries_from,
        triangles: mesh.triangle_count(),
        engine: built.engine,
        tolerance,
        min_distance: middles.iter().copied().fold(f64::INFINITY, f64::min),
        max_distance: middles.iter().copied().fold(0.0, f64::max),
        mean_distance: middles.iter().sum::<f64>() / middles.len().max(1) as f64,
        queries_per_second: if built.query_seconds > 0.0 {
            answers.len() as f64 / built.query_seconds
        } else {
            0.0
        },
        answers,
        seconds: Seconds {
            load: input.seconds,
            build: built.build_seconds,
            queries: built.query_seconds,
        },
    };
    print_report(&report, args.print.json)
}

/// The answers of one engine and what it cost.
struct Built {
    engine: &'static str,
    answers: Vec<Answer>,
    build_seconds: f64,
    query_seconds: f64,
}

/// Exact answers (on every core), or certified intervals at most `tolerance` wide, from
/// the triangle tree.
fn answer(mesh: &TriMesh, points: &[DVec3], tolerance: Option<f64>, quiet: bool) -> Result<Built> {
    let spinner = progress::spinner(
        quiet,
        &format!(
            "building the tree of {} triangles",
            thousands(mesh.triangle_count())
        ),
    );
    let started = Instant::now();
    let tree = TriangleTree::new(mesh);
    let build_seconds = started.elapsed().as_secs_f64();
    spinner.finish_and_clear();
    let tree = tree?;
    let spinner = progress::spinner(
        quiet,
        &format!("querying {} points", thousands(points.len())),
    );
    let started = Instant::now();
    let (engine, answers) = match tolerance {
        None => {
            let closest = tree.closest_many(points);
            let answers = points
                .iter()
                .zip(closest?)
                .map(|(p, c)| Answer {
                    query: p.to_array(),
                    lower: c.distance,
                    upper: c.distance,
                    point: Some(c.point.to_array()),
                    triangle: Some(c.triangle),
                    feature: Some(feature_name(c.feature)),
                })
                .collect();
            ("triangle tree", answers)
        }
        Some(t) => {
            let answers = points
                .iter()
                .zip(tree.closest_approx_many(points, t)?)
                .map(|(p, a)| Answer {
                    query: p.to_array(),
                    lower: a.lower,
                    upper: a.upper,
                    point: Some(a.nearest.point.to_array()),
                    triangle: Some(a.nearest.triangle),
                    feature: Some(feature_name(a.nearest.feature)),
                })
                .collect();
            ("triangle tree, approximate", answers)
        }
    };
    let query_seconds = started.elapsed().as_secs_f64();
    spinner.finish_and_clear();
    Ok(Built {
        engine,
        answers,
        build_seconds,
        query_seconds,
    })
}

/// `vertex 12`, `edge 3 7` or `face`.
fn feature_name(feature: Feature) -> String {
    match feature {
        Feature::Vertex(v) => format!("vertex {v}"),
        Feature::Edge(a, b) => format!("edge {a} {b}"),
        Feature::Face => "face".to_owned(),
    }
}

/// `n` points uniform in the bounding box of `mesh` scaled 1.5x about its centre.
fn random_points(mesh: &TriMesh, n: usize, seed: u64) -> Vec<DVec3> {
    let bounds = mesh.bounding_box();
    let center = 0.5 * (bounds.min + bounds.max);
    let half = 0.75 * (bounds.max - bounds.min);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let u = DVec3::new(
                rng.random::<f64>(),
                rng.random::<f64>(),
                rng.random::<f64>(),
            );
            center + half * (2.0 * u - DVec3::ONE)
        })
        .collect()
}

/// The points of a text file: one `x y z` per line, separated by spaces or commas; blank
/// lines and `#` comments are skipped.
fn read_points(path: &Path) -> Result<Vec<DVec3>> {
    let text = crate::input::read_text(path, "the points file")?;
    parse_points(&text).with_context(|| format!("in {}", path.display()))
}

fn parse_points(text: &str) -> Result<Vec<DVec3>> {
    let mut points = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let values: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        if values.len() != 3 {
            bail!(
                "line {}: expected 3 coordinates, found {}",
                i + 1,
                values.len()
            );
        }
        let mut xyz = [0.0; 3];
        for (slot, value) in xyz.iter_mut().zip(&values) {
            *slot = value
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .with_context(|| format!("line {}: `{value}` is not a finite number", i + 1))?;
        }
        points.push(DVec3::from_array(xyz));
    }
    if points.is_empty() {
        bail!("no points (one `x y z` per line)");
    }
    Ok(points)
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![
            format!("mesh            {}", self.source),
            format!(
                "triangles       {}, {}",
                thousands(self.triangles),
                self.engine
            ),
            format!(
                "queries         {} from {}",
                thousands(self.answers.len()),
                self.queries_from
            ),
            match self.tolerance {
                Some(t) => format!("answers         certified intervals at most {t:.3e} wide"),
                None => "answers         exact".to_owned(),
            },
            format!(
                "distance        min {:.6e}, mean {:.6e}, max {:.6e}",
                self.min_distance, self.mean_distance, self.max_distance
            ),
            format!(
                "time            {:.3} s to read, {:.3} s to build the tree, {:.3} s for the \
                 queries ({:.0} per second)",
                self.seconds.load,
                self.seconds.build,
                self.seconds.queries,
                self.queries_per_second
            ),
        ];
        for a in self.answers.iter().take(TEXT_ANSWERS) {
            let [x, y, z] = a.query;
            lines.push(match (a.point, a.triangle, &a.feature) {
                (Some([px, py, pz]), Some(t), Some(f)) => format!(
                    "  ({x:.4}, {y:.4}, {z:.4}) -> {:.6e} at ({px:.4}, {py:.4}, {pz:.4}), \
                     triangle {t}, {f}",
                    a.lower
                ),
                _ => format!(
                    "  ({x:.4}, {y:.4}, {z:.4}) -> [{:.6e}, {:.6e}]",
                    a.lower, a.upper
                ),
            });
        }
        if self.answers.len() > TEXT_ANSWERS {
            lines.push(format!(
                "  ... {} more (all with --json)",
                thousands(self.answers.len() - TEXT_ANSWERS)
            ));
        }
        lines.join("\n") + "\n"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_parse_with_spaces_commas_and_comments() {
        let points = parse_points("# header\n1 2 3\n\n4,5,6 # fourth\n 7 , 8 9\n").unwrap();
        assert_eq!(
            points,
            vec![
                DVec3::new(1.0, 2.0, 3.0),
                DVec3::new(4.0, 5.0, 6.0),
                DVec3::new(7.0, 8.0, 9.0)
            ]
        );
    }

    #[test]
    fn malformed_points_are_errors_with_the_line() {
        let error = parse_points("1 2 3\n1 2\n").unwrap_err();
        assert!(error.to_string().contains("line 2"), "{error}");
        let error = parse_points("1 2 nan\n").unwrap_err();
        assert!(error.to_string().contains("not a finite number"), "{error}");
        assert!(parse_points("# nothing\n").is_err());
    }

    #[test]
    fn random_points_are_seeded_and_in_the_scaled_box() {
        let mesh = sphaera::mesh::shapes::cube(2.0, 2).unwrap();
        let a = random_points(&mesh, 100, 7);
        assert_eq!(a, random_points(&mesh, 100, 7));
        assert!(a.iter().all(|p| p.abs().max_element() <= 1.5));
    }
}
