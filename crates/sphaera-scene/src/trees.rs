//! The sphere-trees of an object model: the base tree built with it, and the trees built
//! to a tolerance when a detail request needs one, each built once and kept.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Instant;

use sphaera_mesh::geometry::minimum_enclosing_ball_of_balls;
use sphaera_mesh::{Length, Sphere, Surface};
use sphaera_spheretree::select::Cut;
use sphaera_spheretree::{SphereTree, SphereTreeError, SphereTreeOptions, cut_for_tolerance};

use crate::SceneError;

/// One sphere-tree of an [`ObjectModel`](crate::ObjectModel), with what it was built for
/// and the certified error of each of its cuts.
///
/// A model's first tree (index 0) is its **base tree**, built with the model from
/// [`ModelOptions::tree`](crate::ModelOptions::tree). The others are **tolerance trees**,
/// built when a detail request needs a finer tolerance than every tree the model has
/// ([`ObjectModel::tree_for`](crate::ObjectModel::tree_for)): minimax trees whose every
/// leaf's certified error meets the tolerance they were built to, refined only where
/// needed. In such a tree a level alone does not cover the surface: its cuts
/// ([`SphereTree::cut_at`]) do, and [`ModelTree::level_errors`] are theirs.
///
/// # Examples
///
/// ```
/// use sphaera_scene::{ModelOptions, ObjectModel};
/// use sphaera_spheretree::SphereTreeOptions;
///
/// let options = ModelOptions::default().with_tree(SphereTreeOptions::default().with_depth(1).with_branch(4));
/// let model = ObjectModel::build("capsule", sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?, &options)?;
/// let base = model.base_tree();
/// assert_eq!((base.index(), base.tolerance(), base.level_errors().len()), (0, None, 2));
/// // 4 % of the diagonal, in the model's units: a tolerance tree is built for it, once.
/// let tolerance = 0.04 * model.diagonal();
/// let (tree, built) = model.tree_for(tolerance)?;
/// assert!(built && tree.index() == 1 && tree.worst_error() <= tolerance);
/// let (again, built) = model.tree_for(tolerance)?;
/// assert!(!built && again.index() == 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct ModelTree {
    tree: SphereTree,
    index: usize,
    tolerance: Option<f64>,
    level_errors: Vec<f64>,
    worst_error: f64,
    leaves: usize,
    bound: Sphere,
    build_seconds: f64,
}

impl ModelTree {
    /// Wraps `tree`, the model's `index`-th, built to `tolerance` (`None`: to a depth) in
    /// `build_seconds`; `mesh_ball` is the smallest sphere holding the mesh.
    pub(crate) fn new(
        tree: SphereTree,
        index: usize,
        tolerance: Option<f64>,
        build_seconds: f64,
        mesh_ball: Sphere,
    ) -> Result<Self, SceneError> {
        let level_errors = cut_errors(&tree);
        let worst_error = level_errors.last().copied().unwrap_or(0.0);
        let leaves = tree
            .nodes()
            .iter()
            .filter(|n| n.children.is_empty())
            .count();
        // The roots cover the surface (certified), so the ball around them holds it too;
        // the mesh's own ball is added for trees built elsewhere.
        let mut balls = tree.level_spheres(0);
        balls.push(mesh_ball);
        let bound = minimum_enclosing_ball_of_balls(&balls)?;
        Ok(Self {
            tree,
            index,
            tolerance,
            level_errors,
            worst_error,
            leaves,
            bound,
            build_seconds,
        })
    }

    /// The sphere-tree.
    #[must_use]
    pub fn tree(&self) -> &SphereTree {
        &self.tree
    }

    /// Its index among the model's trees, in the order they were built (0: the base
    /// tree).
    #[must_use]
    pub fn index(&self) -> usize {
        self.index
    }

    /// The tolerance it was built to, in the model's units (every leaf's certified error
    /// meets it); `None` for the base tree, built to a depth.
    #[must_use]
    pub fn tolerance(&self) -> Option<f64> {
        self.tolerance
    }

    /// The worst certified node error of each cut [`SphereTree::cut_at`]`(level)`, root
    /// first: how far the spheres of that detail reach beyond the surface, at most. For
    /// a tree built to a depth, the cuts are the levels.
    #[must_use]
    pub fn level_errors(&self) -> &[f64] {
        &self.level_errors
    }

