//! The awkward meshes real users bring (a pinched vertex, a tiny component, slivers,
//! far-apart parts, spikes) as object models: each builds, its ladder is ordered and ends
//! with the input, detail and collision answer, and a copy scaled by 2^40 gives the same
//! choices with errors scaled exactly.

#![allow(clippy::float_cmp)]

use std::sync::Arc;

use sphaera_mesh::DVec3;
use sphaera_mesh::geometry::Similarity;
use sphaera_scene::{Budget, ObjectModel, Scene, Tolerance};

mod common;

#[test]
fn awkward_meshes_make_models_that_answer() {
    let f = 2f64.powi(40);
    for awkward in sphaera_tests::awkward::all() {
        let name = awkward.name;
        let model = Arc::new(
            ObjectModel::build(name, awkward.mesh.clone(), &common::options())
                .unwrap_or_else(|e| panic!("{name}: {e}")),
        );
        let ladder = model.mesh_levels();
        assert!(
            ladder.windows(2).all(|w| w[0].triangles < w[1].triangles),
            "{name}"
        );
        assert_eq!(ladder.last().map(|l| l.error_bound), Some(0.0), "{name}");
        // A copy moved by 10⁻⁶ of the size overlaps the first (parts may be far smaller
        // than the whole); a third far away does not.
        let size = model.diagonal();
        let mut scene = Scene::new();
        scene.add("a", Arc::clone(&model), Similarity::IDENTITY);
        let near = Similarity::from_translation(DVec3::new(1e-6 * size, 0.0, 0.0)).expect("a pose");
        scene.add("b", Arc::clone(&model), near);
        let far = Similarity::from_translation(DVec3::splat(10.0 * size)).expect("a pose");
        scene.add("c", Arc::clone(&model), far);
        let contacts = scene.collide(&Budget::Unlimited).expect("collide");
        let pairs: Vec<_> = contacts.pairs.iter().map(|p| (p.a, p.b)).collect();
        assert_eq!(pairs, [(0, 1)], "{name}");
        let report = scene
            .detail(None, Tolerance::RelativeToDiagonal(0.05))
            .expect("detail");
        assert!(report.instances.iter().all(|d| d.mesh.meets), "{name}");
        assert!(
            report
                .instances
                .iter()
                .all(|d| d.spheres.error <= 0.05 * model.diagonal()),
            "{name}: {report:?}"
        );

        // The same mesh scaled by 2^40: the same choices, every error scaled exactly.
        let scaled_mesh = sphaera_tests::awkward::mapped(&awkward.mesh, |p| p * f, false);
        let scaled = Arc::new(
            ObjectModel::build(name, scaled_mesh, &common::options())
                .unwrap_or_else(|e| panic!("{name} scaled: {e}")),
        );
        let mut big = Scene::new();
        big.add("a", scaled, Similarity::IDENTITY);
        let small = &report.instances[0];
        let large = &big
            .detail(None, Tolerance::RelativeToDiagonal(0.05))
            .expect("detail")
            .instances[0];
        assert_eq!(
            (
                small.tree.index,
                small.spheres.level,
                small.mesh.level,
                small.cut.count
            ),
            (
                large.tree.index,
                large.spheres.level,
                large.mesh.level,
                large.cut.count
            ),
            "{name}"
        );
        assert_eq!(small.mesh.error * f, large.mesh.error, "{name}");
        assert_eq!(small.spheres.error * f, large.spheres.error, "{name}");
    }
}
