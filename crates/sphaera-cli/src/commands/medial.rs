//! `sphaera medial`: spheres around a mesh from its medial axis.
//!
//! `--spheres N` gives exactly N spheres: the minimax cover, a one-level minimax
//! sphere-tree (`sphaera_spheretree::minimax`), whose centres are medial candidates moved
//! on the exact surface so that the worst sphere's error is least. It covers the whole
//! surface by construction (certified), solids and shells (flat sheets, open patches)
//! alike.
//!
//! Otherwise the paper's adaptive medial-axis approximation (`--medial-target M`, 500 by
//! default, or `--max-error`; `--static-points` for Hubbard's static baseline): medial
//! spheres that cover the surface samples they were built from, with at least M spheres
//! (cover spheres can add more). By default the set is then certified to cover the whole
//! surface (`sphaera_spheretree::cover`, as every sphere-tree level is): the few spheres
//! that must grow to close the gaps between samples are grown, and their errors and
//! covered samples are measured again. `--samples-only` skips that and keeps the samples
//! guarantee.

use std::io::Write;
use std::time::Instant;

use anyhow::{Context, Result};
use serde::Serialize;
use sphaera::{
    medial::{
        MedialApproximation, MedialOptions, MedialProgress, SphereKind, Surface, surface_eq2_error,
    },
    mesh::{DVec3, Sphere, io::write_atomic, sampling},
    spheretree::{CoverageCertificate, Method, SphereTreeOptions, build, cover::certify_coverage},
};

use super::spheretree::{SurfaceKind, check_sphere_count};
use crate::{
    cli::MedialArgs,
    input::{Input, read_mesh},
    output::{check_target, print_report, thousands},
    progress,
};

/// The sphere count the adaptive approximation improves to when neither
/// `--medial-target` nor `--max-error` is given.
const DEFAULT_MEDIAL_TARGET: usize = 500;

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
    /// diagonal, the sphere-tree's default; `null` for the minimax cover, certified as
    /// sphere-trees are, at 1e-3 of the diagonal of the mesh in its canonical pose).
    resolution: Option<f64>,
}

/// Everything `sphaera medial` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    /// `minimax` (`--spheres`), `adaptive` or `static`.
    method: &'static str,
    /// `solid`, or `shell` for a mesh without inside (`--spheres` only).
    surface: SurfaceKind,
    /// Surface samples (`null` for minimax, which works on the triangles themselves).
    samples: Option<usize>,
    /// The target: `spheres N` (exactly N), `medial-target M` (at least M) or
    /// `max-error E` (absolute).
    target: String,
    /// With `--spheres N`: N, which `spheres` equals.
    spheres_requested: Option<usize>,
    /// The spheres given.
    spheres: usize,
    internal_spheres: usize,
    cover_spheres: usize,
    /// Forming points of the Voronoi diagram at the end (`null` for minimax).
    forming_points: Option<usize>,
    /// The worst error of the spheres as written (grown by the certificate).
    worst_error: f64,
    /// The worst error as a fraction of the bounding-box diagonal.
    worst_error_relative: f64,
    /// The worst error of the medial spheres before the certificate grew any, which is
    /// what `--max-error` bounds (`worst_error` with `--samples-only`; `null` for
    /// minimax, whose errors are certified with any growth included).
    medial_worst_error: Option<f64>,
    /// The resolved `--max-error` target (text report only).
    #[serde(skip)]
    max_error: Option<f64>,
    mean_error: f64,
    /// Samples no sphere covers (0 for the adaptive method, and whenever the surface is
    /// certified; `null` for minimax, which draws no samples).
    uncovered_samples: Option<usize>,
    /// `surface`: every point of the surface is inside some sphere, certified (see
    /// `certificate`); `samples`: only the surface samples are (`--samples-only`).
    coverage: Coverage,
    /// The surface certificate (`null` with `--samples-only`).
    certificate: Option<Certificate>,
    /// The adaptive approximation's work (`null` for the others).
    improvements: Option<usize>,
    coverage_insertions: Option<usize>,
    output: Option<String>,
    seconds: Seconds,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    /// Sampling the surface, the closest-point tree and the inside test.
    prepare: f64,
    /// The medial approximation itself, or the minimax cover (its certificate included).
    medial: f64,
    /// Certifying coverage of the surface, growing spheres and measuring them again (0
    /// with `--samples-only`).
    certify: f64,
}

