//! The sphere-tree a page shows: read from a file or built, checked against the mesh, and
//! each level's worst error certified.
//!
//! A level is shown as its cut: the level's nodes and the leaves above it, which together
//! cover the surface. In a tree built to a depth that is the level itself; in a tree built
//! to a tolerance (`sphaera spheretree --tolerance`) the leaves end at different depths,
//! and a level alone would leave holes where a shallower leaf stands for its part.

use std::path::Path;

use anyhow::{Context, Result, bail};
use sphaera::mesh::{DVec3, Length, Sphere, Surface, TriMesh};
use sphaera::spheretree::export::{SphFile, TreeFormat, read_sph, tree_from_json};
use sphaera::spheretree::{
    EvaluationOptions, SphereTree, SphereTreeOptions, build_with_progress, evaluate_set,
};

use crate::progress;

/// The levels a page shows, each as its cut.
pub struct Levels {
    /// Per level, the spheres of its cut.
    pub spheres: Vec<Vec<Sphere>>,
    /// Per level, each sphere's certified error bound as the tree records it (its node's
    /// construction error), when the tree records one: not in `.sph` files.
    pub bounds: Vec<Option<Vec<f64>>>,
}

impl Levels {
    /// The cuts of a tree, with its nodes' errors.
    fn of_tree(tree: &SphereTree) -> Self {
        let cuts: Vec<Vec<usize>> = (0..tree.level_count()).map(|l| tree.cut_at(l)).collect();
        let node = |i: usize| &tree.nodes()[i];
        Self {
            spheres: cuts
                .iter()
                .map(|cut| cut.iter().map(|&i| node(i).sphere).collect())
                .collect(),
            bounds: cuts
                .iter()
                .map(|cut| Some(cut.iter().map(|&i| node(i).error).collect()))
                .collect(),
        }
    }

    /// The cuts of a `.sph` tree: per level, its used slots and the used slots above it
    /// whose child slots are all unused (the leaves), in slot order.
    fn of_sph(file: &SphFile) -> Self {
        // The level and leafness of every used slot.
        let mut used: Vec<(usize, Sphere, bool)> = Vec::new();
        for level in 0..file.levels {
            for slot in file.level_range(level) {
                if let Some(Some((sphere, _))) = file.nodes.get(slot) {
                    let leaf = file
                        .children(slot)
                        .all(|c| file.nodes.get(c).is_none_or(Option::is_none));
                    used.push((level, *sphere, leaf));
                }
            }
        }
        let spheres: Vec<Vec<Sphere>> = (0..file.levels)
            .map(|level| {
                used.iter()
                    .filter(|&&(at, _, leaf)| at == level || (at < level && leaf))
                    .map(|&(_, sphere, _)| sphere)
                    .collect()
            })
            .collect();
        let bounds = vec![None; spheres.len()];
        Self { spheres, bounds }
    }
}

/// The levels of a tree file, as cuts: JSON (`sphaera spheretree -o tree.json`) or `.sph`.
pub fn read_tree(path: &Path) -> Result<Levels> {
    let text = crate::input::read_text(path, "the tree")?;
    let levels = if TreeFormat::from_path(path) == Some(TreeFormat::Sph) {
        let file = read_sph(&text, DVec3::ZERO)
            .with_context(|| format!("{}: not a valid .sph file", path.display()))?;
        Levels::of_sph(&file)
    } else {
        let tree = tree_from_json(&text)
            .with_context(|| format!("{}: not a sphere-tree JSON file", path.display()))?;
        Levels::of_tree(&tree)
    };
    if levels.spheres.iter().all(Vec::is_empty) {
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

/// The certified worst error of each level's cut, or `None` without a surface. The upper
/// bound is the tightest certified one: per sphere the smaller of the evaluation's upper
/// bound and the tree's own bound (where the tree records one), largest over the cut.
pub fn evaluate(
    surface: Option<&Surface>,
    levels: &Levels,
    quiet: bool,
) -> Result<Vec<Option<Evaluation>>> {
    let Some(surface) = surface else {
        return Ok(vec![None; levels.spheres.len()]);
    };
    let options = EvaluationOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(1e-3))
        .with_screening(true);
    let bar = progress::bar(
        quiet,
        "certifying each level's error",
        levels.spheres.len() as u64,
    );
    let mut out = Vec::with_capacity(levels.spheres.len());
    for (level, (spheres, bounds)) in levels.spheres.iter().zip(&levels.bounds).enumerate() {
        if spheres.is_empty() {
            out.push(None);
            continue;
        }
        let fit = evaluate_set(surface, spheres, &options)
            .with_context(|| format!("cannot evaluate level {level}"))?;
        let uppers: Vec<f64> = fit
            .fits
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let bound = bounds
                    .as_ref()
                    .and_then(|b| b.get(i).copied())
                    .unwrap_or(f64::INFINITY);
                f.upper.min(bound)
            })
            .collect();
        // The first sphere of the largest bound.
        let (worst, upper) = uppers.iter().copied().enumerate().fold(
            (fit.worst_index, f64::NEG_INFINITY),
            |best, (i, u)| {
                if u > best.1 { (i, u) } else { best }
            },
        );
        out.push(Some(Evaluation {
            lower: fit.worst_lower,
            upper,
            worst,
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

/// The levels to show, as cuts, and where they come from: the tree file, or a tree built
/// with the default options (the main job's) on the surface (a solid or a shell).
pub fn levels(
    tree: Option<&Path>,
    surface: Option<&Surface>,
    source: &str,
    quiet: bool,
) -> Result<(Levels, String)> {
    if let Some(path) = tree {
        return Ok((read_tree(path)?, path.display().to_string()));
    }
    let Some(surface) = surface else {
        bail!("{source}: the mesh has no surface to build a sphere-tree on (give one with --tree)");
    };
    let options = SphereTreeOptions::default();
    let bar = progress::bar(quiet, "building the sphere-tree", 1);
    let tree = build_with_progress(surface, &options, &|_| {})
        .with_context(|| format!("cannot build a sphere-tree of {source}"));
    bar.finish_and_clear();
    let tree = tree?;
    Ok((
        Levels::of_tree(&tree),
        format!("built (depth {}, branch {})", options.depth, options.branch),
    ))
}
