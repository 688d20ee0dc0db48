//! Choosing, for every instance, the spheres and the mesh level a tolerance needs,
//! building the sphere-trees it takes.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;

use serde::Serialize;

use crate::trees::Selection;
use crate::{Camera, Instance, ObjectModel, Scene, SceneError, Tolerance};

/// The level chosen for one instance in its model's mesh ladder.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LevelChoice {
    /// The level (0: the coarsest).
    pub level: usize,
    /// How many levels there are.
    pub levels: usize,
    /// Its triangles.
    pub count: usize,
    /// Its certified error in the scene's units (the model's error times the pose's
    /// scale).
    pub error: f64,
    /// The same error in the tolerance's unit: world units, a fraction of the instance's
    /// diagonal, or pixels on the camera's image (0 for a level the camera cannot see).
    pub measured: f64,
    /// Whether it meets the tolerance (the ladder ends with the input, error 0, which
    /// meets every tolerance: always `true` in a [`DetailReport`]).
    pub meets: bool,
}

/// The spheres chosen for one instance: the coarsest cut
/// [`SphereTree::cut_at`](sphaera_spheretree::SphereTree::cut_at)`(level)` of its
/// model's tree ([`InstanceDetail::tree`]) whose **certified error** meets the
/// tolerance. A cut's certified error is the worst over its spheres of each sphere's
/// node error ([`TreeNode::error`](sphaera_spheretree::TreeNode::error)), or, for a
/// sphere whose node error is over the tolerance, the smaller of it and the upper bound
/// of the sphere evaluated on the exact surface
/// ([`sphaera_spheretree::evaluate::sphere_error`]). Every cut covers the surface
/// (certified), so these spheres hold the object and reach at most `error` beyond it.
/// Get them with [`ObjectModel::detail_spheres`](crate::ObjectModel::detail_spheres).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SphereChoice {
    /// The level of the cut (0: the roots).
    pub level: usize,
    /// The tree's levels.
    pub levels: usize,
    /// Its spheres.
    pub count: usize,
    /// Its certified error in the scene's units (at most the tolerance).
    pub error: f64,
    /// Its worst node error in the scene's units (at least [`SphereChoice::error`]: more
    /// when evaluating its spheres certified a smaller error).
    pub node_error: f64,
    /// The certified error in the tolerance's unit (0 when the camera cannot see it).
    pub measured: f64,
    /// The leaves of its model's finest tree ([`ObjectModel::collision_tree`](crate::ObjectModel::collision_tree)):
    /// the spheres at full detail.
    pub finest: usize,
    /// The spheres saved against full detail, in percent (`100 · (1 − count / finest)`).
    pub saved_percent: f64,
}

/// The smallest cut through the instance's sphere-tree that meets the tolerance: from
/// the roots down, a node stays when its certified error (as in [`SphereChoice`])
/// meets it. Coarse nodes stay where they are tight enough, so it never has more spheres
/// than [`InstanceDetail::spheres`], and often fewer.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CutChoice {
    /// Its spheres.
    pub count: usize,
    /// The deepest level it reaches.
    pub deepest_level: usize,
    /// Its certified error in the scene's units (at most the tolerance).
    pub error: f64,
    /// The same error in the tolerance's unit (0 when the camera cannot see it).
    pub measured: f64,
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
    /// The tolerance asked of it, in the scene's units: [`InstanceDetail::model_tolerance`]
    /// times the pose's scale.
    pub tolerance: f64,
    /// The tolerance asked of its model, in the model's units: the largest error that
    /// meets the scene's tolerance for this instance (a world tolerance divided by the
    /// pose's scale, a fraction of the model's diagonal, or the error the camera shows
    /// as the tolerance's pixels).
    pub model_tolerance: f64,
    /// The sphere-tree the spheres are taken from: the one of the model's trees whose
    /// coarsest cut meeting the tolerance has the fewest spheres, built for it when none
    /// met it.
    pub tree: TreeChoice,
    /// The spheres: the coarsest cut of that tree whose certified error meets the
    /// tolerance.
    pub spheres: SphereChoice,
    /// The smallest cut of that tree meeting the tolerance (a set of nodes of mixed
    /// levels): at most [`InstanceDetail::spheres`]'s spheres.
    pub cut: CutChoice,
    /// The mesh level.
    pub mesh: LevelChoice,
    /// The leaves of its model's finest tree (the spheres at full detail).
    pub full_spheres: usize,
    /// The triangles of its input mesh.
    pub full_triangles: usize,
}

