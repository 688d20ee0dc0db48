//! The sphere-tree a page shows: read from a file or built, checked against the mesh, and
//! each level's worst error certified.

use std::path::Path;

use anyhow::{Context, Result, bail};
use sphaera::mesh::{DVec3, Length, Sphere, Surface, TriMesh};
use sphaera::spheretree::export::{read_sph, tree_from_json};
use sphaera::spheretree::{
    EvaluationOptions, SphereTreeOptions, build_with_progress, evaluate_set,
};

use crate::progress;

/// The levels of a tree file: JSON (`sphaera spheretree -o tree.json`) or `.sph`.
pub fn read_tree(path: &Path) -> Result<Vec<Vec<Sphere>>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the tree {}", path.display()))?;
    let is_sph = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("sph"));
    let levels: Vec<Vec<Sphere>> = if is_sph {
        let file = read_sph(&text, DVec3::ZERO)
            .with_context(|| format!("{}: not a valid .sph file", path.display()))?;
        (0..file.levels).map(|l| file.level(l)).collect()
    } else {
        let tree = tree_from_json(&text)
            .with_context(|| format!("{}: not a sphere-tree JSON file", path.display()))?;
        (0..tree.level_count())
            .map(|l| tree.level_spheres(l))
            .collect()
    };
    if levels.iter().all(Vec::is_empty) {
        bail!("{}: the tree has no spheres", path.display());
    }
    Ok(levels)
}

/// A tree for another mesh is refused: its root level must hold every vertex.
pub fn check_tree_fits(mesh: &TriMesh, levels: &[Vec<Sphere>], source: &str) -> Result<()> {
    let Some(roots) = levels.iter().find(|l| !l.is_empty()) else {
        bail!("{source}: the tree has no spheres");
    };
    let slack = 1e-6 * mesh.bounding_box_diagonal();
    for (i, &p) in mesh.positions().iter().enumerate() {
        let outside = roots
            .iter()
            .map(|s| s.center.distance(p) - s.radius)
            .fold(f64::INFINITY, f64::min);
        if outside > slack {
            bail!(
                "{source}: vertex {i} of the mesh is {outside:.4} outside every root sphere: is it the tree of another mesh?"
            );
        }
    }
    Ok(())
}

/// A level's certified worst error and the sphere that has it.
#[derive(Clone, Copy, Debug)]
pub struct Evaluation {
    pub lower: f64,
    pub upper: f64,
    pub worst: usize,
}

/// The certified worst error of each level, or `None` without a surface.
pub fn evaluate(
    surface: Option<&Surface>,
    levels: &[Vec<Sphere>],
    quiet: bool,
) -> Result<Vec<Option<Evaluation>>> {
    let Some(surface) = surface else {
        return Ok(vec![None; levels.len()]);
    };
    let options = EvaluationOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(1e-3))
        .with_screening(true);
    let bar = progress::bar(quiet, "certifying each level's error", levels.len() as u64);
    let mut out = Vec::with_capacity(levels.len());
    for (level, spheres) in levels.iter().enumerate() {
        if spheres.is_empty() {
            out.push(None);
            continue;
        }
        let fit = evaluate_set(surface, spheres, &options)
            .with_context(|| format!("cannot evaluate level {level}"))?;
        out.push(Some(Evaluation {
            lower: fit.worst_lower,
            upper: fit.worst_upper,
            worst: fit.worst_index,
        }));
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(out)
}

/// The index of the largest sphere.
pub fn largest(spheres: &[Sphere]) -> usize {
    spheres
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.radius.total_cmp(&b.1.radius).then(b.0.cmp(&a.0)))
        .map_or(0, |(i, _)| i)
}

/// The levels to show and where they come from: the tree file, or a tree built with the
/// default options (the main job's).
pub fn levels(
    tree: Option<&Path>,
    surface: Option<&Surface>,
    source: &str,
    quiet: bool,
) -> Result<(Vec<Vec<Sphere>>, String)> {
    if let Some(path) = tree {
        return Ok((read_tree(path)?, path.display().to_string()));
    }
    let Some(surface) = surface else {
        bail!(
            "{source}: the mesh encloses no volume, so it has no sphere-tree (give one with --tree)"
        );
    };
    let options = SphereTreeOptions::default();
    let bar = progress::bar(quiet, "building the sphere-tree", 1);
    let tree = build_with_progress(surface, &options, &|_| {})
        .with_context(|| format!("cannot build a sphere-tree of {source}"));
    bar.finish_and_clear();
    let tree = tree?;
    let levels = (0..tree.level_count())
        .map(|l| tree.level_spheres(l))
        .collect();
    Ok((
        levels,
        format!("built (depth {}, branch {})", options.depth, options.branch),
    ))
}
