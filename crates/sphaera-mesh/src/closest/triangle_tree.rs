//! A static box tree over a mesh's triangles, for exact closest points of independent
//! queries (no coherence to exploit, no session state).

use std::ops::{ControlFlow, Range};

use glam::DVec3;

use crate::bvh::{BoxTree, NearestFirst};
use crate::geometry::{
    Triangle, TriangleClosestPoint, closest_point_on_triangle, point_triangle_distance_squared,
};
use crate::{Aabb, MeshError, TriMesh};

use super::ClosestPoint;

/// Triangles per leaf.
const LEAF_SIZE: usize = 4;

/// An axis-aligned bounding-box tree over a mesh's triangles answering exact
/// closest-point queries; immutable and `Sync`, so one tree serves every thread.
///
/// It answers with a depth-first descent of the [`BoxTree`], nearest box first, pruned by
/// the best distance so far. Degenerate triangles are part of the surface and are
/// searched like any other.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, closest::TriangleTree, shapes};
///
/// let cube = shapes::cube(2.0, 2)?; // the cube [-1, 1]³
/// let tree = TriangleTree::new(&cube)?;
/// let answer = tree.closest(DVec3::new(0.25, 0.0, 0.0))?;
/// assert!((answer.distance - 0.75).abs() < 1e-12);
/// assert!((answer.point.x - 1.0).abs() < 1e-12);
/// // Nothing within 0.5 of the centre.
/// assert!(tree.closest_within(DVec3::ZERO, 0.5)?.is_none());
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Debug, Clone)]
pub struct TriangleTree {
    boxes: BoxTree,
    /// Triangle corners in tree order.
    corners: Vec<[DVec3; 3]>,
    /// Mesh vertex indices of each entry of `corners`.
    vertices: Vec<[u32; 3]>,
}

impl TriangleTree {
    /// Builds the tree over `mesh`'s triangles (median splits along the longest axis of
    /// the triangle centroids; deterministic).
    ///
    /// # Errors
    ///
    /// [`MeshError::EmptyMesh`] if the mesh has no triangle;
    /// [`MeshError::TooManyItems`] beyond what 32-bit triangle indices address.
    ///
    /// # Performance
    ///
    /// `O(n log n)` for `n` triangles; about 120 bytes per triangle.
    pub fn new(mesh: &TriMesh) -> Result<Self, MeshError> {
        let positions = mesh.positions();
        let indexed = mesh.triangles();
        if indexed.is_empty() {
            return Err(MeshError::EmptyMesh);
        }
        let corners_of = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
        let items: Vec<(Aabb, DVec3)> = indexed
            .iter()
            .map(|t| {
                let corners = corners_of(t);
                let [a, b, c] = corners;
                (Aabb::from_points(corners), (a + b + c) / 3.0)
            })
            .collect();
        let boxes = BoxTree::build(&items, LEAF_SIZE)?;
        let corners = boxes
            .order()
            .iter()
            .map(|&t| corners_of(&indexed[t as usize]))
            .collect();
        let vertices = boxes.order().iter().map(|&t| indexed[t as usize]).collect();
        Ok(Self {
            boxes,
            corners,
            vertices,
        })
    }

