//! A query session: the refined mesh and the priority queue, kept between queries.

use glam::DVec3;
use sphaera_mesh::geometry::{Triangle, closest_point_on_triangle};
use sphaera_query::closest::TreeCursor;
use sphaera_simplify::{Hierarchy, Refinement};

use crate::error::{check_non_negative, check_point};
use crate::pose::Pose;
use crate::queue::{Entry, Queue};
use crate::shifted_keys::ShiftedKeys;
use crate::sweeper::WarmStart;
use crate::{
    ClosestPoint, DeformedShape, DistanceBounds, Feature, SessionStats, SweepError, Sweeper,
    Tolerance,
};

mod intervals;
mod motion;
mod options;
mod sweep;

pub use options::SessionOptions;

/// The exact answer of the last single closest-point query and the radius around its
/// query point inside which it stays the answer (paper section 3.3).
#[derive(Clone, Copy, Debug)]
struct SafeBall {
    center: DVec3,
    radius: f64,
    triangle: u32,
}

/// The changing state of Meshsweeper: a selectively refined mesh and a priority queue of
/// its triangles keyed by the lower end of their distance intervals `[d − ε, d + r]`
/// (`d`: distance to the simplified triangle, `ε`: its largest corner radius, `r`: the
/// radius interpolated at the closest point).
///
/// Each query pops the front triangle: a stale one ("dirty", computed for an earlier query
/// point) is re-evaluated; a simplified one has a corner split (with whatever must be
/// split first), its triangles re-queued; a triangle of the input mesh is the exact
/// answer, since its interval is a point and lies below every other interval. Between
/// queries the state stays: a query point moved by `δ` widens every interval by `δ`
/// without reordering the queue (section 5.1), so coherent queries only refine a little
/// more, and a query inside the safe ball of the previous answer costs one point–triangle
/// distance (section 3.3). See [`SessionOptions`] for when it resets.
///
/// The mesh can move too (sections 5.2–5.3). [`Session::move_mesh`] sets a rigid pose:
/// queries and answers are in world coordinates, the hierarchy stays in mesh coordinates,
/// and a pose change widens the intervals like a query move (by the smaller of the local
/// query point's displacement and a bound on the mesh's). [`Session::deform`] switches to
/// a deformed [`DeformedShape`] (key-frames, or inflated radii with [`Session::move_vertices`]):
/// the refined mesh is kept and every interval widened by the largest vertex displacement
/// plus the largest radius increase. Input triangles are always evaluated at their true
/// positions, so `closest` stays exact and every interval stays certified.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_sweep::{Sweeper, Tolerance, build_hierarchy};
///
/// let sphere = shapes::sphere(1.0, 24)?;
/// let hierarchy = build_hierarchy(&sphere)?;
/// let sweeper = Sweeper::new(&hierarchy)?;
/// let mut session = sweeper.session();
///
/// // A smooth path of queries: each refines only a little more.
/// for i in 0..100 {
///     let angle = i as f64 * 0.01;
///     let p = 2.0 * DVec3::new(angle.cos(), angle.sin(), 0.1);
///     let answer = session.closest(p)?;
///     // The mesh lies inside the unit sphere, within its tessellation error.
///     assert!((answer.distance - (p.length() - 1.0)).abs() < 0.05);
/// }
///
/// // An anytime query: a certified interval at most 1e-3 wide.
/// let bounds = session.closest_within(DVec3::new(0.0, 0.0, 3.0), Tolerance::Absolute(1e-3))?;
/// assert!(bounds.lower <= 2.0 + 1e-9 && 2.0 - 0.01 <= bounds.upper);
/// assert!(bounds.gap() <= 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Session<'s> {
    hierarchy: &'s Hierarchy,
    base: &'s [u32],
    /// The pre-refined state a reset goes back to; queue ids from `triangles` on are its
    /// spatial groups.
    warm: &'s WarmStart,
    /// Collapses undone at the warm start (once [`Session::warm_up`] has run).
    warm_undone: usize,
    /// Whether the warm start has been applied.
    warmed: bool,
    /// The split mark when the warm start's groups were last queued: a member touched by
    /// a later split has its own entry and is skipped when its group is expanded.
    warm_mark: u32,
    /// Hierarchy triangles (the first group id).
    triangles: u32,
    /// The bounding-box diagonal of the finest mesh (the scale of the precision rule).
    diagonal: f64,
    options: SessionOptions,
    refinement: Refinement<'s>,
    queue: Queue,
    /// The point the queue's intervals are computed for (widened by the motion since).
    query: Option<DVec3>,
    /// The key shift (total motion since the last reset) and the generation.
    keys: ShiftedKeys,
    /// The smallest upper bound seen for the current query point (widened by motion).
    best_upper: f64,
    /// The distance of the last answer (for the jump policy).
    last_distance: f64,
    safe: Option<SafeBall>,
    stats: SessionStats,
    undone: Vec<u32>,
    touched: Vec<u32>,
    /// Per triangle: the mark of the split that last re-queued it (dedupes `touched`).
    touched_at: Vec<u32>,
    /// The current split's mark (never `u32::MAX`, the "never" value).
    mark: u32,
    /// The mesh's pose: mesh coordinates to world coordinates.
    pose: Pose,
    /// The deformed geometry, or `None` for the hierarchy's own.
    shape: Option<DeformedShape>,
    /// With [`SessionOptions::exact_by_tree`]: the cursor over the input triangles, and
    /// the hierarchy id of each of its triangles.
    cursor: Option<(TreeCursor<'s>, &'s [u32])>,
    /// The bounding box of the current vertex positions (mesh coordinates).
    bounds: (DVec3, DVec3),
}

