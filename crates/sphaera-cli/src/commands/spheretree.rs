//! `sphaera spheretree`: the main job, a sphere-tree of a mesh with every level
//! evaluated the same way (certified worst error, coverage of the surface).

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::mesh::io::write_atomic;
use sphaera::mesh::{Length, Surface};
use sphaera::spheretree::export::{
    CollisionLink, SphFile, write_collision_spheres_yaml, write_sph, write_tree_json,
};
use sphaera::spheretree::{
    CoverageCertificate, EvaluationOptions, SphereTree, SphereTreeOptions, SphereTreeProgress,
    build_with_progress, cut_for_tolerance, evaluate_set,
};

use crate::{
    cli::SpheretreeArgs,
    input::read_mesh,
    output::{check_target, print_report, thousands},
    progress,
};

/// The certified evaluation's tolerance, as a fraction of the diagonal.
const EVALUATION_TOLERANCE: f64 = 1e-3;

/// Everything `sphaera spheretree` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    method: &'static str,
    depth: usize,
    branch: usize,
    samples: usize,
    /// The refinement goal per node (medial methods).
    error_fraction: f64,
    diagonal: f64,
    levels: Vec<LevelReport>,
    /// The shallowest level whose worst error meets `--tolerance` (absolute), if asked.
    tolerance: Option<f64>,
    level_for_tolerance: Option<usize>,
    output: Option<String>,
    seconds: Seconds,
}

/// One level of the tree.
#[derive(Debug, Serialize)]
struct LevelReport {
    level: usize,
    spheres: usize,
    /// The construction error (eq. 2 of the paper), largest over the level.
    construction_error: f64,
    /// The certified worst error: the true worst error lies in `[lower, upper]`
    /// (absent with `--no-evaluation`).
    worst_error_lower: Option<f64>,
    worst_error_upper: Option<f64>,
    /// Mean and variance of the per-sphere certified errors (upper bounds; spheres that
    /// cannot be the worst are bounded to 10 times the evaluation tolerance, so these are
    /// conservative).
    mean_error: Option<f64>,
    error_variance: Option<f64>,
    /// Fraction of 100,000 independent surface samples outside every sphere.
    uncovered_fraction: Option<f64>,
    largest_gap: Option<f64>,
    /// The coverage certificate: triangle pieces, spheres grown and the largest growth
    /// (absent for the baselines, which are not certified).
    certificate: Option<CoverageCertificate>,
    /// Evaluation time of the level.
    evaluation_seconds: f64,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    build: f64,
    evaluate: f64,
}

pub fn run(args: &SpheretreeArgs, quiet: bool) -> Result<()> {
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = &input.loaded.mesh;
    let options = SphereTreeOptions::default()
        .with_method(args.method.method())
        .with_depth(args.depth)
        .with_branch(args.branch)
        .with_samples(args.samples)
        .with_initial_spheres(args.initial_spheres)
        .with_min_spheres_per_node(args.min_spheres_per_node)
        .with_error_fraction(args.error_fraction)
        .with_forming_points(args.forming_points)
        .with_seed(args.seed);
    if let Some(path) = &args.output {
        output_format(path)?;
        check_target(path)?;
    }

    let bar = progress::bar(quiet, "sampling, initial spheres", 1);
    let report_progress = |p: &SphereTreeProgress| {
        bar.set_length(p.total.max(1) as u64);
        bar.set_position(p.done as u64);
        bar.set_message(format!(
            "level {} of {}: node {} of {}",
            p.level,
            args.depth,
            thousands(p.done + 1),
            thousands(p.total)
        ));
    };
    let started = Instant::now();
    let built = Surface::new(mesh)
        .map_err(anyhow::Error::from)
        .and_then(|surface| {
            let tree = build_with_progress(&surface, &options, &report_progress)?;
            Ok((surface, tree))
        });
    bar.finish_and_clear();
    let (surface, tree) =
        built.with_context(|| format!("cannot build a sphere-tree of {}", input.source))?;
    let build_seconds = started.elapsed().as_secs_f64();

    let diagonal = mesh.bounding_box_diagonal();
    let started = Instant::now();
    let levels = evaluate_levels(&surface, &tree, args.no_evaluation, quiet)?;
    let evaluate_seconds = started.elapsed().as_secs_f64();

    let tolerance = args.tolerance.map(|t| t.resolve(diagonal));
    let level_for_tolerance = tolerance.and_then(|t| {
        levels
            .iter()
            .find(|l| l.worst_error_upper.unwrap_or(l.construction_error) <= t)
            .map(|l| l.level)
    });
    if let Some(path) = &args.output {
        let name = input_name(args.mesh.as_deref());
        write_tree(path, &tree, &name, tolerance)?;
    }
    let report = Report {
        mesh: input.source.clone(),
        triangles: mesh.triangle_count(),
        method: args.method.method().name(),
        depth: args.depth,
        branch: args.branch,
        samples: args.samples,
        error_fraction: args.error_fraction,
        diagonal,
        levels,
        tolerance,
        level_for_tolerance,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds {
            load: input.seconds,
            build: build_seconds,
            evaluate: evaluate_seconds,
        },
    };
    print_report(&report, args.print.json)
}

/// The link name of a YAML export: the mesh file's stem, or `bunny` for the embedded
/// mesh.
fn input_name(mesh: Option<&Path>) -> String {
    mesh.and_then(Path::file_stem)
        .and_then(|s| s.to_str())
        .map_or_else(|| "bunny".to_owned(), str::to_owned)
}

