//! `sphaera spheretree`: the main job, a sphere-tree of a mesh with every level
//! evaluated the same way (certified worst error, coverage of the surface).
//!
//! The tree is built to a depth (`--depth`), until every leaf meets a tolerance
//! (`--tolerance`, as deep as needed) or as exactly N spheres in one level (`--spheres`).
//! In a tree built to a tolerance the leaves end at different depths, so a level alone
//! does not cover the surface: each level is reported as its cut
//! ([`SphereTree::cut_at`]), the level's nodes and the leaves above it. In a tree built to
//! a depth the cut is the level itself.

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::mesh::io::write_atomic;
use sphaera::mesh::{Length, Surface};
use sphaera::spheretree::export::{SphFile, TreeFormat, tree_to_text};
use sphaera::spheretree::{
    CoverageCertificate, Effort, EvaluationOptions, MAX_BRANCH, MAX_TREE_NODES, Method, SphereTree,
    SphereTreeError, SphereTreeOptions, SphereTreeProgress, build_with_progress, evaluate_level,
};

use crate::{
    cli::SpheretreeArgs,
    input::read_mesh,
    output::{check_target, print_report, thousands},
    progress,
};

/// What the tree is built to.
#[derive(Debug, Clone, Copy)]
enum Goal {
    /// Every node divided, to this many levels below the root.
    Depth(usize),
    /// Nodes divided until every leaf's certified error meets it (minimax).
    Tolerance(Length),
    /// Exactly this many spheres in one level (minimax).
    Spheres(usize),
}

impl Goal {
    fn of(args: &SpheretreeArgs) -> Self {
        match (args.spheres, args.tolerance) {
            (Some(n), _) => Self::Spheres(n),
            (None, Some(t)) => Self::Tolerance(t),
            (None, None) => Self::Depth(args.depth),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Self::Depth(_) => "depth",
            Self::Tolerance(_) => "tolerance",
            Self::Spheres(_) => "spheres",
        }
    }
}

/// The surface a tree is built on: with an inside, or a shell (a sheet, an open patch).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SurfaceKind {
    Solid,
    Shell,
}

impl SurfaceKind {
    pub fn of(surface: &Surface) -> Self {
        if surface.has_inside() {
            Self::Solid
        } else {
            Self::Shell
        }
    }

    /// How the text reports say it.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Solid => "solid",
            Self::Shell => "shell (no inside)",
        }
    }
}

/// Everything `sphaera spheretree` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    /// `solid`, or `shell` for a mesh without inside (a flat sheet, an open patch).
    surface: SurfaceKind,
    /// The method asked for (`auto` by default).
    method: &'static str,
    /// The method that built the tree (`auto` resolved: `minimax`).
    method_used: &'static str,
    /// What the tree was built to: `depth`, `tolerance` or `spheres`.
    goal: &'static str,
    /// Levels below the root, as built.
    depth: usize,
    /// Children per node at most.
    branch: usize,
    /// Surface samples (`null` for minimax, which works on the triangles themselves).
    samples: Option<usize>,
    /// The refinement goal per node (the paper's medial methods; `null` for the others).
    error_fraction: Option<f64>,
    diagonal: f64,
    /// Per level, its cut (the level's nodes and the leaves above it).
    levels: Vec<LevelReport>,
    /// The leaves: the finest spheres of every part of the surface.
    leaves: usize,
    /// The largest certified error of a leaf (its construction error).
    worst_leaf_error: f64,
    /// With `--spheres N`: N (the deepest level then has exactly N spheres).
    spheres_requested: Option<usize>,
    /// With `--tolerance`: the tolerance, absolute.
    tolerance: Option<f64>,
    /// With `--tolerance`: whether every leaf's certified error is at most it.
    tolerance_met: Option<bool>,
    /// With `--tolerance`: the most nodes the tree could have (`--max-nodes`, else the
    /// library's limit).
    max_nodes: Option<usize>,
    /// The minimax method's effort (`quick`, `default` or `thorough`; `null` for the
    /// other methods).
    effort: Option<&'static str>,
    output: Option<String>,
    seconds: Seconds,
}

