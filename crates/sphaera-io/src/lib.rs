//! # sphaera-io
//!
//! Reading and writing mesh files for Sphaera: OBJ, PLY, STL, OFF and glTF 2.0 (`.gltf`,
//! `.glb`) in; OBJ and PLY out; polygon and point text files; atomic writes. Only the front
//! ends (the CLI, the Python bindings, robots, scenes, the experiments) depend on it: the
//! algorithm crates take a [`TriMesh`] from anywhere.
//!
//! # Quick start
//!
//! ```
//! use sphaera_mesh::{DVec3, TriMesh};
//! use sphaera_io as io;
//!
//! // A unit square as two triangles.
//! let mesh = TriMesh::new(
//!     vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.1, 0.7, 1e-9)],
//!     vec![[0, 1, 2], [0, 2, 3]],
//! )?;
//!
//! let dir = std::env::temp_dir().join(format!("sphaera-io-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let obj = dir.join("square.obj");
//! let ply = dir.join("square.ply");
//! io::write_obj(&obj, &mesh)?;
//! io::write_ply(&ply, &mesh, io::PlyEncoding::BinaryLittleEndian, None)?;
//!
//! // Both read back bit-identical (OBJ coordinates are written in shortest round-trip form).
//! assert_eq!(io::load(&obj)?, mesh);
//! let loaded = io::read(&ply)?;
//! assert_eq!(loaded.mesh, mesh);
//! assert_eq!(loaded.report.format, io::Format::Ply);
//! assert_eq!(loaded.report.faces_in_file, 2);
//! std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Formats read
//!
//! | format | what is read | ignored |
//! |---|---|---|
//! | OBJ | `v` (first three numbers), `f` in the forms `v`, `v/vt`, `v//vn`, `v/vt/vn`, 1-based or negative (relative) indices, forward references, `\` line continuations | `vt`, `vn`, `g`, `o`, `s`, `usemtl`, `mtllib`, `l`, `p`, comments and every other statement |
//! | PLY | `ascii`, `binary_little_endian`, `binary_big_endian`; `vertex` `x y z` of any numeric type (`float`, `double`, `int`, `uchar`..., and the `float32`-style names); `face` list `vertex_indices` or `vertex_index` with any count and index types | every other property (lists included) and element |
//! | STL | ASCII and binary; positions are welded (see below) | normals, attribute bytes, solid names |
//! | OFF | `OFF` and its `ST`/`C`/`N` prefixed variants, counts on the keyword line or the next, `#` comments | vertex colours/normals, face colours, the edge count |
//! | glTF 2.0 | `.gltf` (JSON, buffers in `data:` URIs or in files beside it) and `.glb` (binary); the `TRIANGLES`, `TRIANGLE_STRIP` and `TRIANGLE_FAN` primitives of the default scene's meshes, placed by their nodes' transforms and merged; `POSITION` as `f32` or (normalized) 8/16-bit integers (`KHR_mesh_quantization`), `u8`/`u16`/`u32` indices or none, sparse accessors | points and lines primitives (counted), normals, texture coordinates, materials, images, cameras, animations, skins, morph targets; appearance-only extensions |
//!
//! [`read`] picks the format from the file extension (`obj`, `ply`, `stl`, `off`, `gltf`,
//! `glb`, in any case) and falls back to [`Format::sniff`]ing the content for other
//! extensions. [`read_from_bytes`] parses a buffer in a given format.
//!
//! **glTF** (behind the default `gltf` feature; without it, reading glTF is a clear
//! [`ParseReason::Unsupported`] error): one [`Format::Gltf`] covers both the JSON `.gltf`
//! and the binary `.glb`, told apart by the `glTF` magic, as [`Format::Stl`] covers ASCII
//! and binary STL. Every triangle primitive that the default scene (or the first scene)
//! draws is placed by the world transform of its node (`matrix` or translation × rotation
//! × scale, composed from the root) and merged into one mesh, each primitive instance with
//! its own vertices, in depth-first node order; a file without scenes gives every mesh
//! once, untransformed. A mirroring transform (negative determinant) reverses its
//! triangles' winding so outward faces stay outward. Strips and fans become triangles by
//! the glTF rules. [`LoadReport`] counts the primitives read, skipped (points, lines) and
//! mirrored. Buffer files (`"uri": "mesh.bin"`, percent-decoded) are resolved relative to
//! the glTF file by [`read`]; [`read_from_bytes`] has no folder to resolve them in and
//! reads only `.glb` data and `data:` URIs ([`ParseReason::ExternalBuffer`] otherwise).
//! Required extensions that change the geometry (Draco or meshopt compression, GPU
//! instancing) are refused ([`ParseReason::UnsupportedExtension`]); `KHR_mesh_quantization`
//! is read, appearance-only extensions are ignored.
//!
//! Binary STL detection: a binary STL is `84 + 50 n` bytes for `n` facets. Files of
//! exactly that size are binary even when they start with `solid` (many exporters do
//! that); other files are ASCII only if they start with `solid`, their first 512 bytes
//! are text (no NUL or other control byte) and hold `facet` or `endsolid` (or are the
//! whole file); everything else is binary, so a truncated binary file is a size error,
//! never an empty mesh. A binary file may carry fewer than 50 bytes of trailing padding
//! (ignored); a longer tail, which could hold unannounced facets, is an error. An ASCII
//! file must end with `endsolid` and hold no binary bytes.
//! **STL welding**: STL has no shared vertices, so positions with bit-identical
//! coordinates (`-0.0` = `0.0`) are merged on read, in order of first appearance, and
//! [`LoadReport::welded_vertices`] counts the merged records. Nothing is merged by
//! distance, and no other format is welded: unreferenced vertices, duplicate positions and
//! degenerate faces are kept as in the file (repairs are an explicit, separate step).
//!
//! # Polygons
//!
//! A face with `n > 3` vertices becomes `n - 2` triangles, in place (its triangles follow
//! the previous face's), oriented like the polygon:
//!
//! - the polygon's plane is its Newell normal through the vertex centroid (well defined for
//!   non-planar and non-convex polygons);
//! - if the polygon, projected on that plane, is convex it is fanned from its first vertex;
//! - otherwise it is **ear-clipped** in the plane, which never produces overlapping
//!   triangles for a simple (non-self-intersecting) outline; vertices collinear with their
//!   neighbours are clipped last, as zero-area triangles, when no proper ear is left;
//! - if ear clipping fails (self-intersecting outline, all vertices collinear, or more than
//!   1,024 vertices, since ear clipping is cubic in the worst case) the polygon is fanned
//!   from its first vertex.
//!
//! [`LoadReport`] counts the polygons triangulated, the non-planar ones (a vertex farther
//! than 10⁻⁶ × the polygon's radius from the plane), the non-convex ones and the fan
//! fallbacks, so a caller can reject files that needed the fallback. Faces with fewer than
//! three vertices are an error.
//!
//! # Errors and where they point
//!
//! A malformed file gives [`IoError::Parse`] with the [`Format`], a [`Location`] — the
//! 1-based **line** for text formats (OBJ, ASCII PLY and every PLY header, ASCII STL, OFF),
//! the 0-based **byte offset** for binary PLY and STL and the GLB container, the JSON
//! **line and column** of malformed glTF JSON, or the **glTF object** at fault
//! ([`GltfObject`]: the mesh primitive, node or buffer) — and a structured
//! [`ParseReason`] (expected and found counts, the offending token, the index and the vertex
//! count...). Invalid geometry is caught while parsing, so it points at the line too:
//! NaN or infinite coordinates ([`ParseReason::NonFiniteCoordinate`]), indices out of range
//! (including `0` in OBJ, which is 1-based), faces with fewer than three vertices. Files
//! that end early ([`ParseReason::MissingRecords`], [`ParseReason::SizeMismatch`]) and
//! empty files ([`ParseReason::EmptyFile`]) are errors too. No input makes a reader panic
//! (this is property-tested with random bytes and random truncations).
//!
//! ```
//! use sphaera_io::{Format, Location, ParseReason, read_from_bytes};
//! use sphaera_io::IoError;
//!
//! let err = read_from_bytes(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", Format::Obj).unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "malformed OBJ data at line 4: vertex index 4 is out of range: the file has 3 vertices"
//! );
//! assert!(matches!(
//!     err,
//!     IoError::Parse { location: Location::Line(4), reason: ParseReason::IndexOutOfRange { index: 4, .. }, .. }
//! ));
//! ```
//!
//! # Writing
//!
//! [`write_obj`] and [`write_ply`] (ASCII or binary little-endian, with optional per-vertex
//! RGB colours from [`colormap`]) write **atomically**: to a temporary file in the target's
//! directory, `fsync`ed, then renamed over the target, so an interrupted run never leaves
//! half a file where the user's data was ([`write_atomic`] is public for other formats).
//! Coordinates are written exactly: binary PLY as `double`, text in shortest round-trip
//! form, so writing then reading gives the same mesh bit for bit. [`save`] picks the
//! format from the extension.
//!
//! # Performance
//!
//! Files are read whole into memory and parsed as bytes (no per-line allocation, no hash
//! map except STL welding). The time to read the 871,414-triangle ASCII `dragon_vrip.ply`
//! is in the section *Loading and topology (`sphaera-mesh`)* of `docs/benchmarks.md` in
//! the repository (`cargo bench -p sphaera-io --bench load_topology`).

