//! The polyline type: validated points, open or closed, and its hierarchy of capsules.

use super::hierarchy::{self, Node};
use super::point::{PolylinePoint, closest_on_segment};
use super::session::{PolylineSession, PolylineSessionOptions};
use super::tree::SegmentTree;
use super::{PolylineClosest, PolylineFeature};
use crate::SweepError;
use crate::error::PolylineDefect;

/// The most points a polyline may have (node ids are 32-bit).
const MAX_POINTS: usize = (u32::MAX / 2) as usize;

/// A 2D or 3D polyline, open or closed, with its Douglas–Peucker hierarchy of capsules
/// (paper section 3.1), ready for [`PolylineSession`] queries.
///
/// Segment `i` joins vertex `i` to vertex `i + 1`; a closed polyline has one more segment,
/// from the last vertex back to vertex 0 (do not repeat the first point at the end: that
/// would add a segment of zero length, which works but is useless). Repeated consecutive
/// points (segments of zero length) are allowed.
///
/// The polyline is immutable and `Sync`; any number of sessions (one per thread) can
/// query it at once.
///
/// # Examples
///
/// ```
/// use glam::DVec2;
/// use sphaera_sweep::polyline::Polyline;
///
/// let square = Polyline::closed(vec![
///     DVec2::new(0.0, 0.0),
///     DVec2::new(1.0, 0.0),
///     DVec2::new(1.0, 1.0),
///     DVec2::new(0.0, 1.0),
/// ])?;
/// assert_eq!(square.segment_count(), 4);
/// assert_eq!(square.segment(3), Some((DVec2::new(0.0, 1.0), DVec2::new(0.0, 0.0))));
///
/// let mut session = square.session();
/// let answer = session.closest(DVec2::new(0.5, 0.2))?;
/// assert_eq!(answer.segment, 0);
/// assert!((answer.distance - 0.2).abs() < 1e-15);
/// # Ok::<(), sphaera_sweep::SweepError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Polyline<P> {
    /// The vertices; a closed polyline repeats vertex 0 at the end (so segment `i` is
    /// always `points[i]..points[i + 1]`).
    points: Vec<P>,
    /// The number of vertices given.
    vertex_count: usize,
    closed: bool,
    nodes: Vec<Node>,
    /// The box tree over the segments, for exact and tolerance queries.
    tree: SegmentTree<P>,
    diagonal: f64,
}

impl<P: PolylinePoint> Polyline<P> {
    /// An open polyline through `points`, in order.
    ///
    /// # Errors
    ///
    /// [`SweepError::InvalidPolyline`] with [`PolylineDefect::TooFewPoints`] (fewer than
    /// two points), [`PolylineDefect::NonFinitePoint`] (a NaN or infinite coordinate),
    /// [`PolylineDefect::AllCoincident`] (no two distinct points), or
    /// [`PolylineDefect::TooManyPoints`] (more than 2³¹ − 1).
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// Builds the hierarchy: `O(n log n)` for most curves, `O(n²)` in the worst case (see
    /// the [module docs](super)).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_sweep::{SweepError, polyline::{Polyline, PolylineDefect}};
    ///
    /// let line = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::X, DVec3::ONE])?;
    /// assert_eq!(line.segment_count(), 3); // one of zero length
    ///
    /// let error = Polyline::open(vec![DVec3::ZERO]).unwrap_err();
    /// assert!(matches!(
    ///     error,
    ///     SweepError::InvalidPolyline(PolylineDefect::TooFewPoints { count: 1 })
    /// ));
    /// # Ok::<(), SweepError>(())
    /// ```
    pub fn open(points: Vec<P>) -> Result<Self, SweepError> {
        Self::new(points, false)
    }

    /// A closed polyline through `points`, in order, and back to the first.
    ///
    /// # Errors
    ///
    /// As [`Polyline::open`].
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
    /// let there_and_back = Polyline::closed(vec![DVec2::ZERO, DVec2::X])?;
    /// assert_eq!(there_and_back.segment_count(), 2);
    /// # Ok::<(), sphaera_sweep::SweepError>(())
    /// ```
    pub fn closed(points: Vec<P>) -> Result<Self, SweepError> {
        Self::new(points, true)
    }

