//! The Douglas–Peucker hierarchy of capsules (paper section 3.1).
//!
//! A node covers the vertices `start..=end` of the polyline (indices into the point list,
//! in which a closed polyline repeats its first point at the end), that is the
//! sub-polyline of segments `start..end`. Its *chord* is the segment from vertex `start`
//! to vertex `end`, and its *error* `ε` is the largest distance from the sub-polyline to
//! the chord. The root covers everything; a node of two or more segments has two
//! children, split at its farthest vertex; a node of one segment is a leaf (`ε = 0`).
//!
//! # The error bounds both ways
//!
//! Write `S` for the sub-polyline of a node, `C` for its chord `[A, B]`, `ε` for
//! `max_{s ∈ S} dist(s, C)`.
//!
//! 1. *`S` lies in the capsule of radius `ε` around `C`* (the definition). Since the
//!    distance to a segment is a convex function, its maximum over a segment of `S` is at
//!    one of its two ends, so `ε` is the largest distance of a *vertex*: what the build
//!    computes. This direction gives the lower bound: for a query `p` at distance `d` of
//!    `C`, `dist(p, S) ≥ d − ε` (triangle inequality).
//! 2. *Every point of `C` lies within `ε` of `S`* (the converse, which the paper's upper
//!    bound `d + ε` needs). `S` is a connected path from `A` to `B`. If `A ≠ B`, let
//!    `π(s) ∈ ℝ` be the parameter of the projection of `s` on the line `AB`
//!    (`π(A) = 0`, `π(B) = 1`); `π` is continuous along `S`, so by the intermediate value
//!    theorem every `t ∈ [0, 1]` is `π(s)` for some `s ∈ S`. For the chord point
//!    `c = A + t (B − A)`, that `s` projects onto `c`, which lies on the chord, so
//!    `|s − c| = dist(s, C) ≤ ε`. If `A = B` (a closed loop's root), `C = {A}` and
//!    `A ∈ S`. So the closest point `c` of `C` to `p` has a point of `S` within `ε`, and
//!    `dist(p, S) ≤ d + ε`.
//!
//! Both bounds therefore hold; the session also uses `|p − A|` and `|p − B|` (vertices of
//! `S`) as upper bounds, which is sometimes better than `d + ε`.
//!
//! # Rounding
//!
//! The stored `ε` of an inner node is the computed maximum plus `8 u · scale` (`u` the
//! unit roundoff, `scale` the largest absolute coordinate of the polyline), so it bounds
//! the exact real maximum, not only its floating-point evaluation. A node whose vertices
//! are all within that slack of its chord (a straight run) is split at its middle vertex
//! rather than at its computed farthest one, which would be noise: the bounds do not
//! depend on where a node is split, and straight runs of many points stay balanced.
//!
//! # Cost
//!
//! Building scans each node's vertices once: `O(n · depth)`, `O(n log n)` for curves whose
//! farthest points fall near the middle of their runs, `O(n²)` in the worst case (a curve
//! whose farthest vertex is always next to an end of its run, so that every split peels
//! off one segment). The build is iterative (an explicit stack), so
//! depth is never a stack-overflow risk, and deterministic (ties go to the lowest index).
//! A node takes 24 bytes; a polyline of `s` segments has `2s − 1` nodes.

use super::point::{PolylinePoint, closest_on_segment};

/// The `first_child` of a leaf.
pub(crate) const NO_CHILD: u32 = u32::MAX;

/// The id of the root node.
pub(crate) const ROOT: u32 = 0;

/// A capsule of the hierarchy: the chord from vertex `start` to vertex `end` and its error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Node {
    /// The first vertex (index into the point list).
    pub start: u32,
    /// The last vertex (index into the point list), `> start`.
    pub end: u32,
    /// The first of the two children (the second is `first_child + 1`), or [`NO_CHILD`].
    pub first_child: u32,
    /// The largest distance from the covered sub-polyline to the chord (0 for a leaf).
    pub error: f64,
}

impl Node {
    /// Whether the node is a single segment of the polyline.
    pub(crate) fn is_leaf(&self) -> bool {
        self.first_child == NO_CHILD
    }
}

