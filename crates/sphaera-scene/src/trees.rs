//! The sphere-trees of an object model: the base tree built with it, and the trees built
//! to a tolerance when a detail request needs one, each built once and kept.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Instant;

use sphaera_mesh::geometry::minimum_enclosing_ball_of_balls;
use sphaera_mesh::{Length, Sphere};
use sphaera_query::Surface;
use sphaera_spheretree::evaluate::{EvaluationOptions, sphere_error};
use sphaera_spheretree::{SphereTree, SphereTreeError, SphereTreeOptions, TreeNode};

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
    level_counts: Vec<usize>,
    worst_error: f64,
    leaves: usize,
    bound: Sphere,
    build_seconds: f64,
    certified: bool,
    /// What is known of the nodes looked at so far, by index.
    known: Mutex<HashMap<usize, Known>>,
}

/// What is known of a node's error beyond its node error: at least `lower` (a point of
/// its sphere that far outside the object, found by probing), and at most `upper` once
/// its sphere has been evaluated on the exact surface.
#[derive(Clone, Copy, Debug)]
struct Known {
    lower: f64,
    upper: Option<f64>,
}

/// Points probed on a sphere's boundary before it is evaluated: a point found farther
/// outside than the tolerance settles that it cannot meet it, for a few closest-point
/// queries instead of a branch and bound.
const PROBES: usize = 32;