mod builder;
pub mod colormap;
mod error;
#[cfg(feature = "gltf")]
mod gltf;
mod obj;
mod off;
mod parse_error;
mod ply;
mod policy;
mod polygon;
mod shapes2;
mod stl;
mod text;
mod uri;
mod write;

#[cfg(test)]
mod data_tests;
#[cfg(test)]
mod tests;

use std::fmt;
use std::path::Path;

pub use error::IoError;
pub(crate) use parse_error::describe_path;
pub use parse_error::{GltfObject, Location, ParseReason};
pub use policy::{DEFAULT_MAX_FILE_BYTES, FilePolicy, FileRefusal};
pub use shapes2::{ShapeFormat, Shapes2, parse_shapes, read_shapes};
pub use uri::percent_decode;
pub use write::{
    PlyEncoding, save, write_atomic, write_obj, write_obj_to, write_ply, write_ply_to,
};

use sphaera_mesh::TriMesh;

/// The most vertices a glTF scene may place: 2²⁶ (67 million, about 3 GB with their
/// triangles), about 150 times the 437,645 vertices of the 871k-triangle dragon scan.
/// Instancing (many nodes drawing one mesh) multiplies a file's vertices, so without a
/// limit a file of a few kilobytes could ask for more memory than the machine has;
/// beyond it the reader refuses the file with [`ParseReason::TooManyPlacedVertices`]
/// before reading any data.
pub const MAX_PLACED_VERTICES: u64 = 1 << 26;

