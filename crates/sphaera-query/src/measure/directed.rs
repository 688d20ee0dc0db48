//! One direction: the largest distance from a set of points to a target, over any distance
//! oracle.

use glam::DVec3;

/// The distance from each of `points` to a target, in order: `distance_to_target(p)` for
/// every `p`, in parallel with the `parallel` feature (the result is the same either way:
/// each value is computed on its own and collected in order).
///
/// `distance_to_target` is any oracle: [`crate::closest::TriangleTree::distance`], a brute
/// force over every triangle, another library's projection.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::DVec3;
/// use sphaera_query::measure;
///
/// let points = [DVec3::ZERO, DVec3::new(0.0, 3.0, 4.0)];
/// assert_eq!(measure::distances(&points, |p| p.length()), vec![0.0, 5.0]);
/// ```
pub fn distances<D>(points: &[DVec3], distance_to_target: D) -> Vec<f64>
where
    D: Fn(DVec3) -> f64 + Sync,
{
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        let distance_to_target = &distance_to_target;
        points.par_iter().map(|&p| distance_to_target(p)).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        points.iter().map(|&p| distance_to_target(p)).collect()
    }
}

/// The sample where a [`DirectedDistance`] is reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Farthest {
    /// Its index among the points measured.
    pub index: usize,
    /// The point.
    pub point: DVec3,
}

/// The largest distance from a set of points to a target, where it is reached and how many
/// points were measured.
///
/// When the points lie on a surface `A` and the distances are to a surface `B`, the value
/// is a **lower bound** of the directed Hausdorff distance `h(A → B)` (see the
/// [module documentation](super)).
///
/// The maximum is deterministic: ties go to the lowest index, and a NaN distance (an
/// oracle that could not measure a point, such as a non-finite one) never becomes the
/// maximum.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::DVec3;
/// use sphaera_query::measure::DirectedDistance;
///
/// let points = [DVec3::X, DVec3::new(0.0, -2.0, 0.0), DVec3::new(0.0, 0.0, 2.0)];
/// let to_origin = |p: DVec3| p.length();
/// let directed = DirectedDistance::measure(&points, to_origin);
/// assert_eq!(directed.distance, 2.0);
/// let farthest = directed.farthest.unwrap();
/// assert_eq!((farthest.index, farthest.point), (1, points[1])); // the first of the tie
/// assert_eq!(directed.measured, 3);
/// assert_eq!(directed, DirectedDistance::measure_on_this_thread(&points, to_origin));
///
/// let nothing = DirectedDistance::measure(&[], to_origin);
/// assert_eq!((nothing.distance, nothing.farthest, nothing.measured), (0.0, None, 0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectedDistance {
    /// The largest distance measured; 0 when no point has a distance.
    pub distance: f64,
    /// Where it is reached; `None` when no point has a distance.
    pub farthest: Option<Farthest>,
    /// How many points were measured (handed to the oracle).
    pub measured: usize,
}

impl DirectedDistance {
    /// Measures every point with `distance_to_target`, in parallel with the `parallel`
    /// feature ([`distances`]), and keeps the largest.
    ///
    /// # Performance
    ///
    /// One oracle call per point, and a vector of one `f64` per point.
    pub fn measure<D>(points: &[DVec3], distance_to_target: D) -> Self
    where
        D: Fn(DVec3) -> f64 + Sync,
    {
        Self::from_distances(points, &distances(points, distance_to_target))
    }

    /// [`DirectedDistance::measure`] on the calling thread only, whatever the features:
    /// for a baseline timed on one thread. The result is the same.
    pub fn measure_on_this_thread<D>(points: &[DVec3], mut distance_to_target: D) -> Self
    where
        D: FnMut(DVec3) -> f64,
    {
        let mut result = Self::from_distances(&[], &[]);
        for (index, &point) in points.iter().enumerate() {
            result.consider(index, point, distance_to_target(point));
        }
        result.measured = points.len();
        result
    }

    /// The largest of `distances` measured from `points` (paired in order; the longer
    /// slice's extra entries are ignored).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::DVec3;
    /// use sphaera_query::measure::DirectedDistance;
    ///
    /// let points = [DVec3::X, DVec3::Y, DVec3::Z];
    /// let directed = DirectedDistance::from_distances(&points, &[0.5, f64::NAN, 0.75]);
    /// assert_eq!(directed.distance, 0.75);
    /// assert_eq!(directed.farthest.map(|f| f.point), Some(DVec3::Z));
    /// ```
    pub fn from_distances(points: &[DVec3], distances: &[f64]) -> Self {
        let mut result = Self {
            distance: 0.0,
            farthest: None,
            measured: 0,
        };
        for (index, (&point, &distance)) in points.iter().zip(distances).enumerate() {
            result.consider(index, point, distance);
            result.measured += 1;
        }
        result
    }

    /// Takes `distance` at `point` if it is larger than the best so far (the first number
    /// is always taken; NaN never is).
    fn consider(&mut self, index: usize, point: DVec3, distance: f64) {
        if distance.is_nan() {
            return;
        }
        if self.farthest.is_none() || distance > self.distance {
            self.distance = distance;
            self.farthest = Some(Farthest { index, point });
        }
    }
}
