//! The warm start of cold queries: a pre-refined state of the hierarchy, shared by every
//! session of a [`Sweeper`](crate::Sweeper), with its triangles grouped in space.
//!
//! A session resets to this state instead of the base mesh, so an independent query
//! starts lower in the hierarchy (fewer vertex splits, each undoing fewer collapses).
//! Its triangles are not evaluated one by one: each spatial group enters the queue with
//! one lower bound (the distance to a sphere holding every member's error interval) and
//! is expanded into its members' exact intervals only when it reaches the front.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use glam::DVec3;
use sphaera_simplify::Hierarchy;

/// The default warm start has this fraction (`1 / WARM_START_DIVISOR`) of the finest
/// mesh's triangles (measured on the bunny: `docs/benchmarks.md`).
pub(crate) const WARM_START_DIVISOR: usize = 2;

/// Triangles per spatial group, at most.
const GROUP_SIZE: usize = 16;

/// The relative slack of a group's bound (covers the rounding of the exact intervals).
const BOUND_SLACK: f64 = 1e-9;

/// A pre-refined state and its triangles in spatial groups.
#[derive(Clone, Debug, Default)]
pub(crate) struct WarmStart {
    /// The collapses to undo from the base mesh to reach the state, in order.
    collapses: Vec<u32>,
    /// The live triangles of the state, group by group.
    triangles: Vec<u32>,
    /// Their corners in the state (valid while a triangle is untouched by a split).
    corners: Vec<[u32; 3]>,
    /// The bounding-sphere tree over `triangles` (node 0 is the root).
    nodes: Vec<Node>,
    /// The scale of the rounding slack (the mesh's bounding-box diagonal).
    diagonal: f64,
}

impl WarmStart {
    /// The state reached from the base mesh by splitting the vertex with the largest
    /// radius until at least `target` triangles are live (or nothing is left to split).
    pub(crate) fn new(hierarchy: &Hierarchy, target: usize, diagonal: f64) -> Self {
        let mut refinement = hierarchy.refinement();
        let mut heap: BinaryHeap<(u64, Reverse<u32>)> = (0..hierarchy.vertex_count() as u32)
            .filter(|&v| refinement.can_split(v))
            .map(|v| (refinement.radius(v).to_bits(), Reverse(v)))
            .collect();
        let mut collapses = Vec::new();
        let mut undone = Vec::new();
        while refinement.live_triangle_count() < target {
            let Some((bits, Reverse(v))) = heap.pop() else {
                break;
            };
            if !refinement.can_split(v) || refinement.radius(v).to_bits() != bits {
                continue;
            }
            undone.clear();
            if refinement.split_vertex_into(v, &mut undone).is_err() {
                continue;
            }
            for &c in &undone {
                for x in [hierarchy.removed_vertex(c), hierarchy.kept_vertex(c)]
                    .into_iter()
                    .flatten()
                {
                    if refinement.can_split(x) {
                        heap.push((refinement.radius(x).to_bits(), Reverse(x)));
                    }
                }
            }
            collapses.extend_from_slice(&undone);
        }
        let mut live: Vec<(u32, [u32; 3])> = refinement
            .live_triangles()
            .filter_map(|t| refinement.corners(t).map(|c| (t, c)))
            .collect();
        let position = |v: u32| refinement.position(v);
        let mut nodes = vec![Node::default()];
        build_node(&mut live, 0, 0, &mut nodes, &position, &|v| {
            refinement.radius(v)
        });
        Self {
            collapses,
            triangles: live.iter().map(|&(t, _)| t).collect(),
            corners: live.iter().map(|&(_, c)| c).collect(),
            nodes,
            diagonal,
        }
    }

    /// The collapses to undo from the base mesh, in order.
    pub(crate) fn collapses(&self) -> &[u32] {
        &self.collapses
    }

    /// Number of nodes of the tree (node 0 is the root).
    pub(crate) fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Live triangles of the warm state.
    pub(crate) fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// What node `n` holds: its two children, or its triangles and their corners in the
    /// warm state. Out of range: no triangle.
    pub(crate) fn node(&self, n: usize) -> Contents<'_> {
        let Some(node) = self.nodes.get(n) else {
            return Contents::Triangles(&[], &[]);
        };
        if node.left != NO_CHILD {
            return Contents::Children(node.left, node.left + 1);
        }
        let range = node.lo as usize..node.hi as usize;
        Contents::Triangles(
            self.triangles.get(range.clone()).unwrap_or(&[]),
            self.corners.get(range).unwrap_or(&[]),
        )
    }

    /// A lower bound on `d − ε` of every triangle under node `n` for `p` (with the
    /// hierarchy's own geometry); `−∞` if `n` is out of range.
    pub(crate) fn lower_bound(&self, n: usize, p: DVec3) -> f64 {
        let Some(node) = self.nodes.get(n) else {
            return f64::NEG_INFINITY;
        };
        let d = (p - node.center).length();
        (d - node.radius) - BOUND_SLACK * (d + node.radius + self.diagonal)
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        4 * (self.collapses.len() + self.triangles.len())
            + 12 * self.corners.len()
            + size_of::<Node>() * self.nodes.len()
    }
}

