//! Times the tetrahedralization of 100,000 random points and of 100,000 samples of a
//! cube's surface grid (the two speed cases):
//! `cargo run --release -p sphaera-medial --example delaunay_speed`.

#![allow(clippy::print_stdout)]

use std::time::Instant;

use sphaera_medial::{DVec3, Delaunay};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for (name, points) in [
        (
            "random 100k",
            sphaera_tests::point_sets::random_in_cube(100_000, 1),
        ),
        (
            "cube surface 100k",
            sphaera_tests::point_sets::cube_surface_grid(100_000),
        ),
    ] {
        let start = Instant::now();
        let delaunay = Delaunay::new(&points)?;
        let seconds = start.elapsed().as_secs_f64();
        println!(
            "{name}: {} points, {} tetrahedra, {:.3} s, {:.0} insertions/s",
            points.len(),
            delaunay.tetrahedron_count(),
            seconds,
            points.len() as f64 / seconds
        );
        let _: &[DVec3] = delaunay.points();
    }
    Ok(())
}
