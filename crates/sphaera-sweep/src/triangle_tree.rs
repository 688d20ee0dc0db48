//! A static bounding-box tree over the input triangles, for exact closest points of
//! independent queries (no coherence to exploit, no session state).
//!
//! Meshsweeper ([`crate::Session`]) is the engine for coherent queries and for anytime
//! bounds; a query that jumps far from the previous one pays for a reset and a sweep from
//! the warm start. Callers that ask many unrelated exact questions from several threads
//! (the medial approximation asks one per Voronoi vertex) use this tree instead: it is
//! immutable, shared by reference, and answers with a depth-first descent, nearest box
//! first, pruned by the best distance so far.

use glam::DVec3;
use sphaera_mesh::geometry::{self, Triangle, closest_point_on_triangle};
use sphaera_mesh::{Aabb, TriMesh};

use crate::{ClosestPoint, Feature, SweepError};

/// Triangles per leaf.
const LEAF_SIZE: usize = 4;

/// A node: a leaf holds `count > 0` triangles from `first`; an inner node has `count == 0`,
/// its left child right after it and its right child at `first`.
#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: Aabb,
    first: u32,
    count: u32,
}

/// An axis-aligned bounding-box tree over a mesh's triangles answering exact closest-point
/// queries; immutable and `Sync`, so one tree serves every thread.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_sweep::TriangleTree;
///
/// let cube = shapes::cube(2.0, 2)?; // the cube [-1, 1]³
/// let tree = TriangleTree::new(&cube)?;
/// let answer = tree.closest(DVec3::new(0.25, 0.0, 0.0))?;
/// assert!((answer.distance - 0.75).abs() < 1e-12);
/// assert!((answer.point.x - 1.0).abs() < 1e-12);
/// // Nothing within 0.5 of the centre.
/// assert!(tree.closest_within(DVec3::ZERO, 0.5)?.is_none());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct TriangleTree {
    nodes: Vec<Node>,
    /// Triangle corners in leaf order.
    corners: Vec<[DVec3; 3]>,
    /// Input triangle index of each entry of `corners`.
    ids: Vec<u32>,
    /// Input vertex indices of each entry of `corners`.
    vertices: Vec<[u32; 3]>,
}

impl TriangleTree {
    /// Builds the tree over `mesh`'s triangles (median splits along the longest axis of the
    /// triangle centroids; deterministic).
    ///
    /// # Errors
    ///
    /// [`SweepError::EmptyMesh`] if the mesh has no triangle.
    ///
    /// # Performance
    ///
    /// `O(n log n)` for `n` triangles; about 120 bytes per triangle.
    pub fn new(mesh: &TriMesh) -> Result<Self, SweepError> {
        let positions = mesh.positions();
        let indexed = mesh.triangles();
        if indexed.is_empty() {
            return Err(SweepError::EmptyMesh);
        }
        let corners_of = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
        let mut order: Vec<u32> = (0..indexed.len() as u32).collect();
        let centroids: Vec<DVec3> = indexed
            .iter()
            .map(|t| {
                let [a, b, c] = corners_of(t);
                (a + b + c) / 3.0
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * indexed.len() / LEAF_SIZE + 1);
        // (node slot, range start, range end)
        let mut stack = vec![(usize::MAX, 0_usize, indexed.len())];
        while let Some((parent, start, end)) = stack.pop() {
            let slot = nodes.len();
            if parent != usize::MAX {
                let parent_node: &mut Node = &mut nodes[parent];
                parent_node.first = slot as u32;
            }
            let range = &mut order[start..end];
            let bounds = range.iter().fold(Aabb::EMPTY, |b, &t| {
                corners_of(&indexed[t as usize])
                    .into_iter()
                    .fold(b, Aabb::grown_by_point)
            });
            if range.len() <= LEAF_SIZE {
                nodes.push(Node {
                    bounds,
                    first: start as u32,
                    count: range.len() as u32,
                });
                continue;
            }
            let centre_bounds = range
                .iter()
                .fold(Aabb::EMPTY, |b, &t| b.grown_by_point(centroids[t as usize]));
            let axis = centre_bounds.longest_axis();
            let middle = range.len() / 2;
            range.select_nth_unstable_by(middle, |&a, &b| {
                centroids[a as usize][axis]
                    .total_cmp(&centroids[b as usize][axis])
                    .then(a.cmp(&b))
            });
            nodes.push(Node {
                bounds,
                first: 0,
                count: 0,
            });
            // The left child must come right after this node: push it last.
            stack.push((slot, start + middle, end));
            stack.push((usize::MAX, start, start + middle));
        }
        let corners = order
            .iter()
            .map(|&t| corners_of(&indexed[t as usize]))
            .collect();
        let vertices = order.iter().map(|&t| indexed[t as usize]).collect();
        Ok(Self {
            nodes,
            corners,
            ids: order,
            vertices,
        })
    }

    /// The number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.ids.len()
    }

    /// The exact closest point of the mesh to `p` (ties: the first triangle in the tree's
    /// order, so the same input gives the same answer).
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    ///
    /// # Performance
    ///
    /// Logarithmic for most queries; a point equidistant from much of the surface (the
    /// centre of a sphere mesh) visits all of it.
    pub fn closest(&self, p: DVec3) -> Result<ClosestPoint, SweepError> {
        match self.closest_within(p, f64::INFINITY)? {
            Some(answer) => Ok(answer),
            // Unreachable for a finite query on a non-empty tree; reported rather than
            // assumed.
            None => Err(SweepError::EmptyMesh),
        }
    }

