//! Sphere-trees: certified worst error per level for every method (the paper's figures
//! 17 to 19, Bradshaw and O'Sullivan 2004, section 6.3), and worst error against build
//! time (the speed/accuracy chart of issue 6).
//!
//! For each mesh of [`MESHES`] and the unseen procedural animal
//! ([`sphaera_tests::animal::quadruped`], [`ANIMAL`] in the CSVs: 9,888 triangles, legs
//! whose radius is 1.5 % of the diagonal, horns; issue 36's acceptance mesh), every method
//! of [`METHODS`] builds one tree of depth [`DEPTH`] and branching factor [`BRANCH`] with
//! seed [`SEED`], everything else at its default:
//!
//! `sphaera::spheretree::build` with `SphereTreeOptions::default().with_method(..)`:
//!
//! - **minimax** (the library's default since issue 36: `auto` resolves to it; both are
//!   measured, they build the same tree): the default effort;
//! - **the medial methods** (merge, burst, expand, combined and any other for which
//!   `Method::is_medial` holds): the library's default settings (10,000 surface samples,
//!   an initial medial approximation of 500 spheres refined to at least 100 per node, the
//!   default error fraction);
//! - **octree, grid, hubbard**: the baselines, at the same depth, branch and seed.
//!
//! Measured per tree: the **build time**, the best of [`RUNS`] runs of the surface's
//! preparation and the build, as a user runs them (mesh loading and evaluation excluded;
//! wall-clock, with the
//! `parallel` feature on every core, whereas the toolkit's figures are single-threaded
//! CPU seconds), and per level 1 to
//! [`DEPTH`] the **certified worst error**: `evaluate_set` on the level's spheres with
//! `EvaluationOptions::default().with_tolerance(Length::RelativeToDiagonal(`[`EVALUATION_TOLERANCE`]`))`
//! (the tolerance of `sphaera spheretree`), which bounds the true worst distance from a
//! sphere's surface to the object (the paper's eq. 2, evaluated exactly) in
//! `[lower, upper]`. The charts plot the **upper** end, the CSV has both, with the mean
//! error, the largest construction error the builder reported, and the fraction of
//! 100,000 independent surface samples outside every sphere. Errors are in % of the
//! mesh's bounding-box diagonal.
//!
//! The time chart has three more series on every mesh, measured the same way:
//!
//! - **expand's error-fraction sweep**: [`Method::Expand`] with
//!   `SphereTreeOptions::with_error_fraction` at each fraction of [`ERROR_FRACTIONS`]
//!   (½, ¼, ⅛, 1/16: a node's medial spheres refined to that fraction of the parent's
//!   error before reduction), drawn as one line per mesh with each point labelled by its
//!   fraction: how much time buys how much accuracy;
//! - **minimax's effort sweep**: [`Method::Minimax`] with
//!   `SphereTreeOptions::with_effort` at each [`Effort`] (quick, default, thorough), drawn
//!   as one line per mesh labelled by effort;
//! - **the library's default**: `Method::default()` with `SphereTreeOptions::default()`
//!   (depth, branch and seed pinned to the experiment's, as for every tree here), drawn
//!   as a black hollow marker labelled "default", so the chart shows where a user who
//!   changes nothing lands.
//!
//! A tree whose options equal those of a tree already measured on the mesh (expand at
//! the default fraction, the default method at the default options) is the same tree
//! (builds are deterministic): it is measured once and charted in both roles.
//!
//! The peer: the original toolkit's figures as issue 6 gives them ([`TOOLKIT`]: worst
//! error per level, and CPU seconds where the issue has them, measured by the issue's
//! author with the toolkit single-threaded). **They exist for `bunny_lowres.obj` only**
//! (the toolkit cannot be run here, for licence reasons, so no other mesh has them):
//! drawn as hollow markers on the bunny and written to the CSVs with `source` = `issue`
//! (measured rows say `measured`). They are the only numbers not computed here. Issue 36's
//! target on the bunny, at most 0.9× the toolkit's best per level ([`TARGET`]), is written
//! to the level CSV as the row `target` (source `issue`), and the terminal says per level
//! whether the default meets it.
//!
//! Files: `spheretree_error_vs_level.{svg,csv}` (one panel per mesh, one row per mesh,
//! method and level; the methods of [`METHODS`] only; the table of `docs/benchmarks.md`
//! is generated from this CSV by `cargo xtask tables`) and
//! `spheretree_error_vs_time.{svg,csv}` (two panels, levels 2 and 3; one row per mesh and
//! tree: every method, the error-fraction sweep, the effort sweep and the default, with
//! the error fraction of the medial trees, the effort of the minimax ones and the series
//! each row belongs to). By design they cover only [`MESHES`] and the animal;
//! `cargo xtask charts --check` checks them.
//!
//! The module [`similarity`] is a separate experiment (`--only spheretree_similarity`):
//! the default tree's stability under similarity transforms.

