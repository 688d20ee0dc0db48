//! Sphere-tree against sphere-tree overlap under rigid motions: the paper's interruptible,
//! time-critical collision detection (sections 1 and 6.4–6.5).
//!
//! [`collide`] descends both trees **breadth-first, one level at a time and both trees
//! together**: level 0 tests the roots, level `k + 1` tests the children of every
//! overlapping pair of level `k` against each other. A node without children (a leaf above
//! the deepest level, or every node of a shallower tree) stands for itself in the levels
//! below it. Every completed level is an approximation of the contact: its overlapping
//! pairs cover every place where the objects can touch, and each pair carries an error
//! bound (the sum of the two spheres' errors, [`TreeNode::error`]): the objects'
//! surfaces are within that distance of the pair's spheres. Stopping after any level
//! therefore still gives the best approximation so far; a [`Budget`] decides when.
//!
//! [`overlaps`] answers "do they touch at the deepest level" with a depth-first search that
//! stops at the first overlapping pair of leaves.
//!
//! Both take a [`Similarity`] per tree: a rotation and translation, with an optional uniform
//! scale (a mirror is allowed; shear and non-uniform scale are refused, since they do not
//! map spheres to spheres).
//!
//! [`TreeNode::error`]: crate::TreeNode::error

mod budget;

use std::ops::Range;
use std::time::{Duration, Instant};

use sphaera_mesh::Sphere;

pub use budget::{Budget, CostModel};
/// Where a tree is in the scene (defined in `sphaera-mesh`).
pub use sphaera_mesh::geometry::Similarity;

use crate::SphereTree;
use crate::SphereTreeError;

/// Pair tests between two looks at the clock under a [`Budget::Time`].
const CLOCK_STRIDE: u64 = 64;

/// One overlapping pair of spheres: an approximate contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// The node of the first tree (an index into [`SphereTree::nodes`]).
    pub a: usize,
    /// The node of the second tree.
    pub b: usize,
    /// Node `a`'s sphere in the scene.
    pub sphere_a: Sphere,
    /// Node `b`'s sphere in the scene.
    pub sphere_b: Sphere,
    /// How far the spheres interpenetrate: the sum of their radii minus the distance of
    /// their centres (0 when they touch).
    pub depth: f64,
    /// The sum of the two nodes' errors ([`TreeNode::error`](crate::TreeNode::error)),
    /// scaled to the scene: each object's surface is within its sphere's error of the
    /// sphere, so the true separation of the objects here is at most this.
    pub error_bound: f64,
}

/// The work done by a traversal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct TraversalStats {
    /// `Nu`: spheres placed in the scene (each node at most once).
    pub updates: u64,
    /// `Nv`: sphere-pair overlap tests.
    pub tests: u64,
}

impl TraversalStats {
    /// The cost of this work under `model`.
    #[must_use]
    pub fn cost(&self, model: &CostModel) -> f64 {
        model.cost(self.updates, self.tests)
    }
}

/// The result of [`collide`].
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// The overlapping pairs of the deepest level completed, sorted by `(a, b)`.
    pub contacts: Vec<Contact>,
    /// Whether the traversal reached the end: no pair left, or only pairs of leaves. The
    /// contacts are then the exact answer of the two trees.
    pub completed: bool,
    /// The level the contacts are at (0: the roots). A pair holding a leaf of a shallower
    /// level is carried down unchanged.
    pub level: usize,
    /// The work done, including a level dropped by a [`Budget::Time`].
    pub stats: TraversalStats,
}

impl Collision {
    /// The largest [`Contact::error_bound`], `None` without contacts.
    #[must_use]
    pub fn max_error_bound(&self) -> Option<f64> {
        self.contacts
            .iter()
            .map(|c| c.error_bound)
            .max_by(f64::total_cmp)
    }
}

/// One tree in the scene: its placed spheres, filled level by level.
struct Side<'t> {
    tree: &'t SphereTree,
    world_from_tree: &'t Similarity,
    placed: Vec<Sphere>,
}

