//! `sphaera hal`: the HAL tree of a polygon (Veltkamp), its levels, an adaptive
//! approximation, point inclusion, and a drawing.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::hal::{HalTree2, HalTree3, Location, Node2, Polyline2, parse_points, parse_points3};
use sphaera::mesh::glam::DVec2;
use sphaera::mesh::io::write_atomic;

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
    let text = std::fs::read_to_string(&args.polygon)
        .with_context(|| format!("cannot read {}", args.polygon.display()))?;
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
    let (kept, frontier) = approximation(&tree, refine);
    let approximation = match refine {
        Refine::Width(value) => Some(("tolerance", value)),
        Refine::Level(level) => Some(("level", level as f64)),
        Refine::All => None,
    }
    .map(|(kind, value)| Approximation {
        kind,
        value,
        vertices: kept.len(),
        width: frontier
            .iter()
            .map(|&id| tree.nodes()[id].width)
            .fold(0.0, f64::max),
    });
    let contains = match &args.contains {
        Some(path) => Some(locate(&tree, path)?),
        None => None,
    };
    if let Some(path) = &args.output {
        let points = tree.polyline().points();
        let bytes = if extension(path) == "svg" {
            svg(&tree, &kept, &frontier)
        } else {
            kept.iter()
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
        levels: levels(&tree),
        approximation,
        contains,
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

/// Vertices and width per level, from one pass over the nodes: the level-`k`
/// approximation holds the nodes of level at most `k`, and its edges that are not original
/// are bounded by the nodes of level `k + 1`.
fn levels(tree: &HalTree2) -> Vec<Level> {
    let depth = tree.depth();
    let mut count = vec![0_usize; depth + 2];
    let mut width = vec![0.0_f64; depth + 2];
    for node in tree.nodes() {
        let level = node.level as usize;
        count[level] += 1;
        width[level] = width[level].max(node.width);
    }
    // The level-0 chord's two ends.
    let mut vertices = 2;
    (0..=depth)
        .map(|level| {
            vertices += count[level];
            Level {
                level,
                vertices,
                width: width[level + 1],
            }
        })
        .collect()
}

/// The vertices an approximation keeps (outline order) and the nodes bounding its
/// non-original edges.
fn approximation(tree: &HalTree2, refine: Refine) -> (Vec<usize>, Vec<usize>) {
    let mut kept = Vec::new();
    let mut frontier = Vec::new();
    for chain in tree.chains() {
        kept.push(tree.vertex_at(chain.first));
        // In order: (node, whether its left part is done).
        let mut stack: Vec<(usize, bool)> = chain.node.map(|n| (n, false)).into_iter().collect();
        while let Some((id, left_done)) = stack.pop() {
            let node = &tree.nodes()[id];
            if !refine.refines(node) {
                frontier.push(id);
                continue;
            }
            let [left, right] = node.children();
            if left_done {
                kept.push(tree.vertex_at(node.split));
                stack.extend(right.map(|r| (r, false)));
            } else {
                stack.push((id, true));
                stack.extend(left.map(|l| (l, false)));
            }
        }
    }
    if !tree.polyline().is_closed()
        && let Some(last) = tree.chains().last()
    {
        kept.push(tree.vertex_at(last.last));
    }
    (kept, frontier)
}

/// Point inclusion for every point of `path`.
fn locate(tree: &HalTree2, path: &Path) -> Result<Contains> {
    let points = parse_points(&read_points(path)?)
        .with_context(|| format!("{} is not a file of 2D points", path.display()))?;
    let started = Instant::now();
    let answers: Vec<Location> = points
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
    let answers: Vec<Location> = points.iter().map(|&p| tree.contains(p)).collect();
    Ok(contains_report(
        path,
        &answers,
        started.elapsed().as_secs_f64(),
    ))
}

fn read_points(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}

fn contains_report(path: &Path, answers: &[Location], seconds: f64) -> Contains {
    let count = |l: Location| answers.iter().filter(|&&a| a == l).count();
    Contains {
        file: path.display().to_string(),
        points: answers.len(),
        inside: count(Location::Inside),
        outside: count(Location::Outside),
        boundary: count(Location::Boundary),
        answers: answers
            .iter()
            .map(|a| match a {
                Location::Inside => "inside",
                Location::Outside => "outside",
                Location::Boundary => "boundary",
            })
            .collect(),
        seconds,
    }
}

fn print_contains(c: &Contains) {
    println!(
        "{}: {} points, {} inside, {} outside, {} on the boundary, in {:.4} s",
        c.file,
        thousands(c.points),
        thousands(c.inside),
        thousands(c.outside),
        thousands(c.boundary),
        c.seconds
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
    if let Some(output) = &report.output {
        println!("wrote {output}");
    }
}

/// The drawing: the outline in grey, the approximation in blue, and the bounding area of
/// each of its edges that is not original, shaded (the paper's Figs. 4 and 6). y points
/// up.
fn svg(tree: &HalTree2, kept: &[usize], frontier: &[usize]) -> Vec<u8> {
    let points = tree.polyline().points();
    let (lo, hi) = tree.polyline().bounds();
    let size = (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let margin = 0.05 * size;
    let scale = 1000.0 / (size + 2.0 * margin);
    let map = |p: DVec2| ((p.x - lo.x + margin) * scale, (hi.y - p.y + margin) * scale);
    let path = |vertices: &mut dyn Iterator<Item = DVec2>, close: bool| {
        let mut d = String::new();
        for (k, p) in vertices.enumerate() {
            let (x, y) = map(p);
            let _ = write!(d, "{}{x:.2},{y:.2} ", if k == 0 { "M" } else { "L" });
        }
        if close {
            d.push('Z');
        }
        d
    };
    let width = (hi.x - lo.x + 2.0 * margin) * scale;
    let height = (hi.y - lo.y + 2.0 * margin) * scale;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width:.1} {height:.1}" width="{width:.0}" height="{height:.0}">"#
    );
    let _ = writeln!(
        out,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    for &id in frontier {
        let node = &tree.nodes()[id];
        let outline = lens_outline(tree, node);
        if !outline.is_empty() {
            let _ = writeln!(
                out,
                r##"<path d="{}" fill="#f4a261" fill-opacity="0.25" stroke="#e76f51" stroke-width="0.6"/>"##,
                path(&mut outline.into_iter(), true)
            );
        }
    }
    let closed = tree.polyline().is_closed();
    let _ = writeln!(
        out,
        r##"<path d="{}" fill="none" stroke="#8d99ae" stroke-width="0.8"/>"##,
        path(&mut points.iter().copied(), closed)
    );
    let _ = writeln!(
        out,
        r##"<path d="{}" fill="none" stroke="#1d3557" stroke-width="1.4"/>"##,
        path(&mut kept.iter().map(|&v| points[v]), closed)
    );
    let _ = writeln!(out, "</svg>");
    out.into_bytes()
}

/// The boundary of a node's bounding area as a polygon: the left disc's arc from the
/// chord's start to its end, then the right disc's arc back (a side without vertices is
/// the chord itself). Empty for an unbounded area (a half-plane on a vertex's side).
fn lens_outline(tree: &HalTree2, node: &Node2) -> Vec<DVec2> {
    let (a, b) = (tree.point_at(node.first), tree.point_at(node.last));
    let (w1, w2) = node.lens.widths(a, b);
    if !(w1.is_finite() && w2.is_finite()) || a == b {
        return Vec::new();
    }
    let normal = (b - a).perp().normalize();
    let middle = a.midpoint(b);
    let mut outline = arc(a, b, middle + normal * w1);
    outline.extend(arc(b, a, middle - normal * w2).into_iter().skip(1));
    outline
}

/// Points along the circle through `from`, `apex` and `to`, from `from` to `to` through
/// `apex` (the straight segment when the three are collinear).
fn arc(from: DVec2, to: DVec2, apex: DVec2) -> Vec<DVec2> {
    let Some(center) = circumcentre(from, to, apex) else {
        return vec![from, to];
    };
    let radius = center.distance(from);
    let angle = |p: DVec2| (p - center).to_angle();
    let tau = std::f64::consts::TAU;
    let turn = |x: f64| (x - angle(from)).rem_euclid(tau);
    let (to_end, to_apex) = (turn(angle(to)), turn(angle(apex)));
    let sweep = if to_apex <= to_end {
        to_end
    } else {
        to_end - tau
    };
    (0..=32)
        .map(|k| {
            let t = angle(from) + sweep * f64::from(k) / 32.0;
            center + DVec2::from_angle(t) * radius
        })
        .collect()
}

/// The centre of the circle through three points, if they are not collinear.
fn circumcentre(a: DVec2, b: DVec2, c: DVec2) -> Option<DVec2> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.perp_dot(ac);
    if d.abs() <= 1e-14 * ab.length_squared().max(ac.length_squared()) {
        return None;
    }
    let (lb, lc) = (ab.length_squared(), ac.length_squared());
    Some(a + DVec2::new(ac.y * lb - ab.y * lc, ab.x * lc - ac.x * lb) / d)
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
    output: Option<String>,
    seconds: Seconds,
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

/// The largest width among the triangles an approximation keeps: the nodes reached from
/// the roots through refined parents and not refined themselves.
pub(crate) fn kept_width(tree: &HalTree3, refine: impl Fn(&sphaera::hal::Node3) -> bool) -> f64 {
    let nodes = tree.nodes();
    let mut stack: Vec<u32> = tree.roots().to_vec();
    let mut largest: f64 = 0.0;
    while let Some(n) = stack.pop() {
        let node = &nodes[n as usize];
        if node.children.is_empty() || !refine(node) {
            largest = largest.max(node.width);
        } else {
            stack.extend(node.children.iter().copied());
        }
    }
    largest
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
    let loaded = sphaera::mesh::io::read(&args.polygon)?;
    let mesh = loaded.mesh;
    let load = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let tree = HalTree3::build(&mesh)
        .with_context(|| format!("no HAL tree for {}", args.polygon.display()))?;
    let build = started.elapsed().as_secs_f64();
    let diagonal = mesh.bounding_box_diagonal();
    let mut levels = Vec::new();
    for level in 0..=tree.depth() {
        let width = kept_width(&tree, |n| n.level < level);
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
            kept_width(&tree, |n| n.width > value)
        } else {
            kept_width(&tree, |n| f64::from(n.level) < value)
        },
    });
    let contains = match &args.contains {
        Some(path) => Some(locate3(&tree, path)?),
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
    if let Some(output) = &report.output {
        println!("wrote {output}");
    }
    Ok(())
}
