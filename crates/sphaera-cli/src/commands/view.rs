//! `sphaera view`: one self-contained HTML page showing a mesh and its sphere-tree.
//!
//! The page inlines three.js (npm `three` 0.160.1, MIT, vendored in `assets/three/` with
//! its licence; its single-file ES module, given to the page's script through an import
//! map of a `data:` URL, so nothing is fetched at view time) and the page's own script
//! (`assets/view/view.js`, kept readable in its own file). The mesh and the spheres go in
//! as base64 little-endian typed arrays.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use base64::Engine as _;
use serde::Serialize;
use sphaera::mesh::{DVec3, Length, Sphere, Surface, TriMesh};
use sphaera::simplify::{Simplified, SimplifyOptions, simplify};
use sphaera::spheretree::export::{read_sph, tree_from_json};
use sphaera::spheretree::{
    EvaluationOptions, SphereTreeOptions, build_with_progress, evaluate_set,
};

use crate::{
    cli::ViewArgs,
    input::read_mesh,
    output::{check_target, print_report, thousands},
    progress,
};

/// three.js 0.160.1 (MIT; `assets/three/LICENSE`), the single-file ES module.
const THREE_JS: &str = include_str!("../../assets/three/three.module.min.js");
/// The page around the data and the scripts.
const PAGE: &str = include_str!("../../assets/view/view.html");
/// The page's own script.
const VIEW_JS: &str = include_str!("../../assets/view/view.js");

/// Everything `sphaera view` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    /// The mesh's bounding-box diagonal (the page gives errors as a percentage of it).
    diagonal: f64,
    /// `built` (depth and branch) or the tree file read.
    tree: String,
    /// Per level: spheres and the certified worst error (`null` when the mesh has no
    /// inside to measure against).
    levels: Vec<LevelReport>,
    /// With `--simplify`: the simplified mesh's triangles and its certified error bound.
    simplified: Option<SimplifiedReport>,
    output: String,
    /// The page's size in bytes.
    bytes: usize,
    seconds: f64,
}

#[derive(Clone, Copy, Debug, Serialize)]
struct SimplifiedReport {
    ratio: f64,
    triangles: usize,
    error_bound: f64,
}

#[derive(Debug, Serialize)]
struct LevelReport {
    level: usize,
    spheres: usize,
    error_lower: Option<f64>,
    error_upper: Option<f64>,
}

#[derive(Serialize)]
struct PageLevel {
    count: usize,
    /// `x, y, z, r` per sphere, f32, base64.
    spheres: String,
    /// The index of the sphere reaching farthest beyond the surface (certified), or the
    /// largest sphere when the mesh has no inside to measure against.
    worst: usize,
    error_lower: Option<f64>,
    error_upper: Option<f64>,
}

pub fn run(args: &ViewArgs, quiet: bool) -> Result<()> {
    let started = Instant::now();
    let output: PathBuf = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from("view.html"));
    check_target(&output)?;
    let input = read_mesh(args.mesh.as_deref(), quiet)?;
    let mesh = input.loaded.mesh;
    if mesh.triangle_count() == 0 {
        bail!(
            "{}: the mesh has no triangles: nothing to view",
            input.source
        );
    }
    let surface = Surface::new(&mesh).ok();
    let (levels, tree_source) = match &args.tree {
        Some(path) => (read_tree(path)?, path.display().to_string()),
        None => {
            let Some(surface) = surface.as_ref() else {
                bail!(
                    "{}: the mesh encloses no volume, so it has no sphere-tree (give one with --tree)",
                    input.source
                );
            };
            let options = SphereTreeOptions::default();
            let bar = progress::bar(quiet, "building the sphere-tree", 1);
            let tree = build_with_progress(surface, &options, &|_| {})
                .with_context(|| format!("cannot build a sphere-tree of {}", input.source))?;
            bar.finish_and_clear();
            let levels = (0..tree.level_count())
                .map(|l| tree.level_spheres(l))
                .collect();
            (
                levels,
                format!("built (depth {}, branch {})", options.depth, options.branch),
            )
        }
    };
    check_tree_fits(&mesh, &levels, &tree_source)?;
    let evaluations = evaluate(surface.as_ref(), &levels, quiet)?;
    let simplified = match args.simplify {
        None => None,
        Some(ratio) => {
            let spinner = progress::spinner(quiet, "simplifying");
            let options = SimplifyOptions::default().with_target_ratio(ratio);
            let result = simplify(&mesh, &options)
                .with_context(|| format!("cannot simplify {}", input.source));
            spinner.finish_and_clear();
            Some((ratio, result?))
        }
    };
    let page = page(
        &input.source,
        &mesh,
        &levels,
        &evaluations,
        simplified.as_ref().map(|(_, s)| s),
    );
    sphaera::mesh::io::write_atomic(&output, |w| std::io::Write::write_all(w, page.as_bytes()))
        .with_context(|| format!("cannot write {}", output.display()))?;
    let report = Report {
        mesh: input.source,
        triangles: mesh.triangle_count(),
        diagonal: mesh.bounding_box_diagonal(),
        tree: tree_source,
        levels: levels
            .iter()
            .zip(&evaluations)
            .enumerate()
            .map(|(level, (spheres, e))| LevelReport {
                level,
                spheres: spheres.len(),
                error_lower: e.map(|e| e.lower),
                error_upper: e.map(|e| e.upper),
            })
            .collect(),
        simplified: simplified.as_ref().map(|(ratio, s)| SimplifiedReport {
            ratio: *ratio,
            triangles: s.mesh.triangle_count(),
            error_bound: s.error_bound,
        }),
        output: output.display().to_string(),
        bytes: page.len(),
        seconds: started.elapsed().as_secs_f64(),
    };
    print_report(&report, args.print.json)
}

