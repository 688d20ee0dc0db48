//! `sphaera medial`: the adaptive medial-axis approximation of a mesh.
//!
//! The medial spheres cover the surface samples they were built from. By default the set
//! is then certified to cover the whole surface (`sphaera_spheretree::cover`, as every
//! sphere-tree level is): the few spheres that must grow to close the gaps between
//! samples are grown, and their errors and covered samples are measured again.
//! `--samples-only` skips that and keeps the samples guarantee.

use std::io::Write;
use std::time::Instant;

use anyhow::{Context, Result};
use serde::Serialize;
use sphaera::{
    medial::{
        CoverCriterion, MedialApproximation, MedialOptions, MedialProgress, SphereKind, Surface,
    },
    mesh::{DVec3, Sphere, io::write_atomic, sampling},
    spheretree::{CoverageCertificate, SphereTreeOptions, cover::certify_coverage},
};

use crate::{
    cli::{CoverArg, MedialArgs},
    input::read_mesh,
    output::{check_target, print_report, thousands},
    progress,
};

/// The sphere count improved to when neither `--spheres` nor `--max-error` is given.
const DEFAULT_SPHERES: usize = 500;

/// The containment tolerance when samples are counted, relative to the diagonal (the
/// medial approximation's own: forming points lie on their spheres up to rounding).
const COVER_TOLERANCE: f64 = 1e-9;

/// Which part of the surface the spheres are guaranteed to cover.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
enum Coverage {
    /// Every point of every triangle, certified piece by piece.
    Surface,
    /// The surface samples only (`--samples-only`); gaps between samples may remain.
    Samples,
}

/// The surface certificate: what the sphere-tree's `certify_coverage` did, at which
/// resolution.
#[derive(Debug, Clone, Copy, Serialize)]
struct Certificate {
    /// Triangle pieces found inside a single sphere.
    pieces: usize,
    /// Spheres grown to contain a piece no sphere contained.
    grown_spheres: usize,
    /// The largest radius growth (absolute).
    largest_growth: f64,
    /// The largest growth as a fraction of the bounding-box diagonal.
    largest_growth_relative: f64,
    /// Pieces are split until their longest edge is at most this (absolute; 1e-3 of the
    /// diagonal, the sphere-tree's default).
    resolution: f64,
}

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
    /// The worst error of the spheres as written (grown by the certificate).
    worst_error: f64,
    /// The worst error as a fraction of the bounding-box diagonal.
    worst_error_relative: f64,
    /// The worst error of the medial spheres before the certificate grew any, which is
    /// what `--max-error` bounds (`worst_error` with `--samples-only`).
    medial_worst_error: f64,
    /// The resolved `--max-error` target (text report only).
    #[serde(skip)]
    max_error: Option<f64>,
    mean_error: f64,
    /// Samples no sphere covers (0 for the adaptive method, and whenever the surface is
    /// certified).
    uncovered_samples: usize,
    /// `surface`: every point of the surface is inside some sphere, certified (see
    /// `certificate`); `samples`: only the surface samples are (`--samples-only`).
    coverage: Coverage,
    /// The surface certificate (`null` with `--samples-only`).
    certificate: Option<Certificate>,
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
    /// Certifying coverage of the surface, growing spheres and measuring them again (0
    /// with `--samples-only`).
    certify: f64,
}

/// One sphere in the `-o` file.
#[derive(Debug, Serialize)]
struct SphereRecord {
    centre: [f64; 3],
    /// The radius, grown when the certificate needed it.
    radius: f64,
    /// The eq. 2 error of the sphere as written (with its grown radius).
    error: f64,
    kind: SphereKind,
    /// Samples within the sphere as written.
    covered_samples: usize,
    /// How much the certificate grew the radius (0 for most spheres).
    growth: f64,
}

/// The `-o` file.
#[derive(Debug, Serialize)]
struct SphereFile<'a> {
    mesh: &'a str,
    worst_error: f64,
    coverage: Coverage,
    certificate: Option<Certificate>,
    spheres: Vec<SphereRecord>,
}

/// A sphere of the final set: the medial sphere, grown if the certificate needed it.
#[derive(Debug, Clone)]
struct FinalSphere {
    centre: DVec3,
    radius: f64,
    error: f64,
    kind: SphereKind,
    covered_samples: usize,
    growth: f64,
}