/// No child: the node is a leaf.
const NO_CHILD: u32 = u32::MAX;

/// A node of the bounding-sphere tree: every triangle under it has
/// `d − ε ≥ |p − center| − radius` (`d`: distance to the triangle, `ε`: its largest corner
/// radius).
#[derive(Clone, Copy, Debug, Default)]
struct Node {
    center: DVec3,
    radius: f64,
    /// The first child (the second is `left + 1`), or [`NO_CHILD`].
    left: u32,
    /// The triangles under the node: `triangles[lo..hi]`.
    lo: u32,
    hi: u32,
}

/// What a node holds.
pub(crate) enum Contents<'w> {
    /// Two child nodes.
    Children(u32, u32),
    /// Triangles and their corners in the warm state.
    Triangles(&'w [u32], &'w [[u32; 3]]),
}

/// Fills node `n` over `live[lo..]` (`live` is the slice of the node; `lo` its offset in
/// the whole list), splitting at the median centroid of the longest axis while more than
/// [`GROUP_SIZE`] triangles remain.
fn build_node(
    live: &mut [(u32, [u32; 3])],
    lo: usize,
    n: usize,
    nodes: &mut Vec<Node>,
    position: &impl Fn(u32) -> DVec3,
    radius: &impl Fn(u32) -> f64,
) {
    let (min, max) = live.iter().flat_map(|(_, c)| c.iter()).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(a, b), &v| (a.min(position(v)), b.max(position(v))),
    );
    let center = if min.is_finite() {
        0.5 * (min + max)
    } else {
        DVec3::ZERO
    };
    let (reach, eps) =
        live.iter()
            .flat_map(|(_, c)| c.iter())
            .fold((0.0_f64, 0.0_f64), |(reach, eps), &v| {
                (
                    reach.max((position(v) - center).length()),
                    eps.max(radius(v)),
                )
            });
    let mut node = Node {
        center,
        radius: reach + eps,
        left: NO_CHILD,
        lo: lo as u32,
        hi: (lo + live.len()) as u32,
    };
    if live.len() > GROUP_SIZE {
        let centroid = |c: &[u32; 3]| (position(c[0]) + position(c[1]) + position(c[2])) / 3.0;
        let axis = (max - min).max_position();
        let mid = live.len() / 2;
        live.select_nth_unstable_by(mid, |a, b| {
            centroid(&a.1)[axis]
                .total_cmp(&centroid(&b.1)[axis])
                .then(a.0.cmp(&b.0))
        });
        let left = nodes.len();
        nodes.push(Node::default());
        nodes.push(Node::default());
        node.left = left as u32;
        let (a, b) = live.split_at_mut(mid);
        build_node(a, lo, left, nodes, position, radius);
        build_node(b, lo + mid, left + 1, nodes, position, radius);
    }
    if let Some(slot) = nodes.get_mut(n) {
        *slot = node;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::geometry::{Triangle, closest_point_on_triangle};
    use sphaera_mesh::shapes;

    /// Every node's bound is below `d − ε` of every triangle under it (brute force), and
    /// the leaves hold each warm triangle once.
    #[test]
    fn node_bounds_hold_every_triangle_below() {
        let torus = shapes::torus(1.0, 0.3, 20).expect("torus");
        let hierarchy = crate::build_hierarchy(&torus).expect("hierarchy");
        let warm = WarmStart::new(&hierarchy, hierarchy.finest_triangle_count() / 3, 3.0);
        let mut refinement = hierarchy.refinement();
        let mut out = Vec::new();
        for &c in warm.collapses() {
            refinement.undo_collapse(c, &mut out).expect("valid");
        }
        assert_eq!(refinement.live_triangle_count(), warm.triangle_count());
        let key = |t: u32, p: DVec3| {
            let c = refinement.corners(t).expect("live");
            let q = c.map(|v| refinement.position(v));
            let d = closest_point_on_triangle(p, &Triangle::new(q[0], q[1], q[2]))
                .distance_squared
                .sqrt();
            d - c
                .map(|v| refinement.radius(v))
                .into_iter()
                .fold(0.0, f64::max)
        };
        let mut seen = Vec::new();
        let points = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.2, 0.1),
            DVec3::new(-3.0, 2.0, 1.0),
        ];
        for n in 0..warm.node_count() {
            let mut stack = vec![n];
            let mut under = Vec::new();
            while let Some(m) = stack.pop() {
                match warm.node(m) {
                    Contents::Children(a, b) => stack.extend([a as usize, b as usize]),
                    Contents::Triangles(ts, cs) => {
                        for (&t, &c) in ts.iter().zip(cs) {
                            assert_eq!(refinement.corners(t), Some(c));
                            under.push(t);
                        }
                    }
                }
            }
            if let Contents::Triangles(ts, _) = warm.node(n) {
                seen.extend_from_slice(ts);
            }
            for &p in &points {
                let bound = warm.lower_bound(n, p);
                assert!(under.iter().all(|&t| bound <= key(t, p)), "node {n}");
            }
        }
        seen.sort_unstable();
        let live: Vec<u32> = refinement.live_triangles().collect();
        assert_eq!(seen, live);
    }
}
