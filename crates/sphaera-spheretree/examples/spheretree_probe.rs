//! Builds a sphere-tree and prints each level's size and construction error:
//! `cargo run --release -p sphaera-spheretree --example spheretree_probe -- [MESH] [merge|expand|combined]`.

#![allow(clippy::print_stdout)]

use std::time::Instant;

use sphaera_mesh::{io, shapes};
use sphaera_spheretree::{Params, Reducer, build};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let mesh = match args.get(1) {
        Some(path) => io::load(path)?,
        None => shapes::capsule(0.5, 2.0, 12)?,
    };
    let reducer = match args.get(2).map(String::as_str) {
        Some("merge") => Reducer::Merge,
        Some("expand") => Reducer::Expand,
        _ => Reducer::Combined,
    };
    let diagonal = mesh.bounding_box_diagonal();
    let started = Instant::now();
    let tree = build(&mesh, &Params::default().reducer(reducer))?;
    println!(
        "{reducer:?}: built in {:.2} s",
        started.elapsed().as_secs_f64()
    );
    for level in 0..tree.level_count() {
        let nodes = tree.level(level);
        let worst = nodes.iter().map(|n| n.error).fold(0.0, f64::max);
        println!(
            "level {level}: {} spheres, worst eq. 2 error {:.2} % of the diagonal",
            nodes.len(),
            100.0 * worst / diagonal
        );
    }
    Ok(())
}
