//! The error type of `sphaera-sweep`.

/// Everything that can go wrong with a distance query.
///
/// Messages are lowercase without a final period, so they compose into larger messages.
///
/// # Examples
///
/// ```
/// use sphaera_sweep::SweepError;
///
/// let error = SweepError::NonFiniteQuery { x: f64::NAN, y: 0.0, z: 1.0 };
/// assert_eq!(error.to_string(), "the query point (NaN, 0, 1) is not finite");
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    /// The query point has a NaN or infinite coordinate.
    #[error("the query point ({x}, {y}, {z}) is not finite")]
    NonFiniteQuery {
        /// The x coordinate given.
        x: f64,
        /// The y coordinate given.
        y: f64,
        /// The z coordinate given.
        z: f64,
    },
    /// The hierarchy has no triangle, so there is no closest point.
    #[error("the mesh has no triangles")]
    EmptyMesh,
    /// A parameter is out of its domain (NaN, negative, or out of range).
    #[error("invalid `{name}` ({value}): must be {requirement}")]
    InvalidParameter {
        /// The parameter's name as it appears in the API, e.g. `"tolerance"`.
        name: &'static str,
        /// The value supplied.
        value: f64,
        /// What the value must be, e.g. `"finite and non-negative"`.
        requirement: &'static str,
    },
    /// The points given for a [`Polyline`](crate::polyline::Polyline) do not make one.
    #[error("invalid polyline: {0}")]
    InvalidPolyline(PolylineDefect),
}

/// What makes a list of points not a [`Polyline`](crate::polyline::Polyline), in
/// [`SweepError::InvalidPolyline`].
///
/// # Examples
///
/// ```
/// use sphaera_sweep::{SweepError, polyline::PolylineDefect};
///
/// let error = SweepError::InvalidPolyline(PolylineDefect::NonFinitePoint { index: 3 });
/// assert_eq!(error.to_string(), "invalid polyline: point 3 has a non-finite coordinate");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PolylineDefect {
    /// Fewer than two points: no segment. Give at least two.
    #[error("{count} point(s) given, at least 2 are needed")]
    TooFewPoints {
        /// The number of points given.
        count: usize,
    },
    /// A coordinate is NaN or infinite. Drop or repair that point.
    #[error("point {index} has a non-finite coordinate")]
    NonFinitePoint {
        /// Its index in the points given.
        index: usize,
    },
    /// Every point is the same point: the polyline has no extent, and no segment has a
    /// direction. (Repeated points among distinct ones are fine.)
    #[error("all {count} points coincide")]
    AllCoincident {
        /// The number of points given.
        count: usize,
    },
    /// More points than the 32-bit node ids of the hierarchy can index.
    #[error("{count} points given, at most {max} are supported")]
    TooManyPoints {
        /// The number of points given.
        count: usize,
        /// The largest number supported.
        max: usize,
    },
}

/// `Ok(p)` if every coordinate of `p` is finite.
pub(crate) fn check_point(p: glam::DVec3) -> Result<glam::DVec3, SweepError> {
    if p.is_finite() {
        Ok(p)
    } else {
        Err(SweepError::NonFiniteQuery {
            x: p.x,
            y: p.y,
            z: p.z,
        })
    }
}

/// `Ok(value)` if `value` is finite and non-negative.
pub(crate) fn check_non_negative(name: &'static str, value: f64) -> Result<f64, SweepError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(SweepError::InvalidParameter {
            name,
            value,
            requirement: "finite and non-negative",
        })
    }
}
