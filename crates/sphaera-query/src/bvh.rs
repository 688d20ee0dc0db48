//! The one bounding-volume hierarchy of the workspace: a binary tree of axis-aligned boxes
//! over items (triangles, spheres, …), built by binned surface-area splits.
//!
//! Every tree that Sphaera searches is this tree with different leaves: the exact
//! closest-point [`TriangleTree`](crate::closest::TriangleTree), the far-field expansions
//! of the generalized [winding number](crate::winding), and the union of spheres that
//! `sphaera-spheretree` measures coverage against. The build is the same everywhere so
//! that the trees are the same for the same items, on every run and with or without the
//! `parallel` feature.
//!
//! # Layout
//!
//! Nodes are stored depth first: an inner node's left child is the next node and its
//! right child is at [`BoxNode::right`]. The items are permuted into
//! [`BoxTree::order`] so that every node's items are one contiguous range of it
//! ([`BoxNode::items`]), the inner nodes' ranges included.
//!
//! # Examples
//!
//! ```
//! use sphaera_mesh::{Aabb, DVec3};
//! use sphaera_query::bvh::BoxTree;
//!
//! // Ten points on a line, as degenerate boxes, two per leaf.
//! let items: Vec<(Aabb, DVec3)> = (0..10)
//!     .map(|i| DVec3::new(f64::from(i), 0.0, 0.0))
//!     .map(|p| (Aabb::new(p, p), p))
//!     .collect();
//! let tree = BoxTree::build(&items, 2)?;
//! let root = tree.nodes()[0];
//! assert_eq!(root.items(), 0..10);
//! assert_eq!(root.bounds, Aabb::new(DVec3::ZERO, DVec3::new(9.0, 0.0, 0.0)));
//! // Every leaf holds at most two items, and the leaves partition the items.
//! let leaves: usize = tree.nodes().iter().filter(|n| n.is_leaf()).map(|n| n.items().len()).sum();
//! assert_eq!(leaves, 10);
//! # let _ = tree.order();
//! # Ok::<(), sphaera_query::QueryError>(())
//! ```

use std::ops::{ControlFlow, Range};

use glam::DVec3;

use smallvec::SmallVec;

use crate::QueryError;
use sphaera_mesh::Aabb;

/// One node of a [`BoxTree`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxNode {
    /// The box of the node's items.
    pub bounds: Aabb,
    /// First position of the node's items in [`BoxTree::order`].
    start: u32,
    /// One past the last position.
    end: u32,
    /// The right child's index for an inner node (the left child is the next node);
    /// 0 for a leaf (the root is never a right child).
    right: u32,
}

impl BoxNode {
    /// The positions of the node's items in [`BoxTree::order`] (also the positions in any
    /// per-item array the caller laid out in that order).
    #[must_use]
    pub fn items(&self) -> Range<usize> {
        self.start as usize..self.end as usize
    }

    /// Whether the node is a leaf.
    #[must_use]
    pub fn is_leaf(&self) -> bool {
        self.right == 0
    }

    /// The right child's index for an inner node (its left child is the node right after
    /// it); `None` for a leaf.
    #[must_use]
    pub fn right(&self) -> Option<usize> {
        (!self.is_leaf()).then_some(self.right as usize)
    }
}

/// A binary tree of axis-aligned boxes over items (see the [module docs](self)).
#[derive(Clone, Debug, Default)]
pub struct BoxTree {
    nodes: Vec<BoxNode>,
    order: Vec<u32>,
}

/// What a nearest-first search ([`BoxTree::search_nearest_first`]) asks of its caller.
pub trait NearestFirst {
    /// Whether a node whose box is at squared distance `distance_squared` from the query
    /// may hold an item better than the best so far (`false` prunes it).
    fn may_improve(&self, distance_squared: f64) -> bool;

    /// Visits the leaf items at `positions` of [`BoxTree::order`]; `Break` ends the search.
    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()>;

    /// Called for each node skipped because [`NearestFirst::may_improve`] said no, with its
    /// box's squared distance: a lower bound on every item under it (a search that wants
    /// the nearest item it did not take, for a safe radius, keeps the smallest). Does
    /// nothing by default.
    fn pruned(&mut self, _distance_squared: f64) {}
}

