//! Choosing, for every instance, the spheres and the mesh level a tolerance needs,
//! building the sphere-trees it takes.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;

use serde::Serialize;

use crate::{Camera, Instance, ModelTree, ObjectModel, Scene, SceneError, Tolerance};

/// The level chosen for one instance, in one hierarchy (the sphere-tree it takes its
/// detail from, or its mesh ladder).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LevelChoice {
    /// The level (0: the coarsest). In a sphere-tree, the cut
    /// [`SphereTree::cut_at`](sphaera_spheretree::SphereTree::cut_at)`(level)`: the
    /// nodes of that level and the leaves above it.
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
    /// Whether it meets the tolerance. `false` only when no level does: the finest is
    /// then given.
    pub meets: bool,
}

/// The smallest cut through the instance's sphere-tree that meets the tolerance: the
/// highest nodes whose error meets it ([`sphaera_spheretree::cut_for_tolerance`]).
/// Coarse nodes stay where they are tight enough, so it never has more spheres than a
/// level that meets the tolerance, and often far fewer. These are the spheres the
/// instance needs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CutChoice {
    /// Its spheres.
    pub count: usize,
    /// The deepest level it reaches.
    pub deepest_level: usize,
    /// Its worst node error in the scene's units (certified).
    pub error: f64,
    /// The same error in the tolerance's unit (0 when the camera cannot see it).
    pub measured: f64,
    /// Whether it meets the tolerance (`false` only when no tree of the model could be
    /// built for it: [`InstanceDetail::unmet`] says why).
    pub meets: bool,
}

/// The sphere-tree of its model an instance's detail was taken from.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TreeChoice {
    /// Its index among the model's trees ([`ObjectModel::trees`](crate::ObjectModel::trees);
    /// 0: the base tree).
    pub index: usize,
    /// The tolerance it was built to, in the model's units (`None`: the base tree).
    pub tolerance: Option<f64>,
    /// Its leaves.
    pub leaves: usize,
    /// Whether this request built it.
    pub built: bool,
    /// The seconds its construction took (whichever request built it).
    pub build_seconds: f64,
}

/// The detail chosen for one instance.
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
    /// The tolerance asked of its model, in the model's units: the largest error that
    /// meets the scene's tolerance for this instance (a world tolerance divided by the
    /// pose's scale, a fraction of the model's diagonal, or the error the camera shows
    /// as the tolerance's pixels).
    pub model_tolerance: f64,
    /// The sphere-tree the spheres are taken from: the one of the model's trees whose
    /// smallest cut meeting the tolerance has the fewest spheres, built for it when none
    /// met it.
    pub tree: TreeChoice,
    /// The coarsest level of that tree meeting the tolerance.
    pub spheres: LevelChoice,
    /// The smallest cut of that tree meeting the tolerance (a set of nodes of mixed
    /// levels): the spheres the instance needs, often fewer than
    /// [`InstanceDetail::spheres`].
    pub cut: CutChoice,
    /// The mesh level.
    pub mesh: LevelChoice,
    /// The leaves of that tree (its finest cut).
    pub full_spheres: usize,
    /// The triangles of its input mesh.
    pub full_triangles: usize,
    /// Why the spheres do not meet the tolerance (`None` when they do): the tolerance is
    /// below the model's finest, or out of reach of its trees. The finest cut of its
    /// finest tree is then given.
    pub unmet: Option<String>,
}

/// What [`Scene::detail`] chose, instance by instance, with the totals against full
/// detail and the trees it built.
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
    /// Spheres of the chosen cuts, over all instances: what the scene needs.
    pub cut_spheres: usize,
    /// Leaves of the trees the instances' spheres were taken from.
    pub full_spheres: usize,
    /// Triangles at the chosen levels.
    pub triangles: usize,
    /// Triangles of every instance's input mesh.
    pub full_triangles: usize,
    /// Sphere-trees built by this request (at most a few per model, usually one).
    pub trees_built: usize,
    /// The wall-clock seconds this request spent making sure every model has a tree
    /// meeting its instances' tolerances (building them on every core with the
    /// `parallel` feature).
    pub tree_seconds: f64,
    /// Whether every instance's cut and mesh meet the tolerance.
    pub all_meet: bool,
}