/// A mesh file format.
///
/// # Examples
///
/// ```
/// use sphaera_io::Format;
///
/// assert_eq!(Format::from_extension("PLY"), Some(Format::Ply));
/// assert_eq!(Format::sniff(b"OFF\n3 1 0\n"), Some(Format::Off));
/// assert_eq!(Format::Stl.to_string(), "STL");
/// assert_eq!(Format::from_extension("glb"), Some(Format::Gltf));
/// assert_eq!(Format::sniff(b"glTF\x02\0\0\0"), Some(Format::Gltf));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Format {
    /// Wavefront OBJ (text).
    Obj,
    /// Stanford PLY (ASCII or binary).
    Ply,
    /// Stereolithography STL (ASCII or binary).
    Stl,
    /// Object File Format (text).
    Off,
    /// glTF 2.0, both the JSON `.gltf` and the binary `.glb` (told apart by the content's
    /// `glTF` magic). Read only (with the default `gltf` feature).
    Gltf,
}

impl Format {
    /// The format an extension names (`obj`, `ply`, `stl`, `off`, `gltf`, `glb`, in any
    /// case, without the dot).
    pub fn from_extension(extension: &str) -> Option<Self> {
        match extension.to_ascii_lowercase().as_str() {
            "obj" => Some(Self::Obj),
            "ply" => Some(Self::Ply),
            "stl" => Some(Self::Stl),
            "off" => Some(Self::Off),
            "gltf" | "glb" => Some(Self::Gltf),
            _ => None,
        }
    }

    /// The format a path's extension names.
    pub fn from_path(path: &Path) -> Option<Self> {
        Self::from_extension(path.extension()?.to_str()?)
    }

