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
/// // Read as people write it: a number, or a percentage of the diagonal.
/// assert_eq!("2%".parse::<Length>()?, Length::RelativeToDiagonal(0.02));
/// assert_eq!(" 0.5 ".parse::<Length>()?, Length::Absolute(0.5));
/// assert!("-1".parse::<Length>().is_err());
/// assert_eq!(Length::RelativeToDiagonal(0.02).to_string(), "2%");
/// # Ok::<(), sphaera_mesh::ParseLengthError>(())
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

/// Why a text is not a [`Length`]: it is neither a finite, non-negative number nor such a
/// number followed by `%`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "`{text}` is not a length: give a finite, non-negative number (0.01) or a percentage of the diagonal (1%)"
)]
pub struct ParseLengthError {
    /// The text as given.
    pub text: String,
}

impl std::str::FromStr for Length {
    type Err = ParseLengthError;

    /// A number (`0.01`, absolute) or a percentage of the diagonal (`1%`, `1.5 %`);
    /// surrounding spaces are ignored, negative and non-finite values refused.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let trimmed = text.trim();
        let (number, relative) = match trimmed.strip_suffix('%') {
            Some(number) => (number.trim_end(), true),
            None => (trimmed, false),
        };
        match number.parse::<f64>() {
            Ok(value) if value.is_finite() && value >= 0.0 => Ok(if relative {
                Self::RelativeToDiagonal(value / 100.0)
            } else {
                Self::Absolute(value)
            }),
            _ => Err(ParseLengthError {
                text: text.to_owned(),
            }),
        }
    }
}

impl std::fmt::Display for Length {
    /// As [`str::parse`] reads it: `0.01` or `2%`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::Absolute(length) => write!(f, "{length}"),
            Self::RelativeToDiagonal(fraction) => write!(f, "{}%", fraction * 100.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Length;

    #[test]
    fn lengths_parse_as_written_and_bad_text_is_refused() {
        assert_eq!("1.5 %".parse(), Ok(Length::RelativeToDiagonal(0.015)));
        assert_eq!("0".parse(), Ok(Length::Absolute(0.0)));
        for bad in ["", "%", "abc", "-1", "-2%", "NaN", "inf", "1%%", "1e400"] {
            let error = bad.parse::<Length>().expect_err(bad);
            assert!(error.to_string().contains("is not a length"), "{bad}");
        }
        for length in [Length::Absolute(0.25), Length::RelativeToDiagonal(0.5)] {
            assert_eq!(length.to_string().parse(), Ok(length));
        }
    }
}
