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

/// The smallest cut through an instance's sphere-tree that meets the tolerance: the
/// highest nodes whose error meets it, and leaves where none does
/// ([`sphaera_spheretree::cut_for_tolerance`]). Coarse nodes stay where they are tight
/// enough, so it never has more spheres than a level that meets the tolerance, and
/// often far fewer.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CutChoice {
    /// Its spheres.
    pub count: usize,
    /// The deepest level it reaches.
    pub deepest_level: usize,
    /// Its worst node error in the scene's units.
    pub error: f64,
    /// The same error in the tolerance's unit (0 when the camera cannot see it).
    pub measured: f64,
    /// Whether it meets the tolerance (`false` only when some leaf does not).
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
    /// The smallest sphere-tree cut (a set of nodes of mixed levels), often fewer spheres
    /// than [`InstanceDetail::spheres`] for the same tolerance.
    pub cut: CutChoice,
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
    /// Spheres of the chosen cuts, over all instances.
    pub cut_spheres: usize,
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
    /// `O(levels + cut)` per instance: 200 instances in 1.3 ms for a tolerance in pixels,
    /// about 7 µs each, of which the levels (4 tree levels, 25 mesh levels) take 1.4 µs
    /// and the smallest cut the rest (a bisection of the pixel bound, then the cut's walk)
    /// (`cargo bench -p sphaera-eval --bench scene_vs_rapier`, see `docs/benchmarks.md`).
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
            cut_spheres: sum(&|d| d.cut.count),
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
pub(crate) fn measure(
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

/// The largest error in the model's units whose measure meets the tolerance, where the
/// errors that matter are at most `largest`: direct for world and relative tolerances,
/// found by bisection for pixels (the projected error grows with the error), in a bracket
/// from the projection of the ungrown and the grown bounding sphere.
pub(crate) fn allowed_error(
    instance: &Instance,
    camera: Option<&Camera>,
    tolerance: Tolerance,
    largest: f64,
) -> f64 {
    let model = &instance.model;
    let scale = instance.pose.scale();
    // An error that cannot be seen measures 0: it meets any tolerance in pixels.
    let meets = |e: f64| {
        measure(instance, camera, tolerance, e * scale).unwrap_or(0.0) <= tolerance.value()
    };
    match tolerance {
        Tolerance::World(t) => t / scale,
        Tolerance::Relative(t) => t * model.diagonal(),
        Tolerance::Pixels(_) if meets(largest) => largest,
        Tolerance::Pixels(t) => {
            // `e·k(e)` grows with `e` (`k`: pixels per unit of the sphere grown by `e`),
            // so the threshold lies between `t / k(high)` and `high = t / k(0)`.
            let per_unit = |e: f64| {
                camera.and_then(|c| {
                    let grown = instance.bounding_sphere();
                    c.pixels_per_unit(&sphaera_mesh::Sphere::new(
                        grown.center,
                        grown.radius + e * scale,
                    ))
                })
            };
            let (mut low, mut high, steps) = match per_unit(0.0) {
                Some(k) if k > 0.0 => {
                    let high = (t / (k * scale)).min(largest);
                    let low = per_unit(high).map_or(0.0, |k| t / (k * scale)).min(high);
                    (low, high, 16)
                }
                _ => (0.0, largest, 60),
            };
            if meets(high) {
                low = high;
            }
            // `meets(low)` holds; `meets(high)` does not, unless they are equal.
            for _ in 0..steps {
                let mid = 0.5 * (low + high);
                if meets(mid) {
                    low = mid;
                } else {
                    high = mid;
                }
            }
            low
        }
    }
}

/// The coarsest of `errors` (model units, coarsest first) meeting the tolerance.
pub(crate) fn choose_level(
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
    let cut = choose_cut(instance, camera, tolerance);
    InstanceDetail {
        instance: index,
        name: instance.name.clone(),
        model: model.name().to_owned(),
        visible: camera.is_none_or(|c| c.pixels_per_unit(&instance.bounding_sphere()).is_some()),
        spheres,
        cut,
        mesh,
        full_spheres: tree.level(tree.level_count().saturating_sub(1)).len(),
        full_triangles: model.mesh().triangle_count(),
    }
}

/// The smallest cut meeting the tolerance.
fn choose_cut(instance: &Instance, camera: Option<&Camera>, tolerance: Tolerance) -> CutChoice {
    let model = &instance.model;
    let tree = model.tree();
    let scale = instance.pose.scale();
    let largest = model.tree_errors().iter().copied().fold(0.0, f64::max);
    let bound = allowed_error(instance, camera, tolerance, largest);
    let measured = |e: f64| measure(instance, camera, tolerance, e * scale).unwrap_or(0.0);
    let meets = |e: f64| measured(e) <= tolerance.value();
    let cut = sphaera_spheretree::cut_for_tolerance(tree, bound);
    let deepest_level = cut
        .nodes
        .iter()
        .filter_map(|&i| tree.nodes().get(i))
        .map(|n| n.level as usize)
        .max()
        .unwrap_or(0);
    CutChoice {
        count: cut.nodes.len(),
        deepest_level,
        error: cut.worst_error * scale,
        measured: measured(cut.worst_error),
        meets: meets(cut.worst_error),
    }
}