use std::path::Path;

use anyhow::{Context, Result};
use sphaera::{
    mesh::{Length, Surface, TriMesh},
    spheretree::{
        Effort, EvaluationOptions, Method, SphereTree, SphereTreeOptions, build, evaluate_set,
    },
};

use super::{load_or_skip, min_time};

mod charts;
pub mod similarity;

/// The experiment's name (`--only spheretree`); it writes the two charts below.
pub const NAME: &str = "spheretree";

/// Worst error per level: `spheretree_error_vs_level.{svg,csv}`.
pub const LEVEL_CHART: &str = "spheretree_error_vs_level";

/// Worst error against build time: `spheretree_error_vs_time.{svg,csv}`.
pub const TIME_CHART: &str = "spheretree_error_vs_time";

/// The meshes: file in `shared/data` and label. The paper's bunny (the low-resolution
/// one, the toolkit's reference), a dragon of 11k triangles that is not manifold, and a
/// robot collision mesh, the meshes sphere-trees are made for.
pub const MESHES: &[(&str, &str)] = &[
    ("bunny_lowres.obj", "bunny low-res"),
    ("dragon_vrip_res4.ply", "dragon res4"),
    ("robots/franka_panda/collision/link3.obj", "Panda link3"),
];

/// The procedural animal's name in the CSVs (it has no file).
pub const ANIMAL: &str = "animal (procedural)";

/// The animal's label on the charts.
const ANIMAL_LABEL: &str = "animal (unseen)";

/// Levels below the root (the paper's figures: 3).
pub const DEPTH: usize = 3;

/// Children per node (the paper's 8).
pub const BRANCH: usize = 8;

/// Seed of the surface sampling of every method.
pub const SEED: u64 = 1;

/// Timing runs per build (the minimum is kept).
pub const RUNS: usize = 2;

/// Width of the certified error interval of each sphere, as a fraction of the diagonal
/// (the value `sphaera spheretree` uses).
pub const EVALUATION_TOLERANCE: f64 = sphaera::spheretree::evaluate::LEVEL_REPORT_TOLERANCE;

/// The original toolkit on `bunny_lowres.obj`, from issue 6 (not measured here): name,
/// CPU seconds (single thread) if the issue gives them, worst error in % of the diagonal
/// at levels 1, 2 and 3.
pub const TOOLKIT: &[(&str, Option<f64>, [f64; 3])] = &[
    ("toolkit-merge", Some(94.0), [10.3, 4.42, 2.13]),
    ("toolkit-expand", Some(103.0), [11.0, 3.73, 2.09]),
    ("toolkit-hubbard", None, [13.9, 5.73, 5.82]),
    ("toolkit-octree", None, [42.0, 25.0, 13.0]),
];

/// The only mesh the toolkit's figures exist for.
const TOOLKIT_MESH: &str = "bunny_lowres.obj";