/// One level of the tree, as its cut.
#[derive(Debug, Serialize)]
struct LevelReport {
    level: usize,
    /// Spheres of the cut: the level's nodes and the leaves above it.
    spheres: usize,
    /// Of which leaves above the level (0 in a tree built to a depth).
    leaves_above: usize,
    /// The construction error (eq. 2 of the paper, or the branch-and-bound bound where
    /// tighter; a certified upper bound per sphere), largest over the cut.
    construction_error: f64,
    /// The certified worst error: the true worst error lies in `[lower, upper]`
    /// (absent with `--no-evaluation`). `upper` is the tightest certified bound: per
    /// sphere the smaller of the evaluation's upper bound and the construction error,
    /// largest over the cut.
    worst_error_lower: Option<f64>,
    worst_error_upper: Option<f64>,
    /// Mean and variance of the per-sphere certified upper bounds (a sphere that cannot be
    /// the worst is not evaluated to the tolerance, and keeps its construction error or a
    /// coarser bound, so these are conservative).
    mean_error: Option<f64>,
    error_variance: Option<f64>,
    /// Fraction of 100,000 independent surface samples outside every sphere.
    uncovered_fraction: Option<f64>,
    largest_gap: Option<f64>,
    /// The coverage certificate of the cut: triangle pieces, spheres grown and the
    /// largest growth (absent for the baselines, which are not certified).
    certificate: Option<CoverageCertificate>,
    /// Evaluation time of the cut.
    evaluation_seconds: f64,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    build: f64,
    evaluate: f64,
}

/// Fails unless `count` spheres can be asked for (`--spheres`): 1 to [`MAX_BRANCH`].
pub fn check_sphere_count(count: usize) -> Result<()> {
    if count == 0 || count > MAX_BRANCH {
        bail!(
            "--spheres {count}: must be between 1 and {} (the most spheres of one level)",
            thousands(MAX_BRANCH)
        );
    }
    Ok(())
}

/// Fails before any work when the goal needs a method other than the one asked for.
fn check_goal(goal: Goal, method: Method) -> Result<()> {
    let minimax = method.resolved() == Method::Minimax;
    match goal {
        Goal::Tolerance(_) if !minimax => bail!(
            "--tolerance builds the tree until every leaf meets it, which only the minimax \
             method does (--method minimax or auto); --method {} builds to --depth",
            method.name()
        ),
        Goal::Spheres(_) if !minimax => bail!(
            "--spheres gives exactly N spheres in one level, which only the minimax method \
             does (--method minimax or auto); --method {} gives at most --branch children \
             per node (--depth 1 --branch N)",
            method.name()
        ),
        Goal::Spheres(n) => check_sphere_count(n),
        _ => Ok(()),
    }
}

/// Fails before any work on an effort other than the default with a method that has
/// none, or a node budget out of range.
fn check_minimax_options(args: &SpheretreeArgs, method: Method) -> Result<()> {
    if args.effort != Effort::Default && method.resolved() != Method::Minimax {
        bail!(
            "--effort tunes the minimax method (--method minimax or auto); --method {} has \
             its own parameters (--initial-spheres, --error-fraction, --samples)",
            method.name()
        );
    }
    if let Some(n) = args.max_nodes
        && !(1..=MAX_TREE_NODES).contains(&n)
    {
        bail!(
            "--max-nodes must be between 1 and {} (a tree's most nodes), got {}",
            thousands(MAX_TREE_NODES),
            thousands(n)
        );
    }
    Ok(())
}

