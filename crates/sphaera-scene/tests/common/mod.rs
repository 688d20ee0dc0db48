//! Models shared by the scene tests: built once, small trees so the tests stay fast.

#![allow(dead_code)]

use std::sync::{Arc, OnceLock};

use sphaera_mesh::geometry::Similarity;
use sphaera_mesh::{DVec3, Length, TriMesh, shapes};
use sphaera_scene::{ModelOptions, ObjectModel, Scene};
use sphaera_spheretree::SphereTreeOptions;

/// Small sphere-trees: a base tree of depth 2, branch 4; tolerance trees no finer than
/// 1 % of a model's diagonal.
pub fn options() -> ModelOptions {
    ModelOptions::default()
        .with_tree(
            SphereTreeOptions::default()
                .with_depth(2)
                .with_branch(4)
                .with_samples(800)
                .with_initial_spheres(80)
                .with_min_spheres_per_node(20),
        )
        .with_finest_tolerance(Length::RelativeToDiagonal(0.01))
}

/// Fresh models of [`meshes`] (not shared with other tests: a test that checks exact
/// answers must not see the trees another test's requests built).
pub fn fresh_models() -> Vec<Arc<ObjectModel>> {
    meshes()
        .into_iter()
        .map(|(name, mesh)| Arc::new(ObjectModel::build(name, mesh, &options()).expect(name)))
        .collect()
}

/// The meshes of [`models`]: a ball, a capsule, a torus and a cube, each a few hundred
/// triangles.
pub fn meshes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("ball", shapes::sphere(0.5, 10).expect("sphere")),
        ("capsule", shapes::capsule(0.3, 1.2, 8).expect("capsule")),
        ("torus", shapes::torus(0.6, 0.2, 14).expect("torus")),
        ("cube", shapes::cube(0.8, 3).expect("cube")),
    ]
}

/// One model per mesh of [`meshes`], built once for the whole test binary.
pub fn models() -> &'static [Arc<ObjectModel>] {
    static MODELS: OnceLock<Vec<Arc<ObjectModel>>> = OnceLock::new();
    MODELS.get_or_init(|| {
        meshes()
            .into_iter()
            .map(|(name, mesh)| Arc::new(ObjectModel::build(name, mesh, &options()).expect(name)))
            .collect()
    })
}

/// A pose from a translation, a rotation (axis-angle) and a scale.
pub fn pose(translation: DVec3, axis: DVec3, angle: f64, scale: f64) -> Similarity {
    let rotation = glam::DQuat::from_axis_angle(axis.try_normalize().unwrap_or(DVec3::Z), angle);
    Similarity::new(glam::DAffine3::from_scale_rotation_translation(
        DVec3::splat(scale),
        rotation,
        translation,
    ))
    .expect("a similarity")
}

/// A scene of `placements` (model index, pose) of the shared [`models`].
pub fn scene(placements: &[(usize, Similarity)]) -> Scene {
    scene_of(models(), placements)
}

/// A scene of `placements` (model index, pose) of `models`.
pub fn scene_of(models: &[Arc<ObjectModel>], placements: &[(usize, Similarity)]) -> Scene {
    let mut scene = Scene::new();
    for (k, (model, pose)) in placements.iter().enumerate() {
        let model = &models[model % models.len()];
        scene.add(format!("{}-{k}", model.name()), Arc::clone(model), *pose);
    }
    scene
}

/// Node `index`'s certified error for `need` (model units), recomputed here: its node
/// error when that meets `need`, else the smaller of it and the upper bound of its
/// sphere evaluated on the exact surface.
pub fn certified_error(
    model: &ObjectModel,
    tree: &sphaera_spheretree::SphereTree,
    index: usize,
    need: f64,
) -> f64 {
    let node = &tree.nodes()[index];
    if node.error <= need {
        return node.error;
    }
    let fit = sphaera_spheretree::evaluate::sphere_error(
        model.surface(),
        &node.sphere,
        &sphaera_spheretree::evaluate::EvaluationOptions::default(),
    )
    .expect("a valid sphere");
    fit.upper.min(node.error)
}

/// The certified error of the cut `tree.cut_at(level)` when every node meets `need`,
/// else `None` (nodes over `need` by their node errors evaluated worst first, stopping
/// at the first that fails).
pub fn level_error(
    model: &ObjectModel,
    tree: &sphaera_spheretree::SphereTree,
    level: usize,
    need: f64,
) -> Option<f64> {
    let mut cut = tree.cut_at(level);
    cut.sort_by(|&a, &b| tree.nodes()[b].error.total_cmp(&tree.nodes()[a].error));
    let mut worst = f64::NEG_INFINITY;
    for i in cut {
        let e = certified_error(model, tree, i, need);
        if e.is_nan() || e > need {
            return None;
        }
        worst = worst.max(e);
    }
    Some(worst)
}

/// The smallest cut meeting `need`, recomputed here by recursion from the roots: its
/// nodes (ascending) and certified error.
pub fn smallest_cut(
    model: &ObjectModel,
    tree: &sphaera_spheretree::SphereTree,
    need: f64,
) -> (Vec<usize>, f64) {
    fn visit(
        model: &ObjectModel,
        tree: &sphaera_spheretree::SphereTree,
        i: usize,
        need: f64,
        out: &mut Vec<(usize, f64)>,
    ) {
        let node = &tree.nodes()[i];
        let e = certified_error(model, tree, i, need);
        if e <= need || node.children.is_empty() {
            out.push((i, e));
        } else {
            for child in node.children.start as usize..node.children.end as usize {
                visit(model, tree, child, need, out);
            }
        }
    }
    let mut out = Vec::new();
    for root in 0..tree.level(0).len() {
        visit(model, tree, root, need, &mut out);
    }
    out.sort_by_key(|&(i, _)| i);
    let worst = out
        .iter()
        .map(|&(_, e)| e)
        .fold(f64::NEG_INFINITY, f64::max);
    (out.into_iter().map(|(i, _)| i).collect(), worst)
}