/// Issue 36's target on [`TOOLKIT_MESH`]: the default's certified worst error at levels
/// 1, 2 and 3, in % of the diagonal, at most 0.9× the toolkit's best per level (best
/// 10.26 / 3.73 / 2.09 %).
pub const TARGET: [f64; 3] = [9.23, 3.36, 1.88];

/// The efforts of minimax's sweep in the time chart, quickest first.
const EFFORTS: [Effort; 3] = Effort::ALL;

/// The error fractions of expand's sweep in the time chart, largest first, with the
/// label written beside each point.
pub const ERROR_FRACTIONS: &[(f64, &str)] =
    &[(0.5, "½"), (0.25, "¼"), (0.125, "⅛"), (0.0625, "1/16")];

/// The method of the error-fraction sweep.
const SWEEP_METHOD: Method = Method::Expand;

/// The methods, in the order of the charts' colours: every method of the library.
const METHODS: &[Method] = &Method::ALL;

/// The position of `method` in [`METHODS`], for its colour.
fn method_index(method: Method) -> usize {
    METHODS.iter().position(|&m| m == method).unwrap_or(0)
}

/// The options of every tree here: `SphereTreeOptions::default()` with `method`, at
/// [`DEPTH`], [`BRANCH`] and [`SEED`].
pub(super) fn tree_options(method: Method) -> SphereTreeOptions {
    SphereTreeOptions::default()
        .with_method(method)
        .with_depth(DEPTH)
        .with_branch(BRANCH)
        .with_seed(SEED)
}

/// The tree of `mesh` with `options`, as a user builds it: the surface prepared, then
/// built.
fn build_tree(options: &SphereTreeOptions, mesh: &TriMesh) -> Result<SphereTree> {
    Surface::new(mesh)
        .map_err(anyhow::Error::from)
        .and_then(|surface| Ok(build(&surface, options)?))
        .with_context(|| format!("{} tree failed", options.method.name()))
}

/// Which series a measured tree belongs to.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Variant {
    /// A method of [`METHODS`] at [`tree_options`]: both charts.
    Method,
    /// [`SWEEP_METHOD`] at the error fraction of [`ERROR_FRACTIONS`] with this index:
    /// the time chart's labelled line.
    ErrorFraction(usize),
    /// [`Method::Minimax`] at the effort of [`EFFORTS`] with this index: the time chart's
    /// labelled line.
    Effort(usize),
    /// `Method::default()` at [`tree_options`]: the time chart's "default".
    LibraryDefault,
}

/// Every tree measured on a mesh, with its options, in the order measured.
fn variants() -> Vec<(Variant, SphereTreeOptions)> {
    let mut trees: Vec<(Variant, SphereTreeOptions)> = METHODS
        .iter()
        .map(|&m| (Variant::Method, tree_options(m)))
        .collect();
    trees.extend(
        ERROR_FRACTIONS
            .iter()
            .enumerate()
            .map(|(i, &(fraction, _))| {
                (
                    Variant::ErrorFraction(i),
                    tree_options(SWEEP_METHOD).with_error_fraction(fraction),
                )
            }),
    );
    trees.extend(EFFORTS.iter().enumerate().map(|(i, &effort)| {
        (
            Variant::Effort(i),
            tree_options(Method::Minimax).with_effort(effort),
        )
    }));
    trees.push((Variant::LibraryDefault, tree_options(Method::default())));
    trees
}

/// One evaluated level of a tree; errors relative to the diagonal.
#[derive(Clone)]
struct Level {
    level: usize,
    spheres: usize,
    worst_lower: f64,
    worst_upper: f64,
    mean_error: f64,
    construction_error: f64,
    uncovered: f64,
    converged: bool,
    evaluation_seconds: f64,
}

/// One tree: its build time and levels 1 to [`DEPTH`].
#[derive(Clone)]
struct Measured {
    file: &'static str,
    method: Method,
    variant: Variant,
    /// The options' error fraction (used by the medial methods only).
    error_fraction: f64,
    /// The options' effort (used by minimax only).
    effort: Effort,
    seconds: f64,
    levels: Vec<Level>,
}

