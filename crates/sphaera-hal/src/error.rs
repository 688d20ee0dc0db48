//! What can go wrong building or querying a HAL tree.

use std::path::PathBuf;

/// Why a HAL tree cannot be built or asked something.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HalError {
    /// Too few vertices: a polygon needs three, a polyline two.
    #[error("a {what} needs at least {needed} vertices, got {count}")]
    TooFewVertices {
        /// `"polygon"` or `"polyline"`.
        what: &'static str,
        /// The vertices given.
        count: usize,
        /// The vertices needed.
        needed: usize,
    },
    /// More vertices than 32-bit indices address.
    #[error("{count} vertices are more than a HAL tree indexes (at most u32::MAX − 1)")]
    TooManyVertices {
        /// The vertices given.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate ({x}, {y})")]
    NonFinite {
        /// The vertex's index.
        vertex: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// Point inclusion asked of an open polyline, which has no inside.
    #[error("an open polyline has no inside: point inclusion needs a closed polygon")]
    OpenPolyline,
    /// A polygon file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A line of a polygon file is not two numbers.
    #[error("line {line}: expected `x y` (two numbers), found `{text}`")]
    Parse {
        /// The line number (from 1).
        line: usize,
        /// The line's text.
        text: String,
    },
    /// An error of the mesh crate (the smallest bounding disc).
    #[error(transparent)]
    Mesh(#[from] sphaera_mesh::MeshError),
}
