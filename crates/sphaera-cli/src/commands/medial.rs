//! `sphaera medial`: the adaptive medial-axis approximation of a mesh.

use std::io::Write;
use std::time::Instant;

use anyhow::{Context, Result};
use serde::Serialize;
use sphaera::{
    medial::{
        CoverCriterion, MedialApproximation, MedialOptions, MedialProgress, SphereKind, Surface,
    },
    mesh::{DVec3, io::write_atomic, sampling},
};

use crate::{
    cli::{CoverArg, MedialArgs},
    input::read_mesh,
    output::{print_json, thousands},
    progress,
};

/// The sphere count improved to when neither `--spheres` nor `--max-error` is given.
const DEFAULT_SPHERES: usize = 500;

/// Everything `sphaera medial` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    /// `adaptive` or `static`.
    method: &'static str,
    samples: usize,
    /// The improvement target: `spheres N` or `max-error E` (absolute).
    target: String,
    spheres: usize,
    internal_spheres: usize,
    cover_spheres: usize,
    /// Forming points of the Voronoi diagram at the end.
    forming_points: usize,
    worst_error: f64,
    /// The worst error as a fraction of the bounding-box diagonal.
    worst_error_relative: f64,
    mean_error: f64,
    /// Samples no sphere covers (0 for the adaptive method).
    uncovered_samples: usize,
    improvements: usize,
    coverage_insertions: usize,
    output: Option<String>,
    seconds: Seconds,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    /// Sampling the surface, the closest-point tree and the inside test.
    prepare: f64,
    /// The medial approximation itself.
    medial: f64,
}

/// One sphere in the `-o` file.
#[derive(Debug, Serialize)]
struct SphereRecord {
    centre: [f64; 3],
    radius: f64,
    error: f64,
    kind: SphereKind,
    covered_samples: usize,
}

/// The `-o` file.
#[derive(Debug, Serialize)]
struct SphereFile<'a> {
    mesh: &'a str,
    worst_error: f64,
    spheres: Vec<SphereRecord>,
}

