//! A polyline query session: the refined front of capsules and its priority queue, kept
//! between queries (paper sections 3.2, 3.3 and 5.1).

use super::curve::Polyline;
use super::hierarchy::ROOT;
use super::point::{PolylinePoint, closest_on_segment};
use super::{PolylineBounds, PolylineClosest};
use crate::error::check_non_negative;
use crate::queue::{Entry, Queue};
use crate::shifted_keys::ShiftedKeys;
use crate::{SessionStats, SweepError, Tolerance};

/// When a [`PolylineSession`] goes back to the root capsule before a query.
///
/// A session only refines its front; it coarsens all at once, by a reset, which costs
/// `O(front)`. Not resetting costs re-evaluating the stale capsules that reach the front
/// of the queue. The defaults reset when the front has grown past `max_front` capsules, or
/// when the query point jumped farther than `jump_factor` times the previous distance
/// (then most intervals are too wide to help, and the root is cheaper to start from). A
/// session also resets when its total motion passes 64 bounding-box diagonals (the
/// precision of the shifted keys).
///
/// # Examples
///
/// ```
/// use sphaera_sweep::polyline::PolylineSessionOptions;
///
/// let never_for_jumps = PolylineSessionOptions::default().with_jump_factor(f64::INFINITY);
/// assert_eq!(never_for_jumps.max_front, 16_384);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PolylineSessionOptions {
    /// Reset before a query when the front has more capsules than this.
    pub max_front: usize,
    /// Reset before a query when the query point moved more than this many times the
    /// previous answer's distance (`f64::INFINITY`: never for motion).
    pub jump_factor: f64,
    /// Answer [`PolylineSession::closest`] and [`PolylineSession::closest_within`] from
    /// the polyline's box tree of segments (`true`, the default: the fastest) or by
    /// refining the capsule hierarchy, the paper's way (`false`).
    /// [`PolylineSession::closest_with_budget`] always refines the hierarchy.
    pub exact_by_tree: bool,
}

impl Default for PolylineSessionOptions {
    fn default() -> Self {
        Self {
            max_front: 16_384,
            jump_factor: 1.0,
            exact_by_tree: true,
        }
    }
}

impl PolylineSessionOptions {
    /// With a reset past `n` capsules in the front.
    #[must_use]
    pub fn with_max_front(mut self, n: usize) -> Self {
        self.max_front = n;
        self
    }

    /// With a reset when the query point jumps more than `factor` times the previous
    /// distance.
    #[must_use]
    pub fn with_jump_factor(mut self, factor: f64) -> Self {
        self.jump_factor = factor;
        self
    }

    /// With exact and tolerance queries answered by the segment tree (`true`) or the
    /// paper's way (`false`).
    #[must_use]
    pub fn with_exact_by_tree(mut self, by_tree: bool) -> Self {
        self.exact_by_tree = by_tree;
        self
    }
}

/// The exact answer of the last closest-point query and the radius around its query
/// point inside which that segment stays a closest one (paper section 3.3).
#[derive(Clone, Copy, Debug)]
struct SafeBall<P> {
    center: P,
    radius: f64,
    segment: usize,
    /// The segment's position in the polyline's tree, when the tree answered.
    position: Option<usize>,
}

/// Why the sweep stopped.
enum Stop {
    /// The front capsule is a current leaf: exact.
    Exact(u32),
    /// The interval is narrow enough, or the budget ran out.
    Approximate { lower: f64 },
}

