//! Choosing, for every instance, the coarsest sphere-tree level and mesh level a
//! tolerance allows.

use serde::Serialize;

use crate::{Camera, Instance, Scene, SceneError, Tolerance};

/// The level chosen for one instance, in one hierarchy (its sphere-tree or its mesh
/// ladder).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LevelChoice {
    /// The level (0: the coarsest).
    pub level: usize,
    /// How many levels there are.
    pub levels: usize,
    /// Its spheres or triangles.
    pub count: usize,
    /// Its certified error in the scene's units (the model's error times the pose's
    /// scale).
    pub error: f64,
    /// The same error in the tolerance's unit: world units, a fraction of the instance's
    /// diagonal, or pixels on the camera's image (0 for a level the camera cannot see).
    pub measured: f64,
    /// Whether it meets the tolerance. Only `false` when no level does: the finest level
    /// is then chosen.
    pub meets: bool,
}

/// The levels chosen for one instance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct InstanceDetail {
    /// Its index in the scene.
    pub instance: usize,
    /// Its name.
    pub name: String,
    /// Its model's name.
    pub model: String,
    /// Whether the camera sees its mesh's bounding sphere (always `true` without a
    /// camera).
    pub visible: bool,
    /// The sphere-tree level.
    pub spheres: LevelChoice,
    /// The mesh level.
    pub mesh: LevelChoice,
    /// The spheres of its finest sphere-tree level.
    pub full_spheres: usize,
    /// The triangles of its input mesh.
    pub full_triangles: usize,
}

/// What [`Scene::detail`] chose, instance by instance, with the totals against full
/// detail.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetailReport {
    /// The tolerance, as text (`0.01`, `0.5%`, `2px`).
    pub tolerance: String,
    /// The unit of [`LevelChoice::measured`]: `world`, `relative` or `px`.
    pub unit: &'static str,
    /// One entry per instance, in scene order.
    pub instances: Vec<InstanceDetail>,
    /// Spheres at the chosen levels, over all instances.
    pub spheres: usize,
    /// Spheres at every instance's finest level.
    pub full_spheres: usize,
    /// Triangles at the chosen levels.
    pub triangles: usize,
    /// Triangles of every instance's input mesh.
    pub full_triangles: usize,
    /// Whether every choice meets the tolerance.
    pub all_meet: bool,
}

impl Scene {
    /// For each instance, the coarsest sphere-tree level and the coarsest mesh level whose
    /// certified error meets `tolerance`: in world units, as a fraction of the instance's
    /// size, or in pixels on `camera`'s image (bounded by
    /// [`Camera::projected_error`], so the error drawn is certified too).
    ///
    /// When no sphere-tree level meets the tolerance, the finest is chosen and marked
    /// ([`LevelChoice::meets`]); the mesh ladder ends with the input, which meets every
    /// tolerance. Under a tolerance in pixels, a level the camera cannot see at all (the
    /// mesh's bounding sphere grown by the level's error is out of view) meets the
    /// tolerance, so an instance well out of view takes its coarsest levels (one just
    /// out of view may still need finer ones: a coarse level's error can reach into view). A camera given
    /// with another tolerance only sets [`InstanceDetail::visible`].
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::Arc;
    /// use sphaera_mesh::geometry::Similarity;
    /// use sphaera_scene::{Camera, DVec3, ModelOptions, ObjectModel, Scene, Tolerance};
    /// use sphaera_spheretree::SphereTreeOptions;
    ///
    /// let tree = SphereTreeOptions::default().with_depth(2).with_branch(4).with_samples(600)
    ///     .with_initial_spheres(60).with_min_spheres_per_node(20);
    /// let mesh = sphaera_mesh::shapes::sphere(1.0, 24)?;
    /// let model = Arc::new(ObjectModel::build("ball", mesh, &ModelOptions::default().with_tree(tree))?);
    /// let mut scene = Scene::new();
    /// for (i, z) in [0.0, -30.0, -300.0].into_iter().enumerate() {
    ///     let pose = Similarity::from_translation(DVec3::new(0.0, 0.0, z))?;
    ///     scene.add(format!("ball-{i}"), Arc::clone(&model), pose);
    /// }
    /// let camera = Camera::perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 60.0, 1280, 720)?;
    /// let report = scene.detail(Some(&camera), Tolerance::Pixels(1.0))?;
    /// // The farther, the coarser; every choice is certified within a pixel.
    /// let tri: Vec<usize> = report.instances.iter().map(|d| d.mesh.count).collect();
    /// assert!(tri[0] >= tri[1] && tri[1] >= tri[2] && tri[2] < tri[0]);
    /// assert!(report.instances.iter().all(|d| d.mesh.measured <= 1.0));
    /// assert!(report.triangles < report.full_triangles);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SceneError::InvalidTolerance`] for a NaN, infinite or negative tolerance, and
    /// [`SceneError::NoCamera`] for a tolerance in pixels without a camera.
    ///
    /// # Performance
    ///
    /// `O(levels)` per instance, no allocation beyond the report (the instance names):
    /// 200 instances in 0.27 ms for a tolerance in pixels, about 1.4 µs each with its
    /// 4 tree levels and 25 mesh levels (`cargo bench -p sphaera-eval --bench
    /// scene_vs_rapier`, see `docs/benchmarks.md`).
    pub fn detail(
        &self,
        camera: Option<&Camera>,
        tolerance: Tolerance,
    ) -> Result<DetailReport, SceneError> {
        let tolerance = tolerance.validated()?;
        if matches!(tolerance, Tolerance::Pixels(_)) && camera.is_none() {
            return Err(SceneError::NoCamera);
        }
        let instances: Vec<InstanceDetail> = self
            .instances()
            .iter()
            .enumerate()
            .map(|(index, instance)| choose(index, instance, camera, tolerance))
            .collect();
        let sum = |f: &dyn Fn(&InstanceDetail) -> usize| instances.iter().map(f).sum();
        Ok(DetailReport {
            tolerance: tolerance.to_string(),
            unit: tolerance.unit(),
            spheres: sum(&|d| d.spheres.count),
            full_spheres: sum(&|d| d.full_spheres),
            triangles: sum(&|d| d.mesh.count),
            full_triangles: sum(&|d| d.full_triangles),
            all_meet: instances.iter().all(|d| d.spheres.meets && d.mesh.meets),
            instances,
        })
    }
}

