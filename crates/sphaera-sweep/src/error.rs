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
#[derive(Debug, thiserror::Error)]
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
    /// A mesh pose has a NaN or infinite entry.
    #[error("the mesh pose is not finite")]
    NonFinitePose,
    /// A mesh pose is not a rotation followed by a translation (it scales, shears or
    /// reflects).
    #[error("the mesh pose is not rigid: its linear part is {deviation} away from a rotation")]
    NotRigid {
        /// The largest entry of `|MᵀM − I|`, or `-det M` for a reflection.
        deviation: f64,
    },
    /// A hierarchy given for a deformation was not made from the sweeper's (by
    /// `replay`/`inflate`), so it does not share its tables.
    #[error("the hierarchy does not share the sweeper's tables (not made by replay or inflate)")]
    ForeignHierarchy,
    /// A per-vertex list has the wrong length.
    #[error("`{name}` has {actual} entries, expected {expected} (one per input vertex)")]
    LengthMismatch {
        /// The parameter's name, e.g. `"positions"`.
        name: &'static str,
        /// The length given.
        actual: usize,
        /// The input mesh's vertex count.
        expected: usize,
    },
    /// A per-vertex value is out of its domain.
    #[error("`{name}`[{index}] = {value}: must be {requirement}")]
    InvalidVertexValue {
        /// The parameter's name, e.g. `"displacement"`.
        name: &'static str,
        /// The input vertex.
        index: usize,
        /// The offending value (for a position, its largest coordinate magnitude or its
        /// distance from the reference).
        value: f64,
        /// What the value must be.
        requirement: &'static str,
    },
    /// The hierarchy cannot be deformed: it was built with optimal placement, or
    /// `sphaera-simplify` refused the deformation for another reason (the source error
    /// says which).
    #[error("cannot deform the hierarchy: {0}")]
    Deformation(#[source] sphaera_simplify::SimplifyError),
    /// The points given for a [`Polyline`](crate::polyline::Polyline) do not make one.
    #[error("invalid polyline: {0}")]
    InvalidPolyline(PolylineDefect),
    /// The triangle tree over the input mesh could not be built (more triangles than
    /// 32-bit indices address).
    #[error("cannot build the triangle tree of the input: {0}")]
    Tree(#[source] sphaera_query::QueryError),
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

impl From<sphaera_simplify::SimplifyError> for SweepError {
    fn from(error: sphaera_simplify::SimplifyError) -> Self {
        use sphaera_simplify::SimplifyError as E;
        match error {
            E::LengthMismatch {
                name,
                actual,
                expected,
            } => Self::LengthMismatch {
                name,
                actual,
                expected,
            },
            E::InvalidVertexValue {
                name,
                index,
                value,
                requirement,
            } => Self::InvalidVertexValue {
                name,
                index,
                value,
                requirement,
            },
            other => Self::Deformation(other),
        }
    }
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