/// The levels of a tree file: JSON (`sphaera spheretree -o tree.json`) or `.sph`.
fn read_tree(path: &Path) -> Result<Vec<Vec<Sphere>>> {
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
fn check_tree_fits(mesh: &TriMesh, levels: &[Vec<Sphere>], source: &str) -> Result<()> {
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
struct Evaluation {
    lower: f64,
    upper: f64,
    worst: usize,
}

/// The certified worst error of each level, or `None` without a surface.
fn evaluate(
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

fn base64_of(bytes: &[u8]) -> String {
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

fn f32_base64(values: impl Iterator<Item = f64>) -> String {
    let bytes: Vec<u8> = values.flat_map(|v| (v as f32).to_le_bytes()).collect();
    base64_of(&bytes)
}

/// The whole page: the template with three.js, the data and the script put in.
fn page(
    name: &str,
    mesh: &TriMesh,
    levels: &[Vec<Sphere>],
    evaluations: &[Option<Evaluation>],
    simplified: Option<&Simplified>,
) -> String {
    let centre = mesh.bounding_box().center();
    let radius = mesh
        .positions()
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let positions = f32_base64(
        mesh.positions()
            .iter()
            .flat_map(|&p| (p - centre).to_array()),
    );
    let triangles: Vec<u8> = mesh
        .triangles()
        .iter()
        .flatten()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let page_levels: Vec<PageLevel> = levels
        .iter()
        .zip(evaluations)
        .map(|(spheres, evaluation)| PageLevel {
            count: spheres.len(),
            spheres: f32_base64(spheres.iter().flat_map(|s| {
                let c = s.center - centre;
                [c.x, c.y, c.z, s.radius]
            })),
            worst: evaluation.map_or_else(|| largest(spheres), |e| e.worst),
            error_lower: evaluation.map(|e| e.lower),
            error_upper: evaluation.map(|e| e.upper),
        })
        .collect();
    let simplified = simplified.map(|s| {
        let triangles: Vec<u8> = s
            .mesh
            .triangles()
            .iter()
            .flatten()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        serde_json::json!({
            "triangles_count": s.mesh.triangle_count(),
            "error_bound": s.error_bound,
            "positions": f32_base64(s.mesh.positions().iter().flat_map(|&p| (p - centre).to_array())),
            "triangles": base64_of(&triangles),
        })
    });
    let data = serde_json::json!({
        "name": name,
        "triangles_count": mesh.triangle_count(),
        "diagonal": mesh.bounding_box_diagonal(),
        "radius": radius,
        "offset": centre.to_array(),
        "positions": positions,
        "triangles": base64_of(&triangles),
        "levels": page_levels,
        "simplified": simplified,
    });
    // `</` cannot appear in JSON's output except inside strings; escape it so that the
    // data cannot close its script element.
    let data = data.to_string().replace("</", "<\\/");
    PAGE.replace(
        "SPHAERA_TITLE",
        &html_escape(&format!("sphaera view: {name}")),
    )
    .replace("SPHAERA_THREE_BASE64", &base64_of(THREE_JS.as_bytes()))
    .replace("SPHAERA_DATA", &data)
    .replace("SPHAERA_VIEW_JS", VIEW_JS)
}

/// The index of the largest sphere.
fn largest(spheres: &[Sphere]) -> usize {
    spheres
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.radius.total_cmp(&b.1.radius).then(b.0.cmp(&a.0)))
        .map_or(0, |(i, _)| i)
}

fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![
            format!(
                "mesh            {} ({} triangles)",
                self.mesh,
                thousands(self.triangles)
            ),
            format!("tree            {}", self.tree),
        ];
        for l in &self.levels {
            lines.push(format!(
                "  level {}       {:>6} spheres, certified worst error {}",
                l.level,
                thousands(l.spheres),
                match (l.error_lower, l.error_upper) {
                    (Some(a), Some(b)) => format!("[{a:.6}, {b:.6}]"),
                    _ => "not measured (no inside)".to_owned(),
                }
            ));
        }
        if let Some(s) = &self.simplified {
            lines.push(format!(
                "simplified      {} triangles ({} of the input), certified error bound {:.6}",
                thousands(s.triangles),
                s.ratio,
                s.error_bound
            ));
        }
        lines.push(format!(
            "wrote           {} ({} KB, opens offline in any browser)",
            self.output,
            self.bytes / 1024
        ));
        lines.push(format!("time            {:.3} s", self.seconds));
        lines.join("\n") + "\n"
    }
}
