//! Where a malformed file is wrong ([`Location`]) and why ([`ParseReason`]).

use std::fmt;
use std::path::{Path, PathBuf};

/// Where in a file a problem was found.
///
/// # Examples
///
/// ```
/// use sphaera_io::{GltfObject, Location};
///
/// assert_eq!(Location::Line(12).to_string(), "line 12");
/// assert_eq!(Location::Byte(84).to_string(), "byte offset 84");
/// assert_eq!(Location::Json { line: 3, column: 7 }.to_string(), "JSON line 3, column 7");
/// let primitive = GltfObject::Primitive { mesh: 0, primitive: 2 };
/// assert_eq!(Location::Gltf(primitive).to_string(), "mesh 0, primitive 2");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Location {
    /// A 1-based line number (text formats: OBJ, ASCII PLY, ASCII STL, OFF, and PLY headers).
    Line(usize),
    /// A 0-based byte offset from the start of the file (binary PLY and binary STL, the
    /// container of a binary glTF).
    Byte(u64),
    /// A 1-based line and column in the JSON of a glTF file (of its JSON chunk for a
    /// `.glb`), where the JSON is malformed or does not follow the glTF schema.
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
    },
    /// The glTF object (mesh primitive, node, buffer...) whose data are wrong.
    Gltf(GltfObject),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Line(line) => write!(f, "line {line}"),
            Self::Byte(offset) => write!(f, "byte offset {offset}"),
            Self::Json { line, column } => write!(f, "JSON line {line}, column {column}"),
            Self::Gltf(object) => object.fmt(f),
        }
    }
}

/// An object of a glTF document, by its 0-based index in the document's arrays: where a
/// glTF file is wrong ([`Location::Gltf`]).
///
/// # Examples
///
/// ```
/// use sphaera_io::GltfObject;
///
/// assert_eq!(GltfObject::Node(4).to_string(), "node 4");
/// assert_eq!(GltfObject::Document.to_string(), "the top level");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum GltfObject {
    /// The document as a whole: its `asset` version, `extensionsRequired`, `scene`.
    Document,
    /// A scene (`scenes[i]`).
    Scene(usize),
    /// A node (`nodes[i]`): its transform, its mesh or its children.
    Node(usize),
    /// A mesh primitive (`meshes[mesh].primitives[primitive]`) and the accessors it reads.
    Primitive {
        /// Index of the mesh.
        mesh: usize,
        /// Index of the primitive in the mesh.
        primitive: usize,
    },
    /// A buffer (`buffers[i]`): its URI, file or length.
    Buffer(usize),
}

impl fmt::Display for GltfObject {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Document => f.write_str("the top level"),
            Self::Scene(i) => write!(f, "scene {i}"),
            Self::Node(i) => write!(f, "node {i}"),
            Self::Primitive { mesh, primitive } => write!(f, "mesh {mesh}, primitive {primitive}"),
            Self::Buffer(i) => write!(f, "buffer {i}"),
        }
    }
}