/// One sphere in the `-o` file.
#[derive(Debug, Serialize)]
struct SphereRecord {
    center: [f64; 3],
    /// The radius, grown when the certificate needed it.
    radius: f64,
    /// The eq. 2 error of the sphere as written (with its grown radius).
    error: f64,
    kind: Kind,
    /// Samples within the sphere as written (`null` for minimax).
    covered_samples: Option<usize>,
    /// How much the certificate grew the radius (0 for most spheres; `null` for minimax,
    /// whose errors include any growth).
    growth: Option<f64>,
}

/// Where a sphere of the `-o` file comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
enum Kind {
    /// The adaptive approximation's medial sphere (centred on an internal Voronoi vertex).
    Internal,
    /// The adaptive approximation's cover sphere (centred on an external Voronoi vertex).
    Cover,
    /// A sphere of the minimax cover.
    Minimax,
}

impl From<SphereKind> for Kind {
    fn from(kind: SphereKind) -> Self {
        match kind {
            SphereKind::Internal => Self::Internal,
            // External spheres are never part of the set.
            SphereKind::Cover | SphereKind::External => Self::Cover,
        }
    }
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
    center: DVec3,
    radius: f64,
    error: f64,
    kind: SphereKind,
    covered_samples: usize,
    growth: f64,
}