/// Why the sweep stopped.
enum Stop {
    /// The front triangle is a leaf: exact.
    Exact(u32),
    /// The interval is narrow enough, or the budget ran out.
    Approximate { lower: f64 },
    /// The queue is empty (every triangle was taken by a k-closest query).
    Empty,
}

impl<'s> Session<'s> {
    pub(crate) fn new(sweeper: &'s Sweeper<'s>, options: SessionOptions) -> Self {
        let hierarchy = sweeper.hierarchy();
        let warm = sweeper.warm_start();
        let mut session = Self {
            hierarchy,
            base: sweeper.base_triangles(),
            warm,
            warm_undone: 0,
            warmed: false,
            warm_mark: 0,
            triangles: hierarchy.triangle_count() as u32,
            diagonal: sweeper.diagonal(),
            options,
            // The hierarchy's state is made when a query first needs it (`warm_up`): a
            // session the tree answers never pays for it.
            refinement: Refinement::placeholder(hierarchy),
            queue: Queue::new(0),
            query: None,
            keys: ShiftedKeys::default(),
            best_upper: f64::INFINITY,
            last_distance: f64::INFINITY,
            safe: None,
            stats: SessionStats::default(),
            undone: Vec::new(),
            touched: Vec::new(),
            touched_at: Vec::new(),
            mark: 0,
            pose: Pose::IDENTITY,
            shape: None,
            bounds: (DVec3::ZERO, DVec3::ZERO),
            cursor: options.exact_by_tree.then(|| {
                let (tree, ids) = sweeper.finest();
                (tree.cursor(), ids)
            }),
        };
        if !options.exact_by_tree {
            session.warm_up();
        }
        session
    }

    /// Makes the hierarchy's state (the base mesh, the queue's slots, the mesh's bounds)
    /// and refines to the sweeper's warm start, once: every query that uses the hierarchy
    /// needs it, and a session that only answers from the tree never pays for it.
    pub(crate) fn warm_up(&mut self) {
        if self.warmed {
            return;
        }
        self.warmed = true;
        let triangles = self.hierarchy.triangle_count();
        self.refinement = self.hierarchy.refinement();
        self.queue = Queue::new(triangles + self.warm.node_count());
        self.touched_at = vec![u32::MAX; triangles];
        self.bounds = bounding_box(self.hierarchy.positions());
        let mut undone = Vec::new();
        for &c in self.warm.collapses() {
            // The warm start's collapses are valid and in a valid order (invariant);
            // an error would only leave the session colder.
            let _ = self.refinement.undo_collapse(c, &mut undone);
        }
        self.warm_undone = self.refinement.undone_count();
    }