/// Why a file is malformed: the structured reason inside
/// [`IoError::Parse`](crate::IoError::Parse).
///
/// Messages are lowercase without a final period, like every `sphaera-mesh` error.
///
/// # Examples
///
/// ```
/// use sphaera_io::{Format, ParseReason, read_from_bytes};
/// use sphaera_io::IoError;
///
/// let err = read_from_bytes(b"v 0 0 0\nv 1 0 0\nf 1 2\n", Format::Obj).unwrap_err();
/// match err {
///     IoError::Parse { reason, .. } => {
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

    // glTF -------------------------------------------------------------------------------
    /// The JSON of a glTF file is malformed or does not follow the glTF schema (a missing
    /// `asset`, a string where a number belongs...).
    #[error("not a valid glTF JSON document: {message}")]
    InvalidJson {
        /// The JSON parser's message, without its position (that is the [`Location`]).
        message: String,
    },
    /// A glTF file (or its binary container) of another version than 2.
    #[error("glTF version {version} is not supported (only 2.x is)")]
    UnsupportedVersion {
        /// The version found.
        version: String,
    },
    /// A glTF file requires an extension this reader does not implement (mesh compression,
    /// GPU instancing...).
    #[error("the required extension `{name}` is not supported")]
    UnsupportedExtension {
        /// The extension's name, e.g. `"KHR_draco_mesh_compression"`.
        name: String,
    },
    /// A glTF object refers to another that does not exist.
    #[error("{kind} {index} does not exist (the file has {available})")]
    DanglingReference {
        /// The kind of the missing object, e.g. `"accessor"` or `"node"`.
        kind: &'static str,
        /// The index referred to.
        index: usize,
        /// How many objects of that kind the file has.
        available: usize,
    },
    /// A glTF mesh primitive lacks a required vertex attribute.
    #[error("the primitive has no `{attribute}` attribute")]
    MissingAttribute {
        /// The attribute, `"POSITION"`.
        attribute: &'static str,
    },
    /// A glTF JSON value outside its allowed set (an unknown primitive mode, component
    /// type or accessor type).
    #[error("invalid {what}")]
    InvalidValue {
        /// What holds the value, e.g. `"primitive mode"`.
        what: &'static str,
    },
    /// A glTF accessor holds another kind of element than its use needs.
    #[error("accessor {accessor} holds {found}, expected {expected}")]
    UnexpectedAccessorType {
        /// Index of the accessor.
        accessor: usize,
        /// What its use needs, e.g. `"VEC3 of floats or 8/16-bit integers"`.
        expected: &'static str,
        /// What it holds, e.g. `"VEC2 of F32"`.
        found: String,
    },
    /// A glTF accessor reads past the end of its buffer view.
    #[error(
        "accessor {accessor} ({part}) needs {end} bytes of buffer view {view}, which has {available}"
    )]
    AccessorOutOfBounds {
        /// Index of the accessor.
        accessor: usize,
        /// The part read: `"elements"`, `"sparse indices"` or `"sparse values"`.
        part: &'static str,
        /// Index of the buffer view.
        view: usize,
        /// The end of the last element read, in bytes from the start of the view.
        end: u64,
        /// The view's length in bytes.
        available: u64,
    },
    /// A glTF buffer view ends past the end of its buffer.
    #[error("buffer view {view} ends at byte {end}, but buffer {buffer} has {available} bytes")]
    BufferViewOutOfBounds {
        /// Index of the buffer view.
        view: usize,
        /// Index of its buffer.
        buffer: usize,
        /// The view's end (offset plus length) in bytes.
        end: u64,
        /// The buffer's length in bytes.
        available: u64,
    },
    /// A glTF buffer view's byte stride is shorter than the elements read through it.
    #[error(
        "buffer view {view} has a byte stride of {stride}, less than the {element_size}-byte elements read through it"
    )]
    InvalidStride {
        /// Index of the buffer view.
        view: usize,
        /// The stride in bytes.
        stride: usize,
        /// The size of one element in bytes.
        element_size: usize,
    },
    /// A sparse glTF accessor replaces an element past its end.
    #[error("accessor {accessor} has a sparse index {index}, but only {count} elements")]
    SparseIndexOutOfRange {
        /// Index of the accessor.
        accessor: usize,
        /// The sparse index.
        index: u64,
        /// The accessor's element count.
        count: usize,
    },
    /// A glTF primitive refers to a vertex past the end of its `POSITION` accessor.
    #[error(
        "vertex index {index} (entry {position} of the indices) is out of range: the primitive has {vertex_count} vertices"
    )]
    PrimitiveIndexOutOfRange {
        /// 0-based position of the index in the primitive's index list.
        position: usize,
        /// The vertex index.
        index: u32,
        /// Number of vertices of the primitive.
        vertex_count: usize,
    },
    /// A glTF `TRIANGLES` primitive whose vertex count is not a multiple of three.
    #[error("{count} vertex indices do not make whole triangles (not a multiple of 3)")]
    IncompleteTriangles {
        /// The number of indices (or of vertices, for a primitive without indices).
        count: usize,
    },
    /// A glTF node transform that cannot place anything.
    #[error("invalid node transform: {problem}")]
    InvalidTransform {
        /// What is wrong, e.g. `"a value is NaN or infinite"`.
        problem: &'static str,
    },
    /// A glTF node reached twice while walking a scene: the node hierarchy is not a set of
    /// disjoint trees.
    #[error(
        "node {node} is reached twice: the node hierarchy must be disjoint trees (a cycle, a node with two parents, or a root listed twice)"
    )]
    NodeReachedTwice {
        /// Index of the node.
        node: usize,
    },
    /// A glTF scene places more vertices than [`crate::MAX_PLACED_VERTICES`]:
    /// instancing (many nodes drawing one mesh) multiplies a file's vertices, so a small
    /// file could otherwise ask for more memory than the machine has.
    #[error(
        "the scene places {count} vertices (its nodes draw their meshes that often); at most {limit} are read"
    )]
    TooManyPlacedVertices {
        /// The vertices the scene's nodes would place.
        count: u64,
        /// The most that are read.
        limit: u64,
    },
    /// A glTF buffer has no data: no `uri`, and no binary chunk to stand for it.
    #[error("the buffer has no `uri` and the file has no binary chunk for it")]
    BufferWithoutData,
    /// A glTF buffer holds fewer bytes than its `byteLength`.
    #[error("the buffer declares {expected} bytes, but its data have {found}")]
    BufferTooShort {
        /// The declared `byteLength`.
        expected: u64,
        /// The bytes present.
        found: u64,
    },
    /// A glTF buffer's URI names a separate file, but the data were read from bytes, with
    /// no file path to resolve it against.
    #[error(
        "buffer `{uri}` is a separate file, which only reading the glTF from its path can resolve (use `io::read`)"
    )]
    ExternalBuffer {
        /// The URI (at most 40 characters).
        uri: String,
    },
    /// A glTF buffer's file cannot be read.
    #[error("cannot read buffer `{uri}` ({}): {kind}", path.display())]
    BufferFile {
        /// The URI as written (at most 40 characters).
        uri: String,
        /// The file it resolves to (relative to the glTF file's folder).
        path: PathBuf,
        /// What the operating system said.
        kind: std::io::ErrorKind,
    },
    /// A glTF buffer's file exists but is not read: it is not a regular file, lies
    /// outside the glTF file's folder (or the policy's root), or is larger than the cap
    /// ([`crate::FilePolicy`]).
    #[error("refused to read buffer `{uri}` ({}): {refusal}", path.display())]
    BufferRefused {
        /// The URI as written (at most 40 characters).
        uri: String,
        /// The file it resolves to (relative to the glTF file's folder).
        path: PathBuf,
        /// Why (boxed: a rare error keeps the common ones small).
        refusal: Box<crate::FileRefusal>,
    },
    /// A glTF buffer's URI cannot be decoded (bad base64 or percent-encoding, a URI scheme
    /// other than `data:`).
    #[error("invalid buffer uri `{uri}`: {problem}")]
    InvalidUri {
        /// The URI (at most 40 characters).
        uri: String,
        /// What is wrong with it.
        problem: &'static str,
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