impl<'t> Side<'t> {
    fn new(tree: &'t SphereTree, world_from_tree: &'t Similarity) -> Self {
        Self {
            tree,
            world_from_tree,
            placed: vec![Sphere::default(); tree.nodes.len()],
        }
    }

    /// Places node `i` (an index below `tree.nodes.len()`).
    fn update(&mut self, i: usize) {
        if let (Some(slot), Some(node)) = (self.placed.get_mut(i), self.tree.nodes.get(i)) {
            *slot = self.world_from_tree.sphere(&node.sphere);
        }
    }

    fn sphere(&self, i: usize) -> Sphere {
        self.placed.get(i).copied().unwrap_or_default()
    }
}

/// The roots of `tree` (the nodes of level 0).
fn roots(tree: &SphereTree) -> Range<usize> {
    0..tree.level(0).len()
}

/// The children of node `i`, clamped to the stored nodes.
fn children(tree: &SphereTree, i: usize) -> Range<usize> {
    let len = tree.nodes.len();
    tree.nodes.get(i).map_or(0..0, |n| {
        let end = (n.children.end as usize).min(len);
        (n.children.start as usize).min(end)..end
    })
}

/// What stands for node `i` one level down: its children, or itself for a leaf.
fn expansion(tree: &SphereTree, i: usize) -> Range<usize> {
    let kids = children(tree, i);
    if kids.is_empty() { i..i + 1 } else { kids }
}

fn is_leaf(tree: &SphereTree, i: usize) -> bool {
    children(tree, i).is_empty()
}

/// Whether two placed spheres overlap (touching counts).
fn touch(a: &Sphere, b: &Sphere) -> bool {
    a.intersects(b)
}

/// Finds the overlapping sphere pairs of two placed sphere-trees, level by level, within
/// `budget` (see the [module documentation](self) and [`Budget`]).
///
/// With [`Budget::Unlimited`] the contacts are exactly the pairs of leaves `(x, y)` whose
/// spheres overlap and whose ancestors at every level overlap too (a leaf standing for
/// itself below its level). The result is deterministic: contacts sorted by `(a, b)`.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::collide::{Budget, Similarity, collide};
/// use sphaera_spheretree::{DVec3, SphereTreeOptions, build, Surface};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let options = SphereTreeOptions::default()
///     .with_depth(1)
///     .with_branch(4)
///     .with_samples(400)
///     .with_initial_spheres(60)
///     .with_min_spheres_per_node(20);
/// let tree = build(&Surface::new(&mesh)?, &options)?;
/// let here = Similarity::IDENTITY;
/// let near = Similarity::from_translation(DVec3::new(0.9, 0.0, 0.0))?;
///
/// let exact = collide(&tree, &here, &tree, &near, &Budget::Unlimited)?;
/// assert!(exact.completed && exact.level == 1 && !exact.contacts.is_empty());
///
/// // A budget too small for level 1 stops at the roots: one coarse contact.
/// let coarse = collide(&tree, &here, &tree, &near, &Budget::cost(5.0))?;
/// assert!(!coarse.completed);
/// assert_eq!((coarse.level, coarse.contacts.len()), (0, 1));
/// assert!(coarse.contacts[0].error_bound >= exact.max_error_bound().unwrap());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`SphereTreeError::InvalidParameter`] for a [`Budget::Cost`] whose limit or costs are
/// NaN or negative.
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Allocates one placed sphere per node of each tree; each node is placed at most once.
/// Each level costs one test per child pair of the previous level's overlapping pairs.
/// Two depth-3, branch-8 trees of the low-res bunny in light and in deep contact are
/// timed on one thread by the `collide_probe` example (not kept in `docs/benchmarks.md`;
/// a whole scene's traversal is in its section *Scenes: detail and collision
/// (`sphaera-scene`, issue 21)*).
pub fn collide(
    a: &SphereTree,
    world_from_a: &Similarity,
    b: &SphereTree,
    world_from_b: &Similarity,
    budget: &Budget,
) -> Result<Collision, SphereTreeError> {
    budget.validate()?;
    let start = Instant::now();
    let mut traversal = Traversal::new(a, world_from_a, b, world_from_b);
    let deadline = match budget {
        Budget::Time(limit) => Some((start, *limit)),
        _ => None,
    };
    let completed = loop {
        let Some(next) = traversal.next_level_stats() else {
            break true;
        };
        match budget {
            Budget::Unlimited => {}
            Budget::Cost { limit, model } => {
                if traversal.stats().cost(model) + next.cost(model) > *limit {
                    break false;
                }
            }
            Budget::Time(limit) => {
                if start.elapsed() >= *limit {
                    break false;
                }
            }
        }
        if !traversal.descend_until(deadline) {
            break false;
        }
    };
    Ok(Collision {
        contacts: traversal.contacts(),
        completed,
        level: traversal.level(),
        stats: traversal.stats(),
    })
}