impl Measured {
    /// How the terminal names the tree.
    fn label(&self) -> String {
        match self.variant {
            Variant::Method => self.method.name().to_owned(),
            Variant::ErrorFraction(i) => format!(
                "{} F={}",
                self.method.name(),
                ERROR_FRACTIONS.get(i).map_or("?", |f| f.1)
            ),
            Variant::Effort(i) => format!(
                "{} {}",
                self.method.name(),
                EFFORTS.get(i).map_or("?", |e| e.name())
            ),
            Variant::LibraryDefault => format!("default ({})", self.method.name()),
        }
    }

    /// The worst error (upper end) of `level`, in % of the diagonal.
    fn upper_pct(&self, level: usize) -> Option<f64> {
        self.levels
            .iter()
            .find(|l| l.level == level)
            .map(|l| 100.0 * l.worst_upper)
    }
}

pub fn run(data: &Path, out: &Path) -> Result<()> {
    let mut measured = Vec::new();
    let mut labels = Vec::new();
    for &(file, label) in MESHES {
        let Some(mesh) = load_or_skip(data, file)? else {
            continue;
        };
        labels.push((
            file,
            format!(
                "{label} ({} triangles): worst error per level",
                mesh.triangle_count()
            ),
        ));
        measure_mesh(file, label, &mesh, &mut measured)?;
    }
    let animal = sphaera_tests::animal::quadruped();
    labels.push((
        ANIMAL,
        format!(
            "{ANIMAL_LABEL} ({} triangles): worst error per level",
            animal.triangle_count()
        ),
    ));
    measure_mesh(ANIMAL, ANIMAL_LABEL, &animal, &mut measured)?;
    for line in against_target(&measured) {
        eprintln!("target: {line}");
    }
    for line in oddities(&measured) {
        eprintln!("note: {line}");
    }
    let methods: Vec<Measured> = measured
        .iter()
        .filter(|m| m.variant == Variant::Method)
        .cloned()
        .collect();
    charts::write_level_table(out, &methods)?;
    charts::write_time_table(out, &measured)?;
    charts::draw_levels(out, &methods, &labels)?;
    charts::draw_times(out, &measured)
}

/// Every tree of [`variants`] on one mesh: build (timed), then evaluate levels 1 to
/// [`DEPTH`]; a tree with the options of one already measured is not built again.
fn measure_mesh(
    file: &'static str,
    label: &str,
    mesh: &TriMesh,
    measured: &mut Vec<Measured>,
) -> Result<()> {
    let surface = Surface::new(mesh).context("cannot prepare the surface")?;
    let diagonal = surface.diagonal();
    let options = EvaluationOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(EVALUATION_TOLERANCE));
    let mut built: Vec<(SphereTreeOptions, Measured)> = Vec::new();
    for (variant, tree_options) in variants() {
        if let Some((_, same)) = built.iter().find(|(o, _)| *o == tree_options) {
            let row = Measured {
                variant,
                ..same.clone()
            };
            eprintln!(
                "{label:<14} {:<13} = {} (same options)",
                row.label(),
                same.label()
            );
            measured.push(row);
            continue;
        }
        let method = tree_options.method;
        let (seconds, tree) = min_time(RUNS, || build_tree(&tree_options, mesh))?;
        let mut levels = Vec::new();
        for level in 1..tree.level_count().min(DEPTH + 1) {
            let nodes = tree.level(level);
            if nodes.is_empty() {
                eprintln!("{label}: {} has no level {level}", method.name());
                continue;
            }
            let evaluation = evaluate_set(&surface, &tree.level_spheres(level), &options)
                .with_context(|| format!("cannot evaluate {} level {level}", method.name()))?;
            levels.push(Level {
                level,
                spheres: nodes.len(),
                worst_lower: evaluation.worst_lower / diagonal,
                worst_upper: evaluation.worst_upper / diagonal,
                mean_error: evaluation.mean_error / diagonal,
                construction_error: nodes.iter().map(|n| n.error).fold(0.0, f64::max) / diagonal,
                uncovered: evaluation.coverage.uncovered_fraction,
                converged: evaluation.converged,
                evaluation_seconds: evaluation.elapsed.as_secs_f64(),
            });
        }
        let row = Measured {
            file,
            method,
            variant,
            error_fraction: tree_options.error_fraction,
            effort: tree_options.effort,
            seconds,
            levels,
        };
        report(label, &row);
        built.push((tree_options, row.clone()));
        measured.push(row);
    }
    Ok(())
}

