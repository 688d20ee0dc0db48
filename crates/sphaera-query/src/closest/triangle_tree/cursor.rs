//! [`TreeCursor`]: exact and approximate closest points for a stream of queries that move
//! a little at a time, starting from the previous answer.

use glam::DVec3;
use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};

use super::{ApproxClosest, TriangleTree};
use crate::QueryError;
use crate::closest::ClosestPoint;

impl TriangleTree {
    /// A cursor for a stream of queries that move a little at a time (a path, a moving
    /// body): see [`TreeCursor`].
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let sphere = shapes::sphere(1.0, 32)?;
    /// let tree = TriangleTree::new(&sphere)?;
    /// let mut cursor = tree.cursor();
    /// for i in 0..1000 {
    ///     let a = f64::from(i) * 1e-3;
    ///     let p = DVec3::new(2.0 * a.cos(), 2.0 * a.sin(), 0.3);
    ///     // The same distance an independent query finds.
    ///     let answer = cursor.closest(p)?;
    ///     assert!((answer.distance - tree.closest(p)?.distance).abs() < 1e-12);
    /// }
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    #[must_use]
    pub fn cursor(&self) -> TreeCursor<'_> {
        TreeCursor {
            tree: self,
            last: None,
            queries: 0,
            shortcuts: 0,
        }
    }
}

/// Exact closest points for a stream of queries that move a little at a time, from
/// [`TriangleTree::cursor`].
///
/// Each full search also bounds the distance of every other triangle (the nearest one
/// it did not take, or the nearest box it pruned). The next query checks the previous
/// answer's triangle first: if it is nearer than that bound minus the distance moved, it
/// is still the closest, found in constant time. Otherwise the descent starts with that
/// triangle's distance as its bound, which prunes most of the tree. Answers are exact,
/// as [`TriangleTree::closest`]'s; where two triangles are exactly as near, the one
/// chosen may differ from an independent query's.
#[derive(Clone, Debug)]
pub struct TreeCursor<'t> {
    tree: &'t TriangleTree,
    last: Option<Last>,
    queries: usize,
    shortcuts: usize,
}

/// What a cursor keeps of its last answer.
#[derive(Clone, Copy, Debug)]
struct Last {
    query: DVec3,
    /// The answer's tree position.
    position: usize,
    /// A lower bound on the distance from `query` of every other triangle.
    runner_up: f64,
}

impl TreeCursor<'_> {
    /// The exact closest point of the mesh to `p`.
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    pub fn closest(&mut self, p: DVec3) -> Result<ClosestPoint, QueryError> {
        QueryError::check_query(p)?;
        self.queries += 1;
        let tree = self.tree;
        let (search, runner_up) = match self.last {
            Some(last) => {
                let moved = (p - last.query).length();
                // Every other triangle is at least this far from `p`.
                let others = last.runner_up - moved;
                let answer = tree.answer_at(last.position, p);
                if answer.distance < others {
                    self.shortcuts += 1;
                    self.last = Some(Last {
                        query: p,
                        position: last.position,
                        runner_up: others,
                    });
                    return Ok(answer);
                }
                let [a, b, c] = tree.corners[last.position];
                let bound = point_triangle_distance_squared(p, &Triangle::new(a, b, c));
                let search = tree.search(p, bound, Some(last.position), None);
                let runner_up = search.runner_up_squared.sqrt();
                (search, runner_up)
            }
            None => {
                let search = tree.search(p, f64::INFINITY, None, None);
                let runner_up = search.runner_up_squared.sqrt();
                (search, runner_up)
            }
        };
        // A finite query on a non-empty tree always finds a triangle (invariant).
        let Some((position, _)) = search.best else {
            return Err(QueryError::EmptyMesh);
        };
        let answer = tree.answer_at(position, p);
        self.last = Some(Last {
            query: p,
            position,
            runner_up,
        });
        Ok(answer)
    }

    /// A certified interval for the distance from `p` to the mesh, at most `gap(upper)`
    /// wide, as [`TriangleTree::closest_approx`] gives, with the previous answer's
    /// triangle as the starting bound: on a path of small steps, once the distance is
    /// within the gap of 0 (or the previous triangle is still within the gap of the
    /// best possible), most queries prune the whole tree at its root.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_query::closest::TriangleTree;
    ///
    /// let sphere = shapes::sphere(1.0, 32)?;
    /// let tree = TriangleTree::new(&sphere)?;
    /// let mut cursor = tree.cursor();
    /// for i in 0..100 {
    ///     let a = f64::from(i) * 1e-3;
    ///     let p = DVec3::new(1.5 * a.cos(), 1.5 * a.sin(), 0.2);
    ///     let approx = cursor.closest_approx(p, &|_| 0.01)?;
    ///     let exact = tree.closest(p)?.distance;
    ///     assert!(approx.lower <= exact && exact <= approx.upper);
    ///     assert!(approx.upper - approx.lower <= 0.01);
    /// }
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    pub fn closest_approx(
        &mut self,
        p: DVec3,
        gap: &dyn Fn(f64) -> f64,
    ) -> Result<ApproxClosest, QueryError> {
        QueryError::check_query(p)?;
        self.queries += 1;
        let tree = self.tree;
        // After a small step, a search asks for half the gap: that leaves room for the
        // next queries' shortcut below (a jump would not use it, and a search for half
        // the gap costs more).
        let half = |upper: f64| 0.5 * gap(upper);
        let search = match self.last {
            Some(last) => {
                let [a, b, c] = tree.corners[last.position];
                let bound = point_triangle_distance_squared(p, &Triangle::new(a, b, c));
                // Every other triangle is at least `others` from `p`: if that is within
                // the gap of the previous triangle's distance, the interval between them
                // is narrow enough without a search.
                let moved = (p - last.query).length();
                let others = last.runner_up - moved;
                let upper = bound.sqrt();
                if others >= upper - gap(upper) {
                    self.shortcuts += 1;
                    self.last = Some(Last {
                        query: p,
                        position: last.position,
                        runner_up: others,
                    });
                    let nearest = tree.answer_at(last.position, p);
                    return Ok(ApproxClosest {
                        lower: others.max(0.0).min(nearest.distance),
                        upper: nearest.distance,
                        nearest,
                    });
                }
                if moved < 0.25 * gap(upper) {
                    tree.search(p, bound, Some(last.position), Some(&half))
                } else {
                    tree.search(p, bound, Some(last.position), Some(gap))
                }
            }
            None => tree.search(p, f64::INFINITY, None, Some(gap)),
        };
        // A finite query on a non-empty tree always finds a triangle (invariant).
        let Some((position, _)) = search.best else {
            return Err(QueryError::EmptyMesh);
        };
        let nearest = tree.answer_at(position, p);
        let runner_up = search.runner_up_squared.sqrt();
        // Every other triangle is at least `runner_up` away, so the exact shortcut of
        // the next query may use it too.
        self.last = Some(Last {
            query: p,
            position,
            runner_up,
        });
        Ok(ApproxClosest {
            lower: runner_up.min(nearest.distance),
            upper: nearest.distance,
            nearest,
        })
    }

    /// The tree this cursor walks.
    #[must_use]
    pub fn tree(&self) -> &TriangleTree {
        self.tree
    }

    /// Queries answered so far.
    #[must_use]
    pub fn queries(&self) -> usize {
        self.queries
    }

    /// Queries answered from the previous answer's triangle alone.
    #[must_use]
    pub fn shortcuts(&self) -> usize {
        self.shortcuts
    }
}