pub fn run(args: &SpheretreeArgs, quiet: bool) -> Result<()> {
    let method = args.method;
    let goal = Goal::of(args);
    check_goal(goal, method)?;
    check_minimax_options(args, method)?;
    if let Some(path) = &args.output {
        output_format(path)?;
        check_target(path)?;
    }
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = &input.loaded.mesh;
    let options = SphereTreeOptions::default()
        .with_method(method)
        .with_depth(args.depth)
        .with_branch(args.branch)
        .with_samples(args.samples)
        .with_initial_spheres(args.initial_spheres)
        .with_min_spheres_per_node(args.min_spheres_per_node)
        .with_error_fraction(args.error_fraction)
        .with_forming_points(args.forming_points)
        .with_seed(args.seed)
        .with_effort(args.effort);
    let options = match goal {
        Goal::Depth(_) => options,
        Goal::Tolerance(t) => match args.max_nodes {
            Some(n) => options.with_tolerance(t).with_max_nodes(n),
            None => options.with_tolerance(t),
        },
        Goal::Spheres(n) => options.with_depth(1).with_branch(n),
    };

    let started = Instant::now();
    let built = build(mesh, &options, goal, quiet);
    let (surface, tree) =
        built.with_context(|| format!("cannot build a sphere-tree of {}", input.source))?;
    let build_seconds = started.elapsed().as_secs_f64();

    let diagonal = mesh.bounding_box_diagonal();
    let started = Instant::now();
    let levels = evaluate_levels(&surface, &tree, args.no_evaluation, quiet)?;
    let evaluate_seconds = started.elapsed().as_secs_f64();

    let leaves = tree.leaves();
    let worst_leaf_error = leaves
        .iter()
        .map(|&i| tree.nodes()[i].error)
        .fold(0.0, f64::max);
    let tolerance = match goal {
        Goal::Tolerance(t) => Some(t.resolve(diagonal)),
        _ => None,
    };
    if let Some(path) = &args.output {
        let name = input_name(args.mesh.as_deref());
        write_tree(path, &tree, &name)?;
    }
    let medial = method.is_medial();
    let minimax = method.resolved() == Method::Minimax;
    let report = Report {
        mesh: input.source.clone(),
        triangles: mesh.triangle_count(),
        surface: SurfaceKind::of(&surface),
        method: method.name(),
        method_used: method.resolved().name(),
        goal: goal.name(),
        depth: tree.level_count().saturating_sub(1),
        branch: tree.branch(),
        samples: (!minimax).then_some(args.samples),
        error_fraction: medial.then_some(args.error_fraction),
        diagonal,
        levels,
        leaves: leaves.len(),
        worst_leaf_error,
        spheres_requested: match goal {
            Goal::Spheres(n) => Some(n),
            _ => None,
        },
        tolerance,
        tolerance_met: tolerance.map(|t| worst_leaf_error <= t),
        max_nodes: tolerance.map(|_| options.max_nodes),
        effort: minimax.then_some(args.effort.name()),
        output: args.output.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds {
            load: input.seconds,
            build: build_seconds,
            evaluate: evaluate_seconds,
        },
    };
    print_report(&report, args.print.json)
}

/// The surface of `mesh` (a solid, or a shell when it has no inside) and its tree, with a
/// progress bar: per level, the nodes divided so far (a tolerance tree's depth is not
/// known in advance; a one-level tree of N spheres is one division).
fn build(
    mesh: &sphaera::mesh::TriMesh,
    options: &SphereTreeOptions,
    goal: Goal,
    quiet: bool,
) -> Result<(Surface, SphereTree)> {
    let bar = match goal {
        Goal::Spheres(n) => progress::spinner(
            quiet,
            &format!("dividing the surface between {} spheres", thousands(n)),
        ),
        _ => progress::bar(quiet, "preparing the surface", 1),
    };
    let depth = match goal {
        Goal::Depth(depth) => Some(depth),
        Goal::Tolerance(_) | Goal::Spheres(_) => None,
    };
    let report_progress = |p: &SphereTreeProgress| {
        if matches!(goal, Goal::Spheres(_)) {
            return;
        }
        bar.set_length(p.total.max(1) as u64);
        bar.set_position(p.done as u64);
        let node = format!("node {} of {}", thousands(p.done + 1), thousands(p.total));
        bar.set_message(match depth {
            Some(depth) => format!("level {} of {depth}: {node}", p.level),
            None => format!("level {}: {node}", p.level),
        });
    };
    let built = Surface::solid_or_shell(mesh)
        .map_err(anyhow::Error::from)
        .and_then(|surface| {
            let tree = build_with_progress(&surface, options, &report_progress)?;
            Ok((surface, tree))
        });
    bar.finish_and_clear();
    built
}