impl DetailReport {
    /// The same report with its times set to 0: what two runs of the same requests
    /// agree on exactly.
    #[must_use]
    pub fn without_times(mut self) -> Self {
        self.tree_seconds = 0.0;
        for instance in &mut self.instances {
            instance.tree.build_seconds = 0.0;
        }
        self
    }
}

impl Scene {
    /// For each instance, the spheres and the mesh level its tolerance needs: in world
    /// units, as a fraction of the instance's size, or in pixels on `camera`'s image
    /// (bounded by [`Camera::projected_error`], so the error drawn is certified too).
    ///
    /// **Spheres.** The tolerance comes to a tolerance in each instance's model units
    /// ([`InstanceDetail::model_tolerance`]). Each model is asked once, for the finest
    /// its instances need ([`ObjectModel::tree_for`](crate::ObjectModel::tree_for)):
    /// when none of its trees meets it, it builds a tolerance tree (the models on every
    /// core with the `parallel` feature), once, and keeps it. Each instance then takes,
    /// among its model's trees that meet its tolerance, the one whose smallest cut has
    /// the fewest spheres, and reports that cut ([`InstanceDetail::cut`], certified by
    /// its nodes' errors), the coarsest level of that tree meeting it
    /// ([`InstanceDetail::spheres`]) and the tree ([`InstanceDetail::tree`]: built now or
    /// not, and in how long). A tolerance no tree can be built for (below
    /// [`ModelOptions::finest_tolerance`](crate::ModelOptions::finest_tolerance), or out of
    /// reach) is said per instance ([`InstanceDetail::unmet`]), which then gets the finest
    /// spheres its model has.
    ///
    /// **Meshes.** The coarsest level of the model's mesh ladder meeting the tolerance;
    /// the ladder ends with the input, which meets every tolerance.
    ///
    /// Under a tolerance in pixels, a level the camera cannot see at all (the mesh's
    /// bounding sphere grown by the level's error is out of view) meets the tolerance,
    /// so an instance well out of view takes its coarsest levels (one just out of view
    /// may still need finer ones: a coarse level's error can reach into view). A camera
    /// given with another tolerance only sets [`InstanceDetail::visible`].
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::Arc;
    /// use sphaera_mesh::geometry::Similarity;
    /// use sphaera_scene::{Camera, DVec3, ModelOptions, ObjectModel, Scene, Tolerance};
    ///
    /// let mesh = sphaera_mesh::shapes::torus(1.0, 0.3, 24)?;
    /// let model = Arc::new(ObjectModel::build("torus", mesh, &ModelOptions::default())?);
    /// let mut scene = Scene::new();
    /// for (i, z) in [0.0, -20.0, -200.0].into_iter().enumerate() {
    ///     let pose = Similarity::from_translation(DVec3::new(0.0, 0.0, z))?;
    ///     scene.add(format!("torus-{i}"), Arc::clone(&model), pose);
    /// }
    /// let camera = Camera::perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 60.0, 1280, 720)?;
    /// let report = scene.detail(Some(&camera), Tolerance::Pixels(8.0))?;
    /// // Every instance within 8 px, certified; the farther, the fewer spheres and triangles.
    /// assert!(report.all_meet);
    /// assert!(report.instances.iter().all(|d| d.cut.meets && d.cut.measured <= 8.0));
    /// let spheres: Vec<usize> = report.instances.iter().map(|d| d.cut.count).collect();
    /// let triangles: Vec<usize> = report.instances.iter().map(|d| d.mesh.count).collect();
    /// assert!(spheres[0] > spheres[1] && spheres[1] > spheres[2]);
    /// assert!(triangles[0] > triangles[1] && triangles[1] > triangles[2]);
    /// // The near torus needed a finer tree than the base: it was built, once.
    /// assert_eq!(report.trees_built, 1);
    /// assert!(report.instances[0].tree.built && report.instances[0].tree.index == 1);
    /// // Asked again, nothing is built.
    /// assert_eq!(scene.detail(Some(&camera), Tolerance::Pixels(8.0))?.trees_built, 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SceneError::InvalidTolerance`] for a NaN, infinite or negative tolerance, and
    /// [`SceneError::NoCamera`] for a tolerance in pixels without a camera. A tree that
    /// cannot be built is not an error of the request: the instances it concerns say so.
    ///
    /// # Performance
    ///
    /// Without a build, `O(trees + cut)` per instance: 200 instances in about 1.3 ms
    /// (`cargo bench -p sphaera-eval --bench scene_vs_rapier`, see `docs/benchmarks.md`).
    /// A build costs what the tree costs (0.4–1.5 s of processor time per shared mesh at
    /// 2 % of its size), once per model and tolerance.
    pub fn detail(
        &self,
        camera: Option<&Camera>,
        tolerance: Tolerance,
    ) -> Result<DetailReport, SceneError> {
        let tolerance = tolerance.validated()?;
        if matches!(tolerance, Tolerance::Pixels(_)) && camera.is_none() {
            return Err(SceneError::NoCamera);
        }
        let instances = self.instances();
        let needs: Vec<f64> = instances
            .iter()
            .map(|i| model_tolerance(i, camera, tolerance))
            .collect();
        // Each model once, with every tolerance its instances need.
        let mut models: Vec<(&ObjectModel, Vec<f64>)> = Vec::new();
        let mut slot: HashMap<*const ObjectModel, usize> = HashMap::new();
        for (instance, &need) in instances.iter().zip(&needs) {
            let key = Arc::as_ptr(&instance.model);
            let k = *slot.entry(key).or_insert_with(|| {
                models.push((&instance.model, Vec::new()));
                models.len() - 1
            });
            if let Some((_, model_needs)) = models.get_mut(k) {
                model_needs.push(need);
            }
        }
        let started = Instant::now();
        let ensure =
            |(model, model_needs): &(&ObjectModel, Vec<f64>)| ensure_trees(model, model_needs);
        #[cfg(feature = "parallel")]
        let outcomes: Vec<Outcome> = {
            use rayon::prelude::*;
            models.par_iter().map(ensure).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let outcomes: Vec<Outcome> = models.iter().map(ensure).collect();
        let tree_seconds = started.elapsed().as_secs_f64();
        let no_outcome = Outcome::default();
        let details: Vec<InstanceDetail> = instances
            .iter()
            .zip(&needs)
            .enumerate()
            .map(|(index, (instance, &need))| {
                let outcome = slot
                    .get(&Arc::as_ptr(&instance.model))
                    .and_then(|&k| outcomes.get(k))
                    .unwrap_or(&no_outcome);
                choose(index, instance, camera, tolerance, need, outcome)
            })
            .collect();
        let sum = |f: &dyn Fn(&InstanceDetail) -> usize| details.iter().map(f).sum();
        Ok(DetailReport {
            tolerance: tolerance.to_string(),
            unit: tolerance.unit(),
            spheres: sum(&|d| d.spheres.count),
            cut_spheres: sum(&|d| d.cut.count),
            full_spheres: sum(&|d| d.full_spheres),
            triangles: sum(&|d| d.mesh.count),
            full_triangles: sum(&|d| d.full_triangles),
            trees_built: outcomes.iter().map(|o| o.built.len()).sum(),
            tree_seconds,
            all_meet: details.iter().all(|d| d.cut.meets && d.mesh.meets),
            instances: details,
        })
    }
}

/// What making sure a model meets its instances' tolerances did: the trees it built, and
/// the tolerances it could not build for, with why.
#[derive(Debug, Default)]
struct Outcome {
    built: Vec<Arc<ModelTree>>,
    failed: Vec<(f64, String)>,
}

/// Makes sure `model` has a tree for each of `needs` (model units), finest first: a tree
/// built for one meets every coarser one, and a tolerance that cannot be built for does
/// not keep the coarser ones from their trees.
fn ensure_trees(model: &ObjectModel, needs: &[f64]) -> Outcome {
    let mut needs = needs.to_vec();
    needs.sort_by(f64::total_cmp);
    needs.dedup_by(|a, b| a.to_bits() == b.to_bits());
    let mut outcome = Outcome::default();
    for need in needs {
        if model.best_tree(need).is_some() {
            continue;
        }
        match model.ensure_tree(need) {
            Ok((tree, _, true)) => outcome.built.push(tree),
            Ok(_) => {}
            Err(e) => outcome.failed.push((need, e.to_string())),
        }
    }
    outcome
}

/// The tolerance `instance` asks of its model's sphere-trees, in the model's units.
fn model_tolerance(instance: &Instance, camera: Option<&Camera>, tolerance: Tolerance) -> f64 {
    let largest = instance
        .model
        .tree_errors()
        .iter()
        .copied()
        .fold(0.0, f64::max);
    allowed_error(instance, camera, tolerance, largest)
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
    need: f64,
    outcome: &Outcome,
) -> InstanceDetail {
    let model = &instance.model;
    let scale = instance.pose.scale();
    let (tree, cut, unmet) = match model.best_tree(need) {
        Some((tree, cut)) => (tree, cut, None),
        None => {
            let tree = model.collision_tree();
            let cut = sphaera_spheretree::cut_for_tolerance(tree.tree(), need);
            let why = outcome
                .failed
                .iter()
                .find(|(n, _)| n.to_bits() == need.to_bits())
                .map_or_else(
                    || "no sphere-tree of the model meets it".to_owned(),
                    |(_, why)| why.clone(),
                );
            (tree, cut, Some(why))
        }
    };
    let spheres = choose_level(instance, camera, tolerance, tree.level_errors(), &|l| {
        tree.tree().cut_at(l).len()
    });
    let mesh = choose_level(instance, camera, tolerance, model.mesh_errors(), &|l| {
        model.mesh_levels().get(l).map_or(0, |m| m.triangles)
    });
    let measured = |e: f64| measure(instance, camera, tolerance, e * scale).unwrap_or(0.0);
    let deepest_level = cut
        .nodes
        .iter()
        .filter_map(|&i| tree.tree().nodes().get(i))
        .map(|n| n.level as usize)
        .max()
        .unwrap_or(0);
    let cut_measured = measured(cut.worst_error);
    let cut = CutChoice {
        count: cut.nodes.len(),
        deepest_level,
        error: cut.worst_error * scale,
        measured: cut_measured,
        meets: cut.meets_tolerance && cut_measured <= tolerance.value(),
    };
    InstanceDetail {
        instance: index,
        name: instance.name.clone(),
        model: model.name().to_owned(),
        visible: camera.is_none_or(|c| c.pixels_per_unit(&instance.bounding_sphere()).is_some()),
        model_tolerance: need,
        tree: TreeChoice {
            index: tree.index(),
            tolerance: tree.tolerance(),
            leaves: tree.leaf_count(),
            built: outcome.built.iter().any(|b| Arc::ptr_eq(b, &tree)),
            build_seconds: tree.build_seconds(),
        },
        spheres,
        unmet: match unmet {
            None if !cut.meets => Some(format!(
                "its cut's certified error is {} {}, over the tolerance",
                cut.measured,
                tolerance.unit()
            )),
            other => other,
        },
        cut,
        mesh,
        full_spheres: tree.leaf_count(),
        full_triangles: model.mesh().triangle_count(),
    }
}
