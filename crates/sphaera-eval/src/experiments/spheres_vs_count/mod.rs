//! `spheres_vs_count`: exactly N spheres around a mesh, Sphaera against morphit-rs (issue
//! 36), both measured by the same certified evaluator.
//!
//! The meshes: `bunny_lowres.obj`, `spot.obj` and `fandisk.obj` of `shared/data`, the
//! Franka Panda's collision links (`robots/franka_panda/collision/link1.obj` to
//! `link7.obj` and `hand.obj`; a link without an inside is skipped with a message), and
//! the unseen animal, [`sphaera_tests::animal::quadruped`] ("animal (procedural)" in the
//! CSV; written to a temporary OBJ file for the peer). The counts: `N` in {8, 16, 32,
//! 64, 128, 256, 512} ([`COUNTS`]); on the links, whose planners use a few dozen spheres,
//! 8 to 64 ([`LINK_COUNTS`]).
//!
//! Per mesh and `N`:
//!
//! - **Sphaera** ([`crate::sphere_sets::one_level_minimax`]): `sphaera::spheretree::build(
//!   &Surface::solid_or_shell(mesh), &SphereTreeOptions::default().with_depth(1)
//!   .with_branch(N))`, the spheres of level 1. Timed from the loaded mesh to the spheres
//!   (the surface's preparation included). The spheres produced are recorded (the library
//!   promises exactly `N`), and so is the tree's own certified bound: per sphere its
//!   `TreeNode::error`, and per set the largest over the spheres of
//!   `min(node error, evaluated upper bound)` (the true error of a sphere is at most
//!   both).
//! - **morphit-rs raw** ([`crate::peers::run_morphit`], `peers/morphit_spheres.py`): its
//!   default preset (`MorphIt-B`), seed 0, its default threads (both cores); the script
//!   times `pack` alone. Skipped with a message when `$SPHAERA_MORPHIT_PYTHON` (default
//!   `python3`) cannot import `morphit_rs`
//!   (`python3 -m venv env && env/bin/pip install morphit-rs==0.2.0 numpy`). It may return
//!   fewer than `N` spheres (its final prune); the CSV has both counts.
//! - **morphit-rs grown** ([`crate::sphere_sets::grow_to_cover`]): the raw set with every
//!   radius grown by the same amount, the largest distance from a surface point outside
//!   every sphere to the nearest sphere's surface (on 1,000,000 random surface samples of
//!   another seed than the evaluator's, and every vertex), then certified by
//!   `sphaera::spheretree::cover::certify_coverage` at the library's default resolution
//!   (10⁻³ of the diagonal), which grows single spheres further where a piece of a
//!   triangle is still outside. Both growths are in the CSV (`uniform_growth_pct`,
//!   `certify_growth_pct`, `certify_grown_spheres`). Its time is the raw set's: the growth
//!   is ours, not the peer's.
//!
//! Every set is measured by `sphaera::spheretree::evaluate_set(&surface, &spheres,
//! &EvaluationOptions::default())` on the same `Surface::solid_or_shell(mesh)`: the
//! **worst protrusion** (the largest distance from a point of a sphere's surface outside
//! the object to the object, the per-sphere error of the sphere-tree literature) as a
//! certified interval `[lower, upper]` of width 10⁻⁴ of the diagonal, and the **uncovered
//! share**: the fraction of 100,000 random surface samples outside every sphere. All
//! lengths are in % of the mesh's bounding-box diagonal.
//!
//! Times are the shortest of two runs for `N` ≤ 64 and one run above ([`runs_for`]), the
//! same for both libraries, run one after the other on the same machine.
//!
//! The targets, reported per mesh and `N` on the terminal and in the CSV's
//! `verdict` (Sphaera's rows), not tuned for: exactly `N` spheres, full coverage, a worst
//! protrusion at most half the peer's grown one (Sphaera's upper bound against half the
//! peer's lower bound), and no slower than the peer.
//!
//! Files: `spheres_vs_count.csv` (every row) and `.svg` (one panel per mesh: worst
//! protrusion against `N`); `spheres_vs_count_time.{svg,csv}` (one panel per mesh: time
//! against `N`, both libraries); `spheres_vs_count_uncovered.{svg,csv}` (the peer's raw
//! uncovered share against `N`, every mesh; Sphaera's and the grown sets' are 0). The
//! table in `docs/benchmarks.md` is generated from the first CSV by `cargo xtask tables`.