impl BoxTree {
    /// Builds the tree over `items` (each item's box and split point), at most
    /// `leaf_size` items per leaf (0 is taken as 1).
    ///
    /// A node of more than `leaf_size` items is split along the longest axis of its
    /// items' centroids, at the boundary between 16 equal slabs that minimizes the
    /// surface-area cost (each half's box area times its item count; at the median when
    /// the centroids do not spread), so the same items always give the same tree.
    ///
    /// # Errors
    ///
    /// [`QueryError::TooManyItems`] for more items than 32-bit indices address.
    ///
    /// # Performance
    ///
    /// `O(n log n)` for `n` items; 64 bytes per node (about `2n / leaf_size` nodes) and
    /// 4 bytes per item.
    pub fn build(items: &[(Aabb, DVec3)], leaf_size: usize) -> Result<Self, QueryError> {
        let Ok(count) = u32::try_from(items.len()) else {
            return Err(QueryError::TooManyItems {
                operation: "box tree",
                count: items.len(),
            });
        };
        let leaf_size = leaf_size.max(1);
        let mut order: Vec<u32> = (0..count).collect();
        let nodes = if order.is_empty() {
            Vec::new()
        } else {
            Builder { items, leaf_size }.node(&mut order, 0, 0)
        };
        Ok(Self { nodes, order })
    }

    /// The tree [`BoxTree::build`] gives for `items` and `leaf_size`, from this tree built
    /// from the same items with a larger leaf size: the build decides each split from the
    /// node's items and depth alone, so the finer tree is this one with every leaf of more
    /// than `leaf_size` items built further, from the items as they stand in it. Costs the
    /// small leaves' builds and a pass over the nodes, not a build.
    pub(crate) fn refined(&self, items: &[(Aabb, DVec3)], leaf_size: usize) -> Self {
        let builder = Builder {
            items,
            leaf_size: leaf_size.max(1),
        };
        let mut fine = Self {
            nodes: Vec::with_capacity(2 * self.nodes.len()),
            order: self.order.clone(),
        };
        if !self.nodes.is_empty() {
            self.refine_subtree(0, 0, builder, &mut fine);
        }
        fine
    }

    /// [`BoxTree::refined`] from node `n` at depth `depth`, appending to `fine`.
    fn refine_subtree(&self, n: usize, depth: usize, builder: Builder<'_>, fine: &mut Self) {
        let node = self.nodes[n];
        let at = fine.nodes.len();
        match node.right() {
            Some(right) => {
                fine.nodes.push(node);
                self.refine_subtree(n + 1, depth + 1, builder, fine);
                // Lossless: the finer tree has fewer than 2³² nodes, as its build would.
                fine.nodes[at].right = fine.nodes.len() as u32;
                self.refine_subtree(right, depth + 1, builder, fine);
            }
            None if node.items().len() <= builder.leaf_size => fine.nodes.push(node),
            None => {
                let range = node.items();
                let start = range.start;
                let below = builder.node(&mut fine.order[range], start, depth);
                // Its right children are numbered from its root.
                fine.nodes.extend(below.into_iter().map(|mut b| {
                    if b.right != 0 {
                        b.right += at as u32;
                    }
                    b
                }));
            }
        }
    }

    /// The nodes, depth first (the root first; empty for no items).
    #[must_use]
    pub fn nodes(&self) -> &[BoxNode] {
        &self.nodes
    }

