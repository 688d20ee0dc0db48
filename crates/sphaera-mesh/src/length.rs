//! A length given absolutely or relative to a mesh's size.

/// A length in the mesh's units, or as a fraction of its bounding-box diagonal: how error
/// bounds and tolerances are given, so the same setting means the same thing on a
/// 0.25 m scan and a 100 m model.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::Length;
///
/// assert_eq!(Length::Absolute(0.5).resolve(10.0), 0.5);
/// assert_eq!(Length::RelativeToDiagonal(0.01).resolve(10.0), 0.1);
/// assert_eq!(Length::RelativeToDiagonal(0.01).value(), 0.01);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// In the mesh's length unit.
    Absolute(f64),
    /// As a fraction of the mesh's bounding-box diagonal.
    RelativeToDiagonal(f64),
}

impl Length {
    /// The length in the mesh's units, for a mesh whose bounding-box diagonal is
    /// `diagonal`.
    #[must_use]
    pub fn resolve(self, diagonal: f64) -> f64 {
        match self {
            Self::Absolute(length) => length,
            Self::RelativeToDiagonal(fraction) => fraction * diagonal,
        }
    }

    /// The number as given (a length or a fraction), for validation messages.
    #[must_use]
    pub fn value(self) -> f64 {
        match self {
            Self::Absolute(x) | Self::RelativeToDiagonal(x) => x,
        }
    }
}