    /// The usual (lowercase) extension (`gltf` for glTF, whose binary files use `glb`).
    pub fn extension(self) -> &'static str {
        match self {
            Self::Obj => "obj",
            Self::Ply => "ply",
            Self::Stl => "stl",
            Self::Off => "off",
            Self::Gltf => "gltf",
        }
    }

    /// Guesses the format from the content: the GLB magic `glTF` or a JSON object with an
    /// `"asset"` key in its first 4 KiB (glTF), `ply` magic, an OFF keyword, a binary STL of
    /// consistent size or an ASCII STL starting with `solid`, or a first statement that is
    /// an OBJ keyword (`v`, `vt`, `vn`, `f`, `o`, `g`, `s`, `mtllib`, `usemtl`).
    ///
    /// # Performance
    ///
    /// Looks at the first few lines (and at most 4 KiB) only.
    pub fn sniff(bytes: &[u8]) -> Option<Self> {
        if bytes.starts_with(b"glTF") || looks_like_gltf_json(bytes) {
            return Some(Self::Gltf);
        }
        let first = text::Lines::new(bytes, 1)
            .map(|(_, line)| text::strip_comment(line))
            .find(|line| !text::is_blank(line))
            .and_then(|line| text::tokens(line).next());
        if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
            return Some(Self::Ply);
        }
        if first.and_then(off::header_keyword).is_some() {
            return Some(Self::Off);
        }
        if let Some(count) = bytes.get(80..84) {
            let n = u64::from(u32::from_le_bytes([count[0], count[1], count[2], count[3]]));
            if 84 + 50 * n == bytes.len() as u64 {
                return Some(Self::Stl);
            }
        }
        if stl::starts_with_solid(bytes) {
            return Some(Self::Stl);
        }
        match first {
            Some(b"v" | b"vt" | b"vn" | b"f" | b"o" | b"g" | b"s" | b"mtllib" | b"usemtl") => {
                Some(Self::Obj)
            }
            _ => None,
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Obj => "OBJ",
            Self::Ply => "PLY",
            Self::Stl => "STL",
            Self::Off => "OFF",
            Self::Gltf => "glTF",
        })
    }
}

/// Whether `bytes` look like glTF JSON: a `{` first (after a BOM and whitespace) and an
/// `"asset"` key within the first 4 KiB.
fn looks_like_gltf_json(bytes: &[u8]) -> bool {
    let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let window = &bytes[..bytes.len().min(4096)];
    window.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'{')
        && window.windows(7).any(|w| w == b"\"asset\"")
}

/// What a reader found in a file besides the mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct LoadReport {
    /// The format read.
    pub format: Format,
    /// Vertex records in the file: OBJ `v` lines, the PLY/OFF header count, three per
    /// STL facet (before welding), or for glTF the `POSITION` elements of every primitive
    /// read, once per node that draws it (so the mesh's vertex count).
    pub vertex_records: usize,
    /// Face records in the file (before triangulation); for glTF, the triangles of every
    /// primitive read (strips and fans already split), once per node that draws it.
    pub faces_in_file: usize,
    /// Faces with more than three vertices, split into triangles.
    pub polygons_triangulated: usize,
    /// Of those, the ones that are not convex in their best-fit plane (ear-clipped).
    pub non_convex_polygons: usize,
    /// Of those, the ones whose vertices are not on a common plane (within 10⁻⁶ of their
    /// radius).
    pub non_planar_polygons: usize,
    /// Of those, the ones ear clipping could not handle, fanned from their first vertex
    /// instead (their triangles may overlap).
    pub fan_fallbacks: usize,
    /// STL only: vertex records merged into an earlier bit-identical position.
    pub welded_vertices: usize,
    /// glTF only: triangle primitives (`TRIANGLES`, `TRIANGLE_STRIP`, `TRIANGLE_FAN`)
    /// merged into the mesh, once per node that draws them.
    pub primitives_read: usize,
    /// glTF only: points and lines primitives left out, once per node that draws them.
    pub primitives_skipped: usize,
    /// glTF only: primitives (of `primitives_read`) placed by a mirroring transform
    /// (negative determinant), whose triangles were reversed to keep their orientation.
    pub mirrored_primitives: usize,
}

/// A mesh read from a file, with the [`LoadReport`] of what was in it.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LoadedMesh {
    /// The triangle mesh.
    pub mesh: TriMesh,
    /// What the reader found.
    pub report: LoadReport,
}

/// Reads a mesh file, choosing the reader from the extension (case-insensitive `obj`,
/// `ply`, `stl`, `off`, `gltf`, `glb`) or, for any other extension, from the content
/// ([`Format::sniff`]). A glTF file's separate buffer files are read from its folder.
/// Files are read by the default [`FilePolicy`]: regular files only (a device such as
/// `/dev/zero`, a named pipe or a folder is refused before it is opened), at most
/// [`DEFAULT_MAX_FILE_BYTES`], glTF buffer files inside the glTF file's folder; see
/// [`read_with`] for another cap or a root.
///
/// # Examples
///
/// See the [module documentation](crate).
///
/// # Errors
///
/// - [`IoError::Io`] if the file cannot be read;
/// - [`IoError::Refused`] if it is not a regular file or larger than the cap;
/// - [`IoError::UnknownFormat`] if neither the extension nor the content tells the
///   format;
/// - [`IoError::Parse`], with this `path`, if the file is malformed (see the module
///   docs for the locations and reasons), or if a glTF buffer file it names cannot be
///   read ([`ParseReason::BufferFile`], at the [`GltfObject::Buffer`]).
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Reads the whole file into memory, then parses it in one pass; the time for the ASCII
/// `dragon_vrip.ply` is in the section *Loading and topology (`sphaera-mesh`)* of
/// `docs/benchmarks.md` in the repository.
pub fn read(path: impl AsRef<Path>) -> Result<LoadedMesh, IoError> {
    read_with(path, &FilePolicy::default())
}