/// The link name of a YAML export: the mesh file's stem, or `bunny` for the embedded
/// mesh.
fn input_name(mesh: Option<&Path>) -> String {
    mesh.and_then(Path::file_stem)
        .and_then(|s| s.to_str())
        .map_or_else(|| "bunny".to_owned(), str::to_owned)
}

/// Per level, its cut: sizes, construction error, certificate and (unless skipped) the
/// certified evaluation of the cut's spheres on the surface the tree was built on
/// ([`evaluate_level`]).
fn evaluate_levels(
    surface: &Surface,
    tree: &SphereTree,
    skip: bool,
    quiet: bool,
) -> Result<Vec<LevelReport>> {
    let options = EvaluationOptions::level_report();
    let bar = progress::bar(quiet, "evaluating", tree.level_count() as u64);
    let mut out = Vec::with_capacity(tree.level_count());
    for level in 0..tree.level_count() {
        bar.set_message(format!("evaluating level {level}"));
        let started = Instant::now();
        let certificate = tree.coverage().get(level).copied();
        let report = if skip {
            let cut = tree.cut_at(level);
            LevelReport {
                level,
                spheres: cut.len(),
                leaves_above: cut.len() - tree.level(level).len(),
                construction_error: cut
                    .iter()
                    .map(|&i| tree.nodes()[i].error)
                    .fold(0.0, f64::max),
                worst_error_lower: None,
                worst_error_upper: None,
                mean_error: None,
                error_variance: None,
                uncovered_fraction: None,
                largest_gap: None,
                certificate,
                evaluation_seconds: 0.0,
            }
        } else {
            let evaluated = evaluate_level(surface, tree, level, &options)
                .with_context(|| format!("cannot evaluate level {level}"))?;
            let coverage = &evaluated.evaluation.coverage;
            LevelReport {
                level,
                spheres: evaluated.spheres.len(),
                leaves_above: evaluated.leaves_above,
                construction_error: evaluated.construction_error,
                worst_error_lower: Some(evaluated.worst_lower),
                worst_error_upper: Some(evaluated.worst_upper),
                mean_error: Some(evaluated.mean_upper),
                error_variance: Some(evaluated.upper_variance),
                uncovered_fraction: Some(coverage.uncovered_fraction),
                largest_gap: Some(coverage.largest_gap),
                certificate,
                evaluation_seconds: started.elapsed().as_secs_f64(),
            }
        };
        out.push(report);
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(out)
}

/// The output format of `path`, by its extension.
fn output_format(path: &Path) -> Result<TreeFormat> {
    TreeFormat::from_path(path).with_context(|| {
        format!(
            "{}: unknown output format (use .json, .sph or .yaml)",
            path.display()
        )
    })
}

/// Writes the tree atomically in the format of the path's extension: JSON (the library's
/// format, read back by `tree_from_json`), `.sph`, or a YAML collision-spheres list of the
/// tree's leaves (which meet the tolerance of a tree built to one), named after the mesh.
fn write_tree(path: &Path, tree: &SphereTree, name: &str) -> Result<()> {
    let format = output_format(path)?;
    let context = || format!("cannot write {}", path.display());
    if format == TreeFormat::Sph {
        // The library's error, with what to do instead.
        sph_layout(tree).with_context(context)?;
    }
    let text = tree_to_text(tree, format, name).with_context(context)?;
    write_atomic(path, |w| w.write_all(text.as_bytes())).with_context(context)
}

/// The `.sph` layout of `tree`, or the library's error with what to do instead when the
/// complete tree the format stores has too many slots (a deep tree).
fn sph_layout(tree: &SphereTree) -> Result<SphFile> {
    SphFile::from_tree(tree).map_err(|error| match error {
        SphereTreeError::SphLayout(_) => anyhow::anyhow!(
            "{error}; .sph stores a complete tree, a slot for every node that a tree of {} \
             levels and up to {} children per node could have, used or not (this one has {} \
             nodes): write .json or .yaml, which store only the nodes the tree has",
            tree.level_count(),
            thousands(tree.branch()),
            thousands(tree.nodes().len())
        ),
        other => other.into(),
    })
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
        let method = if self.method == self.method_used {
            self.method.to_owned()
        } else {
            format!("{} ({})", self.method_used, self.method)
        };
        let method = match self.effort {
            Some(effort) if effort != Effort::Default.name() => {
                format!("{method}, {effort} effort")
            }
            _ => method,
        };
        let samples = self.samples.map_or_else(String::new, |s| {
            format!(", {} surface samples", thousands(s))
        });
        let shape = match (self.goal, self.spheres_requested) {
            ("spheres", Some(n)) => format!(
                "{method}, {} spheres asked in one level, {} given{}",
                thousands(n),
                thousands(self.leaves),
                if self.leaves < n {
                    " (fewer than asked)"
                } else {
                    ""
                }
            ),
            ("tolerance", _) => format!(
                "{method}, to the tolerance: depth {} reached, branch {}, {} leaves",
                self.depth,
                thousands(self.branch),
                thousands(self.leaves)
            ),
            _ => format!(
                "{method}, depth {}, branch {}{samples}",
                self.depth,
                thousands(self.branch)
            ),
        };
        let mut lines = vec![
            format!(
                "mesh      {} ({} triangles)",
                self.mesh,
                thousands(self.triangles)
            ),
            format!("surface   {}", self.surface.describe()),
            format!("tree      {shape}"),
            "errors in % of the bounding-box diagonal; coverage on 100,000 independent samples"
                .to_owned(),
        ];
        let cuts = self.levels.iter().any(|l| l.leaves_above > 0);
        if cuts {
            lines.push(
                "each level with the leaves above it (its cut), which together cover the surface"
                    .to_owned(),
            );
        }
        lines.push(format!(
            "{:>5} {:>8} {:>13} {:>17} {:>10} {:>9} {:>7}",
            "level", "spheres", "construction", "certified worst", "uncovered", "grown", "eval s"
        ));
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
        if let (Some(t), Some(met)) = (self.tolerance, self.tolerance_met) {
            lines.push(format!(
                "tolerance {t:.6e} ({:.3} %): {}; worst leaf {:.6e} ({:.3} %)",
                percent(t),
                if met {
                    format!(
                        "met, certified: each of the {} leaves is within it",
                        thousands(self.leaves)
                    )
                } else {
                    "NOT met: a leaf's certified error exceeds it".to_owned()
                },
                self.worst_leaf_error,
                percent(self.worst_leaf_error)
            ));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_counts_outside_one_to_the_cap_are_refused_naming_the_option() {
        assert!(check_sphere_count(1).is_ok());
        assert!(check_sphere_count(MAX_BRANCH).is_ok());
        for bad in [0, MAX_BRANCH + 1] {
            let message = check_sphere_count(bad).expect_err("refused").to_string();
            assert!(
                message.contains("--spheres") && message.contains("10,000"),
                "{message}"
            );
        }
    }

    #[test]
    fn goals_other_than_a_depth_need_minimax() {
        let tolerance = Goal::Tolerance(Length::RelativeToDiagonal(0.01));
        assert!(check_goal(tolerance, Method::Auto).is_ok());
        assert!(check_goal(tolerance, Method::Minimax).is_ok());
        let message = check_goal(tolerance, Method::Merge)
            .expect_err("refused")
            .to_string();
        assert!(message.contains("--tolerance"), "{message}");
        let message = check_goal(Goal::Spheres(8), Method::Octree)
            .expect_err("refused")
            .to_string();
        assert!(message.contains("--spheres"), "{message}");
        assert!(check_goal(Goal::Depth(3), Method::Hubbard).is_ok());
    }
}
