//! A static box tree over a mesh's triangles, for exact closest points of independent
//! queries (no coherence to exploit, no session state).

mod cursor;
mod descent;
#[cfg(test)]
mod tests;

use glam::DVec3;

use crate::QueryError;
use crate::bvh::BoxTree;
use sphaera_mesh::geometry::{Triangle, TriangleClosestPoint, closest_point_on_triangle};
use sphaera_mesh::{Aabb, TriMesh};

use super::ClosestPoint;

pub use cursor::TreeCursor;
use descent::{CornersBound, Distance, Search};

/// Triangles per leaf. Measured on the 69k bunny against 2, 4, 8 and 12: a leaf's
/// triangles are rejected by their boxes at little cost, and fewer levels mean fewer box
/// tests on the way down (uniform queries 1.4× faster than with 4).
pub(crate) const LEAF_SIZE: usize = 16;

/// Every triangle's box and centroid, the items of the box trees over a mesh's triangles
/// (the closest-point tree's and the winding number's).
pub(crate) fn triangle_boxes(mesh: &TriMesh) -> Vec<(Aabb, DVec3)> {
    let positions = mesh.positions();
    mesh.triangles()
        .iter()
        .map(|t| {
            let corners = t.map(|v| positions[v as usize]);
            let [a, b, c] = corners;
            (Aabb::from_points(corners), (a + b + c) / 3.0)
        })
        .collect()
}

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
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_query::closest::TriangleTree;
///
/// let cube = shapes::cube(2.0, 2)?; // the cube [-1, 1]³
/// let tree = TriangleTree::new(&cube)?;
/// let answer = tree.closest(DVec3::new(0.25, 0.0, 0.0))?;
/// assert!((answer.distance - 0.75).abs() < 1e-12);
/// assert!((answer.point.x - 1.0).abs() < 1e-12);
/// // Nothing within 0.5 of the centre.
/// assert!(tree.closest_within(DVec3::ZERO, 0.5)?.is_none());
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Debug, Clone)]
pub struct TriangleTree {
    boxes: BoxTree,
    /// Triangle corners in tree order.
    corners: Vec<[DVec3; 3]>,
    /// Mesh vertex indices of each entry of `corners`.
    vertices: Vec<[u32; 3]>,
    /// Vertices of the mesh the tree was built for.
    vertex_count: usize,
}