fn report(label: &str, row: &Measured) {
    let levels: Vec<String> = row
        .levels
        .iter()
        .map(|l| {
            format!(
                "L{} {:>3} sph {:6.3}–{:6.3} % unc {:.3} % ({:.1} s)",
                l.level,
                l.spheres,
                100.0 * l.worst_lower,
                100.0 * l.worst_upper,
                100.0 * l.uncovered,
                l.evaluation_seconds
            )
        })
        .collect();
    eprintln!(
        "{label:<14} {:<13} build {:8.3} s  {}",
        row.label(),
        row.seconds,
        levels.join("  ")
    );
}

/// Per level, the library's default on [`TOOLKIT_MESH`] against [`TARGET`]: met or
/// missed, with both figures.
fn against_target(measured: &[Measured]) -> Vec<String> {
    let Some(default) = measured
        .iter()
        .find(|m| m.file == TOOLKIT_MESH && m.variant == Variant::LibraryDefault)
    else {
        return Vec::new();
    };
    (1..=DEPTH)
        .filter_map(|level| {
            let ours = default.upper_pct(level)?;
            let target = *TARGET.get(level - 1)?;
            let verdict = if ours <= target { "met" } else { "missed" };
            Some(format!(
                "{TOOLKIT_MESH} level {level}: {} {ours:.2} % against at most {target} %: {verdict}",
                default.label()
            ))
        })
        .collect()
}

/// What a reader should notice among the trees of [`METHODS`]: a level worse than its
/// parent level, combined worse than merge or expand, a medial method worse than
/// Hubbard's.
fn oddities(measured: &[Measured]) -> Vec<String> {
    let mut notes = Vec::new();
    let find = |file: &str, method: Method| {
        measured
            .iter()
            .find(|m| m.file == file && m.method == method && m.variant == Variant::Method)
    };
    for m in measured.iter().filter(|m| m.variant == Variant::Method) {
        for pair in m.levels.windows(2) {
            if pair[1].worst_lower > pair[0].worst_upper {
                notes.push(format!(
                    "{} {}: level {} ({:.3} %) is worse than level {} ({:.3} %)",
                    m.file,
                    m.method.name(),
                    pair[1].level,
                    100.0 * pair[1].worst_lower,
                    pair[0].level,
                    100.0 * pair[0].worst_upper
                ));
            }
        }
        let rivals: &[Method] = match m.method {
            Method::Combined => &[Method::Merge, Method::Expand, Method::Hubbard],
            medial if medial.is_medial() => &[Method::Hubbard],
            _ => &[],
        };
        for &rival in rivals {
            let Some(r) = find(m.file, rival) else {
                continue;
            };
            for level in 1..=DEPTH {
                if let (Some(a), Some(b)) = (m.upper_pct(level), r.upper_pct(level))
                    && a > b
                {
                    notes.push(format!(
                        "{} level {level}: {} ({a:.3} %) is worse than {} ({b:.3} %)",
                        m.file,
                        m.method.name(),
                        rival.name()
                    ));
                }
            }
        }
    }
    notes
}

#[cfg(test)]
mod tests {
    use super::*;