pub fn run(args: &MedialArgs, quiet: bool) -> Result<()> {
    if let Some(path) = &args.output {
        check_target(path)?;
    }
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

    let mut spheres = final_spheres(&medial);
    let medial_worst_error = worst_error(&spheres);
    let mut uncovered = medial.uncovered_samples();
    let started = Instant::now();
    let certificate = if args.samples_only {
        None
    } else {
        let spinner = progress::spinner(quiet, "certifying coverage of the whole surface");
        let resolution = SphereTreeOptions::default()
            .coverage_resolution
            .resolve(diagonal);
        let found = certify(&surface, &samples, &mut spheres, &mut uncovered, resolution);
        spinner.finish_and_clear();
        Some(Certificate {
            pieces: found.pieces,
            grown_spheres: found.grown_spheres,
            largest_growth: found.largest_growth,
            largest_growth_relative: relative(found.largest_growth, diagonal),
            resolution,
        })
    };
    let certify_seconds = started.elapsed().as_secs_f64();
    let coverage = if certificate.is_some() {
        Coverage::Surface
    } else {
        Coverage::Samples
    };

    let worst_error = worst_error(&spheres);
    if let Some(path) = &args.output {
        let file = SphereFile {
            mesh: &input.source,
            worst_error,
            coverage,
            certificate,
            spheres: spheres
                .iter()
                .map(|s| SphereRecord {
                    centre: s.centre.to_array(),
                    radius: s.radius,
                    error: s.error,
                    kind: s.kind,
                    covered_samples: s.covered_samples,
                    growth: s.growth,
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
        worst_error,
        worst_error_relative: relative(worst_error, diagonal),
        medial_worst_error,
        max_error: options.max_error,
        mean_error: if spheres.is_empty() {
            0.0
        } else {
            spheres.iter().map(|s| s.error).sum::<f64>() / spheres.len() as f64
        },
        uncovered_samples: uncovered.len(),
        coverage,
        certificate,
        improvements: stats.improvements,
        coverage_insertions: stats.coverage_insertions,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds {
            load: input.seconds,
            prepare: prepare_seconds,
            medial: medial_seconds,
            certify: certify_seconds,
        },
    };
    print_report(&report, args.print.json)
}

/// The spheres of the set, before any growth.
fn final_spheres(medial: &MedialApproximation<'_>) -> Vec<FinalSphere> {
    medial
        .spheres()
        .into_iter()
        .map(|s| FinalSphere {
            centre: s.centre,
            radius: s.radius,
            error: s.error,
            kind: s.kind,
            covered_samples: s.covers.len(),
            growth: 0.0,
        })
        .collect()
}

/// The largest error of `spheres` (0 for none).
fn worst_error(spheres: &[FinalSphere]) -> f64 {
    spheres.iter().map(|s| s.error).fold(0.0, f64::max)
}

/// `length` as a fraction of `diagonal` (0 for a degenerate diagonal).
fn relative(length: f64, diagonal: f64) -> f64 {
    if diagonal > 0.0 {
        length / diagonal
    } else {
        0.0
    }
}

/// Certifies that `spheres` cover the whole surface (the sphere-tree's `certify_coverage`
/// at `resolution`), growing the few that must grow. A grown sphere keeps its centre; its
/// error is measured again the way the medial approximation measures it (eq. 2: `r − d`
/// for a centre inside, `r + d` outside, `d` the distance from the centre to the
/// surface), its covered samples are counted again, and the samples it now covers leave
/// `uncovered`.
fn certify(
    surface: &Surface,
    samples: &[DVec3],
    spheres: &mut [FinalSphere],
    uncovered: &mut Vec<u32>,
    resolution: f64,
) -> CoverageCertificate {
    let mut balls: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere::new(s.centre, s.radius))
        .collect();
    let (certificate, growth) = certify_coverage(surface.mesh(), &mut balls, resolution);
    let tolerance = COVER_TOLERANCE * surface.diagonal();
    for ((sphere, ball), g) in spheres.iter_mut().zip(&balls).zip(growth) {
        if g <= 0.0 {
            continue;
        }
        sphere.radius = ball.radius;
        sphere.growth = g;
        sphere.error = eq2_error(surface, sphere.centre, sphere.radius);
        let within = |p: &DVec3| p.distance(sphere.centre) <= sphere.radius + tolerance;
        sphere.covered_samples = samples.iter().filter(|p| within(p)).count();
        uncovered.retain(|&i| !samples.get(i as usize).is_some_and(within));
    }
    certificate
}

/// The eq. 2 error of the sphere `(centre, radius)`, as `sphaera-medial` measures it.
fn eq2_error(surface: &Surface, centre: DVec3, radius: f64) -> f64 {
    let Ok(closest) = surface.closest(centre) else {
        return f64::INFINITY;
    };
    let error = if surface.is_inside(centre) {
        radius - closest.distance
    } else {
        radius + closest.distance
    };
    error.max(0.0)
}

impl crate::output::Report for Report {
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
                "worst error     {:.6e} ({:.4} % of the diagonal); mean {:.6e}{}",
                self.worst_error,
                100.0 * self.worst_error_relative,
                self.mean_error,
                if self.worst_error > self.medial_worst_error {
                    format!(
                        "; {:.6e} before the certificate's growth",
                        self.medial_worst_error
                    )
                } else {
                    String::new()
                }
            ),
        ];
        if self.max_error.is_some_and(|e| self.worst_error > e) {
            lines.push(
                "                above --max-error by the certificate's growth (more --samples \
                 shrink it; --samples-only skips it)"
                    .to_owned(),
            );
        }
        lines.extend([
            format!(
                "uncovered       {} samples",
                thousands(self.uncovered_samples)
            ),
            match &self.certificate {
                Some(c) => format!(
                    "coverage        the whole surface, certified: {} triangle pieces, {} spheres grown, \
                     largest growth {:.3e} ({:.4} % of the diagonal)",
                    thousands(c.pieces),
                    thousands(c.grown_spheres),
                    c.largest_growth,
                    100.0 * c.largest_growth_relative
                ),
                None => "coverage        the surface samples only (--samples-only): \
                         the surface between them may lie outside every sphere"
                    .to_owned(),
            },
            format!(
                "work            {} improvements, {} coverage insertions",
                thousands(self.improvements),
                thousands(self.coverage_insertions)
            ),
        ]);
        if let Some(path) = &self.output {
            lines.push(format!("written         {path}"));
        }
        lines.push(format!(
            "time            {:.3} s load, {:.3} s prepare, {:.3} s medial, {:.3} s certify",
            self.seconds.load, self.seconds.prepare, self.seconds.medial, self.seconds.certify
        ));
        lines.join("\n") + "\n"
    }
}
