//! Temporary probe (not committed).
use sphaera_mesh::geometry::Similarity;
use sphaera_scene::{Camera, DVec3, ModelOptions, ObjectModel, Scene, Tolerance};
use std::sync::Arc;
fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mesh = sphaera_mesh::shapes::torus(1.0, 0.3, 24)?;
    let model = Arc::new(ObjectModel::build("ball", mesh, &ModelOptions::default())?);
    println!("base errors {:?}", model.tree_errors());
    let mut scene = Scene::new();
    for (i, z) in [0.0, -20.0, -200.0].into_iter().enumerate() {
        let pose = Similarity::from_translation(DVec3::new(0.0, 0.0, z))?;
        scene.add(format!("ball-{i}"), Arc::clone(&model), pose);
    }
    let camera = Camera::perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 60.0, 1280, 720)?;
    for px in [8.0, 8.0] {
        let report = scene.detail(Some(&camera), Tolerance::Pixels(px))?;
        for d in &report.instances {
            let t = std::time::Instant::now();
            let _ = t;
            println!(
                "{px}px {} need {:.5} tree {:?} cut {:?} mesh {}",
                d.name, d.model_tolerance, d.tree, d.cut, d.mesh.count
            );
        }
    }
    Ok(())
}