pub fn run(args: &MedialArgs, quiet: bool) -> Result<()> {
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = &input.loaded.mesh;
    anyhow::ensure!(
        args.samples >= 4,
        "--samples {}: at least 4 are needed",
        args.samples
    );

    let spinner = progress::spinner(quiet, "sampling the surface, preparing distance queries");
    let started = Instant::now();
    let prepared = sampling::poisson_disk(mesh, args.samples, args.seed)
        .map_err(anyhow::Error::from)
        .and_then(|poisson| {
            let surface = Surface::new(mesh).with_context(|| {
                format!("{} cannot be approximated by medial spheres", input.source)
            })?;
            Ok((poisson, surface))
        });
    spinner.finish_and_clear();
    let (poisson, surface) = prepared?;
    let samples: Vec<DVec3> = poisson.samples.iter().map(|s| s.position).collect();
    let prepare_seconds = started.elapsed().as_secs_f64();

    let diagonal = surface.diagonal();
    let cover = match args.cover {
        CoverArg::SmallestError => CoverCriterion::SmallestError,
        CoverArg::LargestCoverage => CoverCriterion::LargestCoverage,
    };
    let mut options = MedialOptions::default().with_cover(cover);
    let target = match (args.spheres, args.max_error) {
        _ if args.static_points.is_some() => format!(
            "{} forming points, no improvement",
            args.static_points.unwrap_or_default()
        ),
        (_, Some(error)) => {
            let e = error.resolve(diagonal);
            options = options.with_max_error(e);
            format!("max-error {e:.6e}")
        }
        (spheres, None) => {
            let n = spheres.unwrap_or(DEFAULT_SPHERES);
            options = options.with_target_spheres(n);
            format!("spheres {n}")
        }
    };

    let started = Instant::now();
    let (medial, method) = if let Some(points) = args.static_points {
        let spinner = progress::spinner(quiet, "static medial approximation");
        let medial = MedialApproximation::build_static(&surface, &samples, points, None);
        spinner.finish_and_clear();
        (medial?, "static")
    } else {
        let bar = match options.target_spheres {
            Some(n) => progress::bar(quiet, "improving the medial spheres", n as u64),
            None => progress::spinner(quiet, "improving the medial spheres"),
        };
        let report = |p: &MedialProgress| {
            bar.set_position(p.spheres as u64);
            bar.set_message(format!(
                "improving the medial spheres: {} spheres, worst error {:.3e}",
                thousands(p.spheres),
                p.worst_error
            ));
        };
        let medial =
            MedialApproximation::build_with_progress(&surface, &samples, &options, &report);
        bar.finish_and_clear();
        (medial?, "adaptive")
    };
    let medial_seconds = started.elapsed().as_secs_f64();

    let spheres = medial.spheres();
    if let Some(path) = &args.output {
        let file = SphereFile {
            mesh: &input.source,
            worst_error: medial.worst_error(),
            spheres: spheres
                .iter()
                .map(|s| SphereRecord {
                    centre: s.centre.to_array(),
                    radius: s.radius,
                    error: s.error,
                    kind: s.kind,
                    covered_samples: s.covers.len(),
                })
                .collect(),
        };
        write_atomic(path, |w| {
            serde_json::to_writer_pretty(&mut *w, &file).map_err(std::io::Error::other)?;
            w.write_all(b"\n")
        })
        .with_context(|| format!("cannot write {}", path.display()))?;
    }

    let stats = medial.stats();
    let count = |kind| spheres.iter().filter(|s| s.kind == kind).count();
    let report = Report {
        mesh: input.source.clone(),
        triangles: mesh.triangle_count(),
        method,
        samples: samples.len(),
        target,
        spheres: spheres.len(),
        internal_spheres: count(SphereKind::Internal),
        cover_spheres: count(SphereKind::Cover),
        forming_points: medial.delaunay().vertex_count(),
        worst_error: medial.worst_error(),
        worst_error_relative: if diagonal > 0.0 {
            medial.worst_error() / diagonal
        } else {
            0.0
        },
        mean_error: if spheres.is_empty() {
            0.0
        } else {
            spheres.iter().map(|s| s.error).sum::<f64>() / spheres.len() as f64
        },
        uncovered_samples: medial.uncovered_samples().len(),
        improvements: stats.improvements,
        coverage_insertions: stats.coverage_insertions,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds {
            load: input.seconds,
            prepare: prepare_seconds,
            medial: medial_seconds,
        },
    };
    if args.print.json {
        print_json(&report)
    } else {
        print!("{}", report.to_text());
        Ok(())
    }
}

impl Report {
    fn to_text(&self) -> String {
        let mut lines = vec![
            format!(
                "mesh            {} ({} triangles)",
                self.mesh,
                thousands(self.triangles)
            ),
            format!(
                "method          {} ({}), {} surface samples",
                self.method,
                self.target,
                thousands(self.samples)
            ),
            format!(
                "spheres         {} ({} internal, {} cover) from {} forming points",
                thousands(self.spheres),
                thousands(self.internal_spheres),
                thousands(self.cover_spheres),
                thousands(self.forming_points)
            ),
            format!(
                "worst error     {:.6e} ({:.4} % of the diagonal); mean {:.6e}",
                self.worst_error,
                100.0 * self.worst_error_relative,
                self.mean_error
            ),
            format!(
                "uncovered       {} samples",
                thousands(self.uncovered_samples)
            ),
            format!(
                "work            {} improvements, {} coverage insertions",
                thousands(self.improvements),
                thousands(self.coverage_insertions)
            ),
        ];
        if let Some(path) = &self.output {
            lines.push(format!("written         {path}"));
        }
        lines.push(format!(
            "time            {:.3} s load, {:.3} s prepare, {:.3} s medial",
            self.seconds.load, self.seconds.prepare, self.seconds.medial
        ));
        lines.join("\n") + "\n"
    }
}