/// Meshsweeper on a polyline: a front of capsules covering the polyline (a cut of the
/// hierarchy) in a priority queue keyed by the lower ends of their distance intervals
/// `[d − ε, min(d + ε, |p − A|, |p − B|)]` (`d`: distance from the query `p` to the chord
/// `[A, B]`, `ε`: its error radius; see the [module docs](super) for why both ends hold).
///
/// A query takes the front capsule: a stale one (computed for an earlier query point) is
/// re-evaluated; an inner one is replaced by its two children; a leaf (one segment) is the
/// exact answer, since its interval is a single value below every other lower bound.
///
/// # Coherence
///
/// The front and the queue stay between queries. Moving the query point by `δ` widens
/// every interval by `δ` (a capsule's distance is 1-Lipschitz in the query point) without
/// reordering the queue: keys are stored shifted by the total motion. A query within the
/// *safe radius* of the last exact answer — half the gap between its distance and the
/// next lower bound in the queue, `(d₂ − ε₂ − d₁) / 2` — is answered from the same segment
/// with one point–segment distance and no queue work: moving by `δ ≤ r` takes that
/// segment at most `δ` farther and every other capsule at most `δ` nearer, so it stays a
/// closest one (section 3.3). [`PolylineSessionOptions`] says when the session
/// resets.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_sweep::{Tolerance, polyline::Polyline};
///
/// // A helix of 2000 points around the z axis, radius 1.
/// let helix: Vec<DVec3> = (0..2000)
///     .map(|i| {
///         let a = f64::from(i) * 0.05;
///         DVec3::new(a.cos(), a.sin(), 0.01 * a)
///     })
///     .collect();
/// let polyline = Polyline::open(helix)?;
/// let mut session = polyline.session();
///
/// // A smooth path of queries outside the helix.
/// for i in 0..100 {
///     let a = f64::from(i) * 0.01;
///     let p = DVec3::new(2.0 * a.cos(), 2.0 * a.sin(), 0.5);
///     let answer = session.closest(p)?;
///     assert!((answer.distance - 1.0).abs() < 1e-3);
/// }
///
/// // An anytime query: a certified interval at most 0.01 wide.
/// let bounds = session.closest_within(DVec3::new(0.0, 0.0, 1.0), Tolerance::Absolute(0.01))?;
/// assert!(bounds.lower <= 1.0 && 0.99 <= bounds.upper && bounds.gap() <= 0.01);
///
/// let stats = session.stats();
/// assert_eq!(stats.queries, 101);
/// # Ok::<(), sphaera_sweep::SweepError>(())
/// ```
#[derive(Clone, Debug)]
pub struct PolylineSession<'p, P> {
    polyline: &'p Polyline<P>,
    options: PolylineSessionOptions,
    queue: Queue,
    /// The point the queue's intervals were computed for (widened by the motion since).
    query: Option<P>,
    /// The key shift (total motion since the last reset) and the generation.
    keys: ShiftedKeys,
    /// The smallest upper bound seen for the current query point (widened by motion).
    best_upper: f64,
    /// The distance of the last exact answer (for the jump policy).
    last_distance: f64,
    safe: Option<SafeBall<P>>,
    stats: SessionStats,
}

impl<'p, P: PolylinePoint> PolylineSession<'p, P> {
    pub(crate) fn new(polyline: &'p Polyline<P>, options: PolylineSessionOptions) -> Self {
        Self {
            polyline,
            options,
            queue: Queue::new(polyline.node_count()),
            query: None,
            keys: ShiftedKeys::default(),
            best_upper: f64::INFINITY,
            last_distance: f64::INFINITY,
            safe: None,
            stats: SessionStats::default(),
        }
    }