/// A [`collide`] traversal driven one level at a time by its caller: for a scene of many
/// pairs sharing one budget (`sphaera-scene` descends every pair's level `k` before any
/// pair's level `k + 1`).
///
/// [`Traversal::new`] places the roots and tests the root pairs (level 0);
/// [`Traversal::next_level_stats`] tells the work of the next level before it is done,
/// and [`Traversal::descend`] does it. After any number of levels,
/// [`Traversal::contacts`] is what [`collide`] would return had its budget stopped there.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::collide::{Budget, Similarity, Traversal, collide};
/// use sphaera_spheretree::{DVec3, SphereTreeOptions, build, Surface};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let options = SphereTreeOptions::default()
///     .with_depth(1)
///     .with_branch(4)
///     .with_samples(400)
///     .with_initial_spheres(60)
///     .with_min_spheres_per_node(20);
/// let tree = build(&Surface::new(&mesh)?, &options)?;
/// let here = Similarity::IDENTITY;
/// let near = Similarity::from_translation(DVec3::new(0.9, 0.0, 0.0))?;
///
/// let mut traversal = Traversal::new(&tree, &here, &tree, &near);
/// assert_eq!(traversal.level(), 0);
/// let roots = traversal.stats();
/// let work = traversal.next_level_stats().expect("level 1 is left");
/// assert!(traversal.descend());
/// assert_eq!(traversal.stats().tests, roots.tests + work.tests);
/// assert!(traversal.next_level_stats().is_none() && !traversal.descend());
/// let exact = collide(&tree, &here, &tree, &near, &Budget::Unlimited)?;
/// assert_eq!(traversal.contacts(), exact.contacts);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Traversal<'t> {
    sa: Side<'t>,
    sb: Side<'t>,
    /// The overlapping pairs of the current level, sorted.
    frontier: Vec<(usize, usize)>,
    /// The work of the next level.
    plan: Plan,
    level: usize,
    stats: TraversalStats,
}

impl<'t> Traversal<'t> {
    /// Places the roots of both trees and tests every root pair: level 0.
    #[must_use]
    pub fn new(
        a: &'t SphereTree,
        world_from_a: &'t Similarity,
        b: &'t SphereTree,
        world_from_b: &'t Similarity,
    ) -> Self {
        let mut sa = Side::new(a, world_from_a);
        let mut sb = Side::new(b, world_from_b);
        let mut stats = TraversalStats::default();
        for i in roots(a) {
            sa.update(i);
            stats.updates += 1;
        }
        for j in roots(b) {
            sb.update(j);
            stats.updates += 1;
        }
        let mut frontier = Vec::new();
        for i in roots(a) {
            for j in roots(b) {
                stats.tests += 1;
                if touch(&sa.sphere(i), &sb.sphere(j)) {
                    frontier.push((i, j));
                }
            }
        }
        let plan = Plan::new(a, b, &frontier);
        Self {
            sa,
            sb,
            frontier,
            plan,
            level: 0,
            stats,
        }
    }

