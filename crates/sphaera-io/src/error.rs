//! The error type of `sphaera-io`: files that cannot be opened, read or written, and data
//! that do not follow their format.

use std::path::PathBuf;

use sphaera_mesh::MeshError;

/// Everything that can go wrong reading or writing a mesh file.
///
/// Every variant says what was wrong and where (the file, the line or byte offset, the glTF
/// object). Messages are lowercase and carry no final period, so they compose into larger
/// messages (`"cannot load bunny.obj: {error}"`).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IoError {
    /// The operating system refused to read or write a file.
    #[error("cannot access {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },

    /// A file exists but the [`FilePolicy`](crate::FilePolicy) does not read it: not a
    /// regular file, outside the allowed folder, or larger than the cap.
    #[error("refused to read {}: {refusal}", path.display())]
    Refused {
        /// The file, as named.
        path: PathBuf,
        /// Why.
        refusal: crate::FileRefusal,
    },

    /// A mesh file (or byte buffer) is malformed: the data do not follow the format, or they
    /// describe invalid geometry (a NaN coordinate, an index out of range, a face with fewer
    /// than three vertices).
    ///
    /// `location` is a 1-based line for text formats, a 0-based byte offset for binary
    /// ones, a JSON line and column or the glTF object (mesh primitive, node, buffer) for
    /// glTF; `reason` is a structured [`crate::ParseReason`].
    #[error(
        "malformed {format} data{} at {location}: {reason}",
        crate::describe_path(path.as_deref())
    )]
    Parse {
        /// The file, when the data came from one ([`crate::read`] fills it in).
        path: Option<PathBuf>,
        /// The format the data were parsed as.
        format: crate::Format,
        /// Where in the data the problem is.
        location: crate::Location,
        /// What is wrong.
        reason: crate::ParseReason,
    },
    /// The mesh format of a file could not be determined: its extension is not one of
    /// `obj`, `ply`, `stl`, `off`, `gltf`, `glb` (in any case), and its content does not
    /// look like any of them.
    #[error(
        "cannot tell the mesh format{}: the extension is not obj, ply, stl, off, gltf or glb and the content is not recognised",
        crate::describe_path(path.as_deref())
    )]
    UnknownFormat {
        /// The file, when the data came from one.
        path: Option<PathBuf>,
    },
    /// A 2D shapes file whose extension is not `.geojson`, `.json` or `.wkt`.
    #[error(
        "cannot tell the shapes format of {}: the extension is not geojson, json or wkt",
        path.display()
    )]
    UnknownShapeFormat {
        /// The file.
        path: PathBuf,
    },
    /// A GeoJSON or WKT file (or text) is malformed.
    #[error("malformed {format} data{}: {message}", crate::describe_path(path.as_deref()))]
    MalformedShapes {
        /// The file, when the text came from one.
        path: Option<PathBuf>,
        /// The format the text was parsed as.
        format: crate::ShapeFormat,
        /// What is wrong, and where (the JSON line and column, the feature and polygon).
        message: String,
    },
    /// Writing this format is not supported (only OBJ and PLY are written).
    #[error("writing {format} files is not supported (write obj or ply instead)")]
    UnsupportedWriteFormat {
        /// The requested format.
        format: crate::Format,
    },

    /// Per-vertex values given to a writer (colours) do not have one entry per vertex.
    #[error("expected {expected} per-vertex values, got {actual}")]
    VertexCountMismatch {
        /// Number of vertices in the mesh.
        expected: usize,
        /// Number of values supplied.
        actual: usize,
    },
    /// The mesh read is not a valid mesh (a failure of `sphaera-mesh`).
    #[error(transparent)]
    Mesh(#[from] MeshError),
}