    /// The number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.corners.len()
    }

    /// The exact closest point of the mesh to `p` (ties: the first triangle in the tree's
    /// order, so the same input gives the same answer).
    ///
    /// # Errors
    ///
    /// [`MeshError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    ///
    /// # Performance
    ///
    /// Logarithmic for most queries; a point equidistant from much of the surface (the
    /// centre of a sphere mesh) visits all of it.
    pub fn closest(&self, p: DVec3) -> Result<ClosestPoint, MeshError> {
        match self.closest_within(p, f64::INFINITY)? {
            Some(answer) => Ok(answer),
            // Unreachable for a finite query on a non-empty tree; reported rather than
            // assumed.
            None => Err(MeshError::EmptyMesh),
        }
    }

    /// The exact closest point of the mesh to `p` if it lies within `max_distance`
    /// (inclusive), else `None`; a known bound prunes the descent from the start.
    ///
    /// # Errors
    ///
    /// [`MeshError::NonFiniteQuery`] for a non-finite `p`;
    /// [`MeshError::InvalidParameter`] for a NaN or negative `max_distance`.
    pub fn closest_within(
        &self,
        p: DVec3,
        max_distance: f64,
    ) -> Result<Option<ClosestPoint>, MeshError> {
        if !p.is_finite() {
            return Err(MeshError::NonFiniteQuery {
                x: p.x,
                y: p.y,
                z: p.z,
            });
        }
        if max_distance.is_nan() || max_distance < 0.0 {
            return Err(MeshError::InvalidParameter {
                name: "max_distance",
                value: max_distance,
                requirement: "a non-negative number",
            });
        }
        let mut search = Search {
            corners: &self.corners,
            p,
            best_squared: max_distance * max_distance,
            best: None,
        };
        self.boxes.search_nearest_first(p, &mut search);
        Ok(search.best.map(|(i, hit)| self.answer(i, p, &hit)))
    }

    /// The distance from `p` to the mesh, for callers that need only the number: the
    /// same descent as [`TriangleTree::closest`] with the cheaper
    /// [`point_triangle_distance_squared`] per triangle (about three times faster; it may
    /// differ from `closest(p)?.distance` in the last bit).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, closest::TriangleTree, shapes};
    ///
    /// let tree = TriangleTree::new(&shapes::cube(2.0, 2)?)?; // the cube [-1, 1]³
    /// assert!((tree.distance(DVec3::new(3.0, 0.5, 0.0))? - 2.0).abs() < 1e-12);
    /// assert!(tree.distance(DVec3::NAN).is_err());
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`MeshError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    pub fn distance(&self, p: DVec3) -> Result<f64, MeshError> {
        if !p.is_finite() {
            return Err(MeshError::NonFiniteQuery {
                x: p.x,
                y: p.y,
                z: p.z,
            });
        }
        let mut search = Distance {
            corners: &self.corners,
            p,
            best_squared: f64::INFINITY,
        };
        self.boxes.search_nearest_first(p, &mut search);
        Ok(search.best_squared.sqrt())
    }

    fn answer(&self, i: usize, p: DVec3, hit: &TriangleClosestPoint) -> ClosestPoint {
        ClosestPoint {
            point: hit.point,
            distance: (hit.point - p).length(),
            triangle: self.boxes.order()[i],
            feature: hit.feature.in_mesh(self.vertices[i]),
        }
    }
}

/// The state of one closest-point descent.
struct Search<'a> {
    corners: &'a [[DVec3; 3]],
    p: DVec3,
    best_squared: f64,
    /// The best triangle so far (its position in tree order) and its closest point.
    best: Option<(usize, TriangleClosestPoint)>,
}

impl NearestFirst for Search<'_> {
    fn may_improve(&self, distance_squared: f64) -> bool {
        distance_squared <= self.best_squared
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        for i in positions {
            let [a, b, c] = self.corners[i];
            // The triangle's box first: the exact test costs ten times more.
            let bounds = Aabb::new(a.min(b).min(c), a.max(b).max(c));
            if bounds.distance_squared_to_point(self.p) > self.best_squared {
                continue;
            }
            let hit = closest_point_on_triangle(self.p, &Triangle::new(a, b, c));
            let better = hit.distance_squared < self.best_squared
                || (self.best.is_none() && hit.distance_squared <= self.best_squared);
            if better {
                self.best_squared = hit.distance_squared;
                self.best = Some((i, hit));
            }
        }
        ControlFlow::Continue(())
    }
}

/// The state of one distance-only descent.
struct Distance<'a> {
    corners: &'a [[DVec3; 3]],
    p: DVec3,
    best_squared: f64,
}

impl NearestFirst for Distance<'_> {
    fn may_improve(&self, distance_squared: f64) -> bool {
        distance_squared < self.best_squared
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        for &[a, b, c] in &self.corners[positions] {
            let d = point_triangle_distance_squared(self.p, &Triangle::new(a, b, c));
            self.best_squared = self.best_squared.min(d);
        }
        ControlFlow::Continue(())
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::float_cmp)]

    use super::*;
    use crate::shapes;

    fn brute(mesh: &TriMesh, p: DVec3) -> f64 {
        (0..mesh.triangle_count())
            .filter_map(|t| mesh.triangle(t))
            .map(|t| point_triangle_distance_squared(p, &t))
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
            assert!((tree.distance(p)? - answer.distance).abs() <= 1e-15 * (1.0 + answer.distance));
            let t = mesh.triangle(answer.triangle as usize).ok_or("triangle")?;
            assert!((point_triangle_distance_squared(answer.point, &t)).sqrt() < 1e-12);
        }
        Ok(())
    }

    #[test]
    fn points_on_the_surface_are_at_distance_zero() -> Result<(), Box<dyn std::error::Error>> {
        let cube = shapes::cube(2.0, 3)?;
        let tree = TriangleTree::new(&cube)?;
        for &p in cube.positions() {
            assert!(tree.distance(p)? < 1e-12);
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
            Err(MeshError::NonFiniteQuery { .. })
        ));
        assert!(matches!(
            tree.closest_within(DVec3::ZERO, -1.0),
            Err(MeshError::InvalidParameter { .. })
        ));
        assert!(matches!(
            tree.closest_within(DVec3::ZERO, f64::NAN),
            Err(MeshError::InvalidParameter { .. })
        ));
        let empty = TriMesh::new(vec![DVec3::ZERO], Vec::new())?;
        assert!(matches!(
            TriangleTree::new(&empty),
            Err(MeshError::EmptyMesh)
        ));
        Ok(())
    }
}
