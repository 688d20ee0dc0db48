//! Where a malformed file is wrong ([`Location`]) and why ([`ParseReason`]).

use std::fmt;
use std::path::Path;

/// Where in a file a problem was found.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::io::Location;
///
/// assert_eq!(Location::Line(12).to_string(), "line 12");
/// assert_eq!(Location::Byte(84).to_string(), "byte offset 84");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Location {
    /// A 1-based line number (text formats: OBJ, ASCII PLY, ASCII STL, OFF, and PLY headers).
    Line(usize),
    /// A 0-based byte offset from the start of the file (binary PLY and binary STL).
    Byte(u64),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Line(line) => write!(f, "line {line}"),
            Self::Byte(offset) => write!(f, "byte offset {offset}"),
        }
    }
}

/// Why a file is malformed: the structured reason inside [`crate::MeshError::Parse`].
///
/// Messages are lowercase without a final period, like every `sphaera-mesh` error.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::io::{Format, ParseReason, read_from_bytes};
/// use sphaera_mesh::MeshError;
///
/// let err = read_from_bytes(b"v 0 0 0\nv 1 0 0\nf 1 2\n", Format::Obj).unwrap_err();
/// match err {
///     MeshError::Parse { reason, .. } => {
///         assert_eq!(reason, ParseReason::TooFewFaceVertices { count: 2 });
///     }
///     other => panic!("unexpected error {other}"),
/// }
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParseReason {
    /// The data hold nothing but whitespace (and comments).
    #[error("the file is empty")]
    EmptyFile,
    /// The data do not start with the format's signature.
    #[error("the data do not start with `{expected}`")]
    BadMagic {
        /// The signature the format requires, e.g. `"ply"` or `"solid"`.
        expected: &'static str,
    },
    /// A valid feature of the format that this reader does not handle.
    #[error("{feature} is not supported")]
    Unsupported {
        /// The feature, e.g. `"binary OFF"`.
        feature: &'static str,
    },
    /// A token other than the one the grammar allows here.
    #[error("expected {expected}, found `{found}`")]
    UnexpectedToken {
        /// What the grammar allows, e.g. `"a PLY header keyword"`.
        expected: &'static str,
        /// The token found (at most 40 characters, lossily decoded).
        found: String,
    },
    /// A token that should be a number of the given kind is not.
    #[error("expected {expected}, found `{found}`")]
    InvalidNumber {
        /// What was expected, e.g. `"a floating-point coordinate"` or `"a vertex index"`.
        expected: &'static str,
        /// The token found (at most 40 characters, lossily decoded).
        found: String,
    },
    /// A line (or record) has fewer values than the format requires.
    #[error("expected {expected} values, found {found}")]
    MissingValues {
        /// Number of values required.
        expected: usize,
        /// Number of values present.
        found: usize,
    },
    /// A line (or record) has more values than its declaration allows.
    #[error("expected {expected} values, found {found}")]
    TooManyValues {
        /// Number of values declared.
        expected: usize,
        /// Number of values present.
        found: usize,
    },
    /// The data end before all the records announced in the header.
    #[error("the header announces {expected} {element} records, but the data end after {found}")]
    MissingRecords {
        /// The kind of record, e.g. `"vertex"` or `"face"`.
        element: String,
        /// Number announced in the header.
        expected: usize,
        /// Number actually present.
        found: usize,
    },
    /// The data end in the middle of a construct.
    #[error("unexpected end of data while reading {expected}")]
    UnexpectedEnd {
        /// What was being read, e.g. `"a facet"` or `"the header"`.
        expected: &'static str,
    },
    /// A binary file's size does not match the size its header implies.
    #[error("the header implies {expected} bytes, but the data have {found}")]
    SizeMismatch {
        /// The implied size in bytes.
        expected: u64,
        /// The actual size in bytes.
        found: u64,
    },
    /// A required property or element is missing from a header.
    #[error("the {element} element has no `{property}` property")]
    MissingProperty {
        /// The element, e.g. `"vertex"`.
        element: &'static str,
        /// The property, e.g. `"x"` or `"vertex_indices"`.
        property: &'static str,
    },
    /// A count (element size, list length) is negative or too large.
    #[error("invalid {what} {value}")]
    InvalidCount {
        /// What is being counted, e.g. `"list length"`.
        what: &'static str,
        /// The value found.
        value: f64,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite {axis} coordinate ({value})")]
    NonFiniteCoordinate {
        /// 0-based index of the vertex (in file order).
        vertex: usize,
        /// The axis: `'x'`, `'y'` or `'z'`.
        axis: char,
        /// The offending value.
        value: f64,
    },
    /// A binary STL facet has a NaN or infinite coordinate.
    #[error("facet {facet}, corner {corner} has a non-finite {axis} coordinate ({value})")]
    NonFiniteFacetCoordinate {
        /// 0-based index of the facet (in file order).
        facet: usize,
        /// 0-based corner of the facet: 0, 1 or 2.
        corner: usize,
        /// The axis: `'x'`, `'y'` or `'z'`.
        axis: char,
        /// The offending value.
        value: f64,
    },
    /// A face's vertex index is not a non-negative integer (a float-typed PLY index that
    /// is NaN, infinite or fractional).
    #[error("vertex index {value} is not an integer")]
    NonIntegerIndex {
        /// The value found.
        value: f64,
    },
    /// Text data contain a byte no text file holds (NUL or another control character).
    #[error("unexpected binary byte {byte:#04x} in text data")]
    BinaryByte {
        /// The byte found.
        byte: u8,
    },
    /// A face refers to a vertex that does not exist.
    #[error("vertex index {index} is out of range: the file has {vertex_count} vertices")]
    IndexOutOfRange {
        /// The index as written in the file (1-based, or negative relative, for OBJ).
        index: i64,
        /// Number of vertices available.
        vertex_count: usize,
    },
    /// An OBJ face uses index 0 (OBJ indices start at 1; negative ones count back).
    #[error("vertex index 0 is invalid (OBJ indices start at 1)")]
    ZeroIndex,
    /// A face has fewer than three vertices.
    #[error("a face has {count} vertices, at least 3 are needed")]
    TooFewFaceVertices {
        /// The number of vertices of the face.
        count: usize,
    },
    /// More vertices than a `u32` index can address.
    #[error("{count} vertices are more than a u32 index can address")]
    TooManyVertices {
        /// The number of vertices.
        count: u64,
    },
}

/// `" in <path>"` or nothing: the path part of an error message.
pub(crate) fn describe_path(path: Option<&Path>) -> String {
    path.map(|p| format!(" in {}", p.display()))
        .unwrap_or_default()
}

/// A token for an error message: lossily decoded, at most 40 characters.
pub(crate) fn token_text(token: &[u8]) -> String {
    let text = String::from_utf8_lossy(token);
    if text.chars().count() > 40 {
        let mut short: String = text.chars().take(40).collect();
        short.push('…');
        short
    } else {
        text.into_owned()
    }
}