/// What one sphere-tree offers a tolerance: the coarsest cut
/// [`SphereTree::cut_at`]`(level)` whose certified error meets it, and the smallest cut
/// of mixed levels whose nodes all do.
#[derive(Clone, Debug)]
pub(crate) struct Selection {
    /// The tree.
    pub(crate) tree: Arc<ModelTree>,
    /// The level of the coarsest level cut meeting the tolerance.
    pub(crate) level: usize,
    /// Its spheres.
    pub(crate) spheres: usize,
    /// Its certified error: the worst over its nodes of the node's error, or of the
    /// evaluated bound where that is smaller (model units).
    pub(crate) error: f64,
    /// Its worst node error (model units).
    pub(crate) node_error: f64,
    /// The smallest cut meeting the tolerance (node indices, ascending).
    pub(crate) cut: Vec<usize>,
    /// Its certified error (model units).
    pub(crate) cut_error: f64,
    /// The deepest level it reaches.
    pub(crate) cut_deepest: usize,
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
        let (level_errors, level_counts) = cut_errors(&tree);
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
        let certified = tree.level_count() > 0 && tree.coverage().len() == tree.level_count();
        Ok(Self {
            tree,
            index,
            tolerance,
            level_errors,
            level_counts,
            worst_error,
            leaves,
            bound,
            build_seconds,
            certified,
            known: Mutex::new(HashMap::new()),
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

    /// The spheres of each cut [`SphereTree::cut_at`]`(level)`, root first.
    #[must_use]
    pub fn level_counts(&self) -> &[usize] {
        &self.level_counts
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

    /// Whether every cut's coverage of the surface is certified (one coverage
    /// certificate per level, as [`sphaera_spheretree::build`] records them): only such a
    /// tree is used for detail, since an error bound says nothing of a surface the
    /// spheres leave uncovered.
    #[must_use]
    pub fn coverage_certified(&self) -> bool {
        self.certified
    }

    /// Node `index`'s error for `tolerance`, certified: its node error when that meets the
    /// tolerance, else the smaller of it and the upper end of the node's sphere evaluated
    /// on the exact surface ([`sphaera_spheretree::evaluate::sphere_error`], kept for
    /// later requests). A node whose sphere has a probed point farther outside the object
    /// than the tolerance cannot meet it, and keeps its node error without an evaluation
    /// (the answer is the same: over the tolerance).
    fn certified_error(&self, surface: &Surface, index: usize, tolerance: f64) -> f64 {
        let Some(node) = self.tree.nodes().get(index) else {
            return f64::INFINITY;
        };
        if node.error <= tolerance {
            return node.error;
        }
        let known = lock(&self.known).get(&index).copied();
        let known = known.unwrap_or_else(|| {
            let known = Known {
                lower: probe(surface, &node.sphere),
                upper: None,
            };
            lock(&self.known).insert(index, known);
            known
        });
        if known.lower > tolerance {
            return node.error;
        }
        let upper = known.upper.or_else(|| {
            let upper = sphere_error(surface, &node.sphere, &evaluation_options())
                .ok()
                .map(|f| f.upper);
            if let Some(upper) = upper {
                lock(&self.known).insert(
                    index,
                    Known {
                        upper: Some(upper),
                        ..known
                    },
                );
            }
            upper
        });
        upper.map_or(node.error, |u| u.min(node.error))
    }

    /// The nodes of the cut [`SphereTree::cut_at`]`(level)`.
    fn cut_nodes(&self, level: usize) -> impl Iterator<Item = (usize, &TreeNode)> {
        self.tree.nodes().iter().enumerate().filter(move |(_, n)| {
            let depth = n.level as usize;
            depth == level || (depth < level && n.children.is_empty())
        })
    }

    /// What this tree offers `tolerance` (model units): `None` when no level cut's
    /// certified error meets it, or its coverage is not certified.
    pub(crate) fn select(self: &Arc<Self>, surface: &Surface, tolerance: f64) -> Option<Selection> {
        if !self.certified {
            return None;
        }
        let (level, error) = (0..self.level_errors.len()).find_map(|level| {
            let node_error = self.level_errors[level];
            if node_error <= tolerance {
                return Some((level, node_error));
            }
            // The nodes over the tolerance by their node errors, worst first: the first
            // whose evaluation does not bring it within settles the level.
            let mut worst = f64::NEG_INFINITY;
            let mut over = Vec::new();
            for (i, node) in self.cut_nodes(level) {
                if node.error <= tolerance {
                    worst = worst.max(node.error);
                } else {
                    over.push((i, node.error));
                }
            }
            over.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
            for (i, _) in over {
                let certified = self.certified_error(surface, i, tolerance);
                if certified.is_nan() || certified > tolerance {
                    return None;
                }
                worst = worst.max(certified);
            }
            Some((level, worst))
        })?;
        // The smallest cut: from the roots down, a node stays when its certified error
        // meets the tolerance. It never goes below `level`, whose nodes all meet it.
        let nodes = self.tree.nodes();
        let mut cut = Vec::new();
        let mut cut_error = f64::NEG_INFINITY;
        let mut cut_deepest = 0;
        let mut stack: Vec<usize> = (0..self.tree.level(0).len()).collect();
        while let Some(i) = stack.pop() {
            let Some(node) = nodes.get(i) else { continue };
            let certified = self.certified_error(surface, i, tolerance);
            let end = (node.children.end as usize).min(nodes.len());
            let start = (node.children.start as usize).min(end);
            if certified <= tolerance || start == end {
                cut.push(i);
                cut_error = cut_error.max(certified);
                cut_deepest = cut_deepest.max(node.level as usize);
            } else {
                stack.extend(start..end);
            }
        }
        cut.sort_unstable();
        Some(Selection {
            tree: Arc::clone(self),
            level,
            spheres: self.level_counts[level],
            error,
            node_error: self.level_errors[level],
            cut,
            cut_error,
            cut_deepest,
        })
    }
}

/// A lower bound on the error of `sphere`: the farthest outside the object of
/// [`PROBES`] points spread over its boundary (certified sides and exact distances; 0
/// when none is outside).
fn probe(surface: &Surface, sphere: &Sphere) -> f64 {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..PROBES)
        .filter_map(|k| {
            let z = 1.0 - (2 * k + 1) as f64 / PROBES as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let angle = golden * k as f64;
            let p = sphere.center
                + sphere.radius * glam::DVec3::new(r * angle.cos(), r * angle.sin(), z);
            let side = surface.signed_closest(p).ok()?;
            (!side.inside).then_some(side.closest.distance)
        })
        .fold(0.0, f64::max)
}

/// How node spheres are evaluated: intervals 10⁻⁴ of the diagonal wide (the library's
/// default).
fn evaluation_options() -> EvaluationOptions {
    EvaluationOptions::default()
}

/// The worst error and the number of spheres of each cut `cut_at(level)`: the nodes of
/// the level and the leaves above it, in one pass.
fn cut_errors(tree: &SphereTree) -> (Vec<f64>, Vec<usize>) {
    let levels = tree.level_count();
    let mut at_level = vec![(f64::NEG_INFINITY, 0_usize); levels];
    let mut leaves_at = vec![(f64::NEG_INFINITY, 0_usize); levels];
    for node in tree.nodes() {
        let level = node.level as usize;
        if let Some((worst, count)) = at_level.get_mut(level) {
            *worst = worst.max(node.error);
            *count += 1;
        }
        if node.children.is_empty()
            && let Some((worst, count)) = leaves_at.get_mut(level)
        {
            *worst = worst.max(node.error);
            *count += 1;
        }
    }
    let mut above = (f64::NEG_INFINITY, 0);
    at_level
        .iter()
        .zip(&leaves_at)
        .map(|(&(here, count), &(leaves, leaf_count))| {
            let cut = (here.max(above.0), count + above.1);
            above = (above.0.max(leaves), above.1 + leaf_count);
            cut
        })
        .unzip()
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

    /// Among the trees with a level cut whose certified error meets `tolerance`, the one
    /// whose coarsest such cut has the fewest spheres (the earliest on a tie), with what
    /// it offers.
    pub(crate) fn best(&self, surface: &Surface, tolerance: f64) -> Option<Selection> {
        let mut best: Option<Selection> = None;
        for tree in self.all() {
            if let Some(selection) = tree.select(surface, tolerance)
                && best.as_ref().is_none_or(|b| selection.spheres < b.spheres)
            {
                best = Some(selection);
            }
        }
        best
    }

    /// What the model's trees offer `tolerance` (model units), building a tree when none
    /// meets it (and whether it did). The tree is built to `tolerance`, or to half the
    /// finest tolerance built so far when that is smaller, so a run of slowly tightening
    /// requests builds once per halving, not once per request.
    pub(crate) fn ensure(
        &self,
        model: &str,
        tolerance: f64,
        surface: &Surface,
        policy: &TreePolicy,
        mesh_ball: Sphere,
    ) -> Result<(Selection, bool), SceneError> {
        let diagonal = surface.diagonal();
        if let Some(selection) = self.best(surface, tolerance) {
            return Ok((selection, false));
        }
        if tolerance.is_nan() || tolerance < policy.finest {
            return Err(SceneError::ToleranceBelowFinest {
                model: model.to_owned(),
                tolerance,
                finest: policy.finest,
                diagonal,
            });
        }
        let _building = lock(&self.building);
        // Another request may have built what this one needs while it waited.
        if let Some(selection) = self.best(surface, tolerance) {
            return Ok((selection, false));
        }
        let unreachable = |reason: Arc<SphereTreeError>| SceneError::ToleranceTree {
            model: model.to_owned(),
            tolerance,
            diagonal,
            reason,
        };
        let finest_built = {
            let state = lock(&self.state);
            if let Some((out_of_reach, why)) = &state.unreachable
                && tolerance <= *out_of_reach
            {
                return Err(unreachable(Arc::clone(why)));
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
                .with_certify_coverage(true)
                .with_tolerance(Length::Absolute(target - margin));
            let started = Instant::now();
            let error = match sphaera_spheretree::build(surface, &options) {
                Ok(tree) => {
                    let seconds = started.elapsed().as_secs_f64();
                    let built = ModelTree::new(tree, 0, Some(target), seconds, mesh_ball)?;
                    let missed = built.worst_error - target;
                    if missed <= 0.0 && built.certified {
                        let mut state = lock(&self.state);
                        let tree = Arc::new(ModelTree {
                            index: state.built.len() + 1,
                            ..built
                        });
                        state.built.push(Arc::clone(&tree));
                        drop(state);
                        // Every leaf meets `target`, at most `tolerance`: the leaves do.
                        return tree
                            .select(surface, tolerance)
                            .map(|selection| (selection, true))
                            .ok_or_else(|| {
                                unreachable(Arc::new(SphereTreeError::ToleranceUnreachable {
                                    tolerance,
                                    worst: tree.worst_error,
                                    spheres: tree.tree.nodes().len(),
                                    levels: tree.tree.level_count(),
                                    limit: sphaera_spheretree::MAX_TREE_NODES,
                                    depth: sphaera_spheretree::MAX_MEDIAL_DEPTH,
                                }))
                            });
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
                drop(state);
                // The halved target was out of reach; the one asked may not be.
                if target < tolerance {
                    target = tolerance;
                    margin = target * BUILD_MARGIN;
                    retried = false;
                    continue;
                }
            }
            return Err(unreachable(reason));
        }
    }
}
