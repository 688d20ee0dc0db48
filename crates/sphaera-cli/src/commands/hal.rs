//! `sphaera hal`: the HAL tree of a polygon (Veltkamp), its levels, an adaptive
//! approximation, point inclusion, and a drawing.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::hal::{
    Containment, HalTree2, HalTree3, Node2, Polyline2, approximation_svg, parse_points,
    parse_points3,
};
use sphaera::mesh::io::write_atomic;

use super::hal_shapes;
use crate::{
    cli::HalArgs,
    output::{check_target, print_json, thousands},
};

/// Everything `sphaera hal` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    polygon: String,
    closed: bool,
    vertices: usize,
    /// Nodes of the tree (one per vertex off the level-0 chord).
    nodes: usize,
    depth: usize,
    /// The bounding-box diagonal the relative tolerances refer to.
    diagonal: f64,
    /// Per level 0 to the depth: the approximation's vertices and its covering width.
    levels: Vec<Level>,
    /// The approximation asked for (`--tolerance` or `--level`), if any.
    approximation: Option<Approximation>,
    /// Point inclusion of `--contains`, if given.
    contains: Option<Contains>,
    /// Intersection with `--intersect`, if given.
    intersect: Option<hal_shapes::Intersect>,
    output: Option<String>,
    seconds: Seconds,
}

#[derive(Debug, Serialize)]
struct Level {
    level: usize,
    vertices: usize,
    /// The largest width of a bounding area of the level's non-original edges (eq. 1).
    width: f64,
}

#[derive(Debug, Serialize)]
struct Approximation {
    /// `tolerance` or `level`.
    kind: &'static str,
    /// The absolute tolerance, or the level.
    value: f64,
    vertices: usize,
    width: f64,
}