    /// Recomputes every node's box from its items' boxes (`bounds(position)` for the item
    /// at each position of [`BoxTree::order`]), keeping the tree's shape: for items that
    /// moved (a deforming mesh), in one pass from the leaves up. The boxes are exact; the
    /// splits may fit the new positions worse than a new build would.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{Aabb, DVec3};
    /// use sphaera_query::bvh::BoxTree;
    ///
    /// let points: Vec<DVec3> = (0..10).map(|i| DVec3::new(f64::from(i), 0.0, 0.0)).collect();
    /// let items: Vec<(Aabb, DVec3)> = points.iter().map(|&p| (Aabb::new(p, p), p)).collect();
    /// let mut tree = BoxTree::build(&items, 2)?;
    /// // Every point moves up by 1.
    /// let order = tree.order().to_vec();
    /// tree.refit(|i| {
    ///     let p = points[order[i] as usize] + DVec3::Y;
    ///     Aabb::new(p, p)
    /// });
    /// assert_eq!(tree.nodes()[0].bounds, Aabb::new(DVec3::Y, DVec3::new(9.0, 1.0, 0.0)));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    pub fn refit(&mut self, bounds: impl Fn(usize) -> Aabb + Sync) {
        refit_subtree(&mut self.nodes, 0, &bounds);
    }

    /// The item indices in tree order: every node's items are a contiguous range of it.
    #[must_use]
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// Visits the leaves nearest first from `p`: the nearer child of each node is
    /// searched first, and a node is skipped when `search.may_improve` says its box is too
    /// far (asked when the node is reached, so a bound that tightened meanwhile prunes it).
    ///
    /// # Examples
    ///
    /// The nearest of a thousand points, visiting a few leaves:
    ///
    /// ```
    /// use std::ops::{ControlFlow, Range};
    /// use sphaera_mesh::{Aabb, DVec3};
    /// use sphaera_query::bvh::{BoxTree, NearestFirst};
    ///
    /// let points: Vec<DVec3> = (0..1000)
    ///     .map(|i| f64::from(i))
    ///     .map(|t| DVec3::new(t.sin(), (0.7 * t).cos(), (0.3 * t).sin()))
    ///     .collect();
    /// let items: Vec<(Aabb, DVec3)> = points.iter().map(|&p| (Aabb::new(p, p), p)).collect();
    /// let tree = BoxTree::build(&items, 4)?;
    ///
    /// struct Nearest<'a> { p: DVec3, points: &'a [DVec3], order: &'a [u32], best: f64, leaves: usize }
    /// impl NearestFirst for Nearest<'_> {
    ///     fn may_improve(&self, distance_squared: f64) -> bool { distance_squared < self.best }
    ///     fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
    ///         self.leaves += 1;
    ///         for &i in &self.order[positions] {
    ///             self.best = self.best.min(self.p.distance_squared(self.points[i as usize]));
    ///         }
    ///         ControlFlow::Continue(())
    ///     }
    /// }
    /// let p = DVec3::new(0.2, 0.1, -0.3);
    /// let mut search = Nearest { p, points: &points, order: tree.order(), best: f64::INFINITY, leaves: 0 };
    /// tree.search_nearest_first(p, &mut search);
    /// let brute = points.iter().map(|&q| p.distance_squared(q)).fold(f64::INFINITY, f64::min);
    /// assert_eq!(search.best, brute);
    /// assert!(search.leaves < 250 / 4);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    pub fn search_nearest_first(&self, p: DVec3, search: &mut impl NearestFirst) {
        self.search_nearest_first_by(|bounds| bounds.distance_squared_to_point(p), search);
    }

    /// [`search_nearest_first`](Self::search_nearest_first) with another measure of how
    /// near a node is: `key(bounds)` of a node's box is what `search.may_improve` is asked
    /// about, and the child with the smaller key is searched first. Any key works for the
    /// order; for pruning to be sound it must be a lower bound of what the search looks
    /// for under that box (for a point, the squared distance to the box).
    ///
    /// # Examples
    ///
    /// The point nearest to *both* of two points in the sense of the larger distance
    /// (the key is the larger squared distance from either to the box):
    ///
    /// ```
    /// use std::ops::{ControlFlow, Range};
    /// use sphaera_mesh::{Aabb, DVec3};
    /// use sphaera_query::bvh::{BoxTree, NearestFirst};
    ///
    /// let points: Vec<DVec3> = (0..500).map(|i| DVec3::new(f64::from(i), 0.0, 0.0)).collect();
    /// let items: Vec<(Aabb, DVec3)> = points.iter().map(|&p| (Aabb::new(p, p), p)).collect();
    /// let tree = BoxTree::build(&items, 4)?;
    /// let (a, b) = (DVec3::new(100.0, 1.0, 0.0), DVec3::new(110.0, -1.0, 0.0));
    ///
    /// struct Both<'a> { a: DVec3, b: DVec3, points: &'a [DVec3], order: &'a [u32], best: f64 }
    /// impl NearestFirst for Both<'_> {
    ///     fn may_improve(&self, key: f64) -> bool { key < self.best }
    ///     fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
    ///         for &i in &self.order[positions] {
    ///             let q = self.points[i as usize];
    ///             self.best = self.best.min(self.a.distance_squared(q).max(self.b.distance_squared(q)));
    ///         }
    ///         ControlFlow::Continue(())
    ///     }
    /// }
    /// let mut search = Both { a, b, points: &points, order: tree.order(), best: f64::INFINITY };
    /// let key = |bounds: &Aabb| bounds.distance_squared_to_point(a).max(bounds.distance_squared_to_point(b));
    /// tree.search_nearest_first_by(key, &mut search);
    /// assert_eq!(search.best, 26.0); // the point at x = 105
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    pub fn search_nearest_first_by(
        &self,
        key: impl Fn(&Aabb) -> f64,
        search: &mut impl NearestFirst,
    ) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        // Each entry keeps its box's key, computed once when its parent was opened. A
        // balanced tree over 32-bit item counts is at most 33 levels deep and the stack
        // holds at most one entry per level plus one, so it stays inline.
        let mut stack: SmallVec<[(u32, f64); 64]> = SmallVec::new();
        stack.push((0, key(&root.bounds)));
        while let Some((n, to_node)) = stack.pop() {
            if !search.may_improve(to_node) {
                search.pruned(to_node);
                continue;
            }
            let node = self.nodes[n as usize];
            match node.right() {
                None => {
                    if search.visit_leaf(node.items()).is_break() {
                        return;
                    }
                }
                Some(right) => {
                    let left = n + 1;
                    let to_left = key(&self.nodes[left as usize].bounds);
                    let to_right = key(&self.nodes[right].bounds);
                    // The nearer child on top of the stack.
                    let (near, far) = if to_left <= to_right {
                        ((left, to_left), (right as u32, to_right))
                    } else {
                        ((right as u32, to_right), (left, to_left))
                    };
                    stack.push(far);
                    stack.push(near);
                }
            }
        }
    }
}