pub fn run(args: &MedialArgs, quiet: bool) -> Result<()> {
    if let Some(count) = args.spheres {
        check_sphere_count(count)?;
    }
    if let Some(path) = &args.output {
        check_target(path)?;
    }
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    if let Some(count) = args.spheres {
        return run_minimax(args, &input, count, quiet);
    }
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
            let surface = Surface::new(mesh).map_err(|error| {
                let hint = if matches!(error, sphaera::query::QueryError::NoInside { .. }) {
                    " (`--spheres N` covers a surface without inside)"
                } else {
                    ""
                };
                anyhow::Error::from(error).context(format!(
                    "{} cannot be approximated by medial spheres{hint}",
                    input.source
                ))
            })?;
            Ok((poisson, surface))
        });
    spinner.finish_and_clear();
    let (poisson, surface) = prepared?;
    let samples: Vec<DVec3> = poisson.samples.iter().map(|s| s.position).collect();
    let prepare_seconds = started.elapsed().as_secs_f64();

    let diagonal = surface.diagonal();
    let mut options = MedialOptions::default().with_cover(args.cover);
    let target = match (args.medial_target, args.max_error) {
        _ if args.static_points.is_some() => format!(
            "{} forming points, no improvement",
            args.static_points.unwrap_or_default()
        ),
        (_, Some(error)) => {
            let e = error.resolve(diagonal);
            options = options.with_max_error(e);
            format!("max-error {e:.6e}")
        }
        (target, None) => {
            let n = target.unwrap_or(DEFAULT_MEDIAL_TARGET);
            options = options.with_target_spheres(n);
            format!("medial-target {n}")
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
            resolution: Some(resolution),
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
        write_spheres(
            path,
            &SphereFile {
                mesh: &input.source,
                worst_error,
                coverage,
                certificate,
                spheres: spheres
                    .iter()
                    .map(|s| SphereRecord {
                        center: s.center.to_array(),
                        radius: s.radius,
                        error: s.error,
                        kind: s.kind.into(),
                        covered_samples: Some(s.covered_samples),
                        growth: Some(s.growth),
                    })
                    .collect(),
            },
        )?;
    }

    let stats = medial.stats();
    let count = |kind| spheres.iter().filter(|s| s.kind == kind).count();
    let report = Report {
        mesh: input.source.clone(),
        triangles: mesh.triangle_count(),
        method,
        surface: SurfaceKind::Solid,
        samples: Some(samples.len()),
        target,
        spheres_requested: None,
        spheres: spheres.len(),
        internal_spheres: count(SphereKind::Internal),
        cover_spheres: count(SphereKind::Cover),
        forming_points: Some(medial.delaunay().vertex_count()),
        worst_error,
        worst_error_relative: relative(worst_error, diagonal),
        medial_worst_error: Some(medial_worst_error),
        max_error: options.max_error,
        mean_error: if spheres.is_empty() {
            0.0
        } else {
            spheres.iter().map(|s| s.error).sum::<f64>() / spheres.len() as f64
        },
        uncovered_samples: Some(uncovered.len()),
        coverage,
        certificate,
        improvements: Some(stats.improvements),
        coverage_insertions: Some(stats.coverage_insertions),
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

/// `--spheres N`: exactly N spheres, the minimax cover (a one-level minimax sphere-tree
/// of N children), on the solid or, for a mesh without inside, the shell.
fn run_minimax(args: &MedialArgs, input: &Input, count: usize, quiet: bool) -> Result<()> {
    let mesh = &input.loaded.mesh;
    let spinner = progress::spinner(quiet, "preparing distance queries and the inside test");
    let started = Instant::now();
    let surface = Surface::solid_or_shell(mesh);
    spinner.finish_and_clear();
    let surface =
        surface.with_context(|| format!("{} cannot be covered by spheres", input.source))?;
    let prepare_seconds = started.elapsed().as_secs_f64();

    let spinner = progress::spinner(
        quiet,
        &format!("dividing the surface between {} spheres", thousands(count)),
    );
    let started = Instant::now();
    let options = SphereTreeOptions::default()
        .with_method(Method::Minimax)
        .with_depth(1)
        .with_branch(count);
    let tree = build(&surface, &options);
    spinner.finish_and_clear();
    let tree = tree.with_context(|| format!("cannot cover {} by spheres", input.source))?;
    let medial_seconds = started.elapsed().as_secs_f64();

    let nodes = tree.level(1);
    let diagonal = surface.diagonal();
    let worst_error = nodes.iter().map(|n| n.error).fold(0.0, f64::max);
    let certificate = tree.coverage().get(1).map(|c| Certificate {
        pieces: c.pieces,
        grown_spheres: c.grown_spheres,
        largest_growth: c.largest_growth,
        largest_growth_relative: relative(c.largest_growth, diagonal),
        resolution: None,
    });
    let coverage = Coverage::Surface;
    if let Some(path) = &args.output {
        write_spheres(
            path,
            &SphereFile {
                mesh: &input.source,
                worst_error,
                coverage,
                certificate,
                spheres: nodes
                    .iter()
                    .map(|n| SphereRecord {
                        center: n.sphere.center.to_array(),
                        radius: n.sphere.radius,
                        error: n.error,
                        kind: Kind::Minimax,
                        covered_samples: None,
                        growth: None,
                    })
                    .collect(),
            },
        )?;
    }
    let report = Report {
        mesh: input.source.clone(),
        triangles: mesh.triangle_count(),
        method: "minimax",
        surface: SurfaceKind::of(&surface),
        samples: None,
        target: format!("spheres {count}"),
        spheres_requested: Some(count),
        spheres: nodes.len(),
        internal_spheres: 0,
        cover_spheres: 0,
        forming_points: None,
        worst_error,
        worst_error_relative: relative(worst_error, diagonal),
        medial_worst_error: None,
        max_error: None,
        mean_error: if nodes.is_empty() {
            0.0
        } else {
            nodes.iter().map(|n| n.error).sum::<f64>() / nodes.len() as f64
        },
        uncovered_samples: None,
        coverage,
        certificate,
        improvements: None,
        coverage_insertions: None,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds {
            load: input.seconds,
            prepare: prepare_seconds,
            medial: medial_seconds,
            certify: 0.0,
        },
    };
    print_report(&report, args.print.json)
}

/// Writes the `-o` file, atomically.
fn write_spheres(path: &std::path::Path, file: &SphereFile<'_>) -> Result<()> {
    write_atomic(path, |w| {
        serde_json::to_writer_pretty(&mut *w, file).map_err(std::io::Error::other)?;
        w.write_all(b"\n")
    })
    .with_context(|| format!("cannot write {}", path.display()))
}

/// The spheres of the set, before any growth.
fn final_spheres(medial: &MedialApproximation<'_>) -> Vec<FinalSphere> {
    medial
        .spheres()
        .into_iter()
        .map(|s| FinalSphere {
            center: s.center,
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
        .map(|s| Sphere::new(s.center, s.radius))
        .collect();
    let (certificate, growth) = certify_coverage(surface.mesh(), &mut balls, resolution);
    let tolerance = COVER_TOLERANCE * surface.diagonal();
    for ((sphere, ball), g) in spheres.iter_mut().zip(&balls).zip(growth) {
        if g <= 0.0 {
            continue;
        }
        sphere.radius = ball.radius;
        sphere.growth = g;
        sphere.error = surface_eq2_error(surface, sphere.center, sphere.radius);
        let within = |p: &DVec3| p.distance(sphere.center) <= sphere.radius + tolerance;
        sphere.covered_samples = samples.iter().filter(|p| within(p)).count();
        uncovered.retain(|&i| !samples.get(i as usize).is_some_and(within));
    }
    certificate
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![
            format!(
                "mesh            {} ({} triangles, {})",
                self.mesh,
                thousands(self.triangles),
                self.surface.describe()
            ),
            match self.samples {
                Some(samples) => format!(
                    "method          {} ({}), {} surface samples",
                    self.method,
                    self.target,
                    thousands(samples)
                ),
                None => format!(
                    "method          {} ({}): one level of a minimax sphere-tree",
                    self.method, self.target
                ),
            },
            match (self.spheres_requested, self.forming_points) {
                (Some(asked), _) => format!(
                    "spheres         {} ({} asked{})",
                    thousands(self.spheres),
                    thousands(asked),
                    if self.spheres < asked {
                        "; fewer than asked"
                    } else {
                        ""
                    }
                ),
                (None, forming_points) => format!(
                    "spheres         {} ({} internal, {} cover) from {} forming points",
                    thousands(self.spheres),
                    thousands(self.internal_spheres),
                    thousands(self.cover_spheres),
                    thousands(forming_points.unwrap_or_default())
                ),
            },
            format!(
                "worst error     {:.6e} ({:.4} % of the diagonal{}); mean {:.6e}{}",
                self.worst_error,
                100.0 * self.worst_error_relative,
                if self.spheres_requested.is_some() {
                    ", certified"
                } else {
                    ""
                },
                self.mean_error,
                match self.medial_worst_error {
                    Some(before) if self.worst_error > before => {
                        format!("; {before:.6e} before the certificate's growth")
                    }
                    _ => String::new(),
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
        if let Some(uncovered) = self.uncovered_samples {
            lines.push(format!("uncovered       {} samples", thousands(uncovered)));
        }
        lines.push(match &self.certificate {
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
        });
        if let (Some(improvements), Some(insertions)) =
            (self.improvements, self.coverage_insertions)
        {
            lines.push(format!(
                "work            {} improvements, {} coverage insertions",
                thousands(improvements),
                thousands(insertions)
            ));
        }
        if let Some(path) = &self.output {
            lines.push(format!("written         {path}"));
        }
        lines.push(if self.spheres_requested.is_some() {
            format!(
                "time            {:.3} s load, {:.3} s prepare, {:.3} s cover (certificate included)",
                self.seconds.load, self.seconds.prepare, self.seconds.medial
            )
        } else {
            format!(
                "time            {:.3} s load, {:.3} s prepare, {:.3} s medial, {:.3} s certify",
                self.seconds.load, self.seconds.prepare, self.seconds.medial, self.seconds.certify
            )
        });
        lines.join("\n") + "\n"
    }
}
