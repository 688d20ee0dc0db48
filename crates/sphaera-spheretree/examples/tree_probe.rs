//! Builds a sphere-tree and prints each level's (cut's) size, construction error and
//! certified error: `cargo run --release -p sphaera-spheretree --example tree_probe --
//! MESH [METHOD] [DEPTH] [BRANCH] [TOLERANCE%]` (environment: `SPH_EFFORT`, `SPH_NOEVAL` to
//! skip the evaluation, `SPH_FULLEVAL` for the unbounded one, `SPH_WORST` to print the
//! deepest worst node and its ancestors).

#![allow(clippy::print_stdout)]

use std::time::Instant;

use sphaera_io as io;
use sphaera_mesh::{Length, shapes};
use sphaera_query::Surface;
use sphaera_spheretree::{
    EvaluationOptions, Method, SphereTreeOptions, build, evaluate_set, evaluate_set_bounded,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let mesh = match args.get(1).map(String::as_str) {
        Some("-") | None => shapes::capsule(0.5, 2.0, 12)?,
        Some(path) => io::load(path)?,
    };
    let method = args
        .get(2)
        .map_or(Some(Method::Auto), |name| Method::from_name(name))
        .ok_or("unknown method")?;
    let depth: usize = args.get(3).map_or(Ok(3), |s| s.parse())?;
    let branch: usize = args.get(4).map_or(Ok(8), |s| s.parse())?;
    let mut options = SphereTreeOptions::default()
        .with_method(method)
        .with_depth(depth)
        .with_branch(branch);
    if let Ok(e) = std::env::var("SPH_EFFORT") {
        options = options.with_effort(e.parse()?);
    }
    if let Some(t) = args.get(5) {
        options = options.with_tolerance(Length::RelativeToDiagonal(t.parse::<f64>()? / 100.0));
    }
    let diagonal = mesh.bounding_box_diagonal();
    let started = Instant::now();
    let surface = Surface::solid_or_shell(&mesh)?;
    let tree = build(&surface, &options)?;
    println!(
        "{}: built in {:.3} s ({} nodes, {} leaves, {} levels)",
        method.name(),
        started.elapsed().as_secs_f64(),
        tree.nodes().len(),
        tree.leaves().len(),
        tree.level_count()
    );
    if std::env::var("SPH_WORST").is_ok() {
        // The deepest level's worst node and its ancestors: error and radius, % of the diagonal.
        let cut = tree.cut_at(tree.level_count() - 1);
        let mut at = cut
            .iter()
            .copied()
            .max_by(|&a, &b| tree.nodes()[a].error.total_cmp(&tree.nodes()[b].error));
        while let Some(i) = at {
            let node = &tree.nodes()[i];
            println!(
                "node {i} level {}: error {:.3} %, radius {:.3} %, {} children",
                node.level,
                100.0 * node.error / diagonal,
                100.0 * node.sphere.radius / diagonal,
                node.children.len()
            );
            at = node.parent.map(|p| p as usize);
        }
    }
    if std::env::var("SPH_NOEVAL").is_ok() {
        let levels: Vec<String> = (1..tree.level_count())
            .map(|level| {
                let worst = tree
                    .cut_at(level)
                    .iter()
                    .map(|&i| tree.nodes()[i].error)
                    .fold(0.0, f64::max);
                format!("{:.2}", 100.0 * worst / diagonal)
            })
            .collect();
        println!("eq2 % per level: {}", levels.join(" / "));
        return Ok(());
    }
    let evaluation = EvaluationOptions::default()
        .with_tolerance(Length::RelativeToDiagonal(1e-3))
        .with_screening(true);
    let started = Instant::now();
    for level in 0..tree.level_count() {
        let cut = tree.cut_at(level);
        let worst = cut
            .iter()
            .map(|&i| tree.nodes()[i].error)
            .fold(0.0, f64::max);
        let spheres = tree.cut_spheres(level);
        let e = if std::env::var("SPH_FULLEVAL").is_ok() {
            evaluate_set(&surface, &spheres, &evaluation)?
        } else {
            let bounds: Vec<f64> = cut.iter().map(|&i| tree.nodes()[i].error).collect();
            evaluate_set_bounded(&surface, &spheres, &bounds, &evaluation)?
        };
        println!(
            "level {level}: {} spheres, eq. 2 {:.2} %, certified {:.2}–{:.2} %, uncovered {:.4} %",
            cut.len(),
            100.0 * worst / diagonal,
            100.0 * e.worst_lower / diagonal,
            100.0 * e.worst_upper / diagonal,
            100.0 * e.coverage.uncovered_fraction,
        );
    }
    println!("evaluated in {:.3} s", started.elapsed().as_secs_f64());
    Ok(())
}