    /// The exact closest point of the mesh to `p`.
    ///
    /// By default ([`SessionOptions::exact_by_tree`]) the sweeper's tree of input
    /// triangles answers, through a cursor that starts from the previous answer, while the
    /// mesh has its own shape; otherwise (the option off, or a deformed mesh) the
    /// hierarchy is refined, the paper's way.
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite.
    ///
    /// # Performance
    ///
    /// From the tree: logarithmic, about as fast as parry3d-f64's BVH (see the section
    /// *Closest-point queries (`sphaera-sweep`)* of `docs/benchmarks.md` in the
    /// repository). The paper's way: constant when `p` is inside the safe ball of the
    /// previous answer; otherwise the intervals still below the answer are re-evaluated and
    /// split. Worst case linear in the mesh size either way (a query at the centre of a
    /// sphere mesh touches every triangle).
    pub fn closest(&mut self, p: DVec3) -> Result<ClosestPoint, SweepError> {
        let p = self.pose.to_local(check_point(p)?);
        self.stats.queries += 1;
        if self.shape.is_none()
            && let Some((cursor, ids)) = &mut self.cursor
        {
            let shortcuts = cursor.shortcuts();
            // The point is finite and the tree non-empty, so the cursor answers.
            let hit = cursor.closest(p).map_err(|_| SweepError::EmptyMesh)?;
            if cursor.shortcuts() > shortcuts {
                self.stats.constant_time += 1;
            }
            self.stats.tree_queries += 1;
            let t = ids
                .get(hit.triangle as usize)
                .copied()
                .ok_or(SweepError::EmptyMesh)?;
            return Ok(self.to_world(self.tree_answer(hit, t)));
        }
        if let Some(safe) = self.safe
            && (p - safe.center).length() <= safe.radius
            && let Some(answer) = self.leaf_answer(safe.triangle, p)
        {
            self.stats.constant_time += 1;
            return Ok(self.to_world(answer));
        }
        self.move_to(p);
        match self.sweep(p, None, usize::MAX) {
            Stop::Exact(t) => {
                let answer = self.exact(t, p)?;
                let second = self
                    .queue
                    .second_key()
                    .map_or(f64::INFINITY, |k| self.lower(k));
                self.safe = Some(SafeBall {
                    center: p,
                    radius: (0.5 * (second - answer.distance)).max(0.0),
                    triangle: t,
                });
                Ok(self.to_world(answer))
            }
            Stop::Approximate { .. } | Stop::Empty => Err(SweepError::EmptyMesh),
        }
    }