    /// The level the current pairs are at (0: the roots).
    #[must_use]
    pub fn level(&self) -> usize {
        self.level
    }

    /// The work done so far.
    #[must_use]
    pub fn stats(&self) -> TraversalStats {
        self.stats
    }

    /// Whether the traversal is over: no pair left, or only pairs of leaves.
    #[must_use]
    pub fn is_complete(&self) -> bool {
        self.plan.is_final
    }

    /// The work the next level takes (spheres to place, pairs to test), `None` when the
    /// traversal is complete.
    #[must_use]
    pub fn next_level_stats(&self) -> Option<TraversalStats> {
        (!self.plan.is_final).then_some(TraversalStats {
            updates: self.plan.updates,
            tests: self.plan.tests,
        })
    }

    /// Descends one level; `false` (and nothing done) when the traversal is complete.
    pub fn descend(&mut self) -> bool {
        self.descend_until(None)
    }

    /// Descends one level unless the time limit `(start, limit)` passes first (looked at
    /// every 64 pair tests): the level's partial work is then dropped, its cost kept in
    /// the stats. `false` when nothing was descended.
    pub fn descend_until(&mut self, deadline: Option<(Instant, Duration)>) -> bool {
        if self.plan.is_final {
            return false;
        }
        match descend(
            &mut self.sa,
            &mut self.sb,
            &self.frontier,
            &self.plan,
            deadline,
            &mut self.stats,
        ) {
            Some(next) => {
                self.frontier = next;
                self.level += 1;
                self.plan = Plan::new(self.sa.tree, self.sb.tree, &self.frontier);
                true
            }
            None => false,
        }
    }

    /// The overlapping pairs of the current level, sorted by `(a, b)` (as
    /// [`Collision::contacts`]).
    #[must_use]
    pub fn contacts(&self) -> Vec<Contact> {
        self.frontier
            .iter()
            .map(|&(i, j)| contact(&self.sa, &self.sb, i, j))
            .collect()
    }

    /// The number of overlapping pairs at the current level.
    #[must_use]
    pub fn contact_count(&self) -> usize {
        self.frontier.len()
    }
}

/// The work of the next level, known before it is started.
struct Plan {
    /// Nodes of the first tree whose children are placed.
    parents_a: Vec<usize>,
    /// Nodes of the second tree whose children are placed.
    parents_b: Vec<usize>,
    updates: u64,
    tests: u64,
    /// No pair has a node with children: the traversal is over.
    is_final: bool,
}

impl Plan {
    /// `frontier` is sorted by `(a, b)`.
    fn new(a: &SphereTree, b: &SphereTree, frontier: &[(usize, usize)]) -> Self {
        let mut parents_a: Vec<usize> = frontier
            .iter()
            .map(|p| p.0)
            .filter(|&i| !is_leaf(a, i))
            .collect();
        parents_a.dedup();
        let mut parents_b: Vec<usize> = frontier
            .iter()
            .map(|p| p.1)
            .filter(|&j| !is_leaf(b, j))
            .collect();
        parents_b.sort_unstable();
        parents_b.dedup();
        let updates = parents_a
            .iter()
            .map(|&i| children(a, i).len() as u64)
            .chain(parents_b.iter().map(|&j| children(b, j).len() as u64))
            .sum();
        let tests = frontier
            .iter()
            .filter(|&&(i, j)| !(is_leaf(a, i) && is_leaf(b, j)))
            .map(|&(i, j)| expansion(a, i).len() as u64 * expansion(b, j).len() as u64)
            .sum();
        let is_final = parents_a.is_empty() && parents_b.is_empty();
        Self {
            parents_a,
            parents_b,
            updates,
            tests,
            is_final,
        }
    }
}

