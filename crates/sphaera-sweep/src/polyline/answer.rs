//! What polyline queries return: exact closest points and certified distance intervals.

/// Where on the polyline a closest point lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PolylineFeature {
    /// A vertex, by its index in the points given (a closed polyline's last segment ends at
    /// vertex 0).
    Vertex(usize),
    /// The interior of the segment (strictly between its two ends).
    SegmentInterior,
}

/// An exact closest point on a polyline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolylineClosest<P> {
    /// The closest point.
    pub point: P,
    /// Its distance to the query point.
    pub distance: f64,
    /// The segment it lies on: segment `i` joins vertex `i` to vertex `i + 1` (to vertex 0
    /// for the last segment of a closed polyline).
    pub segment: usize,
    /// Its parameter along that segment, in `[0, 1]` (`0` at vertex `i`; `0` on a segment
    /// of zero length).
    pub parameter: f64,
    /// The vertex it is, or the segment interior.
    pub feature: PolylineFeature,
}

/// A certified interval for the distance from a query point to a polyline: the true
/// distance `d` satisfies `lower ≤ d ≤ upper` (the polyline analogue of
/// [`DistanceBounds`](crate::DistanceBounds)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolylineBounds<P> {
    /// A lower bound of the distance (never negative).
    pub lower: f64,
    /// An upper bound of the distance.
    pub upper: f64,
    /// The exact answer when the process ran to the end (then `lower == upper ==
    /// closest.distance`).
    pub closest: Option<PolylineClosest<P>>,
    /// Capsule splits this query performed.
    pub splits: usize,
}

impl<P> PolylineBounds<P> {
    /// `upper − lower`.
    pub fn gap(&self) -> f64 {
        self.upper - self.lower
    }

    /// The middle of the interval, the estimate with the smallest worst-case error.
    pub fn midpoint(&self) -> f64 {
        0.5 * (self.lower + self.upper)
    }
}
