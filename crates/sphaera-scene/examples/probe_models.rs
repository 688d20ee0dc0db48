//! Temporary: time model parts (not committed).
use sphaera_mesh::{Length, Surface};
use sphaera_spheretree::SphereTreeOptions;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let files = [
        "bunny_lowres.obj",
        "spot.obj",
        "robots/objects/duck.obj",
        "fandisk.obj",
    ];
    let spec = args.get(1).cloned().unwrap_or_else(|| "d3".into());
    let only = args.get(2).cloned();
    let t_all = Instant::now();
    for f in files {
        if only.as_ref().is_some_and(|o| !f.contains(o.as_str())) {
            continue;
        }
        let mesh = sphaera_mesh::io::load(format!("/work/shared/data/{f}"))?;
        let surface = Surface::new(&mesh)?;
        let o = if let Some(d) = spec.strip_prefix('d') {
            SphereTreeOptions::default().with_depth(d.parse()?)
        } else {
            let t: f64 = spec.strip_prefix('t').unwrap_or(&spec).parse()?;
            SphereTreeOptions::default()
                .with_branch(std::env::var("BR").map_or(8, |b| b.parse().unwrap()))
                .with_tolerance(Length::RelativeToDiagonal(t))
        };
        let t = Instant::now();
        let tree = sphaera_spheretree::build(&surface, &o)?;
        let worst = tree
            .leaves()
            .iter()
            .map(|&l| tree.nodes()[l].error)
            .fold(0.0, f64::max)
            / surface.diagonal();
        println!(
            "{f} {spec}: {:.3}s {} leaves {} levels worst {:.4}",
            t.elapsed().as_secs_f64(),
            tree.leaves().len(),
            tree.level_count(),
            worst
        );
    }
    println!("all {:.3}", t_all.elapsed().as_secs_f64());
    Ok(())
}
