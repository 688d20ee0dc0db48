//! Contacts in a whole scene within one budget: a broad phase over the instances' bounding
//! spheres, then every close pair's sphere-trees descended together, level by level.

use std::sync::Arc;
use std::time::Instant;

use serde::Serialize;
use sphaera_mesh::Sphere;
use sphaera_spheretree::collide::{Budget, Contact, Traversal, TraversalStats};

use crate::{Instance, ModelTree, Scene, SceneError};

/// The contacts of one pair of instances.
#[derive(Clone, Debug, PartialEq)]
pub struct PairContacts {
    /// The first instance (the smaller index).
    pub a: usize,
    /// The second instance.
    pub b: usize,
    /// The sphere-tree level the contacts are at (0: the roots).
    pub level: usize,
    /// Whether the pair's trees were descended to their leaves: the contacts are then the
    /// trees' exact answer.
    pub completed: bool,
    /// The overlapping sphere pairs, in the scene, sorted by node; each carries its error
    /// bound (the objects are at most that far apart there).
    pub contacts: Vec<Contact>,
}

impl PairContacts {
    /// The smallest error bound of the pair's contacts: the instances are at most this
    /// far apart (as solids). `None` without contacts.
    #[must_use]
    pub fn separation_bound(&self) -> Option<f64> {
        self.contacts
            .iter()
            .map(|c| c.error_bound)
            .min_by(f64::total_cmp)
    }

    /// The largest error bound of the pair's contacts: every contact is within this of
    /// the objects' true contact region.
    #[must_use]
    pub fn max_error_bound(&self) -> Option<f64> {
        self.contacts
            .iter()
            .map(|c| c.error_bound)
            .max_by(f64::total_cmp)
    }
}

/// What [`Scene::collide`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneCollision {
    /// The pairs of instances still in contact at the level they were descended to,
    /// sorted by `(a, b)`. A pair not listed does not touch: its bounding spheres or its
    /// trees are apart.
    pub pairs: Vec<PairContacts>,
    /// The pairs whose bounding spheres overlap (the broad phase's output).
    pub broad_phase_pairs: usize,
    /// The shallowest level every pair in contact reached.
    pub level: usize,
    /// Whether every pair was descended to its leaves.
    pub completed: bool,
    /// The work done over all pairs, in the paper's cost model.
    pub stats: TraversalStats,
}

/// A summary of a [`SceneCollision`] for reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CollisionSummary {
    /// Pairs in contact.
    pub pairs_in_contact: usize,
    /// Sphere contacts over all pairs.
    pub contacts: usize,
    /// The broad phase's pairs.
    pub broad_phase_pairs: usize,
    /// The shallowest level reached by a pair in contact.
    pub level: usize,
    /// Whether every pair reached its leaves.
    pub completed: bool,
    /// Spheres placed.
    pub updates: u64,
    /// Sphere pairs tested.
    pub tests: u64,
    /// The largest error bound of any contact, `None` without contacts.
    pub max_error_bound: Option<f64>,
}

impl SceneCollision {
    /// Counts and the worst error bound, for reports.
    #[must_use]
    pub fn summary(&self) -> CollisionSummary {
        CollisionSummary {
            pairs_in_contact: self.pairs.len(),
            contacts: self.pairs.iter().map(|p| p.contacts.len()).sum(),
            broad_phase_pairs: self.broad_phase_pairs,
            level: self.level,
            completed: self.completed,
            updates: self.stats.updates,
            tests: self.stats.tests,
            max_error_bound: self
                .pairs
                .iter()
                .filter_map(PairContacts::max_error_bound)
                .max_by(f64::total_cmp),
        }
    }
}

impl Scene {
    /// The pairs of instances whose bounding spheres overlap, sorted: a sweep along `x`
    /// over each instance's [`Instance::root_bound`] (around its mesh and the roots of
    /// its model's collision tree).
    #[must_use]
    pub fn broad_phase(&self) -> Vec<(usize, usize)> {
        let bounds: Vec<Sphere> = self.instances().iter().map(Instance::root_bound).collect();
        sweep(&bounds)
    }