impl TriangleTree {
    /// Builds the tree over `mesh`'s triangles (median splits along the longest axis of
    /// the triangle centroids; deterministic).
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`] if the mesh has no triangle;
    /// [`QueryError::TooManyItems`] beyond what 32-bit triangle indices address.
    ///
    /// # Performance
    ///
    /// `O(n log n)` for `n` triangles; about 120 bytes per triangle.
    pub fn new(mesh: &TriMesh) -> Result<Self, QueryError> {
        if mesh.triangles().is_empty() {
            return Err(QueryError::EmptyMesh);
        }
        let boxes = BoxTree::build(&triangle_boxes(mesh), LEAF_SIZE)?;
        Ok(Self::with_boxes(mesh, boxes))
    }

    /// The tree over `mesh`'s triangles (at least one) with the box tree `boxes`, built
    /// over [`triangle_boxes`] with [`LEAF_SIZE`] (or refined from such a build).
    pub(crate) fn with_boxes(mesh: &TriMesh, boxes: BoxTree) -> Self {
        let positions = mesh.positions();
        let indexed = mesh.triangles();
        let corners_of = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
        let corners = boxes
            .order()
            .iter()
            .map(|&t| corners_of(&indexed[t as usize]))
            .collect();
        let vertices = boxes.order().iter().map(|&t| indexed[t as usize]).collect();
        Self {
            boxes,
            corners,
            vertices,
            vertex_count: positions.len(),
        }
    }

    /// The number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.corners.len()
    }

    /// Moves the mesh's vertices to `positions` (one per vertex of the mesh the tree was
    /// built from, same triangles) and refits every box, keeping the tree's shape: a
    /// deforming mesh gets exact answers again in one linear pass, without a new build.
    /// The splits fit large deformations worse than a new build would (queries slow
    /// down, never go wrong).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let sphere = shapes::sphere(1.0, 24)?;
    /// let mut tree = TriangleTree::new(&sphere)?;
    /// // Inflate the sphere to radius 2: the point at 3 along x is now 1 away.
    /// let moved: Vec<DVec3> = sphere.positions().iter().map(|&p| 2.0 * p).collect();
    /// tree.refit(&moved)?;
    /// let d = tree.closest(DVec3::new(3.0, 0.0, 0.0))?.distance;
    /// assert!((d - 1.0).abs() < 0.02);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::VertexCountMismatch`] for another number of positions;
    /// [`QueryError::Mesh`] (`MeshError::NonFiniteCoordinate`) for a NaN or infinite coordinate (the tree is
    /// left unchanged either way).
    ///
    /// # Performance
    ///
    /// Linear in the triangles, on every core with the `parallel` feature (the same tree
    /// either way); no allocation.
    pub fn refit(&mut self, positions: &[DVec3]) -> Result<(), QueryError> {
        if positions.len() != self.vertex_count {
            return Err(QueryError::VertexCountMismatch {
                expected: self.vertex_count,
                actual: positions.len(),
            });
        }
        TriMesh::check_positions(positions)?;
        let gather = |(corners, indices): (&mut [DVec3; 3], &[u32; 3])| {
            *corners = indices.map(|v| positions[v as usize]);
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            self.corners
                .par_iter_mut()
                .zip(self.vertices.par_iter())
                .with_min_len(4096)
                .for_each(gather);
        }
        #[cfg(not(feature = "parallel"))]
        self.corners.iter_mut().zip(&self.vertices).for_each(gather);
        let corners = &self.corners;
        self.boxes.refit(|i| Aabb::from_points(corners[i]));
        Ok(())
    }

    /// Bytes of the tree's arrays (corners, vertex indices, nodes and order).
    #[must_use]
    pub fn memory_bytes(&self) -> usize {
        size_of_val(self.corners.as_slice())
            + size_of_val(self.vertices.as_slice())
            + size_of_val(self.boxes.nodes())
            + size_of_val(self.boxes.order())
    }

    /// The exact closest point of the mesh to `p` (ties: the first triangle in the tree's
    /// order, so the same input gives the same answer).
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    ///
    /// # Performance
    ///
    /// Logarithmic for most queries; a point equidistant from much of the surface (the
    /// centre of a sphere mesh) visits all of it.
    pub fn closest(&self, p: DVec3) -> Result<ClosestPoint, QueryError> {
        match self.closest_within(p, f64::INFINITY)? {
            Some(answer) => Ok(answer),
            // Unreachable for a finite query on a non-empty tree; reported rather than
            // assumed.
            None => Err(QueryError::EmptyMesh),
        }
    }

    /// The exact closest point of the mesh to `p` if it lies within `max_distance`
    /// (inclusive), else `None`; a known bound prunes the descent from the start.
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] for a non-finite `p`;
    /// [`QueryError::InvalidParameter`] for a NaN or negative `max_distance`.
    pub fn closest_within(
        &self,
        p: DVec3,
        max_distance: f64,
    ) -> Result<Option<ClosestPoint>, QueryError> {
        QueryError::check_query(p)?;
        if max_distance.is_nan() || max_distance < 0.0 {
            return Err(QueryError::InvalidParameter {
                name: "max_distance",
                value: max_distance,
                requirement: "a non-negative number",
            });
        }
        let search = self.search(p, max_distance * max_distance, None, None);
        Ok(search.best.map(|(i, _)| self.answer_at(i, p)))
    }

    /// The exact closest point of every point of `points`, in order: [`TriangleTree::closest`]
    /// for each, on every core with the `parallel` feature (the answers are the same
    /// either way).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let tree = TriangleTree::new(&shapes::cube(2.0, 2)?)?; // the cube [-1, 1]³
    /// let points: Vec<DVec3> = (0..100).map(|i| DVec3::new(2.0 + f64::from(i), 0.0, 0.0)).collect();
    /// let answers = tree.closest_many(&points)?;
    /// assert_eq!(answers[7].distance, 8.0);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] for the first non-finite point (no answer is
    /// returned).
    pub fn closest_many(&self, points: &[DVec3]) -> Result<Vec<ClosestPoint>, QueryError> {
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            points.par_iter().map(|&p| self.closest(p)).collect()
        }
        #[cfg(not(feature = "parallel"))]
        {
            points.iter().map(|&p| self.closest(p)).collect()
        }
    }

    /// The descent: the nearest triangle within `bound_squared` (inclusive), starting
    /// from `seed` (a tree position already known at that squared distance, or `None`),
    /// and the smallest squared distance of anything else.
    fn search<'s>(
        &'s self,
        p: DVec3,
        bound_squared: f64,
        seed: Option<usize>,
        gap: Option<&'s dyn Fn(f64) -> f64>,
    ) -> Search<'s> {
        let mut search = Search {
            corners: &self.corners,
            p,
            best_squared: bound_squared,
            limit_squared: bound_squared,
            gap,
            best: None,
            runner_up_squared: f64::INFINITY,
        };
        if let Some(i) = seed {
            search.set_best(i, bound_squared);
        }
        self.boxes.search_nearest_first(p, &mut search);
        search
    }

    /// A certified interval for the distance from `p` to the mesh, at most `gap(upper)`
    /// wide, and the point of the mesh at distance `upper` (the closest point of the
    /// nearest triangle found): the descent skips every box that cannot bring the
    /// distance down by more than the gap allowed. With a gap of 0 it is
    /// [`TriangleTree::closest`] (`lower == upper`).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let sphere = shapes::sphere(1.0, 48)?;
    /// let tree = TriangleTree::new(&sphere)?;
    /// let p = DVec3::new(0.3, 2.5, -0.4);
    /// let exact = tree.closest(p)?.distance;
    /// let approx = tree.closest_approx(p, &|_| 0.05)?;
    /// assert!(approx.lower <= exact && exact <= approx.upper);
    /// assert!(approx.upper - approx.lower <= 0.05);
    /// assert_eq!(approx.nearest.distance, approx.upper);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    pub fn closest_approx(
        &self,
        p: DVec3,
        gap: &dyn Fn(f64) -> f64,
    ) -> Result<ApproxClosest, QueryError> {
        QueryError::check_query(p)?;
        let search = self.search(p, f64::INFINITY, None, Some(gap));
        // A finite query on a non-empty tree always finds a triangle (invariant).
        let Some((i, _)) = search.best else {
            return Err(QueryError::EmptyMesh);
        };
        let nearest = self.answer_at(i, p);
        let upper = nearest.distance;
        let lower = search.runner_up_squared.sqrt().min(upper);
        Ok(ApproxClosest {
            lower,
            upper,
            nearest,
        })
    }

    /// [`TriangleTree::closest_approx`] for every point of `points`, each interval at most
    /// `gap` wide, in order: on every core with the `parallel` feature (the answers are the
    /// same either way). What `sphaera distance --tolerance` and Python's
    /// `sphaera.distance(..., tolerance=)` answer: the interval and, always, the point of
    /// the mesh at distance `upper` (the closest point itself when `lower == upper`).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let tree = TriangleTree::new(&shapes::sphere(1.0, 32)?)?;
    /// let points: Vec<DVec3> = (0..50).map(|i| DVec3::new(2.0, f64::from(i) * 0.1, 0.0)).collect();
    /// let answers = tree.closest_approx_many(&points, 0.01)?;
    /// for (p, a) in points.iter().zip(&answers) {
    ///     let exact = tree.closest(*p)?.distance;
    ///     assert!(a.lower <= exact && exact <= a.upper && a.upper - a.lower <= 0.01);
    /// }
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] for a non-finite point (no answer is returned);
    /// [`QueryError::InvalidParameter`] for a negative or NaN `gap`.
    pub fn closest_approx_many(
        &self,
        points: &[DVec3],
        gap: f64,
    ) -> Result<Vec<ApproxClosest>, QueryError> {
        if gap.is_nan() || gap < 0.0 {
            return Err(QueryError::InvalidParameter {
                name: "gap",
                value: gap,
                requirement: "non-negative",
            });
        }
        let one = |&p: &DVec3| self.closest_approx(p, &|_| gap);
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            points.par_iter().map(one).collect()
        }
        #[cfg(not(feature = "parallel"))]
        {
            points.iter().map(one).collect()
        }
    }

    /// An upper bound of the distance from **every point** of the triangle with corners
    /// `corners` to the mesh: the smallest, over the mesh's triangles `T`, of the largest
    /// distance from a corner to `T`. The distance to a triangle is convex, so over the
    /// triangle `corners` it is largest at a corner, and the distance to the mesh is at
    /// most the distance to any one `T`. The descent stops at the first `T` whose bound is
    /// at most `enough` (pass 0 for the smallest).
    ///
    /// Computed in floating point: callers that certify add their rounding slack.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let tree = TriangleTree::new(&shapes::cube(2.0, 2)?)?; // the cube [-1, 1]³
    /// // A small triangle floating 0.5 above the top face, over one of its triangles.
    /// let corners = [DVec3::new(0.75, -0.55, 1.5), DVec3::new(0.85, -0.55, 1.5), DVec3::new(0.8, -0.45, 1.5)];
    /// assert!((tree.triangle_upper_bound(corners, 0.0)? - 0.5).abs() < 1e-12);
    /// // A large one straddles several: no single triangle lies under it, the bound grows.
    /// let large = [DVec3::new(-0.9, -0.9, 1.5), DVec3::new(0.9, -0.9, 1.5), DVec3::new(0.0, 0.9, 1.5)];
    /// assert!(tree.triangle_upper_bound(large, 0.0)? > 0.6);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] if a corner has a NaN or infinite coordinate.
    pub fn triangle_upper_bound(
        &self,
        corners: [DVec3; 3],
        enough: f64,
    ) -> Result<f64, QueryError> {
        for &p in &corners {
            QueryError::check_query(p)?;
        }
        let mut search = CornersBound {
            corners: &self.corners,
            x: corners,
            best_squared: f64::INFINITY,
            enough_squared: enough.max(0.0) * enough.max(0.0),
        };
        let key = |bounds: &Aabb| {
            corners
                .iter()
                .map(|&p| bounds.distance_squared_to_point(p))
                .fold(0.0_f64, f64::max)
        };
        self.boxes.search_nearest_first_by(key, &mut search);
        Ok(search.best_squared.sqrt())
    }

    /// The box tree over the triangles (its [`BoxTree::order`] maps tree positions to
    /// mesh triangles).
    pub(crate) fn boxes(&self) -> &BoxTree {
        &self.boxes
    }

    /// The triangles' corners, in tree order.
    pub(crate) fn corners(&self) -> &[[DVec3; 3]] {
        &self.corners
    }

    /// The triangles' vertex indices, in tree order.
    pub(crate) fn vertices(&self) -> &[[u32; 3]] {
        &self.vertices
    }

    /// The answer on the triangle at tree position `i`.
    pub(crate) fn answer_at(&self, i: usize, p: DVec3) -> ClosestPoint {
        let [a, b, c] = self.corners[i];
        let hit = closest_point_on_triangle(p, &Triangle::new(a, b, c));
        self.answer(i, p, &hit)
    }

    /// The distance from `p` to the mesh, for callers that need only the number: the
    /// same descent as [`TriangleTree::closest`] with the cheaper
    /// [`point_triangle_distance_squared`](sphaera_mesh::geometry::point_triangle_distance_squared)
    /// per triangle (faster; it may differ from `closest(p)?.distance` in the last bit).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let tree = TriangleTree::new(&shapes::cube(2.0, 2)?)?; // the cube [-1, 1]³
    /// assert!((tree.distance(DVec3::new(3.0, 0.5, 0.0))? - 2.0).abs() < 1e-12);
    /// assert!(tree.distance(DVec3::NAN).is_err());
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    pub fn distance(&self, p: DVec3) -> Result<f64, QueryError> {
        QueryError::check_query(p)?;
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

/// What [`TriangleTree::closest_approx`] returns: a certified interval for the distance
/// and a point of the mesh at its upper end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ApproxClosest {
    /// A lower bound of the distance.
    pub lower: f64,
    /// An upper bound of the distance: `nearest.distance`.
    pub upper: f64,
    /// The closest point of the nearest triangle found (the exact answer when
    /// `lower == upper`).
    pub nearest: ClosestPoint,
}