    /// The worst certified error of its leaves (its finest cut).
    #[must_use]
    pub fn worst_error(&self) -> f64 {
        self.worst_error
    }

    /// Its leaves: the spheres of its finest cut.
    #[must_use]
    pub fn leaf_count(&self) -> usize {
        self.leaves
    }

    /// A sphere holding the mesh and the tree's roots, in the model's frame: what the
    /// broad phase of [`Scene::collide`](crate::Scene::collide) tests.
    #[must_use]
    pub fn bound(&self) -> Sphere {
        self.bound
    }

    /// The seconds its construction took (0 for a tree given to
    /// [`ObjectModel::from_parts`](crate::ObjectModel::from_parts)).
    #[must_use]
    pub fn build_seconds(&self) -> f64 {
        self.build_seconds
    }
}

/// The worst error of each cut `cut_at(level)`: the nodes of the level and the leaves
/// above it, in one pass.
fn cut_errors(tree: &SphereTree) -> Vec<f64> {
    let levels = tree.level_count();
    let mut at_level = vec![f64::NEG_INFINITY; levels];
    let mut leaves_at = vec![f64::NEG_INFINITY; levels];
    for node in tree.nodes() {
        let level = node.level as usize;
        if let Some(worst) = at_level.get_mut(level) {
            *worst = worst.max(node.error);
        }
        if node.children.is_empty()
            && let Some(worst) = leaves_at.get_mut(level)
        {
            *worst = worst.max(node.error);
        }
    }
    let mut above = f64::NEG_INFINITY;
    at_level
        .iter()
        .zip(&leaves_at)
        .map(|(&here, &leaves)| {
            let worst = here.max(above);
            above = above.max(leaves);
            worst
        })
        .collect()
}

/// The fraction of a tolerance trees are built inside it (2⁻¹⁰): room for the growth
/// the library's coverage certificate may give a sphere after the construction met the
/// tolerance.
const BUILD_MARGIN: f64 = 1.0 / 1024.0;

/// How a model builds its tolerance trees: the options (their tolerance is set per
/// build) and the finest tolerance it accepts, in the model's units.
#[derive(Clone, Debug)]
pub(crate) struct TreePolicy {
    pub(crate) options: SphereTreeOptions,
    pub(crate) finest: f64,
}

/// A model's trees: the base tree, then the tolerance trees in the order they were built.
#[derive(Debug)]
pub(crate) struct Trees {
    base: Arc<ModelTree>,
    state: Mutex<State>,
    /// Held while a tolerance tree is built: one build at a time per model, so that two
    /// requests for the same tolerance build once.
    building: Mutex<()>,
}

#[derive(Debug, Default)]
struct State {
    built: Vec<Arc<ModelTree>>,
    /// The largest tolerance a build found unreachable, and why: a request at or below it
    /// fails the same way at once.
    unreachable: Option<(f64, Arc<SphereTreeError>)>,
}

fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    // A build that panicked leaves nothing half-written: the list is only pushed to.
    mutex.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Trees {
    pub(crate) fn new(base: ModelTree) -> Self {
        Self {
            base: Arc::new(base),
            state: Mutex::new(State::default()),
            building: Mutex::new(()),
        }
    }

    pub(crate) fn base(&self) -> &ModelTree {
        &self.base
    }

    /// Every tree, base first, in build order.
    pub(crate) fn all(&self) -> Vec<Arc<ModelTree>> {
        let state = lock(&self.state);
        std::iter::once(Arc::clone(&self.base))
            .chain(state.built.iter().cloned())
            .collect()
    }

    /// The tree with the smallest worst leaf error (the earliest on a tie).
    pub(crate) fn finest(&self) -> Arc<ModelTree> {
        self.all()
            .into_iter()
            .reduce(|best, t| {
                if t.worst_error < best.worst_error {
                    t
                } else {
                    best
                }
            })
            .unwrap_or_else(|| Arc::clone(&self.base))
    }

    /// Among the trees whose smallest cut for `tolerance` meets it, the one whose cut has
    /// the fewest spheres (the earliest on a tie), with that cut.
    pub(crate) fn best(&self, tolerance: f64) -> Option<(Arc<ModelTree>, Cut)> {
        let mut best: Option<(Arc<ModelTree>, Cut)> = None;
        for tree in self.all() {
            let cut = cut_for_tolerance(&tree.tree, tolerance);
            if cut.meets_tolerance
                && best
                    .as_ref()
                    .is_none_or(|(_, b)| cut.nodes.len() < b.nodes.len())
            {
                best = Some((tree, cut));
            }
        }
        best
    }

    /// A tree meeting `tolerance` (model units) with its smallest cut for it, building
    /// one when none does (and whether it did). The tree is built to `tolerance`, or to
    /// half the finest tolerance built so far when that is smaller, so a run of slowly
    /// tightening requests builds once per halving, not once per request.
    pub(crate) fn ensure(
        &self,
        model: &str,
        tolerance: f64,
        surface: &Surface,
        policy: &TreePolicy,
        mesh_ball: Sphere,
    ) -> Result<(Arc<ModelTree>, Cut, bool), SceneError> {
        if let Some((tree, cut)) = self.best(tolerance) {
            return Ok((tree, cut, false));
        }
        if !(tolerance >= policy.finest) {
            return Err(SceneError::ToleranceBelowFinest {
                model: model.to_owned(),
                tolerance,
                finest: policy.finest,
            });
        }
        let _building = lock(&self.building);
        // Another request may have built what this one needs while it waited.
        if let Some((tree, cut)) = self.best(tolerance) {
            return Ok((tree, cut, false));
        }
        let finest_built = {
            let state = lock(&self.state);
            if let Some((unreachable, why)) = &state.unreachable
                && tolerance <= *unreachable
            {
                return Err(SceneError::ToleranceTree {
                    model: model.to_owned(),
                    tolerance,
                    reason: Arc::clone(why),
                });
            }
            state
                .built
                .iter()
                .filter_map(|t| t.tolerance)
                .fold(f64::INFINITY, f64::min)
        };
        let mut target = tolerance.min((0.5 * finest_built).max(policy.finest));
        // The library certifies coverage after it meets the tolerance, and may grow a
        // sphere by a rounding's worth there: build a little inside the target, and once
        // more inside it by twice what was missed if that was not enough.
        let mut margin = target * BUILD_MARGIN;
        let mut retried = false;
        loop {
            let options = policy
                .options
                .clone()
                .with_tolerance(Length::Absolute(target - margin));
            let started = Instant::now();
            let error = match sphaera_spheretree::build(surface, &options) {
                Ok(tree) => {
                    let seconds = started.elapsed().as_secs_f64();
                    let built = ModelTree::new(tree, 0, Some(target), seconds, mesh_ball)?;
                    let cut = cut_for_tolerance(&built.tree, tolerance);
                    let missed = built.worst_error - target;
                    if cut.meets_tolerance && missed <= 0.0 {
                        let mut state = lock(&self.state);
                        let tree = Arc::new(ModelTree {
                            index: state.built.len() + 1,
                            ..built
                        });
                        state.built.push(Arc::clone(&tree));
                        return Ok((tree, cut, true));
                    }
                    if !retried && missed > 0.0 && margin + 2.0 * missed < target {
                        retried = true;
                        margin += 2.0 * missed;
                        continue;
                    }
                    // Every leaf was built within the target: only a library defect gets
                    // here.
                    SphereTreeError::ToleranceUnreachable {
                        tolerance: target,
                        worst: built.worst_error,
                        spheres: built.tree.nodes().len(),
                        levels: built.tree.level_count(),
                        limit: sphaera_spheretree::MAX_TREE_NODES,
                        depth: sphaera_spheretree::MAX_MEDIAL_DEPTH,
                    }
                }
                Err(error) => error,
            };
            let reason = Arc::new(error);
            if matches!(*reason, SphereTreeError::ToleranceUnreachable { .. }) {
                let mut state = lock(&self.state);
                if state.unreachable.as_ref().is_none_or(|(u, _)| target > *u) {
                    state.unreachable = Some((target, Arc::clone(&reason)));
                }
                // The halved target was out of reach; the one asked may not be.
                if target < tolerance {
                    target = tolerance;
                    margin = target * BUILD_MARGIN;
                    retried = false;
                    continue;
                }
            }
            return Err(SceneError::ToleranceTree {
                model: model.to_owned(),
                tolerance,
                reason,
            });
        }
    }
}