    /// Every contact in the scene within `budget`: the broad phase, then every close pair's
    /// sphere-trees descended together (the interruptible traversal of
    /// [`sphaera_spheretree::collide()`]), **level `k` of every pair before level `k + 1`
    /// of any**, so a budget too small for the whole scene leaves every pair equally
    /// refined rather than a few exact and the rest at their roots.
    ///
    /// Each instance's tree is its model's collision tree
    /// ([`ObjectModel::collision_tree`](crate::ObjectModel::collision_tree)): the base
    /// tree, or the finest tolerance tree once [`Scene::detail`] has built one, so the
    /// contacts are as tight as the scene's tolerance asked. A tree built to a tolerance
    /// has leaves at several depths; a leaf above the deepest level stands for itself
    /// below it.
    ///
    /// - [`Budget::Unlimited`]: every pair down to its leaves.
    /// - [`Budget::Cost`]: the broad phase and every pair's root test are always done;
    ///   then pair levels are descended in the order (level, pair) while their cost (known
    ///   in advance) fits in what is left. The first that does not fit stops the
    ///   traversal, so a larger budget does the same work and more: **the answer improves
    ///   monotonically** (every pair at least as deep, its contacts a refinement of the
    ///   smaller budget's).
    /// - [`Budget::Time`]: the same order, stopped when the time is up (a pair's level in
    ///   progress is dropped).
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::Arc;
    /// use sphaera_mesh::geometry::Similarity;
    /// use sphaera_scene::{Budget, DVec3, ModelOptions, ObjectModel, Scene};
    /// use sphaera_spheretree::SphereTreeOptions;
    ///
    /// let tree = SphereTreeOptions::default().with_depth(2).with_branch(4).with_samples(600)
    ///     .with_initial_spheres(60).with_min_spheres_per_node(20);
    /// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 12)?;
    /// let model = Arc::new(ObjectModel::build("capsule", mesh, &ModelOptions::default().with_tree(tree))?);
    /// let mut scene = Scene::new();
    /// for x in [0.0, 0.9, 1.8, 10.0] {
    ///     scene.add(format!("c{x}"), Arc::clone(&model), Similarity::from_translation(DVec3::new(x, 0.0, 0.0))?);
    /// }
    /// let exact = scene.collide(&Budget::Unlimited)?;
    /// assert!(exact.completed);
    /// assert_eq!(exact.pairs.iter().map(|p| (p.a, p.b)).collect::<Vec<_>>(), [(0, 1), (1, 2)]);
    /// // A small budget stops at the roots, with looser contacts.
    /// let coarse = scene.collide(&Budget::cost(10.0))?;
    /// assert_eq!(coarse.level, 0);
    /// assert!(coarse.summary().max_error_bound >= exact.summary().max_error_bound);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SceneError::SphereTree`] for a [`Budget::Cost`] whose limit or costs are NaN or
    /// negative.
    ///
    /// # Performance
    ///
    /// The broad phase is a sort and a sweep, `O(n log n + close pairs)`. With the
    /// `parallel` feature, the pairs of a level are descended on every core (the answer is
    /// the same either way).
    pub fn collide(&self, budget: &Budget) -> Result<SceneCollision, SceneError> {
        budget.validate()?;
        let start = Instant::now();
        let instances = self.instances();
        // The trees descended, taken once: a tree built meanwhile changes nothing here.
        let trees: Vec<Arc<ModelTree>> =
            instances.iter().map(|i| i.model.collision_tree()).collect();
        let bounds: Vec<Sphere> = instances
            .iter()
            .zip(&trees)
            .map(|(i, t)| i.pose.sphere(&t.bound()))
            .collect();
        let close = sweep(&bounds);
        let mut traversals: Vec<(usize, usize, Traversal<'_>)> = close
            .iter()
            .filter_map(|&(a, b)| {
                let (ia, ib) = (instances.get(a)?, instances.get(b)?);
                let (ta, tb) = (trees.get(a)?, trees.get(b)?);
                let t = Traversal::new(ta.tree(), &ia.pose, tb.tree(), &ib.pose);
                Some((a, b, t))
            })
            .collect();
        let stats_of = |ts: &[(usize, usize, Traversal<'_>)]| {
            ts.iter()
                .fold(TraversalStats::default(), |mut s, (_, _, t)| {
                    let own = t.stats();
                    s.updates += own.updates;
                    s.tests += own.tests;
                    s
                })
        };
        let mut stopped = false;
        while !stopped {
            // Pairs still touching and not at their leaves are all at the same level.
            let due: Vec<usize> = (0..traversals.len())
                .filter(|&k| traversals[k].2.contact_count() > 0 && !traversals[k].2.is_complete())
                .collect();
            if due.is_empty() {
                break;
            }
            let chosen: Vec<usize> = match budget {
                Budget::Unlimited | Budget::Time(_) => due.clone(),
                Budget::Cost { limit, model } => {
                    let mut spent = stats_of(&traversals).cost(model);
                    let mut chosen = Vec::with_capacity(due.len());
                    for &k in &due {
                        let next = traversals[k].2.next_level_stats().unwrap_or_default();
                        spent += next.cost(model);
                        if spent > *limit {
                            break;
                        }
                        chosen.push(k);
                    }
                    chosen
                }
            };
            stopped = chosen.len() < due.len();
            match budget {
                Budget::Time(limit) => {
                    for &k in &chosen {
                        if start.elapsed() >= *limit
                            || !traversals[k].2.descend_until(Some((start, *limit)))
                        {
                            stopped = true;
                            break;
                        }
                    }
                }
                _ => descend_all(&mut traversals, &chosen),
            }
        }
        let stats = stats_of(&traversals);
        let pairs: Vec<PairContacts> = traversals
            .iter()
            .filter(|(_, _, t)| t.contact_count() > 0)
            .map(|(a, b, t)| PairContacts {
                a: *a,
                b: *b,
                level: t.level(),
                completed: t.is_complete(),
                contacts: t.contacts(),
            })
            .collect();
        Ok(SceneCollision {
            level: pairs.iter().map(|p| p.level).min().unwrap_or(0),
            completed: pairs.iter().all(|p| p.completed),
            broad_phase_pairs: close.len(),
            stats,
            pairs,
        })
    }
}

/// The pairs of `bounds` that overlap, sorted: a sweep along `x`.
fn sweep(bounds: &[Sphere]) -> Vec<(usize, usize)> {
    let mut order: Vec<usize> = (0..bounds.len()).collect();
    let low = |i: usize| bounds[i].center.x - bounds[i].radius;
    order.sort_by(|&i, &j| low(i).total_cmp(&low(j)).then(i.cmp(&j)));
    let mut pairs = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        let high = bounds[i].center.x + bounds[i].radius;
        for &j in order.get(k + 1..).unwrap_or(&[]) {
            if low(j) > high {
                break;
            }
            if bounds[i].intersects(&bounds[j]) {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

/// Descends the traversals at `chosen` (sorted indices) one level each.
fn descend_all(traversals: &mut [(usize, usize, Traversal<'_>)], chosen: &[usize]) {
    let mut picked: Vec<&mut Traversal<'_>> = Vec::with_capacity(chosen.len());
    let mut wanted = chosen.iter().peekable();
    for (k, (_, _, t)) in traversals.iter_mut().enumerate() {
        if wanted.peek() == Some(&&k) {
            wanted.next();
            picked.push(t);
        }
    }
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        picked.par_iter_mut().for_each(|t| {
            t.descend();
        });
    }
    #[cfg(not(feature = "parallel"))]
    for t in &mut picked {
        t.descend();
    }
}
