//! Names of the workspace's method enums, as users type them.

/// A name that is not one of an enum's: what was asked for, and what is accepted.
///
/// Every method enum of the workspace (`spheretree::Method`, `simplify::Placement`,
/// `silhouette::Contours`...) parses its names with `FromStr` and shows them with
/// `Display`, failing with this error.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::ParseNameError;
///
/// let error = ParseNameError::new("method", "nope", "merge, burst or minimax");
/// assert_eq!(
///     error.to_string(),
///     "`nope` is not a method: give merge, burst or minimax"
/// );
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{text}` is not a {kind}: give {expected}")]
pub struct ParseNameError {
    /// What was being named, e.g. `"method"`.
    pub kind: &'static str,
    /// The text as given.
    pub text: String,
    /// The names accepted, e.g. `"subset or optimal"`.
    pub expected: &'static str,
}

impl ParseNameError {
    /// The error for `text`, not a `kind`; `expected` lists the names accepted.
    #[must_use]
    pub fn new(kind: &'static str, text: &str, expected: &'static str) -> Self {
        Self {
            kind,
            text: text.to_owned(),
            expected,
        }
    }
}