    fn level(level: usize, lower: f64, upper: f64) -> Level {
        Level {
            level,
            spheres: BRANCH.pow(level as u32),
            worst_lower: lower,
            worst_upper: upper,
            mean_error: lower / 2.0,
            construction_error: lower,
            uncovered: 0.0,
            converged: true,
            evaluation_seconds: 0.0,
        }
    }

    pub(super) fn measured(method: Method, uppers: [f64; 3]) -> Measured {
        Measured {
            file: TOOLKIT_MESH,
            method,
            variant: Variant::Method,
            error_fraction: 0.5,
            effort: Effort::Default,
            seconds: 1.0,
            levels: uppers
                .iter()
                .enumerate()
                .map(|(i, &u)| level(i + 1, u - 0.001, u))
                .collect(),
        }
    }

    /// A unique empty folder under the system's temporary folder.
    pub(super) fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("sphaera-eval-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn variants_are_the_methods_the_sweep_and_the_default() {
        let trees = variants();
        assert_eq!(
            trees.len(),
            METHODS.len() + ERROR_FRACTIONS.len() + EFFORTS.len() + 1
        );
        for (variant, options) in &trees {
            assert_eq!(
                (options.depth, options.branch, options.seed),
                (DEPTH, BRANCH, SEED)
            );
            match *variant {
                Variant::Method => {}
                Variant::ErrorFraction(i) => {
                    assert_eq!(options.method, SWEEP_METHOD);
                    assert!((options.error_fraction - ERROR_FRACTIONS[i].0).abs() < 1e-15);
                }
                Variant::Effort(i) => {
                    assert_eq!(options.method, Method::Minimax);
                    assert_eq!(options.effort, EFFORTS[i]);
                }
                Variant::LibraryDefault => assert_eq!(options.method, Method::default()),
            }
        }
        let methods: Vec<Method> = trees
            .iter()
            .filter(|(v, _)| *v == Variant::Method)
            .map(|(_, o)| o.method)
            .collect();
        assert_eq!(methods, METHODS);
        // Largest fraction first, each half the one before.
        for pair in ERROR_FRACTIONS.windows(2) {
            assert!((pair[1].0 - pair[0].0 / 2.0).abs() < 1e-15);
        }
    }

    #[test]
    fn the_default_is_judged_against_the_target_per_level() {
        let default = Measured {
            variant: Variant::LibraryDefault,
            ..measured(Method::default(), [0.09, 0.04, 0.015])
        };
        let notes = against_target(&[measured(Method::Merge, [0.5, 0.5, 0.5]), default]);
        assert_eq!(notes.len(), DEPTH, "{notes:?}");
        assert!(
            notes[0].ends_with("met") && notes[2].ends_with("met"),
            "{notes:?}"
        );
        assert!(notes[1].ends_with("missed"), "{notes:?}");
        // The target is 0.9x the toolkit's best per level, rounded.
        for (level, &target) in TARGET.iter().enumerate() {
            let best = TOOLKIT
                .iter()
                .map(|t| t.2[level])
                .fold(f64::INFINITY, f64::min);
            assert!((target - 0.9 * best).abs() < 0.05, "level {}", level + 1);
        }
    }

    #[test]
    fn oddities_name_worse_levels_and_worse_combined() {
        let fine = [
            measured(Method::Merge, [0.10, 0.05, 0.02]),
            measured(Method::Expand, [0.11, 0.04, 0.02]),
            measured(Method::Combined, [0.10, 0.04, 0.02]),
            measured(Method::Hubbard, [0.14, 0.06, 0.06]),
        ];
        assert!(oddities(&fine).is_empty(), "{:?}", oddities(&fine));
        let odd = [
            measured(Method::Merge, [0.10, 0.05, 0.06]),
            measured(Method::Combined, [0.10, 0.055, 0.02]),
        ];
        let notes = oddities(&odd);
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(notes[0].contains("merge: level 3"));
        assert!(notes[1].contains("level 2: combined"));
    }
}