mod charts;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use sphaera::mesh::{Surface, TriMesh, io};
use sphaera::spheretree::{
    CoverageCertificate, EvaluationOptions, SetEvaluation, SphereTreeOptions, evaluate_set,
};

use super::{load_or_skip, min_time};
use crate::peers::{MorphitRun, morphit_python, run_morphit};
use crate::sphere_sets::{grow_to_cover, one_level_minimax};

/// The experiment's name, and its main chart's.
pub(super) const NAME: &str = "spheres_vs_count";

/// The sphere counts of the shared meshes and the animal.
const COUNTS: &[usize] = &[8, 16, 32, 64, 128, 256, 512];

/// The sphere counts of the robot links.
const LINK_COUNTS: &[usize] = &[8, 16, 32, 64];

/// The meshes of `shared/data`, with their counts.
const MESHES: &[(&str, &[usize])] = &[
    ("bunny_lowres.obj", COUNTS),
    ("spot.obj", COUNTS),
    ("fandisk.obj", COUNTS),
    ("robots/franka_panda/collision/link1.obj", LINK_COUNTS),
    ("robots/franka_panda/collision/link2.obj", LINK_COUNTS),
    ("robots/franka_panda/collision/link3.obj", LINK_COUNTS),
    ("robots/franka_panda/collision/link4.obj", LINK_COUNTS),
    ("robots/franka_panda/collision/link5.obj", LINK_COUNTS),
    ("robots/franka_panda/collision/link6.obj", LINK_COUNTS),
    ("robots/franka_panda/collision/link7.obj", LINK_COUNTS),
    ("robots/franka_panda/collision/hand.obj", LINK_COUNTS),
];

/// The procedural animal's name in the CSV.
const ANIMAL: &str = "animal (procedural)";

/// The method names in the CSV.
const SPHAERA: &str = "sphaera";
/// morphit-rs as it returns its spheres.
const MORPHIT_RAW: &str = "morphit_raw";
/// morphit-rs grown until its spheres cover the surface.
const MORPHIT_GROWN: &str = "morphit_grown";

/// Timed runs at `n` spheres: two up to 64, one above (the largest builds take seconds).
fn runs_for(n: usize) -> usize {
    if n <= 64 { 2 } else { 1 }
}

/// One mesh, one method, one count.
struct Row {
    mesh: String,
    method: &'static str,
    requested: usize,
    fit: SetEvaluation,
    /// Sphaera: the largest `TreeNode::error`, and the largest per-sphere
    /// `min(node error, evaluated upper)`.
    node_bound: Option<(f64, f64)>,
    seconds: f64,
    runs: usize,
    /// The grown set: the uniform growth and what `certify_coverage` added.
    growth: Option<(f64, CoverageCertificate)>,
    diagonal: f64,
    /// Sphaera's rows: the comparison with the peer, filled once both are measured.
    verdict: Option<Verdict>,
}

/// Sphaera's row against the peer's at the same mesh and count.
struct Verdict {
    /// Sphaera's worst upper bound over the peer's grown worst lower bound (≤ 0.5 meets
    /// the target); `None` without the peer.
    protrusion_ratio: Option<f64>,
    /// Sphaera's time over the peer's (≤ 1 meets the target); `None` without the peer.
    time_ratio: Option<f64>,
    /// Exactly `N` spheres came back.
    exact: bool,
    /// No coverage sample outside every sphere.
    covered: bool,
}

impl Verdict {
    /// `met`, or the targets missed (`missed count coverage protrusion time`), with
    /// `no peer` when the peer was not measured.
    fn text(&self) -> String {
        let mut missed = Vec::new();
        if !self.exact {
            missed.push("count");
        }
        if !self.covered {
            missed.push("coverage");
        }
        let peer = self.protrusion_ratio.zip(self.time_ratio);
        if let Some((protrusion, time)) = peer {
            if protrusion > 0.5 {
                missed.push("protrusion");
            }
            if time > 1.0 {
                missed.push("time");
            }
        }
        let verdict = if missed.is_empty() {
            "met".to_owned()
        } else {
            format!("missed {}", missed.join(" "))
        };
        match peer {
            Some(_) => verdict,
            None => format!("{verdict}; no peer"),
        }
    }
}