/// Per level: sizes, construction error, certificate and (unless skipped) the certified
/// evaluation on the surface the tree was built on.
fn evaluate_levels(
    surface: &Surface,
    tree: &SphereTree,
    skip: bool,
    quiet: bool,
) -> Result<Vec<LevelReport>> {
    // The worst error to the tolerance; the other spheres (the mean) more coarsely.
    let options = EvaluationOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(EVALUATION_TOLERANCE))
        .with_screening(true);
    let bar = progress::bar(quiet, "evaluating", tree.level_count() as u64);
    let mut out = Vec::with_capacity(tree.level_count());
    for level in 0..tree.level_count() {
        bar.set_message(format!("evaluating level {level}"));
        let nodes = tree.level(level);
        let started = Instant::now();
        let evaluation = if skip {
            None
        } else {
            Some(
                evaluate_set(surface, &tree.level_spheres(level), &options)
                    .with_context(|| format!("cannot evaluate level {level}"))?,
            )
        };
        out.push(LevelReport {
            level,
            spheres: nodes.len(),
            construction_error: nodes.iter().map(|n| n.error).fold(0.0, f64::max),
            worst_error_lower: evaluation.as_ref().map(|e| e.worst_lower),
            worst_error_upper: evaluation.as_ref().map(|e| e.worst_upper),
            mean_error: evaluation.as_ref().map(|e| e.mean_error),
            error_variance: evaluation.as_ref().map(|e| e.error_variance),
            uncovered_fraction: evaluation.as_ref().map(|e| e.coverage.uncovered_fraction),
            largest_gap: evaluation.as_ref().map(|e| e.coverage.largest_gap),
            certificate: tree.coverage().get(level).copied(),
            evaluation_seconds: started.elapsed().as_secs_f64(),
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(out)
}

/// The output formats, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Json,
    Sph,
    Yaml,
}

fn output_format(path: &Path) -> Result<Format> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("json") => Ok(Format::Json),
        Some("sph") => Ok(Format::Sph),
        Some("yaml" | "yml") => Ok(Format::Yaml),
        _ => bail!(
            "{}: unknown output format (use .json, .sph or .yaml)",
            path.display()
        ),
    }
}

/// Writes the tree: JSON (the library's format, read back by `tree_from_json`), `.sph`,
/// or a YAML collision-spheres list of the smallest cut meeting the tolerance (the
/// deepest level without one), named after the mesh.
fn write_tree(path: &Path, tree: &SphereTree, name: &str, tolerance: Option<f64>) -> Result<()> {
    let written = match output_format(path)? {
        Format::Json => write_tree_json(path, tree).map_err(anyhow::Error::from),
        Format::Sph => write_sph(&SphFile::from_tree(tree)?, sphaera::mesh::DVec3::ZERO)
            .map_err(anyhow::Error::from)
            .and_then(|text| {
                write_atomic(path, |w| w.write_all(text.as_bytes())).map_err(anyhow::Error::from)
            }),
        Format::Yaml => {
            let link = match tolerance {
                Some(t) => CollisionLink::from_cut(name, tree, &cut_for_tolerance(tree, t)),
                None => CollisionLink::from_level(name, tree, tree.level_count().saturating_sub(1)),
            };
            write_collision_spheres_yaml(path, &[link]).map_err(anyhow::Error::from)
        }
    };
    written.with_context(|| format!("cannot write {}", path.display()))
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let percent = |x: f64| {
            if self.diagonal > 0.0 {
                100.0 * x / self.diagonal
            } else {
                0.0
            }
        };
        let mut lines = vec![
            format!(
                "mesh      {} ({} triangles)",
                self.mesh,
                thousands(self.triangles)
            ),
            format!(
                "tree      {}, depth {}, branch {}, {} surface samples",
                self.method,
                self.depth,
                self.branch,
                thousands(self.samples)
            ),
            "errors in % of the bounding-box diagonal; coverage on 100,000 independent samples"
                .to_owned(),
            format!(
                "{:>5} {:>8} {:>13} {:>17} {:>10} {:>9} {:>7}",
                "level",
                "spheres",
                "construction",
                "certified worst",
                "uncovered",
                "grown",
                "eval s"
            ),
        ];
        for l in &self.levels {
            let worst = match (l.worst_error_lower, l.worst_error_upper) {
                (Some(a), Some(b)) => format!("{:.3}–{:.3}", percent(a), percent(b)),
                _ => "–".to_owned(),
            };
            let uncovered = l
                .uncovered_fraction
                .map_or_else(|| "–".to_owned(), |u| format!("{:.3} %", 100.0 * u));
            lines.push(format!(
                "{:>5} {:>8} {:>13.3} {:>17} {:>10} {:>9} {:>7.2}",
                l.level,
                thousands(l.spheres),
                percent(l.construction_error),
                worst,
                uncovered,
                l.certificate
                    .map_or_else(|| "–".to_owned(), |c| thousands(c.grown_spheres)),
                l.evaluation_seconds
            ));
        }
        if let Some(t) = self.tolerance {
            lines.push(match self.level_for_tolerance {
                Some(level) => {
                    format!("tolerance {t:.6e}: level {level} is the shallowest that meets it")
                }
                None => format!("tolerance {t:.6e}: no level meets it (build deeper)"),
            });
        }
        if let Some(path) = &self.output {
            lines.push(format!("written   {path}"));
        }
        lines.push(format!(
            "time      {:.3} s load, {:.3} s build, {:.3} s evaluation",
            self.seconds.load, self.seconds.build, self.seconds.evaluate
        ));
        lines.join("\n") + "\n"
    }
}