/// Refits the subtree whose nodes are `nodes` (depth first, so a subtree is a contiguous
/// run: its root, its left subtree, its right subtree), the root being node `offset` of
/// the tree; large subtrees refit their halves side by side with `parallel`.
fn refit_subtree(nodes: &mut [BoxNode], offset: usize, bounds: &(impl Fn(usize) -> Aabb + Sync)) {
    let Some((root, below)) = nodes.split_first_mut() else {
        return;
    };
    let Some(right) = root.right() else {
        root.bounds = root.items().fold(Aabb::EMPTY, |b, i| b.union(bounds(i)));
        return;
    };
    // The right child's index within `below`.
    let split = right - offset - 1;
    let (left, right_nodes) = below.split_at_mut(split);
    #[cfg(feature = "parallel")]
    {
        if below_len(left, right_nodes) >= PARALLEL_REFIT_NODES {
            rayon::join(
                || refit_subtree(left, offset + 1, bounds),
                || refit_subtree(right_nodes, right, bounds),
            );
        } else {
            refit_subtree(left, offset + 1, bounds);
            refit_subtree(right_nodes, right, bounds);
        }
    }
    #[cfg(not(feature = "parallel"))]
    {
        refit_subtree(left, offset + 1, bounds);
        refit_subtree(right_nodes, right, bounds);
    }
    if let (Some(l), Some(r)) = (left.first(), right_nodes.first()) {
        root.bounds = l.bounds.union(r.bounds);
    }
}

/// The nodes of both halves.
#[cfg(feature = "parallel")]
fn below_len(left: &[BoxNode], right: &[BoxNode]) -> usize {
    left.len() + right.len()
}

/// Subtrees of at least this many nodes refit their halves side by side with `parallel`.
#[cfg(feature = "parallel")]
const PARALLEL_REFIT_NODES: usize = 2048;