#[derive(Debug, Serialize)]
struct Contains {
    file: String,
    points: usize,
    inside: usize,
    outside: usize,
    boundary: usize,
    /// One answer per point, in file order: `inside`, `outside` or `boundary`.
    answers: Vec<&'static str>,
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct Seconds {
    load: f64,
    build: f64,
}

/// Which parts an approximation refines.
#[derive(Clone, Copy, Debug)]
enum Refine {
    Width(f64),
    Level(usize),
    All,
}

impl Refine {
    fn refines(self, node: &Node2) -> bool {
        match self {
            Self::Width(tolerance) => node.width > tolerance,
            Self::Level(level) => node.level as usize <= level,
            Self::All => true,
        }
    }
}

/// Extensions a 3D approximation may be written as.
const MESH_EXTENSIONS: &[&str] = &["obj", "ply", "stl", "off"];

pub fn run(args: &HalArgs) -> Result<()> {
    // A mesh file (any extension the mesh reader knows, glTF included): a 3D HAL tree;
    // anything else is read as a polygon.
    if sphaera::mesh::io::Format::from_path(&args.polygon).is_some() {
        return run_mesh(args);
    }
    if sphaera::mesh::io::ShapeFormat::from_path(&args.polygon).is_some() {
        return hal_shapes::run_shapes(args);
    }
    if let Some(path) = &args.output {
        let extension = extension(path);
        if extension != "txt" && extension != "svg" {
            bail!(
                "cannot write {}: the approximation is written as .txt or .svg",
                path.display()
            );
        }
        check_target(path)?;
    }
    let started = Instant::now();
    let text = crate::input::read_text(&args.polygon, "the polygon")?;
    let polyline = Polyline2::parse(&text, !args.open)
        .with_context(|| format!("{} is not a polygon", args.polygon.display()))?;
    let load = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let tree = HalTree2::build(&polyline)?;
    let build = started.elapsed().as_secs_f64();

    let (lo, hi) = polyline.bounds();
    let diagonal = lo.distance(hi);
    let refine = match (args.tolerance, args.level) {
        (Some(tolerance), _) => Refine::Width(tolerance.resolve(diagonal)),
        (None, Some(level)) => Refine::Level(level),
        (None, None) => Refine::All,
    };
    let approximated = tree.approximation_by(|node| refine.refines(node));
    let approximation = match refine {
        Refine::Width(value) => Some(("tolerance", value)),
        Refine::Level(level) => Some(("level", level as f64)),
        Refine::All => None,
    }
    .map(|(kind, value)| Approximation {
        kind,
        value,
        vertices: approximated.vertices.len(),
        width: approximated.width,
    });
    let contains = match &args.contains {
        Some(path) => Some(locate(&tree, path)?),
        None => None,
    };
    let intersect = match &args.intersect {
        Some(path) => Some(hal_shapes::intersect(
            &hal_shapes::read_shape(&args.polygon, args.open)?,
            &hal_shapes::read_shape(path, false)?,
            path,
        )),
        None => None,
    };
    if let Some(path) = &args.output {
        let points = tree.polyline().points();
        let bytes = if extension(path) == "svg" {
            approximation_svg(&tree, &approximated).into_bytes()
        } else {
            approximated
                .vertices
                .iter()
                .fold(String::new(), |mut out, &v| {
                    let _ = writeln!(out, "{} {}", points[v].x, points[v].y);
                    out
                })
                .into_bytes()
        };
        write_atomic(path, |w| w.write_all(&bytes))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    let report = Report {
        polygon: args.polygon.display().to_string(),
        closed: polyline.is_closed(),
        vertices: polyline.points().len(),
        nodes: tree.nodes().len(),
        depth: tree.depth(),
        diagonal,
        levels: tree
            .level_summaries()
            .into_iter()
            .map(|l| Level {
                level: l.level,
                vertices: l.vertices,
                width: l.width,
            })
            .collect(),
        approximation,
        contains,
        intersect,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds { load, build },
    };
    if args.print.json {
        print_json(&report)
    } else {
        print_text(&report);
        Ok(())
    }
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Point inclusion for every point of `path`.
fn locate(tree: &HalTree2, path: &Path) -> Result<Contains> {
    let points = parse_points(&read_points(path)?)
        .with_context(|| format!("{} is not a file of 2D points", path.display()))?;
    let started = Instant::now();
    let answers: Vec<Containment> = points
        .iter()
        .map(|&p| tree.contains(p))
        .collect::<Result<_, _>>()?;
    Ok(contains_report(
        path,
        &answers,
        started.elapsed().as_secs_f64(),
    ))
}

/// Point inclusion in a closed genus-0 mesh for every point of `path`.
fn locate3(tree: &HalTree3, path: &Path) -> Result<Contains> {
    let points = parse_points3(&read_points(path)?)
        .with_context(|| format!("{} is not a file of 3D points", path.display()))?;
    let started = Instant::now();
    let answers: Vec<Containment> = points.iter().map(|&p| tree.contains(p)).collect();
    Ok(contains_report(
        path,
        &answers,
        started.elapsed().as_secs_f64(),
    ))
}

fn read_points(path: &Path) -> Result<String> {
    crate::input::read_text(path, "the points")
}

fn contains_report(path: &Path, answers: &[Containment], seconds: f64) -> Contains {
    let count = |l: Containment| answers.iter().filter(|&&a| a == l).count();
    Contains {
        file: path.display().to_string(),
        points: answers.len(),
        inside: count(Containment::Inside),
        outside: count(Containment::Outside),
        boundary: count(Containment::Boundary),
        answers: answers.iter().map(|&a| hal_shapes::name(a)).collect(),
        seconds,
    }
}

/// The first line of a `--contains` report: the file, the counts and the time.
pub(super) fn contains_summary(
    file: &str,
    [points, inside, outside, boundary]: [usize; 4],
    seconds: f64,
) -> String {
    format!(
        "{file}: {} points, {} inside, {} outside, {} on the boundary, in {seconds:.4} s",
        thousands(points),
        thousands(inside),
        thousands(outside),
        thousands(boundary),
    )
}

fn print_contains(c: &Contains) {
    println!(
        "{}",
        contains_summary(
            &c.file,
            [c.points, c.inside, c.outside, c.boundary],
            c.seconds
        )
    );
    for answer in &c.answers {
        println!("{answer}");
    }
}

fn print_text(report: &Report) {
    println!(
        "{}: {} vertices ({}), {} nodes, depth {}",
        report.polygon,
        thousands(report.vertices),
        if report.closed {
            "polygon"
        } else {
            "open polyline"
        },
        thousands(report.nodes),
        report.depth
    );
    println!(
        "built in {:.3} s (read in {:.3} s)",
        report.seconds.build, report.seconds.load
    );
    println!("level  vertices  width (% of diagonal)");
    let shown = report.levels.len().min(24);
    for level in &report.levels[..shown] {
        println!(
            "{:>5}  {:>8}  {:.4}",
            level.level,
            thousands(level.vertices),
            100.0 * level.width / report.diagonal
        );
    }
    if report.levels.len() > shown {
        println!(
            "  … {} deeper levels (--json lists them all)",
            report.levels.len() - shown
        );
    }
    if let Some(a) = &report.approximation {
        println!(
            "approximation ({} {}): {} vertices, width {:.4} % of the diagonal",
            a.kind,
            a.value,
            thousands(a.vertices),
            100.0 * a.width / report.diagonal
        );
    }
    if let Some(c) = &report.contains {
        print_contains(c);
    }
    if let Some(i) = &report.intersect {
        hal_shapes::print_intersect(i);
    }
    if let Some(output) = &report.output {
        println!("wrote {output}");
    }
}

/// What `sphaera hal MESH` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct MeshReport {
    mesh: String,
    triangles: usize,
    nodes: usize,
    /// Root triangles (one or two: the root's three paths may leave one patch).
    roots: usize,
    depth: u32,
    diagonal: f64,
    /// Per level: the approximation's triangles and the largest width of its triangles'
    /// bounding volumes (Definition 6).
    levels: Vec<MeshLevel>,
    approximation: Option<MeshApproximation>,
    /// Point inclusion of `--contains`, if given.
    contains: Option<Contains>,
    /// Intersection with `--intersect`, if given.
    intersect: Option<MeshIntersect>,
    output: Option<String>,
    seconds: Seconds,
}

/// What `--intersect OTHER_MESH` reports.
#[derive(Debug, Serialize)]
struct MeshIntersect {
    file: String,
    /// Whether the solids meet: surfaces cross or touch, or one holds the other.
    intersects: bool,
    /// Pairs of intersecting faces.
    pairs: usize,
    /// Every pair: a face of the first mesh, one of the other.
    face_pairs: Vec<[usize; 2]>,
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct MeshApproximation {
    /// `tolerance` or `level`.
    kind: &'static str,
    /// The absolute tolerance, or the level.
    value: f64,
    triangles: usize,
    /// The largest width of its triangles' bounding volumes (0 for original faces).
    width: f64,
}

#[derive(Debug, Serialize)]
struct MeshLevel {
    level: u32,
    triangles: usize,
    width: f64,
}

/// `sphaera hal MESH`: the 3D HAL tree of a closed genus-0 mesh.
fn run_mesh(args: &HalArgs) -> Result<()> {
    if args.open {
        bail!("--open is for polylines; a mesh must be closed");
    }
    if let Some(path) = &args.output {
        if !MESH_EXTENSIONS.contains(&extension(path).as_str()) {
            bail!(
                "cannot write {}: a 3D approximation is written as .obj, .ply, .stl or .off",
                path.display()
            );
        }
        check_target(path)?;
    }
    let started = Instant::now();
    let loaded = sphaera::mesh::io::read_with(&args.polygon, &crate::input::file_policy())?;
    let mesh = loaded.mesh;
    let load = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let tree = HalTree3::build(&mesh)
        .with_context(|| format!("no HAL tree for {}", args.polygon.display()))?;
    let build = started.elapsed().as_secs_f64();
    let diagonal = mesh.bounding_box_diagonal();
    let mut levels = Vec::new();
    for level in 0..=tree.depth() {
        let width = tree.kept_width(|n| n.level < level);
        levels.push(MeshLevel {
            level,
            triangles: tree.level(level)?.triangle_count(),
            width,
        });
    }
    let chosen = match (args.tolerance, args.level) {
        (Some(tolerance), _) => {
            let value = tolerance.resolve(diagonal);
            Some(("tolerance", value, tree.approximate(value)?))
        }
        (None, Some(level)) => {
            let level = u32::try_from(level).unwrap_or(u32::MAX);
            Some(("level", f64::from(level), tree.level(level)?))
        }
        (None, None) => None,
    };
    if let Some(path) = &args.output {
        let approximation = match &chosen {
            Some((_, _, mesh)) => mesh.clone(),
            None => tree.level(tree.depth())?,
        };
        sphaera::mesh::io::save(path, &approximation)
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    let approximation = chosen.map(|(kind, value, approximation)| MeshApproximation {
        kind,
        value,
        triangles: approximation.triangle_count(),
        width: if kind == "tolerance" {
            tree.kept_width(|n| n.width > value)
        } else {
            tree.kept_width(|n| f64::from(n.level) < value)
        },
    });
    let contains = match &args.contains {
        Some(path) => Some(locate3(&tree, path)?),
        None => None,
    };
    let intersect = match &args.intersect {
        Some(path) => Some(intersect3(&tree, path)?),
        None => None,
    };
    let report = MeshReport {
        mesh: args.polygon.display().to_string(),
        triangles: mesh.triangle_count(),
        nodes: tree.nodes().len(),
        roots: tree.roots().len(),
        depth: tree.depth(),
        diagonal,
        levels,
        approximation,
        contains,
        intersect,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        seconds: Seconds { load, build },
    };
    if args.print.json {
        return print_json(&report);
    }
    println!(
        "{}: {} triangles, {} nodes, {} root triangle(s), depth {}",
        report.mesh,
        thousands(report.triangles),
        thousands(report.nodes),
        report.roots,
        report.depth
    );
    println!("built in {build:.3} s (read in {load:.3} s)");
    println!("level  triangles  width (% of diagonal)");
    for level in &report.levels {
        println!(
            "{:>5}  {:>9}  {:.4}",
            level.level,
            thousands(level.triangles),
            100.0 * level.width / diagonal
        );
    }
    if let Some(a) = &report.approximation {
        println!(
            "approximation ({} {}): {} triangles, width {:.4} % of the diagonal",
            a.kind,
            a.value,
            thousands(a.triangles),
            100.0 * a.width / diagonal
        );
    }
    if let Some(c) = &report.contains {
        print_contains(c);
    }
    if let Some(i) = &report.intersect {
        println!(
            "{} {}: {} pairs of faces meet, in {:.4} s",
            if i.intersects {
                "intersects"
            } else {
                "does not intersect"
            },
            i.file,
            thousands(i.pairs),
            i.seconds
        );
        for [a, b] in i.face_pairs.iter().take(10) {
            println!("  face {a} meets face {b}");
        }
        if i.pairs > 10 {
            println!("  … {} more (--json lists them all)", i.pairs - 10);
        }
    }
    if let Some(output) = &report.output {
        println!("wrote {output}");
    }
    Ok(())
}

/// Intersection of `tree`'s solid with the closed genus-0 mesh of `path`.
fn intersect3(tree: &HalTree3, path: &Path) -> Result<MeshIntersect> {
    let other = sphaera::mesh::io::read_with(path, &crate::input::file_policy())?.mesh;
    let other =
        HalTree3::build(&other).with_context(|| format!("no HAL tree for {}", path.display()))?;
    let started = Instant::now();
    let identity = sphaera::mesh::geometry::Similarity::IDENTITY;
    let intersects = tree.intersects(&other, &identity);
    let face_pairs: Vec<[usize; 2]> = tree
        .intersecting_faces(&other, &identity)
        .into_iter()
        .map(|(a, b)| [a, b])
        .collect();
    Ok(MeshIntersect {
        file: path.display().to_string(),
        intersects,
        pairs: face_pairs.len(),
        face_pairs,
        seconds: started.elapsed().as_secs_f64(),
    })
}