/// An error of `world` scene units, in the tolerance's unit; `None` when the camera does
/// not see the instance under a tolerance in pixels.
fn measure(
    instance: &Instance,
    camera: Option<&Camera>,
    tolerance: Tolerance,
    world: f64,
) -> Option<f64> {
    match tolerance {
        Tolerance::World(_) => Some(world),
        Tolerance::Relative(_) => Some(world / instance.diagonal()),
        Tolerance::Pixels(_) => {
            camera.and_then(|c| c.projected_error(&instance.bounding_sphere(), world))
        }
    }
}

/// The coarsest of `errors` (model units, coarsest first) meeting the tolerance.
fn choose_level(
    instance: &Instance,
    camera: Option<&Camera>,
    tolerance: Tolerance,
    errors: &[f64],
    count: &dyn Fn(usize) -> usize,
) -> LevelChoice {
    let scale = instance.pose.scale();
    let levels = errors.len();
    let at = |level: usize, measured: f64, meets: bool| LevelChoice {
        level,
        levels,
        count: count(level),
        error: errors.get(level).copied().unwrap_or(0.0) * scale,
        measured,
        meets,
    };
    let mut finest = None;
    for (level, &e) in errors.iter().enumerate() {
        match measure(instance, camera, tolerance, e * scale) {
            // Nothing of this level can be seen (its surface is within `e` of the mesh's
            // bounding sphere): it draws nothing, so it meets any tolerance in pixels.
            None => return at(level, 0.0, true),
            Some(m) if m <= tolerance.value() => return at(level, m, true),
            Some(m) => finest = Some((level, m)),
        }
    }
    let (level, m) = finest.unwrap_or((0, 0.0));
    at(level, m, levels == 0)
}

fn choose(
    index: usize,
    instance: &Instance,
    camera: Option<&Camera>,
    tolerance: Tolerance,
) -> InstanceDetail {
    let model = &instance.model;
    let tree = model.tree();
    let spheres = choose_level(instance, camera, tolerance, model.tree_errors(), &|l| {
        tree.level(l).len()
    });
    let mesh = choose_level(instance, camera, tolerance, model.mesh_errors(), &|l| {
        model.mesh_levels().get(l).map_or(0, |m| m.triangles)
    });
    InstanceDetail {
        instance: index,
        name: instance.name.clone(),
        model: model.name().to_owned(),
        visible: camera.is_none_or(|c| c.pixels_per_unit(&instance.bounding_sphere()).is_some()),
        spheres,
        mesh,
        full_spheres: tree.level(tree.level_count().saturating_sub(1)).len(),
        full_triangles: model.mesh().triangle_count(),
    }
}