pub(super) fn run(data: &Path, out: &Path) -> Result<()> {
    let started = std::time::Instant::now();
    let python = morphit_python(NAME);
    let mut rows = Vec::new();
    for &(file, counts) in MESHES {
        let Some(mesh) = load_or_skip(data, file)? else {
            continue;
        };
        rows.extend(mesh_rows(
            file,
            &mesh,
            &data.join(file),
            counts,
            python.as_deref(),
        )?);
    }
    // The peer reads files: the animal goes through a temporary OBJ.
    let animal = sphaera_tests::animal::quadruped();
    let animal_file =
        std::env::temp_dir().join(format!("sphaera-eval-animal-{}.obj", std::process::id()));
    io::write_obj(&animal_file, &animal).context("writing the animal for the peer")?;
    let animal_rows = mesh_rows(ANIMAL, &animal, &animal_file, COUNTS, python.as_deref());
    let _ = std::fs::remove_file(&animal_file);
    rows.extend(animal_rows?);
    if rows.is_empty() {
        eprintln!("{NAME}: no mesh found, nothing written");
        return Ok(());
    }
    charts::write_outputs(out, &rows)?;
    eprintln!(
        "{NAME}: {} rows in {:.0} s",
        rows.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Every row of one mesh (`name` in the CSV, `path` for the peer).
fn mesh_rows(
    name: &str,
    mesh: &TriMesh,
    path: &Path,
    counts: &[usize],
    python: Option<&Path>,
) -> Result<Vec<Row>> {
    let surface = Surface::solid_or_shell(mesh).with_context(|| format!("preparing {name}"))?;
    if !surface.has_inside() {
        eprintln!("{name}: no inside (not a solid), skipped");
        return Ok(Vec::new());
    }
    let diagonal = surface.diagonal();
    let evaluation = EvaluationOptions::default();
    let pct = |v: f64| 100.0 * v / diagonal;
    let mut rows = Vec::new();
    for &n in counts {
        let runs = runs_for(n);
        let (seconds, set) = min_time(runs, || one_level_minimax(mesh, n))
            .with_context(|| format!("Sphaera on {name} at {n}"))?;
        let fit = evaluate_set(&surface, &set.spheres, &evaluation)
            .with_context(|| format!("evaluating Sphaera on {name} at {n}"))?;
        let node_error = set.node_errors.iter().copied().fold(0.0, f64::max);
        let bound = set
            .node_errors
            .iter()
            .zip(&fit.fits)
            .map(|(&e, f)| e.min(f.upper))
            .fold(0.0, f64::max);
        eprintln!(
            "{name}: Sphaera {n:>3} -> {:>3} spheres in {seconds:.3} s, worst {:.3} % \
             (node bound {:.3} %), uncovered {:.3} %",
            set.spheres.len(),
            pct(fit.worst_upper),
            pct(node_error),
            100.0 * fit.coverage.uncovered_fraction
        );
        rows.push(Row {
            mesh: name.to_owned(),
            method: SPHAERA,
            requested: n,
            fit,
            node_bound: Some((node_error, bound)),
            seconds,
            runs,
            growth: None,
            diagonal,
            verdict: None,
        });
    }
    if let Some(python) = python {
        let resolution = SphereTreeOptions::default()
            .coverage_resolution
            .resolve(diagonal);
        for run in morphit_runs(python, path, counts)? {
            let n = run.requested;
            let spheres = match run.spheres {
                Ok(spheres) if !spheres.is_empty() => spheres,
                Ok(_) => {
                    eprintln!("{name}: morphit-rs returned no sphere at {n}, skipped");
                    continue;
                }
                Err(error) => {
                    eprintln!("{name}: morphit-rs failed at {n} ({error}), skipped");
                    continue;
                }
            };
            let raw = evaluate_set(&surface, &spheres, &evaluation)
                .with_context(|| format!("evaluating morphit-rs on {name} at {n}"))?;
            let grown = grow_to_cover(mesh, &spheres, resolution)
                .with_context(|| format!("growing morphit-rs on {name} at {n}"))?;
            let grown_fit = evaluate_set(&surface, &grown.spheres, &evaluation)
                .with_context(|| format!("evaluating grown morphit-rs on {name} at {n}"))?;
            eprintln!(
                "{name}: morphit {n:>3} -> {:>3} spheres in {:.3} s, raw worst {:.3} % \
                 uncovered {:.2} %; grown by {:.3} % (+{:.3} % on {} spheres) worst {:.3} %",
                spheres.len(),
                run.seconds,
                pct(raw.worst_upper),
                100.0 * raw.coverage.uncovered_fraction,
                pct(grown.uniform),
                pct(grown.certificate.largest_growth),
                grown.certificate.grown_spheres,
                pct(grown_fit.worst_upper)
            );
            let runs = runs_for(n);
            let peer = |method, fit, growth| Row {
                mesh: name.to_owned(),
                method,
                requested: n,
                fit,
                node_bound: None,
                seconds: run.seconds,
                runs,
                growth,
                diagonal,
                verdict: None,
            };
            rows.push(peer(MORPHIT_RAW, raw, None));
            rows.push(peer(
                MORPHIT_GROWN,
                grown_fit,
                Some((grown.uniform, grown.certificate)),
            ));
        }
    }
    judge(&mut rows);
    Ok(rows)
}

/// The peer at `counts` on the mesh file `path`: the counts up to 64 with two runs each,
/// the rest with one ([`runs_for`]), in the order of `counts`.
fn morphit_runs(python: &Path, path: &Path, counts: &[usize]) -> Result<Vec<MorphitRun>> {
    let mut out = Vec::new();
    for runs in [2, 1] {
        let these: Vec<usize> = counts
            .iter()
            .copied()
            .filter(|&n| runs_for(n) == runs)
            .collect();
        if !these.is_empty() {
            out.extend(run_morphit(python, path, &these, runs)?);
        }
    }
    Ok(out)
}

/// Fills the verdict of every Sphaera row of one mesh and prints it.
fn judge(rows: &mut [Row]) {
    let peer = |method: &str, n: usize, rows: &[Row]| {
        rows.iter()
            .find(|r| r.method == method && r.requested == n)
            .map(|r| (r.fit.worst_lower, r.seconds))
    };
    for i in 0..rows.len() {
        if rows[i].method != SPHAERA {
            continue;
        }
        let n = rows[i].requested;
        let grown = peer(MORPHIT_GROWN, n, rows);
        let ours = &rows[i];
        let verdict = Verdict {
            protrusion_ratio: grown.map(|(lower, _)| ours.fit.worst_upper / lower),
            time_ratio: grown.map(|(_, seconds)| ours.seconds / seconds),
            exact: ours.fit.sphere_count == n,
            covered: ours.fit.coverage.uncovered == 0,
        };
        let pct = |v: f64| 100.0 * v / ours.diagonal;
        let peer_text = grown.map_or_else(
            || "no peer".to_owned(),
            |(lower, seconds)| {
                format!(
                    "{:.2} % vs half the grown peer's {:.2} %, {:.2} s vs {:.2} s",
                    pct(ours.fit.worst_upper),
                    pct(0.5 * lower),
                    ours.seconds,
                    seconds
                )
            },
        );
        eprintln!(
            "verdict {} N={n}: {} spheres, {} uncovered samples, {peer_text}: {}",
            ours.mesh,
            ours.fit.sphere_count,
            ours.fit.coverage.uncovered,
            verdict.text()
        );
        rows[i].verdict = Some(verdict);
    }
}

/// The short name of a mesh for chart panels: the file stem, links as "panda link1".
fn short_name(mesh: &str) -> String {
    let path = PathBuf::from(mesh);
    let stem = path
        .file_stem()
        .map_or_else(|| mesh.to_owned(), |s| s.to_string_lossy().into_owned());
    if mesh.contains("franka_panda") {
        format!("panda {stem}")
    } else if mesh.ends_with(".obj") {
        stem
    } else {
        mesh.to_owned()
    }
}