/// Subtrees over at least this many items build their two halves side by side with
/// `parallel`; smaller ones are not worth a task.
#[cfg(feature = "parallel")]
const PARALLEL_ITEMS: usize = 4096;

/// Bins of the surface-area split.
const BINS: usize = 16;

/// Below this depth every split is a median split: a surface-area split may cut off a
/// few items at a time (items spread exponentially), and the median bounds the depth at
/// this plus `log2(n / leaf_size)`.
const MAX_AREA_SPLIT_DEPTH: usize = 48;

/// What every node of a build reads.
#[derive(Clone, Copy)]
struct Builder<'a> {
    items: &'a [(Aabb, DVec3)],
    leaf_size: usize,
}

impl Builder<'_> {
    /// The subtree over `order` (whose first item sits at `offset` of the final order),
    /// its nodes depth first with child indices relative to its root. The two halves touch
    /// disjoint items, so they can be built in any order, or at once, with the same
    /// result.
    fn node(self, order: &mut [u32], offset: usize, depth: usize) -> Vec<BoxNode> {
        let items = self.items;
        let bounds = order
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(items[i as usize].0));
        // Lossless: the build checked that the item count fits a u32.
        let start = offset as u32;
        let node = BoxNode {
            bounds,
            start,
            end: start + order.len() as u32,
            right: 0,
        };
        if order.len() <= self.leaf_size {
            return vec![node];
        }
        let count = order.len();
        let middle = self.split(order, depth < MAX_AREA_SPLIT_DEPTH);
        let (left, right) = order.split_at_mut(middle);
        let mut build_left = move || self.node(left, offset, depth + 1);
        let mut build_right = move || self.node(right, offset + middle, depth + 1);
        #[cfg(feature = "parallel")]
        let (left, right) = if count >= PARALLEL_ITEMS {
            rayon::join(build_left, build_right)
        } else {
            (build_left(), build_right())
        };
        #[cfg(not(feature = "parallel"))]
        let (left, right) = {
            let _ = count;
            (build_left(), build_right())
        };
        let mut nodes = Vec::with_capacity(1 + left.len() + right.len());
        // Lossless: a tree over at most u32::MAX items has fewer than 2³² nodes.
        let right_at = 1 + left.len() as u32;
        nodes.push(BoxNode {
            right: right_at,
            ..node
        });
        for (shift, half) in [(1, left), (right_at, right)] {
            nodes.extend(half.into_iter().map(|mut n| {
                if n.right != 0 {
                    n.right += shift;
                }
                n
            }));
        }
        nodes
    }

    /// Splits `order` (more than one item) in two non-empty halves and returns the size
    /// of the first: along the longest axis of the centroids, at the boundary between
    /// [`BINS`] equal slabs that minimizes the surface-area cost (each half's box area
    /// times its item count), the first such boundary on ties; at the median of the
    /// centroids (ties by item index) when the centroids coincide or every item falls in
    /// one slab, or when `by_area` is false. Items keep their relative order within each
    /// half, so the same items always give the same tree.
    fn split(self, order: &mut [u32], by_area: bool) -> usize {
        let items = self.items;
        let centroids = Aabb::from_points(order.iter().map(|&i| items[i as usize].1));
        let axis = centroids.longest_axis();
        let (low, extent) = (centroids.min[axis], centroids.extent()[axis]);
        let middle = order.len() / 2;
        let median = |order: &mut [u32]| {
            order.select_nth_unstable_by(middle, |&a, &b| {
                items[a as usize].1[axis]
                    .total_cmp(&items[b as usize].1[axis])
                    .then(a.cmp(&b))
            });
            middle
        };
        if !(by_area && extent > 0.0 && extent.is_finite()) {
            return median(order);
        }
        let scale = BINS as f64 / extent;
        let bin = |i: u32| (((items[i as usize].1[axis] - low) * scale) as usize).min(BINS - 1);
        let mut boxes = [Aabb::EMPTY; BINS];
        let mut counts = [0_usize; BINS];
        for &i in order.iter() {
            let b = bin(i);
            boxes[b] = boxes[b].union(items[i as usize].0);
            counts[b] += 1;
        }
        // Costs of the boundaries after bin k (k = 0 .. BINS − 2), from both sides.
        let mut below = [(Aabb::EMPTY, 0_usize); BINS];
        let mut running = (Aabb::EMPTY, 0);
        for k in 0..BINS {
            running = (running.0.union(boxes[k]), running.1 + counts[k]);
            below[k] = running;
        }
        let mut best: Option<(f64, usize)> = None;
        let mut above = (Aabb::EMPTY, 0);
        for k in (0..BINS - 1).rev() {
            above = (above.0.union(boxes[k + 1]), above.1 + counts[k + 1]);
            let (left, right) = (below[k], above);
            if left.1 == 0 || right.1 == 0 {
                continue;
            }
            let cost = half_area(left.0) * left.1 as f64 + half_area(right.0) * right.1 as f64;
            // `<=` while walking down: the first boundary wins ties.
            if best.is_none_or(|(c, _)| cost <= c) {
                best = Some((cost, k));
            }
        }
        let Some((_, k)) = best else {
            return median(order);
        };
        let (first, second): (Vec<u32>, Vec<u32>) = order.iter().partition(|&&i| bin(i) <= k);
        let size = first.len();
        for (slot, i) in order.iter_mut().zip(first.into_iter().chain(second)) {
            *slot = i;
        }
        size
    }
}