/// Builds the hierarchy of `points` (at least two; a closed polyline's list repeats its
/// first point at the end); `scale` is the largest absolute coordinate. Node 0 is the root.
pub(crate) fn build<P: PolylinePoint>(points: &[P], scale: f64) -> Vec<Node> {
    let segments = points.len().saturating_sub(1);
    if segments == 0 {
        return Vec::new();
    }
    let slack = 8.0 * f64::EPSILON * scale;
    let mut nodes = Vec::with_capacity(2 * segments - 1);
    nodes.push(Node {
        start: 0,
        end: segments as u32,
        first_child: NO_CHILD,
        error: 0.0,
    });
    let mut stack = vec![ROOT];
    while let Some(id) = stack.pop() {
        let Some(&node) = nodes.get(id as usize) else {
            continue;
        };
        let (start, end) = (node.start as usize, node.end as usize);
        if end - start < 2 {
            continue;
        }
        let (Some(&a), Some(&b), Some(inner)) = (
            points.get(start),
            points.get(end),
            points.get(start + 1..end),
        ) else {
            continue;
        };
        let mut farthest = start + 1;
        let mut farthest_squared = -1.0;
        for (k, &v) in inner.iter().enumerate() {
            let d2 = closest_on_segment(v, a, b).distance_squared;
            if d2 > farthest_squared {
                farthest_squared = d2;
                farthest = start + 1 + k;
            }
        }
        let error = farthest_squared.max(0.0).sqrt();
        let split = if error <= slack {
            start + (end - start) / 2
        } else {
            farthest
        };
        let first_child = nodes.len() as u32;
        if let Some(n) = nodes.get_mut(id as usize) {
            n.error = error + slack;
            n.first_child = first_child;
        }
        nodes.push(Node {
            start: start as u32,
            end: split as u32,
            first_child: NO_CHILD,
            error: 0.0,
        });
        nodes.push(Node {
            start: split as u32,
            end: end as u32,
            first_child: NO_CHILD,
            error: 0.0,
        });
        stack.push(first_child + 1);
        stack.push(first_child);
    }
    nodes
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values on exactly representable inputs
mod tests {
    use glam::{DVec2, DVec3};

    use super::*;
    use sphaera_tests::random::Lcg64;

    fn scale<P: PolylinePoint>(points: &[P]) -> f64 {
        points.iter().map(|p| p.max_abs()).fold(0.0, f64::max)
    }

    /// Every vertex a node covers is within its error of its chord; children partition
    /// their parent; leaves are exactly the segments, in order.
    fn check<P: PolylinePoint>(points: &[P]) {
        let nodes = build(points, scale(points));
        let segments = points.len() - 1;
        assert_eq!(nodes.len(), 2 * segments - 1);
        let mut leaves = Vec::new();
        let mut stack = vec![ROOT];
        while let Some(id) = stack.pop() {
            let node = nodes[id as usize];
            assert!(node.end > node.start);
            let (a, b) = (points[node.start as usize], points[node.end as usize]);
            for &v in &points[node.start as usize..=node.end as usize] {
                let d = closest_on_segment(v, a, b).distance_squared.sqrt();
                assert!(d <= node.error, "{d} > {} at node {id}", node.error);
            }
            if node.is_leaf() {
                assert_eq!(node.end, node.start + 1);
                assert_eq!(node.error, 0.0);
                leaves.push(node.start);
            } else {
                let (l, r) = (
                    nodes[node.first_child as usize],
                    nodes[node.first_child as usize + 1],
                );
                assert_eq!(
                    (l.start, l.end, r.start, r.end),
                    (node.start, l.end, l.end, node.end)
                );
                stack.push(node.first_child + 1);
                stack.push(node.first_child);
            }
        }
        assert_eq!(leaves, (0..segments as u32).collect::<Vec<_>>());
    }

    #[test]
    fn every_point_is_within_its_nodes_error() {
        let mut rng = Lcg64::new(5);
        for n in [2, 3, 4, 7, 50, 301] {
            let random2: Vec<DVec2> = (0..n)
                .map(|_| DVec2::new(rng.unit(), rng.unit()) * 10.0)
                .collect();
            check(&random2);
            let random3: Vec<DVec3> = (0..n)
                .map(|_| DVec3::new(rng.unit(), rng.unit(), rng.unit()))
                .collect();
            check(&random3);
            // A closed loop: the first point repeated at the end.
            let mut closed = random3.clone();
            closed.push(random3[0]);
            check(&closed);
        }
    }

    #[test]
    fn repeated_and_collinear_points() {
        let repeated = [
            DVec2::ZERO,
            DVec2::ZERO,
            DVec2::X,
            DVec2::X,
            DVec2::X,
            DVec2::ONE,
        ];
        check(&repeated);
        let line: Vec<DVec3> = (0..1000).map(|i| DVec3::X * f64::from(i) * 0.1).collect();
        check(&line);
        // Straight runs are split at the middle: the depth stays logarithmic.
        let nodes = build(&line, 100.0);
        let root = nodes[0];
        assert_eq!(nodes[root.first_child as usize].end, 499);
    }

    #[test]
    fn the_root_error_of_a_half_circle_is_its_height() {
        let arc: Vec<DVec2> = (0..=64)
            .map(|i| {
                let a = std::f64::consts::PI * f64::from(i) / 64.0;
                DVec2::new(a.cos(), a.sin())
            })
            .collect();
        let nodes = build(&arc, 1.0);
        assert!((nodes[0].error - 1.0).abs() < 1e-12);
        assert_eq!(nodes[nodes[0].first_child as usize].end, 32);
    }

    #[test]
    fn deep_hierarchies_build_without_recursion() {
        // A steep convex curve: deep, unbalanced splits.
        let points: Vec<DVec2> = (0..5_000)
            .map(|i| DVec2::new(f64::from(i), 1.001_f64.powi(i)))
            .collect();
        let nodes = build(&points, 1e9);
        assert_eq!(nodes.len(), 2 * 4_999 - 1);
    }
}