/// What [`Scene::detail`] chose, instance by instance, with the totals against full
/// detail and the trees it built. Every choice in it meets the tolerance (certified):
/// a tolerance that cannot be met is an error, not a report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetailReport {
    /// The tolerance, as text (`0.01`, `0.5%`, `2px`).
    pub tolerance: String,
    /// The unit of [`SphereChoice::measured`] and [`LevelChoice::measured`]: `world`,
    /// `relative` or `px`.
    pub unit: &'static str,
    /// One entry per instance, in scene order.
    pub instances: Vec<InstanceDetail>,
    /// Spheres of the chosen level cuts, over all instances.
    pub spheres: usize,
    /// Spheres of the smallest cuts, over all instances (at most
    /// [`DetailReport::spheres`]).
    pub cut_spheres: usize,
    /// Leaves of the instances' models' finest trees: the spheres at full detail.
    pub full_spheres: usize,
    /// The spheres saved against full detail, in percent (0 for an empty scene).
    pub spheres_saved_percent: f64,
    /// Triangles at the chosen levels.
    pub triangles: usize,
    /// Triangles of every instance's input mesh.
    pub full_triangles: usize,
    /// The triangles saved against full detail, in percent (0 for an empty scene).
    pub triangles_saved_percent: f64,
    /// Sphere-trees built by this request (at most a few per model, usually one).
    pub trees_built: usize,
    /// The wall-clock seconds this request spent making sure every model has a tree
    /// meeting its instances' tolerances and choosing their cuts (building the models'
    /// trees on every core with the `parallel` feature).
    pub tree_seconds: f64,
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

/// `100 · (1 − part / whole)`, 0 when `whole` is 0.
fn saved_percent(part: usize, whole: usize) -> f64 {
    if whole == 0 {
        0.0
    } else {
        100.0 * (1.0 - part as f64 / whole as f64)
    }
}

impl Scene {
    /// For each instance, the spheres and the mesh level its tolerance needs: in world
    /// units, as a fraction of the instance's size, or in pixels on `camera`'s image
    /// (bounded by [`Camera::projected_error`], so the error drawn is certified too).
    /// **Every tolerance asked is met**, or the request fails and says why.
    ///
    /// **Spheres.** The tolerance comes to a tolerance in each instance's model units
    /// ([`InstanceDetail::model_tolerance`]). Each model is asked once per distinct
    /// tolerance, finest first ([`ObjectModel::tree_for`](crate::ObjectModel::tree_for)):
    /// when none of its trees meets it, it builds a minimax tree to it (the models on
    /// every core with the `parallel` feature), once, and keeps it; later requests, and
    /// coarser tolerances, reuse it. Each instance then takes, among its model's trees,
    /// the one whose coarsest cut [`SphereTree::cut_at`](sphaera_spheretree::SphereTree::cut_at)`(level)`
    /// with a certified error within the tolerance has the fewest spheres, and that cut
    /// ([`InstanceDetail::spheres`], see [`SphereChoice`] for how the error is certified),
    /// with the smallest cut of mixed levels ([`InstanceDetail::cut`]) and the tree
    /// ([`InstanceDetail::tree`]: built now or not, and in how long).
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
    /// assert!(report.instances.iter().all(|d| d.spheres.measured <= 8.0 && d.cut.measured <= 8.0));
    /// let spheres: Vec<usize> = report.instances.iter().map(|d| d.spheres.count).collect();
    /// let triangles: Vec<usize> = report.instances.iter().map(|d| d.mesh.count).collect();
    /// assert!(spheres[0] > spheres[1] && spheres[1] >= spheres[2]);
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
    /// [`SceneError::InvalidTolerance`] for a NaN, infinite or negative tolerance,
    /// [`SceneError::NoCamera`] for a tolerance in pixels without a camera, and, when
    /// an instance's tolerance cannot be met, the first such model's (in scene order)
    /// [`SceneError::ToleranceBelowFinest`] (below
    /// [`ModelOptions::finest_tolerance`](crate::ModelOptions::finest_tolerance)) or
    /// [`SceneError::ToleranceTree`] (out of reach of any tree, or invalid tree options),
    /// each naming the model, the tolerance and its diagonal. The trees built before the
    /// failure are kept.
    ///
    /// # Performance
    ///
    /// Without a build, `O(trees · nodes)` per model and distinct tolerance, and `O(1)`
    /// per instance, plus the first time a tolerance is asked of a tree the evaluation of
    /// the nodes over it that probing does not rule out. A build costs what the tree
    /// costs, once per model and tolerance. See the crate's Performance section.
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
        let select =
            |(model, model_needs): &(&ObjectModel, Vec<f64>)| select_all(model, model_needs);
        #[cfg(feature = "parallel")]
        let outcomes: Vec<Result<Outcome, SceneError>> = {
            use rayon::prelude::*;
            models.par_iter().map(select).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let outcomes: Vec<Result<Outcome, SceneError>> = models.iter().map(select).collect();
        // The first model, in scene order, whose tolerance cannot be met.
        let outcomes: Vec<Outcome> = outcomes.into_iter().collect::<Result<_, _>>()?;
        let tree_seconds = started.elapsed().as_secs_f64();
        let mut details = Vec::with_capacity(instances.len());
        for (index, (instance, &need)) in instances.iter().zip(&needs).enumerate() {
            let selection = slot
                .get(&Arc::as_ptr(&instance.model))
                .and_then(|&k| outcomes.get(k))
                .and_then(|o| o.selections.get(&need.to_bits()));
            // Every need of every model was selected for above.
            let Some(selection) = selection else {
                return Err(SceneError::NoSuchInstance {
                    index,
                    count: instances.len(),
                });
            };
            let built = slot
                .get(&Arc::as_ptr(&instance.model))
                .and_then(|&k| outcomes.get(k))
                .is_some_and(|o| o.built.iter().any(|&b| b == selection.tree.index()));
            details.push(describe(
                index, instance, camera, tolerance, need, selection, built,
            ));
        }
        let sum = |f: &dyn Fn(&InstanceDetail) -> usize| details.iter().map(f).sum::<usize>();
        let spheres = sum(&|d| d.spheres.count);
        let full_spheres = sum(&|d| d.full_spheres);
        let triangles = sum(&|d| d.mesh.count);
        let full_triangles = sum(&|d| d.full_triangles);
        Ok(DetailReport {
            tolerance: tolerance.to_string(),
            unit: tolerance.unit(),
            spheres,
            cut_spheres: sum(&|d| d.cut.count),
            full_spheres,
            spheres_saved_percent: saved_percent(spheres, full_spheres),
            triangles,
            full_triangles,
            triangles_saved_percent: saved_percent(triangles, full_triangles),
            trees_built: outcomes.iter().map(|o| o.built.len()).sum(),
            tree_seconds,
            instances: details,
        })
    }
}