    /// A polyline through `points`, closed if `closed`.
    ///
    /// # Errors
    ///
    /// As [`Polyline::open`].
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
    /// let polyline = Polyline::new(vec![DVec2::ZERO, DVec2::X, DVec2::Y], true)?;
    /// assert!(polyline.is_closed());
    /// # Ok::<(), sphaera_sweep::SweepError>(())
    /// ```
    pub fn new(mut points: Vec<P>, closed: bool) -> Result<Self, SweepError> {
        let count = points.len();
        let defect = |defect| Err(SweepError::InvalidPolyline(defect));
        if count < 2 {
            return defect(PolylineDefect::TooFewPoints { count });
        }
        if count > MAX_POINTS {
            return defect(PolylineDefect::TooManyPoints {
                count,
                max: MAX_POINTS,
            });
        }
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return defect(PolylineDefect::NonFinitePoint { index });
        }
        let first = points[0];
        if points.iter().all(|&p| p == first) {
            return defect(PolylineDefect::AllCoincident { count });
        }
        let mut low = [f64::INFINITY; 3];
        let mut high = [f64::NEG_INFINITY; 3];
        let mut scale = 0.0_f64;
        for p in &points {
            let c = p.coordinates();
            for axis in 0..3 {
                low[axis] = low[axis].min(c[axis]);
                high[axis] = high[axis].max(c[axis]);
            }
            scale = scale.max(p.max_abs());
        }
        let diagonal = (0..3)
            .map(|axis| (high[axis] - low[axis]).powi(2))
            .sum::<f64>()
            .sqrt();
        if closed {
            points.push(first);
        }
        let nodes = hierarchy::build(&points, scale);
        let tree = SegmentTree::new(&points)?;
        Ok(Self {
            points,
            vertex_count: count,
            closed,
            nodes,
            tree,
            diagonal,
        })
    }

    /// The vertices, as given.
    pub fn points(&self) -> &[P] {
        self.points.get(..self.vertex_count).unwrap_or(&self.points)
    }

    /// Whether the last vertex joins the first.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The number of segments: vertices − 1 if open, vertices if closed.
    pub fn segment_count(&self) -> usize {
        self.points.len() - 1
    }

    /// Segment `i` as its two ends, or `None` past the last.
    pub fn segment(&self, i: usize) -> Option<(P, P)> {
        Some((*self.points.get(i)?, *self.points.get(i.checked_add(1)?)?))
    }

    /// The diagonal of the axis-aligned bounding box.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The number of capsules in the hierarchy (`2 · segments − 1`).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The error radius of the root capsule: the largest distance from the polyline to the
    /// chord from its first to its last vertex (to its first vertex, if closed).
    pub fn root_error(&self) -> f64 {
        self.nodes.first().map_or(0.0, |n| n.error)
    }

    /// Bytes held (points, hierarchy and segment tree).
    pub fn memory_bytes(&self) -> usize {
        self.points.capacity() * size_of::<P>()
            + self.nodes.capacity() * size_of::<Node>()
            + self.tree.memory_bytes()
    }

    /// A query session with the default [`PolylineSessionOptions`].
    pub fn session(&self) -> PolylineSession<'_, P> {
        PolylineSession::new(self, PolylineSessionOptions::default())
    }

    /// A query session with `options`.
    pub fn session_with(&self, options: &PolylineSessionOptions) -> PolylineSession<'_, P> {
        PolylineSession::new(self, *options)
    }

    /// The box tree over the segments.
    pub(crate) fn tree(&self) -> &SegmentTree<P> {
        &self.tree
    }

    /// The hierarchy (node 0 is the root).
    pub(crate) fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The vertex list with a closed polyline's first vertex repeated at the end.
    pub(crate) fn chain(&self) -> &[P] {
        &self.points
    }

    /// The exact closest point of segment `segment` to `p`.
    pub(crate) fn closest_on(&self, segment: usize, p: P) -> Option<PolylineClosest<P>> {
        let (a, b) = self.segment(segment)?;
        let hit = closest_on_segment(p, a, b);
        let feature = if hit.parameter <= 0.0 {
            PolylineFeature::Vertex(segment)
        } else if hit.parameter >= 1.0 {
            PolylineFeature::Vertex(if segment + 1 == self.vertex_count {
                0
            } else {
                segment + 1
            })
        } else {
            PolylineFeature::SegmentInterior
        };
        Some(PolylineClosest {
            point: hit.point,
            distance: hit.distance_squared.sqrt(),
            segment,
            parameter: hit.parameter,
            feature,
        })
    }
}