    /// A certified interval for the distance from `p` to the mesh, at most `tolerance`
    /// wide (or exact, if the process reaches the input triangles first). With
    /// [`SessionOptions::exact_by_tree`] and the mesh in its own shape, the tree of input
    /// triangles answers (skipping every box that cannot bring the distance down by more
    /// than the tolerance); otherwise the hierarchy is refined, the paper's way.
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] for a non-finite `p`;
    /// [`SweepError::InvalidParameter`] for a negative or non-finite tolerance.
    pub fn closest_within(
        &mut self,
        p: DVec3,
        tolerance: Tolerance,
    ) -> Result<DistanceBounds, SweepError> {
        check_non_negative("tolerance", tolerance.value())?;
        if self.shape.is_none()
            && let Some((cursor, ids)) = &mut self.cursor
        {
            let local = self.pose.to_local(check_point(p)?);
            self.stats.queries += 1;
            self.stats.tree_queries += 1;
            let gap = |upper: f64| tolerance.allowed_gap(upper);
            // The point is finite and the tree non-empty, so the tree answers.
            let approx = cursor
                .closest_approx(local, &gap)
                .map_err(|_| SweepError::EmptyMesh)?;
            // Exact when the interval closed (lower never exceeds upper).
            let closest = if approx.lower >= approx.upper {
                let t = ids
                    .get(approx.nearest.triangle as usize)
                    .copied()
                    .ok_or(SweepError::EmptyMesh)?;
                Some(self.to_world(self.tree_answer(approx.nearest, t)))
            } else {
                None
            };
            return Ok(DistanceBounds {
                lower: approx.lower,
                upper: approx.upper,
                closest,
                splits: 0,
            });
        }
        self.bounded(p, Some(tolerance), usize::MAX)
    }

    /// A certified interval for the distance from `p` to the mesh after at most
    /// `max_splits` vertex splits (the anytime query: `0` answers from the current mesh).
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] for a non-finite `p`.
    pub fn closest_with_budget(
        &mut self,
        p: DVec3,
        max_splits: usize,
    ) -> Result<DistanceBounds, SweepError> {
        self.bounded(p, None, max_splits)
    }

    /// The `k` input triangles closest to `p`, nearest first, each with its closest point
    /// (fewer if the mesh has fewer triangles).
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] for a non-finite `p`.
    pub fn k_closest(&mut self, p: DVec3, k: usize) -> Result<Vec<ClosestPoint>, SweepError> {
        self.collect(p, k, f64::INFINITY)
    }

    /// Every input triangle within distance `d` of `p` (inclusive), nearest first, each
    /// with its closest point.
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] for a non-finite `p`;
    /// [`SweepError::InvalidParameter`] for a negative or non-finite `d`.
    pub fn within(&mut self, p: DVec3, d: f64) -> Result<Vec<ClosestPoint>, SweepError> {
        check_non_negative("distance", d)?;
        self.collect(p, usize::MAX, d)
    }

    /// Back to the base mesh (also done automatically, see [`SessionOptions`]).
    pub fn reset(&mut self) {
        self.warm_up();
        // A deformed session goes back to the base mesh: the warm start's bounds are for
        // the hierarchy's own geometry.
        let keep = if self.shape.is_none() {
            self.warm_undone
        } else {
            0
        };
        self.refinement.reset_to(keep);
        self.queue.clear();
        self.query = None;
        self.keys.restart();
        self.best_upper = f64::INFINITY;
        self.safe = None;
        self.stats.resets += 1;
    }

    /// The counters since the session was created.
    pub fn stats(&self) -> SessionStats {
        self.stats
    }

    /// Live triangles of the refined mesh now (0 until a query first needs the
    /// hierarchy: a session the tree answers never refines).
    pub fn live_triangle_count(&self) -> usize {
        self.refinement.live_triangle_count()
    }

    /// Bytes of this session's own state (the refinement and the queue, once a query
    /// needed the hierarchy; the hierarchy's tables are shared).
    pub fn memory_bytes(&self) -> usize {
        let state = if self.warmed {
            4 * (self.hierarchy.vertex_count() + self.hierarchy.collapse_count())
        } else {
            0
        };
        state
            + 4 * self.refinement.undone_count()
            + self.queue.bytes()
            + self.shape.as_ref().map_or(0, DeformedShape::bytes)
            + 4 * (self.undone.capacity() + self.touched.capacity() + self.touched_at.capacity())
    }

    /// Current position of vertex `v` (mesh coordinates).
    fn position(&self, v: u32) -> DVec3 {
        match &self.shape {
            Some(shape) => shape
                .positions()
                .get(v as usize)
                .copied()
                .unwrap_or(DVec3::ZERO),
            None => self.refinement.position(v),
        }
    }

    /// Current radius of present vertex `v`.
    fn radius(&self, v: u32) -> f64 {
        match &self.shape {
            // The tables were checked when the shape was set (invariant); an infinite
            // radius would only make the bound useless, never wrong.
            Some(shape) => self
                .refinement
                .radius_in(v, shape.radii())
                .unwrap_or(f64::INFINITY),
            None => self.refinement.radius(v),
        }
    }

    /// `answer` (mesh coordinates) in world coordinates.
    fn to_world(&self, answer: ClosestPoint) -> ClosestPoint {
        ClosestPoint {
            point: self.pose.to_world(answer.point),
            ..answer
        }
    }

    /// The bounded query behind [`Session::closest_within`] and
    /// [`Session::closest_with_budget`].
    fn bounded(
        &mut self,
        p: DVec3,
        tolerance: Option<Tolerance>,
        max_splits: usize,
    ) -> Result<DistanceBounds, SweepError> {
        let p = self.pose.to_local(check_point(p)?);
        self.stats.queries += 1;
        self.move_to(p);
        let before = self.stats.splits;
        let stop = self.sweep(p, tolerance, max_splits);
        let splits = self.stats.splits - before;
        match stop {
            Stop::Exact(t) => {
                let answer = self.exact(t, p)?;
                Ok(DistanceBounds {
                    lower: answer.distance,
                    upper: answer.distance,
                    closest: Some(self.to_world(answer)),
                    splits,
                })
            }
            Stop::Approximate { lower } => Ok(DistanceBounds {
                lower: lower.max(0.0),
                upper: self.best_upper,
                closest: None,
                splits,
            }),
            Stop::Empty => Err(SweepError::EmptyMesh),
        }
    }

    /// Takes leaves off the queue in order of distance while fewer than `k` are taken and
    /// the front's lower bound is at most `limit`; puts them back afterwards.
    fn collect(&mut self, p: DVec3, k: usize, limit: f64) -> Result<Vec<ClosestPoint>, SweepError> {
        let p = self.pose.to_local(check_point(p)?);
        self.stats.queries += 1;
        self.move_to(p);
        let mut taken: Vec<Entry> = Vec::new();
        let mut answers = Vec::new();
        while answers.len() < k {
            match self.sweep_until(p, limit) {
                Some(t) => {
                    let answer = self.exact(t, p)?;
                    if answer.distance > limit {
                        break;
                    }
                    answers.push(self.to_world(answer));
                    taken.extend(self.queue.remove(t));
                }
                None => break,
            }
        }
        for entry in taken {
            self.queue.set(entry);
        }
        Ok(answers)
    }

    /// The exact answer on leaf `t`, remembering its distance for the jump policy.
    fn exact(&mut self, t: u32, p: DVec3) -> Result<ClosestPoint, SweepError> {
        let answer = self.leaf_answer(t, p).ok_or(SweepError::EmptyMesh)?;
        self.last_distance = answer.distance;
        self.best_upper = self.best_upper.min(answer.distance);
        Ok(answer)
    }

    /// An answer of the sweeper's tree (hierarchy vertex ids, the tree's own triangle
    /// index) for hierarchy triangle `t`, named in the input mesh as
    /// [`Session::leaf_answer`] names it: the tree holds the finest positions, so the point
    /// and distance stand.
    fn tree_answer(&self, hit: ClosestPoint, t: u32) -> ClosestPoint {
        let input = |v: u32| self.hierarchy.original_vertex(v).unwrap_or(v);
        ClosestPoint {
            triangle: self.hierarchy.original_triangle(t).unwrap_or(t),
            feature: match hit.feature {
                Feature::Vertex(v) => Feature::Vertex(input(v)),
                Feature::Edge(a, b) => Feature::Edge(input(a), input(b)),
                Feature::Face => Feature::Face,
            },
            ..hit
        }
    }

    /// The closest point of input triangle `t` (a leaf) to `p`.
    fn leaf_answer(&self, t: u32, p: DVec3) -> Option<ClosestPoint> {
        let corners = self.hierarchy.triangle(t)?;
        let at = |i: usize| self.position(corners[i]);
        let triangle = Triangle::new(at(0), at(1), at(2));
        let hit = closest_point_on_triangle(p, &triangle);
        let original = corners.map(|v| self.hierarchy.original_vertex(v).unwrap_or(v));
        Some(ClosestPoint {
            point: hit.point,
            distance: hit.distance_squared.sqrt(),
            triangle: self.hierarchy.original_triangle(t).unwrap_or(t),
            feature: hit.feature.in_mesh(original),
        })
    }
}

/// The bounding box of `points` (an empty box far away if there are none).
pub(crate) fn bounding_box(points: &[DVec3]) -> (DVec3, DVec3) {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    if lo.is_finite() && hi.is_finite() {
        (lo, hi)
    } else {
        (DVec3::ZERO, DVec3::ZERO)
    }
}