/// Half the surface area of a box (the split cost's measure; 0 for an empty box).
fn half_area(b: Aabb) -> f64 {
    let e = b.extent().max(DVec3::ZERO);
    e.x * e.y + e.y * e.z + e.z * e.x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(n: u32) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let t = f64::from(i);
                DVec3::new((t * 0.37).sin(), (t * 0.71).cos(), (t * 0.13).sin()) * 3.0
            })
            .collect()
    }

    #[test]
    fn a_refined_tree_is_the_finer_build() {
        for n in [1, 7, 17, 333, 5000] {
            let centroids = points(n);
            let items: Vec<(Aabb, DVec3)> = centroids
                .iter()
                .enumerate()
                .map(|(i, &c)| (Aabb::new(c - 0.01 * (i % 7) as f64, c + 0.1), c))
                .collect();
            for (coarse, fine) in [(16, 8), (16, 16), (9, 1), (64, 4)] {
                let refined = BoxTree::build(&items, coarse)
                    .unwrap()
                    .refined(&items, fine);
                let built = BoxTree::build(&items, fine).unwrap();
                assert_eq!(refined.nodes, built.nodes, "{n} {coarse} {fine}");
                assert_eq!(refined.order, built.order, "{n} {coarse} {fine}");
            }
        }
    }

    #[test]
    fn nodes_partition_their_items_and_boxes_contain_them() {
        let centroids = points(333);
        let items: Vec<(Aabb, DVec3)> = centroids
            .iter()
            .map(|&c| (Aabb::new(c - 0.1, c + 0.2), c))
            .collect();
        let boxes: Vec<Aabb> = items.iter().map(|i| i.0).collect();
        let tree = BoxTree::build(&items, 4).unwrap();
        let mut sorted = tree.order().to_vec();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..333).collect::<Vec<_>>());
        for (index, node) in tree.nodes().iter().enumerate() {
            for &item in &tree.order()[node.items()] {
                let b = boxes[item as usize];
                assert_eq!(node.bounds.union(b), node.bounds);
            }
            match node.right() {
                None => assert!(node.items().len() <= 4 && !node.items().is_empty()),
                Some(right) => {
                    let (l, r) = (tree.nodes()[index + 1], tree.nodes()[right]);
                    assert_eq!(l.items().start, node.items().start);
                    assert_eq!(l.items().end, r.items().start);
                    assert_eq!(r.items().end, node.items().end);
                }
            }
        }
    }

    #[test]
    fn a_refit_gives_every_node_the_union_of_its_items_boxes() {
        // Large enough for the parallel refit to split (over 2,048 nodes).
        let centroids = points(20_000);
        let items: Vec<(Aabb, DVec3)> = centroids.iter().map(|&c| (Aabb::new(c, c), c)).collect();
        let mut tree = BoxTree::build(&items, 2).unwrap();
        assert!(tree.nodes().len() > 8 * 2048);
        let order = tree.order().to_vec();
        let moved = |i: usize| {
            let c = centroids[order[i] as usize];
            let p = DVec3::new(c.y * 3.0 - 1.0, c.z * c.x, -c.x);
            Aabb::new(p - 0.01, p + 0.02)
        };
        tree.refit(moved);
        for (index, node) in tree.nodes().iter().enumerate() {
            let expected = match node.right() {
                None => node.items().fold(Aabb::EMPTY, |b, i| b.union(moved(i))),
                Some(right) => tree.nodes()[index + 1]
                    .bounds
                    .union(tree.nodes()[right].bounds),
            };
            assert_eq!(node.bounds, expected, "node {index}");
        }
        let all = (0..order.len()).fold(Aabb::EMPTY, |b, i| b.union(moved(i)));
        assert_eq!(tree.nodes()[0].bounds, all);
    }

    #[test]
    fn items_spread_exponentially_keep_the_tree_shallow() {
        // Each surface-area split would cut off one item: the median takes over deep down.
        let items: Vec<(Aabb, DVec3)> = (0..3000)
            .map(|i| DVec3::new(1.2_f64.powi(i / 8 - 150), f64::from(i % 8), 0.0))
            .map(|p| (Aabb::new(p, p), p))
            .collect();
        let tree = BoxTree::build(&items, 1).expect("3000 items");
        let mut deepest = 0;
        let mut stack = vec![(0_usize, 1_usize)];
        while let Some((n, depth)) = stack.pop() {
            deepest = deepest.max(depth);
            if let Some(right) = tree.nodes()[n].right() {
                stack.extend([(n + 1, depth + 1), (right, depth + 1)]);
            }
        }
        assert!(deepest <= MAX_AREA_SPLIT_DEPTH + 14, "depth {deepest}");
        let leaves: usize = tree
            .nodes()
            .iter()
            .filter(|n| n.is_leaf())
            .map(|n| n.items().len())
            .sum();
        assert_eq!(leaves, 3000);
    }

    #[test]
    fn the_same_items_give_the_same_tree() {
        let items: Vec<(Aabb, DVec3)> = points(200)
            .into_iter()
            .map(|c| (Aabb::new(c, c), c))
            .collect();
        let (a, b) = (
            BoxTree::build(&items, 3).unwrap(),
            BoxTree::build(&items, 3).unwrap(),
        );
        assert_eq!(a.order(), b.order());
        assert_eq!(a.nodes(), b.nodes());
        assert!(BoxTree::build(&[], 4).unwrap().nodes().is_empty());
    }

    /// The nearest centroid by a nearest-first search.
    struct Nearest<'a> {
        p: DVec3,
        centroids: &'a [DVec3],
        order: &'a [u32],
        best: f64,
        visited: usize,
    }

    impl NearestFirst for Nearest<'_> {
        fn may_improve(&self, distance_squared: f64) -> bool {
            distance_squared < self.best
        }

        fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
            for &i in &self.order[positions] {
                self.visited += 1;
                self.best = self
                    .best
                    .min(self.p.distance_squared(self.centroids[i as usize]));
            }
            ControlFlow::Continue(())
        }
    }

    #[test]
    fn nearest_first_search_finds_the_nearest_and_prunes() {
        let centroids = points(1000);
        let items: Vec<(Aabb, DVec3)> = centroids.iter().map(|&c| (Aabb::new(c, c), c)).collect();
        let tree = BoxTree::build(&items, 4).unwrap();
        let p = DVec3::new(0.5, -1.0, 0.25);
        let mut search = Nearest {
            p,
            centroids: &centroids,
            order: tree.order(),
            best: f64::INFINITY,
            visited: 0,
        };
        tree.search_nearest_first(p, &mut search);
        let brute = centroids
            .iter()
            .map(|&c| p.distance_squared(c))
            .fold(f64::INFINITY, f64::min);
        assert_eq!(search.best.to_bits(), brute.to_bits());
        assert!(search.visited < 1000 / 4, "visited {}", search.visited);
    }
}
