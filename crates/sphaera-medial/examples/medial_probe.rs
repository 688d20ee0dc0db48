//! Prints the adaptive medial approximation's progress on a mesh:
//! `cargo run --release -p sphaera-medial --example medial_probe -- [MESH] [SPHERES]`.

#![allow(clippy::print_stdout)]

use std::time::Instant;

use sphaera_io as io;
use sphaera_medial::{MedialApproximation, MedialOptions, Surface};
use sphaera_mesh::shapes;
use sphaera_query::sampling;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let mesh = match args.get(1) {
        Some(path) => io::load(path)?,
        None => shapes::capsule(0.5, 2.0, 12)?,
    };
    let target: usize = args.get(2).map_or(Ok(500), |s| s.parse())?;
    let surface = Surface::new(&mesh)?;
    let samples: Vec<_> = sampling::poisson_disk(&mesh, 10_000, 1)?
        .samples
        .iter()
        .map(|s| s.position)
        .collect();
    for n in [target / 4, target / 2, target] {
        let start = Instant::now();
        let medial = MedialApproximation::build(
            &surface,
            &samples,
            &MedialOptions::default().with_target_spheres(n),
        )?;
        println!(
            "target {n}: {} spheres, worst error {:.4} ({:.3} % diag), uncovered {}, {:?}, {:.3} s",
            medial.sphere_count(),
            medial.worst_error(),
            100.0 * medial.worst_error() / surface.diagonal(),
            medial.uncovered_samples().len(),
            medial.stats(),
            start.elapsed().as_secs_f64()
        );
    }
    let medial = MedialApproximation::build(
        &surface,
        &samples,
        &MedialOptions::default().with_target_spheres(target),
    )?;
    let mut spheres = medial.spheres();
    spheres.sort_by(|a, b| b.error.total_cmp(&a.error));
    for s in spheres.iter().take(5) {
        println!(
            "  {:?} center {:.3?} r {:.4} e {:.4} d {:.4} covers {}",
            s.kind,
            s.center.to_array(),
            s.radius,
            s.error,
            (s.closest - s.center).length(),
            s.covers.len()
        );
    }
    Ok(())
}