/// The overlapping pairs one level below `frontier`, sorted; `None` when the deadline
/// passes first.
fn descend(
    sa: &mut Side<'_>,
    sb: &mut Side<'_>,
    frontier: &[(usize, usize)],
    plan: &Plan,
    deadline: Option<(Instant, Duration)>,
    stats: &mut TraversalStats,
) -> Option<Vec<(usize, usize)>> {
    for &i in &plan.parents_a {
        for c in children(sa.tree, i) {
            sa.update(c);
            stats.updates += 1;
        }
    }
    for &j in &plan.parents_b {
        for c in children(sb.tree, j) {
            sb.update(c);
            stats.updates += 1;
        }
    }
    let mut next = Vec::with_capacity(frontier.len());
    for &(i, j) in frontier {
        if is_leaf(sa.tree, i) && is_leaf(sb.tree, j) {
            next.push((i, j));
            continue;
        }
        let kids_b = expansion(sb.tree, j);
        for ci in expansion(sa.tree, i) {
            let sphere_i = sa.sphere(ci);
            for cj in kids_b.clone() {
                stats.tests += 1;
                if touch(&sphere_i, &sb.sphere(cj)) {
                    next.push((ci, cj));
                }
                if let Some((start, limit)) = deadline
                    && stats.tests.is_multiple_of(CLOCK_STRIDE)
                    && start.elapsed() >= limit
                {
                    return None;
                }
            }
        }
    }
    next.sort_unstable();
    Some(next)
}

fn contact(sa: &Side<'_>, sb: &Side<'_>, i: usize, j: usize) -> Contact {
    let sphere_a = sa.sphere(i);
    let sphere_b = sb.sphere(j);
    let error = |side: &Side<'_>, k: usize| {
        side.tree.nodes.get(k).map_or(0.0, |n| n.error) * side.world_from_tree.scale()
    };
    Contact {
        a: i,
        b: j,
        sphere_a,
        sphere_b,
        depth: sphere_a.radius + sphere_b.radius - sphere_a.center.distance(sphere_b.center),
        error_bound: error(sa, i) + error(sb, j),
    }
}

/// Whether two placed sphere-trees overlap at their deepest level: some pair of leaves
/// overlaps whose ancestors all overlap (the same pairs as an unlimited [`collide`]),
/// found depth-first with an early exit.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::collide::{Similarity, overlaps};
/// use sphaera_spheretree::{DVec3, SphereTreeOptions, build, Surface};
///
/// let mesh = sphaera_mesh::shapes::capsule(0.5, 2.0, 8)?;
/// let options = SphereTreeOptions::default()
///     .with_depth(1)
///     .with_branch(4)
///     .with_samples(400)
///     .with_initial_spheres(60)
///     .with_min_spheres_per_node(20);
/// let tree = build(&Surface::new(&mesh)?, &options)?;
/// let here = Similarity::IDENTITY;
/// assert!(overlaps(&tree, &here, &tree, &Similarity::from_translation(DVec3::X)?));
/// assert!(!overlaps(&tree, &here, &tree, &Similarity::from_translation(DVec3::X * 5.0)?));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Places spheres on demand (a node may be placed more than once); stops at the first
/// overlapping pair of leaves, so touching objects usually answer after a few descents.
#[must_use]
pub fn overlaps(
    a: &SphereTree,
    world_from_a: &Similarity,
    b: &SphereTree,
    world_from_b: &Similarity,
) -> bool {
    let place = |tree: &SphereTree, world_from_tree: &Similarity, i: usize| {
        tree.nodes
            .get(i)
            .map_or_else(Sphere::default, |n| world_from_tree.sphere(&n.sphere))
    };
    let mut stack: Vec<(usize, usize)> = Vec::new();
    for i in roots(a).rev() {
        for j in roots(b).rev() {
            stack.push((i, j));
        }
    }
    while let Some((i, j)) = stack.pop() {
        if !touch(&place(a, world_from_a, i), &place(b, world_from_b, j)) {
            continue;
        }
        if is_leaf(a, i) && is_leaf(b, j) {
            return true;
        }
        let kids_b = expansion(b, j);
        for ci in expansion(a, i).rev() {
            for cj in kids_b.clone().rev() {
                stack.push((ci, cj));
            }
        }
    }
    false
}
