//! What queries return besides exact closest points ([`ClosestPoint`], defined in
//! `sphaera-mesh`): certified distance intervals, tolerances and session counters.

use sphaera_query::closest::ClosestPoint;

/// A certified interval for the distance from a query point to the mesh: the true distance
/// `d` satisfies `lower ≤ d ≤ upper`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceBounds {
    /// A lower bound of the distance (never negative).
    pub lower: f64,
    /// An upper bound of the distance.
    pub upper: f64,
    /// The exact answer when the process ran to the end (then `lower == upper ==
    /// closest.distance`).
    pub closest: Option<ClosestPoint>,
    /// Vertex splits this query performed.
    pub splits: usize,
}

impl DistanceBounds {
    /// `upper − lower`.
    pub fn gap(&self) -> f64 {
        self.upper - self.lower
    }

    /// The middle of the interval, the estimate with the smallest worst-case error.
    pub fn midpoint(&self) -> f64 {
        0.5 * (self.lower + self.upper)
    }
}

/// When an approximate closest-point query may stop: once `upper − lower` is at most
/// this. (Tolerances relative to a mesh's size, such as the Hausdorff distance's, are a
/// [`Length`](sphaera_mesh::Length).)
///
/// # Examples
///
/// ```
/// use sphaera_sweep::Tolerance;
///
/// assert_eq!(Tolerance::Absolute(0.01).allowed_gap(5.0), 0.01);
/// assert_eq!(Tolerance::RelativeToUpper(0.01).allowed_gap(5.0), 0.05);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// An absolute gap, in the mesh's units.
    Absolute(f64),
    /// A fraction of the upper bound (`0.01`: the distance is known to 1 %).
    RelativeToUpper(f64),
}

impl Tolerance {
    /// The gap allowed when the upper bound is `upper`.
    pub fn allowed_gap(self, upper: f64) -> f64 {
        match self {
            Self::Absolute(t) => t,
            Self::RelativeToUpper(t) => t * upper,
        }
    }

    /// The tolerance's value.
    pub(crate) fn value(self) -> f64 {
        match self {
            Self::Absolute(t) | Self::RelativeToUpper(t) => t,
        }
    }
}

/// Counters of a [`Session`](crate::Session), cumulative since it was created.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SessionStats {
    /// Queries answered (each of `closest`, `closest_within`, `k_closest`, `within`).
    pub queries: usize,
    /// Of those, answered in constant time inside the safe radius of the previous answer
    /// (paper section 3.3), without touching the queue.
    pub constant_time: usize,
    /// Vertex splits (each may undo several collapses).
    pub splits: usize,
    /// Point–triangle distance evaluations.
    pub distance_evaluations: usize,
    /// Resets to the base mesh.
    pub resets: usize,
    /// Exact queries answered by the tree of input triangles
    /// ([`SessionOptions::exact_by_tree`](crate::SessionOptions::exact_by_tree)).
    pub tree_queries: usize,
}