/// [`read`] by a [`FilePolicy`]: the file, and a glTF file's buffer files, are read only if
/// the policy admits them (regular files, within its size cap and root; buffer files also
/// inside the glTF file's folder).
///
/// # Examples
///
/// ```
/// use sphaera_io::{FilePolicy, FileRefusal, IoError, read_with};
///
/// let folder = std::env::temp_dir().join(format!("sphaera-read-with-{}", std::process::id()));
/// std::fs::create_dir_all(&folder)?;
/// let path = folder.join("tri.obj");
/// std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")?;
/// let policy = FilePolicy::default().with_root(&folder);
/// assert_eq!(read_with(&path, &policy)?.mesh.triangle_count(), 1);
/// let small = policy.with_max_bytes(16);
/// assert!(matches!(
///     read_with(&path, &small),
///     Err(IoError::Refused { refusal: FileRefusal::TooLarge { bytes: 32, cap: 16 }, .. })
/// ));
/// std::fs::remove_dir_all(&folder)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// As [`read`]; [`IoError::Refused`] for a file the policy does not read, and
/// [`ParseReason::BufferRefused`] for such a glTF buffer file.
pub fn read_with(path: impl AsRef<Path>, policy: &FilePolicy) -> Result<LoadedMesh, IoError> {
    let path = path.as_ref();
    let bytes = policy.read(path)?;
    let format = Format::from_path(path)
        .or_else(|| Format::sniff(&bytes))
        .ok_or_else(|| IoError::UnknownFormat {
            path: Some(path.to_path_buf()),
        })?;
    let base = match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder,
        _ => Path::new("."),
    };
    read_bytes(&bytes, format, Some((base, policy))).map_err(|error| match error {
        IoError::Parse {
            format,
            location,
            reason,
            ..
        } => IoError::Parse {
            path: Some(path.to_path_buf()),
            format,
            location,
            reason,
        },
        other => other,
    })
}

/// Reads a mesh file and keeps only the mesh (see [`read`]).
///
/// # Examples
///
/// See the [module documentation](crate).
///
/// # Errors
///
/// As [`read`].
pub fn load(path: impl AsRef<Path>) -> Result<TriMesh, IoError> {
    read(path).map(|loaded| loaded.mesh)
}

/// Parses a mesh from bytes in the given format.
///
/// # Examples
///
/// ```
/// use sphaera_io::{Format, read_from_bytes};
///
/// let quad = b"OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
/// let loaded = read_from_bytes(quad, Format::Off)?;
/// assert_eq!(loaded.mesh.triangles(), &[[0, 1, 2], [0, 2, 3]]);
/// assert_eq!(loaded.report.polygons_triangulated, 1);
/// # Ok::<(), sphaera_io::IoError>(())
/// ```
///
/// # Errors
///
/// [`IoError::Parse`] (without a path) if the data are malformed, or if glTF data name a
/// separate buffer file ([`ParseReason::ExternalBuffer`]: there is no folder to find it
/// in; use [`read`]).
///
/// # Panics
///
/// Never.
pub fn read_from_bytes(bytes: &[u8], format: Format) -> Result<LoadedMesh, IoError> {
    read_bytes(bytes, format, None)
}

/// Parses a mesh from bytes; glTF buffer files are resolved in `base` and read by its
/// policy (none without it).
fn read_bytes(
    bytes: &[u8],
    format: Format,
    base: Option<(&Path, &FilePolicy)>,
) -> Result<LoadedMesh, IoError> {
    match format {
        Format::Obj => obj::read_obj(bytes),
        Format::Ply => ply::read_ply(bytes),
        Format::Stl => stl::read_stl(bytes),
        Format::Off => off::read_off(bytes),
        #[cfg(feature = "gltf")]
        Format::Gltf => gltf::read_gltf(bytes, base),
        #[cfg(not(feature = "gltf"))]
        Format::Gltf => {
            let _ = base;
            Err(IoError::Parse {
                path: None,
                format,
                location: Location::Byte(0),
                reason: ParseReason::Unsupported {
                    feature: "reading glTF without the `gltf` feature of sphaera-mesh",
                },
            })
        }
    }
}

/// The quick start of the crate's `README.md` (what crates.io shows), run as a doctest so
/// that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
