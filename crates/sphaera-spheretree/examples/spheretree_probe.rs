//! Builds a sphere-tree and prints each level's size and construction error:
//! `cargo run --release -p sphaera-spheretree --example spheretree_probe -- [MESH]
//! [merge|burst|expand|combined|octree|grid|hubbard]`.

#![allow(clippy::print_stdout)]

use std::time::Instant;

use sphaera_io as io;
use sphaera_mesh::{Length, shapes};
use sphaera_query::Surface;
use sphaera_spheretree::{EvaluationOptions, Method, SphereTreeOptions, build, evaluate_set};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let mesh = match args.get(1) {
        Some(path) => io::load(path)?,
        None => shapes::capsule(0.5, 2.0, 12)?,
    };
    let method = args
        .get(2)
        .map_or(Some(Method::Combined), |name| Method::from_name(name))
        .ok_or("unknown method")?;
    let diagonal = mesh.bounding_box_diagonal();
    let started = Instant::now();
    let surface = Surface::new(&mesh)?;
    let tree = build(&surface, &SphereTreeOptions::default().with_method(method))?;
    println!(
        "{}: built in {:.2} s",
        method.name(),
        started.elapsed().as_secs_f64()
    );
    let options = EvaluationOptions::default().with_tolerance(Length::RelativeToDiagonal(1e-3));
    for level in 0..tree.level_count() {
        let nodes = tree.level(level);
        let worst = nodes.iter().map(|n| n.error).fold(0.0, f64::max);
        let evaluation = evaluate_set(&surface, &tree.level_spheres(level), &options)?;
        println!(
            "level {level}: {} spheres, worst eq. 2 error {:.2} %, certified worst error {:.2}–{:.2} %, \
             uncovered surface {:.3} % (largest gap {:.3} %)",
            nodes.len(),
            100.0 * worst / diagonal,
            100.0 * evaluation.worst_lower / diagonal,
            100.0 * evaluation.worst_upper / diagonal,
            100.0 * evaluation.coverage.uncovered_fraction,
            100.0 * evaluation.coverage.largest_gap / diagonal,
        );
    }
    Ok(())
}
