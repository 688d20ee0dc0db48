//! How much error a scene accepts: world units, a fraction of each object's size, or
//! pixels on a camera's screen.

use std::fmt;
use std::str::FromStr;

use sphaera_mesh::Length;

use crate::SceneError;

/// The error a scene accepts for each instance: a [`Length`] (absolute, or relative to
/// each instance's diagonal), or pixels on a camera.
///
/// - [`Tolerance::Absolute`]: a distance in the scene's units (what a physics engine wants:
///   "no contact off by more than 1 mm").
/// - [`Tolerance::RelativeToDiagonal`]: a fraction of each instance's own size (the
///   bounding-box diagonal of its mesh, scaled by its pose): "0.5 % of each object".
/// - [`Tolerance::Pixels`]: pixels on a [`Camera`](crate::Camera)'s image, certified
///   under perspective (see [`Camera::pixels_per_unit`](crate::Camera::pixels_per_unit)).
///
/// Parsed from text as the CLI takes it: `0.01` (absolute), `0.5%` (relative, as
/// [`Length`] parses it), `2px`.
///
/// # Examples
///
/// ```
/// use sphaera_scene::Tolerance;
///
/// assert_eq!("0.01".parse::<Tolerance>()?, Tolerance::Absolute(0.01));
/// assert_eq!("0.5%".parse::<Tolerance>()?, Tolerance::RelativeToDiagonal(0.005));
/// assert_eq!("2px".parse::<Tolerance>()?, Tolerance::Pixels(2.0));
/// assert_eq!(Tolerance::Pixels(2.0).to_string(), "2px");
/// assert!("nan".parse::<Tolerance>().is_err());
/// # Ok::<(), sphaera_scene::SceneError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// A distance in the scene's units.
    Absolute(f64),
    /// A fraction of each instance's bounding-box diagonal (0.005 for 0.5 %).
    RelativeToDiagonal(f64),
    /// Pixels on the camera's image.
    Pixels(f64),
}

impl Tolerance {
    /// The number, whatever its unit.
    #[must_use]
    pub fn value(&self) -> f64 {
        match *self {
            Self::Absolute(v) | Self::RelativeToDiagonal(v) | Self::Pixels(v) => v,
        }
    }

    /// The same tolerance `k` times as large, in the same unit.
    #[must_use]
    pub fn scaled(self, k: f64) -> Self {
        match self {
            Self::Absolute(v) => Self::Absolute(v * k),
            Self::RelativeToDiagonal(v) => Self::RelativeToDiagonal(v * k),
            Self::Pixels(v) => Self::Pixels(v * k),
        }
    }

    /// The unit's name in reports: `"world"`, `"relative"` or `"px"`.
    #[must_use]
    pub fn unit(&self) -> &'static str {
        match self {
            Self::Absolute(_) => "world",
            Self::RelativeToDiagonal(_) => "relative",
            Self::Pixels(_) => "px",
        }
    }

    /// `Ok(self)` when the number is finite and not negative.
    ///
    /// # Errors
    ///
    /// [`SceneError::InvalidTolerance`] otherwise.
    pub fn validated(self) -> Result<Self, SceneError> {
        let v = self.value();
        if v.is_finite() && v >= 0.0 {
            Ok(self)
        } else {
            Err(SceneError::InvalidTolerance {
                text: self.to_string(),
            })
        }
    }
}

impl From<Length> for Tolerance {
    fn from(length: Length) -> Self {
        match length {
            Length::Absolute(v) => Self::Absolute(v),
            Length::RelativeToDiagonal(v) => Self::RelativeToDiagonal(v),
        }
    }
}

impl fmt::Display for Tolerance {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Absolute(v) => write!(f, "{v}"),
            Self::RelativeToDiagonal(v) => write!(f, "{}%", v * 100.0),
            Self::Pixels(v) => write!(f, "{v}px"),
        }
    }
}

impl FromStr for Tolerance {
    type Err = SceneError;

    fn from_str(text: &str) -> Result<Self, SceneError> {
        let invalid = || SceneError::InvalidTolerance {
            text: text.to_owned(),
        };
        let trimmed = text.trim();
        let tolerance = if let Some(px) = trimmed.strip_suffix("px") {
            Self::Pixels(px.trim().parse::<f64>().map_err(|_| invalid())?)
        } else {
            trimmed.parse::<Length>().map_err(|_| invalid())?.into()
        };
        tolerance.validated().map_err(|_| invalid())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_unit_parses_and_bad_text_is_refused() {
        assert_eq!(
            " 3 px ".parse::<Tolerance>().ok(),
            Some(Tolerance::Pixels(3.0))
        );
        assert_eq!(
            "10%".parse::<Tolerance>().ok(),
            Some(Tolerance::RelativeToDiagonal(0.1))
        );
        assert_eq!(
            "0".parse::<Tolerance>().ok(),
            Some(Tolerance::Absolute(0.0))
        );
        for bad in ["", "px", "%", "-1", "inf", "NaN%", "2 pixels", "1e400"] {
            assert!(bad.parse::<Tolerance>().is_err(), "{bad}");
        }
    }
}