/// What one model offers each tolerance its instances need, and the trees it built for
/// them (their indices).
#[derive(Debug, Default)]
struct Outcome {
    selections: HashMap<u64, Selection>,
    built: Vec<usize>,
}

/// Selects for each of `needs` (model units) on `model`, finest first: a tree built for
/// one may meet the coarser ones too.
fn select_all(model: &ObjectModel, needs: &[f64]) -> Result<Outcome, SceneError> {
    let mut needs = needs.to_vec();
    needs.sort_by(f64::total_cmp);
    needs.dedup_by(|a, b| a.to_bits() == b.to_bits());
    let mut outcome = Outcome::default();
    for need in needs {
        let (selection, built) = model.ensure_tree(need)?;
        if built {
            outcome.built.push(selection.tree.index());
        }
        outcome.selections.insert(need.to_bits(), selection);
    }
    Ok(outcome)
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
        Tolerance::Absolute(_) => Some(world),
        Tolerance::RelativeToDiagonal(_) => Some(world / instance.diagonal()),
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
        Tolerance::Absolute(t) => t / scale,
        Tolerance::RelativeToDiagonal(t) => t * model.diagonal(),
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

/// The detail of `instance` from what its model's trees offer its `need`.
fn describe(
    index: usize,
    instance: &Instance,
    camera: Option<&Camera>,
    tolerance: Tolerance,
    need: f64,
    selection: &Selection,
    built: bool,
) -> InstanceDetail {
    let model = &instance.model;
    let scale = instance.pose.scale();
    let tree = &selection.tree;
    let measured = |e: f64| measure(instance, camera, tolerance, e * scale).unwrap_or(0.0);
    let finest = model.collision_tree().leaf_count();
    let mesh = choose_level(instance, camera, tolerance, model.mesh_errors(), &|l| {
        model.mesh_levels().get(l).map_or(0, |m| m.triangles)
    });
    InstanceDetail {
        instance: index,
        name: instance.name.clone(),
        model: model.name().to_owned(),
        visible: camera.is_none_or(|c| c.pixels_per_unit(&instance.bounding_sphere()).is_some()),
        tolerance: need * scale,
        model_tolerance: need,
        tree: TreeChoice {
            index: tree.index(),
            tolerance: tree.tolerance(),
            leaves: tree.leaf_count(),
            built,
            build_seconds: tree.build_seconds(),
        },
        spheres: SphereChoice {
            level: selection.level,
            levels: tree.tree().level_count(),
            count: selection.spheres,
            error: selection.error * scale,
            node_error: selection.node_error * scale,
            measured: measured(selection.error),
            finest,
            saved_percent: saved_percent(selection.spheres, finest),
        },
        cut: CutChoice {
            count: selection.cut.len(),
            deepest_level: selection.cut_deepest,
            error: selection.cut_error * scale,
            measured: measured(selection.cut_error),
        },
        mesh,
        full_spheres: finest,
        full_triangles: model.mesh().triangle_count(),
    }
}