    /// The exact closest point of the polyline to `p` (one of them, if several are at the
    /// same distance).
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] if a coordinate of `p` is NaN or infinite (in 2D its
    /// `z` is reported as 0).
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// Constant when `p` is inside the safe ball of the previous answer; otherwise the
    /// capsules whose intervals reach below the answer are split, `O(log n)` each. Worst
    /// case linear: at the centre of a polygonal circle every capsule is split (paper
    /// section 7).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_sweep::polyline::{Polyline, PolylineFeature};
    ///
    /// let polyline = Polyline::open(vec![DVec2::ZERO, DVec2::X, DVec2::new(1.0, 1.0)])?;
    /// let mut session = polyline.session();
    /// let below = session.closest(DVec2::new(0.5, -1.0))?;
    /// assert_eq!((below.segment, below.parameter), (0, 0.5));
    /// assert_eq!(below.feature, PolylineFeature::SegmentInterior);
    /// // Nearby: answered from the same segment, no queue work.
    /// let near = session.closest(DVec2::new(0.51, -1.01))?;
    /// assert!((near.distance - 1.01).abs() < 1e-15);
    /// assert_eq!(session.stats().constant_time, 1);
    ///
    /// let corner = session.closest(DVec2::new(2.0, -1.0))?;
    /// assert_eq!(corner.feature, PolylineFeature::Vertex(1));
    /// assert!((corner.distance - 2f64.sqrt()).abs() < 1e-15);
    /// # Ok::<(), sphaera_sweep::SweepError>(())
    /// ```
    pub fn closest(&mut self, p: P) -> Result<PolylineClosest<P>, SweepError> {
        let p = check_query(p)?;
        self.stats.queries += 1;
        if let Some(safe) = self.safe
            && (p - safe.center).length() <= safe.radius
            && let Some(answer) = self.polyline.closest_on(safe.segment, p)
        {
            self.stats.constant_time += 1;
            self.stats.distance_evaluations += 1;
            return Ok(answer);
        }
        if self.options.exact_by_tree {
            self.stats.tree_queries += 1;
            // A finite query on a polyline (at least one segment) always finds one.
            let seed = self.safe.and_then(|s| s.position);
            let found = self
                .polyline
                .tree()
                .search(p, None, seed)
                .ok_or(SweepError::EmptyMesh)?;
            let answer = self
                .polyline
                .closest_on(found.segment, p)
                .ok_or(SweepError::EmptyMesh)?;
            self.safe = Some(SafeBall {
                center: p,
                radius: (0.5 * (found.runner_up_squared.sqrt() - answer.distance)).max(0.0),
                segment: answer.segment,
                position: Some(found.position),
            });
            return Ok(answer);
        }
        self.move_to(p);
        let Stop::Exact(leaf) = self.sweep(p, None, usize::MAX) else {
            // Unreachable: without a tolerance or a budget the sweep runs to a leaf.
            return Err(SweepError::EmptyMesh);
        };
        let answer = self.exact(leaf, p)?;
        let second = self
            .queue
            .second_key()
            .map_or(f64::INFINITY, |k| self.lower(k));
        self.safe = Some(SafeBall {
            center: p,
            radius: (0.5 * (second - answer.distance)).max(0.0),
            segment: answer.segment,
            position: None,
        });
        Ok(answer)
    }

    /// A certified interval for the distance from `p` to the polyline, at most
    /// `tolerance` wide (or exact, if the process reaches a segment first).
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] for a non-finite `p`;
    /// [`SweepError::InvalidParameter`] for a negative or non-finite tolerance.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_sweep::{Tolerance, polyline::Polyline};
    ///
    /// let circle: Vec<DVec2> = (0..1000)
    ///     .map(|i| DVec2::from_angle(f64::from(i) * std::f64::consts::TAU / 1000.0))
    ///     .collect();
    /// let polyline = Polyline::closed(circle)?;
    /// let mut session = polyline.session();
    /// let bounds = session.closest_within(DVec2::new(3.0, 0.0), Tolerance::RelativeToUpper(0.01))?;
    /// assert!(bounds.lower <= 2.0 && 2.0 <= bounds.upper);
    /// assert!(bounds.gap() <= 0.01 * bounds.upper);
    /// # Ok::<(), sphaera_sweep::SweepError>(())
    /// ```
    pub fn closest_within(
        &mut self,
        p: P,
        tolerance: Tolerance,
    ) -> Result<PolylineBounds<P>, SweepError> {
        check_non_negative("tolerance", tolerance.value())?;
        if self.options.exact_by_tree {
            let p = check_query(p)?;
            self.stats.queries += 1;
            self.stats.tree_queries += 1;
            let gap = |upper: f64| tolerance.allowed_gap(upper);
            let found = self
                .polyline
                .tree()
                .search(p, Some(&gap), None)
                .ok_or(SweepError::EmptyMesh)?;
            let upper = found.distance_squared.sqrt();
            // Every other segment is at least this far.
            let lower = found.runner_up_squared.sqrt().min(upper);
            let closest = if lower >= upper {
                self.polyline.closest_on(found.segment, p)
            } else {
                None
            };
            return Ok(PolylineBounds {
                lower,
                upper,
                closest,
                splits: 0,
            });
        }
        self.bounded(p, Some(tolerance), usize::MAX)
    }

    /// A certified interval for the distance from `p` to the polyline after at most
    /// `max_splits` capsule splits (`0` answers from the current front).
    ///
    /// # Errors
    ///
    /// [`SweepError::NonFiniteQuery`] for a non-finite `p`.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_sweep::polyline::Polyline;
    ///
    /// let polyline = Polyline::open(vec![DVec2::ZERO, DVec2::new(1.0, 0.5), DVec2::X])?;
    /// let mut session = polyline.session();
    /// let rough = session.closest_with_budget(DVec2::new(0.5, -1.0), 0)?;
    /// assert!(rough.lower <= 1.0 && 1.0 <= rough.upper && rough.closest.is_none());
    /// # Ok::<(), sphaera_sweep::SweepError>(())
    /// ```
    pub fn closest_with_budget(
        &mut self,
        p: P,
        max_splits: usize,
    ) -> Result<PolylineBounds<P>, SweepError> {
        self.bounded(p, None, max_splits)
    }

    /// Back to the root capsule (also done automatically, see
    /// [`PolylineSessionOptions`]).
    pub fn reset(&mut self) {
        self.queue.clear();
        self.query = None;
        self.keys.restart();
        self.best_upper = f64::INFINITY;
        self.safe = None;
        self.stats.resets += 1;
    }

    /// The counters since the session was created (`splits` counts capsule splits,
    /// `distance_evaluations` point–segment distances).
    pub fn stats(&self) -> SessionStats {
        self.stats
    }

    /// The number of capsules in the front now.
    pub fn front_len(&self) -> usize {
        self.queue.len()
    }

    /// Bytes of this session's own state (the queue and its slots; the polyline is
    /// shared).
    pub fn memory_bytes(&self) -> usize {
        self.queue.bytes()
    }

    /// The bounded query behind [`Self::closest_within`] and
    /// [`Self::closest_with_budget`].
    fn bounded(
        &mut self,
        p: P,
        tolerance: Option<Tolerance>,
        max_splits: usize,
    ) -> Result<PolylineBounds<P>, SweepError> {
        let p = check_query(p)?;
        self.stats.queries += 1;
        self.move_to(p);
        let before = self.stats.splits;
        let stop = self.sweep(p, tolerance, max_splits);
        let splits = self.stats.splits - before;
        match stop {
            Stop::Exact(leaf) => {
                let answer = self.exact(leaf, p)?;
                Ok(PolylineBounds {
                    lower: answer.distance,
                    upper: answer.distance,
                    closest: Some(answer),
                    splits,
                })
            }
            Stop::Approximate { lower } => Ok(PolylineBounds {
                lower: lower.max(0.0).min(self.best_upper),
                upper: self.best_upper,
                closest: None,
                splits,
            }),
        }
    }

    /// Moves the query point to `p`: widens every interval by the motion (lazily, through
    /// the key shift), or resets per [`PolylineSessionOptions`].
    fn move_to(&mut self, p: P) {
        self.safe = None;
        let jump = self.query.map_or(0.0, |q| (p - q).length());
        if self.query.is_some() {
            let grown = self.queue.len() > self.options.max_front;
            let far = jump > self.options.jump_factor * self.last_distance;
            let imprecise = self.keys.exhausted(jump, self.polyline.diagonal());
            if grown || far || imprecise {
                self.reset();
            }
        }
        if self.query.is_none() || self.queue.len() == 0 {
            self.queue.clear();
            self.query = Some(p);
            self.keys.restart();
            self.best_upper = f64::INFINITY;
            self.evaluate(ROOT, p);
            return;
        }
        if jump > 0.0 {
            self.query = Some(p);
            self.keys.widen(jump);
            self.best_upper += jump;
        }
    }

    /// Until the front is a current leaf, the interval is within `tolerance`, or
    /// `max_splits` splits were made.
    fn sweep(&mut self, p: P, tolerance: Option<Tolerance>, max_splits: usize) -> Stop {
        let nodes = self.polyline.nodes();
        let mut splits = 0;
        loop {
            let Some(front) = self.queue.first() else {
                // Unreachable: the front always covers the polyline. Start over.
                self.evaluate(ROOT, p);
                continue;
            };
            if front.stamp != self.keys.stamp() {
                self.evaluate(front.triangle, p);
                continue;
            }
            let Some(node) = nodes.get(front.triangle as usize) else {
                self.queue.remove(front.triangle);
                continue;
            };
            if node.is_leaf() {
                return Stop::Exact(front.triangle);
            }
            let lower = self.lower(front.key);
            let done = tolerance.is_some_and(|t| {
                self.best_upper - lower.max(0.0) <= t.allowed_gap(self.best_upper)
            });
            if done || splits >= max_splits {
                return Stop::Approximate { lower };
            }
            self.queue.remove(front.triangle);
            self.evaluate(node.first_child, p);
            self.evaluate(node.first_child + 1, p);
            self.stats.splits += 1;
            splits += 1;
        }
    }

    /// The lower end of the interval of an entry with `key`: the key minus the motion
    /// since the reset, minus a rounding slack proportional to the motion.
    fn lower(&self, key: f64) -> f64 {
        self.keys.lower(key)
    }

    /// Computes the interval of capsule `id` for `p` and queues it.
    fn evaluate(&mut self, id: u32, p: P) {
        let Some(node) = self.polyline.nodes().get(id as usize) else {
            return;
        };
        let chain = self.polyline.chain();
        let (Some(&a), Some(&b)) = (chain.get(node.start as usize), chain.get(node.end as usize))
        else {
            return;
        };
        self.stats.distance_evaluations += 1;
        let hit = closest_on_segment(p, a, b);
        let d = hit.distance_squared.sqrt();
        let upper = if node.is_leaf() {
            d
        } else {
            let (pa, pb) = (p - a, p - b);
            (d + node.error).min(pa.dot(pa).min(pb.dot(pb)).sqrt())
        };
        self.best_upper = self.best_upper.min(upper);
        self.queue.set(Entry {
            key: self.keys.key(d - node.error),
            triangle: id,
            stamp: self.keys.stamp(),
        });
    }

    /// The exact answer on leaf `id`, remembering its distance for the jump policy.
    fn exact(&mut self, id: u32, p: P) -> Result<PolylineClosest<P>, SweepError> {
        let segment = self
            .polyline
            .nodes()
            .get(id as usize)
            .map(|n| n.start as usize);
        let answer = segment
            .and_then(|s| self.polyline.closest_on(s, p))
            .ok_or(SweepError::EmptyMesh)?;
        self.last_distance = answer.distance;
        self.best_upper = self.best_upper.min(answer.distance);
        Ok(answer)
    }
}

/// `Ok(p)` if every coordinate of `p` is finite.
fn check_query<P: PolylinePoint>(p: P) -> Result<P, SweepError> {
    if p.is_finite() {
        Ok(p)
    } else {
        let [x, y, z] = p.coordinates();
        Err(SweepError::NonFiniteQuery { x, y, z })
    }
}