    /// The exact closest point of the mesh to `p` if it lies within `max_distance`
    /// (inclusive), else `None`; a known bound prunes the descent from the start.
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] for a non-finite `p`;
    /// [`SweepError::InvalidParameter`] for a NaN or negative `max_distance`.
    pub fn closest_within(
        &self,
        p: DVec3,
        max_distance: f64,
    ) -> Result<Option<ClosestPoint>, SweepError> {
        if !p.is_finite() {
            return Err(SweepError::NonFiniteQuery {
                x: p.x,
                y: p.y,
                z: p.z,
            });
        }
        if max_distance.is_nan() || max_distance < 0.0 {
            return Err(SweepError::InvalidParameter {
                name: "max_distance",
                value: max_distance,
                requirement: "a non-negative number",
            });
        }
        let mut best_squared = max_distance * max_distance;
        let mut best: Option<(usize, geometry::TriangleClosestPoint)> = None;
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = self.nodes[n as usize];
            if node.bounds.distance_squared_to_point(p) > best_squared {
                continue;
            }
            if node.count > 0 {
                let range = node.first as usize..(node.first + node.count) as usize;
                for i in range {
                    let [a, b, c] = self.corners[i];
                    // The triangle's box first: the exact test costs ten times more.
                    let bounds = Aabb::new(a.min(b).min(c), a.max(b).max(c));
                    if bounds.distance_squared_to_point(p) > best_squared {
                        continue;
                    }
                    let hit = closest_point_on_triangle(p, &Triangle::new(a, b, c));
                    let better = hit.distance_squared < best_squared
                        || (best.is_none() && hit.distance_squared <= best_squared);
                    if better {
                        best_squared = hit.distance_squared;
                        best = Some((i, hit));
                    }
                }
                continue;
            }
            let (left, right) = (n + 1, node.first);
            let dl = self.nodes[left as usize]
                .bounds
                .distance_squared_to_point(p);
            let dr = self.nodes[right as usize]
                .bounds
                .distance_squared_to_point(p);
            // Nearest child on top of the stack.
            if dl <= dr {
                stack.push(right);
                stack.push(left);
            } else {
                stack.push(left);
                stack.push(right);
            }
        }
        Ok(best.map(|(i, hit)| self.answer(i, p, &hit)))
    }

    fn answer(&self, i: usize, p: DVec3, hit: &geometry::TriangleClosestPoint) -> ClosestPoint {
        let v = self.vertices[i];
        let feature = match hit.feature {
            geometry::Feature::Vertex(k) => Feature::Vertex(v[usize::from(k)]),
            geometry::Feature::Edge(k) => {
                Feature::Edge(v[usize::from(k)], v[(usize::from(k) + 1) % 3])
            }
            geometry::Feature::Face => Feature::Face,
        };
        ClosestPoint {
            point: hit.point,
            distance: (hit.point - p).length(),
            triangle: self.ids[i],
            feature,
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)]

    use super::*;
    use sphaera_mesh::shapes;

    fn brute(mesh: &TriMesh, p: DVec3) -> f64 {
        (0..mesh.triangle_count())
            .filter_map(|t| mesh.triangle(t))
            .map(|t| geometry::point_triangle_distance_squared(p, &t))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    #[test]
    fn agrees_with_brute_force_on_a_torus() -> Result<(), Box<dyn std::error::Error>> {
        let mesh = shapes::torus(1.0, 0.3, 20)?;
        let tree = TriangleTree::new(&mesh)?;
        assert_eq!(tree.triangle_count(), mesh.triangle_count());
        for i in 0..200 {
            let f = f64::from(i);
            let p = DVec3::new(
                (f * 0.37).sin() * 1.7,
                (f * 0.91).cos() * 1.6,
                (f * 0.13).sin(),
            );
            let answer = tree.closest(p)?;
            assert!((answer.distance - brute(&mesh, p)).abs() < 1e-12);
            let t = mesh.triangle(answer.triangle as usize).ok_or("triangle")?;
            assert!((geometry::point_triangle_distance_squared(answer.point, &t)).sqrt() < 1e-12);
        }
        Ok(())
    }

    #[test]
    fn a_bound_prunes_and_is_inclusive() -> Result<(), Box<dyn std::error::Error>> {
        let mesh = shapes::cube(2.0, 2)?;
        let tree = TriangleTree::new(&mesh)?;
        let p = DVec3::new(0.5, 0.0, 0.0);
        assert!(tree.closest_within(p, 0.4)?.is_none());
        let at = tree.closest_within(p, 0.5)?.ok_or("inclusive bound")?;
        assert_eq!(at.distance, 0.5);
        Ok(())
    }

    #[test]
    fn bad_queries_are_errors() -> Result<(), Box<dyn std::error::Error>> {
        let tree = TriangleTree::new(&shapes::cube(2.0, 2)?)?;
        assert!(matches!(
            tree.closest(DVec3::new(f64::NAN, 0.0, 0.0)),
            Err(SweepError::NonFiniteQuery { .. })
        ));
        assert!(matches!(
            tree.closest_within(DVec3::ZERO, -1.0),
            Err(SweepError::InvalidParameter { .. })
        ));
        assert!(matches!(
            tree.closest_within(DVec3::ZERO, f64::NAN),
            Err(SweepError::InvalidParameter { .. })
        ));
        Ok(())
    }
}
