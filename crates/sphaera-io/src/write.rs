//! OBJ and PLY writers, and the atomic file write they use.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use super::Format;
use crate::IoError;
use sphaera_mesh::TriMesh;

/// How [`write_ply`] encodes the body.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum PlyEncoding {
    /// `binary_little_endian`: compact and fast, exact `f64` coordinates (the default).
    #[default]
    BinaryLittleEndian,
    /// `ascii`: human-readable; coordinates are written in shortest round-trip form, so
    /// they read back bit-identical.
    Ascii,
}

fn io_error(path: &Path, source: io::Error) -> IoError {
    IoError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The path [`IoError::Io`] names when a caller's writer (not a file) fails.
const STREAM: &str = "<stream>";

/// Writes a file atomically: the bytes go to a temporary file in the same directory, which
/// is flushed to disk (`fsync`) and then renamed over `path`. A crash or an error leaves
/// either the old file or the complete new one, never half a file; on error the temporary
/// file is removed.
///
/// `write` receives a buffered writer on the temporary file.
///
/// # Examples
///
/// ```
/// use std::io::Write;
///
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("note.txt");
/// sphaera_io::write_atomic(&path, |w| w.write_all(b"hello"))?;
/// assert_eq!(std::fs::read(&path)?, b"hello");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`IoError::Io`] (naming `path`) if the directory is not writable, the disk is full,
/// `write` fails, or the rename fails.
///
/// # Panics
///
/// Never (unless `write` panics; the temporary file is then left behind).
pub fn write_atomic<F>(path: &Path, write: F) -> Result<(), IoError>
where
    F: FnOnce(&mut BufWriter<File>) -> io::Result<()>,
{
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let Some(name) = path.file_name() else {
        return Err(io_error(
            path,
            io::Error::new(io::ErrorKind::InvalidInput, "the path has no file name"),
        ));
    };
    let dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let unique = COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut temp_name = std::ffi::OsString::from(".");
    temp_name.push(name);
    temp_name.push(format!(".{}.{unique}.tmp", std::process::id()));
    let temp = dir.join(temp_name);
    let result = (|| {
        let file = File::create_new(&temp)?;
        let mut writer = BufWriter::with_capacity(1 << 16, file);
        write(&mut writer)?;
        let file = writer
            .into_inner()
            .map_err(io::IntoInnerError::into_error)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&temp, path)
    })();
    if let Err(source) = result {
        let _ = std::fs::remove_file(&temp);
        return Err(io_error(path, source));
    }
    // Make the rename itself durable where the platform allows it (best effort).
    if let Ok(dir_handle) = File::open(&dir) {
        let _ = dir_handle.sync_all();
    }
    Ok(())
}

/// Writes `mesh` as OBJ text to `writer`: `v x y z` lines with shortest round-trip `f64`
/// (reading the file back gives bit-identical coordinates), then `f a b c` lines
/// (1-based).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, TriMesh};
///
/// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::new(0.1, 0.2, 0.3)], vec![[0, 1, 2]])?;
/// let mut text = Vec::new();
/// sphaera_io::write_obj_to(&mut text, &mesh)?;
/// assert!(String::from_utf8(text)?.ends_with("v 0.1 0.2 0.3\nf 1 2 3\n"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`IoError::Io`] with the path `<stream>` if `writer` fails.
///
/// # Performance
///
/// Linear; wrap an unbuffered writer in a [`BufWriter`].
pub fn write_obj_to<W: Write>(writer: &mut W, mesh: &TriMesh) -> Result<(), IoError> {
    encode_obj(writer, mesh).map_err(|source| io_error(Path::new(STREAM), source))
}

fn encode_obj<W: Write>(writer: &mut W, mesh: &TriMesh) -> io::Result<()> {
    writeln!(writer, "# written by sphaera-mesh")?;
    writeln!(
        writer,
        "# {} vertices, {} triangles",
        mesh.vertex_count(),
        mesh.triangle_count()
    )?;
    for p in mesh.positions() {
        writeln!(writer, "v {} {} {}", p.x, p.y, p.z)?;
    }
    for [a, b, c] in mesh.triangles() {
        writeln!(writer, "f {} {} {}", a + 1, b + 1, c + 1)?;
    }
    Ok(())
}

/// Writes `mesh` to an OBJ file at `path`, atomically (see [`write_atomic`]).
///
/// # Examples
///
/// See the [module documentation](crate).
///
/// # Errors
///
/// [`IoError::Io`] if the file cannot be written.
pub fn write_obj(path: impl AsRef<Path>, mesh: &TriMesh) -> Result<(), IoError> {
    write_atomic(path.as_ref(), |w| encode_obj(w, mesh))
}

/// Writes `mesh` as PLY to `writer`: `double` coordinates, optional `uchar`
/// `red`/`green`/`blue` per vertex, and faces as `list uchar uint vertex_indices`.
///
/// # Examples
///
/// ```
/// use sphaera_io::{Format, PlyEncoding, read_from_bytes, write_ply_to};
/// use sphaera_mesh::{DVec3, TriMesh};
///
/// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])?;
/// let colors = [[0, 0, 255], [0, 255, 0], [255, 0, 0]];
/// let mut bytes = Vec::new();
/// write_ply_to(&mut bytes, &mesh, PlyEncoding::Ascii, Some(&colors))?;
/// assert!(String::from_utf8_lossy(&bytes).contains("property uchar red"));
/// assert_eq!(read_from_bytes(&bytes, Format::Ply)?.mesh, mesh);
/// # Ok::<(), sphaera_io::IoError>(())
/// ```
///
/// # Errors
///
/// [`IoError::VertexCountMismatch`] if `colors` does not have one entry per vertex
/// (checked before anything is written); [`IoError::Io`] with the path `<stream>` if
/// `writer` fails.
pub fn write_ply_to<W: Write>(
    writer: &mut W,
    mesh: &TriMesh,
    encoding: PlyEncoding,
    colors: Option<&[[u8; 3]]>,
) -> Result<(), IoError> {
    check_colors(mesh, colors)?;
    encode_ply(writer, mesh, encoding, colors).map_err(|source| io_error(Path::new(STREAM), source))
}

/// Writes `mesh` to a PLY file at `path`, atomically (see [`write_atomic`] and
/// [`write_ply_to`] for the layout). `colors`, when given, are per-vertex RGB (see
/// [`super::colormap`]).
///
/// # Examples
///
/// See the [module documentation](crate).
///
/// # Errors
///
/// [`IoError::VertexCountMismatch`] if `colors` has the wrong length (nothing is
/// written), [`IoError::Io`] if the file cannot be written.
pub fn write_ply(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    encoding: PlyEncoding,
    colors: Option<&[[u8; 3]]>,
) -> Result<(), IoError> {
    check_colors(mesh, colors)?;
    write_atomic(path.as_ref(), |w| encode_ply(w, mesh, encoding, colors))
}

/// Writes `mesh` to `path` in the format its extension names: `.obj` as OBJ, `.ply` as
/// binary little-endian PLY (case-insensitive), atomically.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, TriMesh};
/// use sphaera_io as io;
///
/// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])?;
/// let dir = tempfile::tempdir()?;
/// io::save(dir.path().join("tri.PLY"), &mesh)?;
/// assert_eq!(io::load(dir.path().join("tri.PLY"))?, mesh);
/// assert!(io::save(dir.path().join("tri.stl"), &mesh).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`IoError::UnsupportedWriteFormat`] for `.stl` and `.off`,
/// [`IoError::UnknownFormat`] for any other extension, [`IoError::Io`] if the file
/// cannot be written.
pub fn save(path: impl AsRef<Path>, mesh: &TriMesh) -> Result<(), IoError> {
    let path = path.as_ref();
    match Format::from_path(path) {
        Some(Format::Obj) => write_obj(path, mesh),
        Some(Format::Ply) => write_ply(path, mesh, PlyEncoding::BinaryLittleEndian, None),
        Some(format) => Err(IoError::UnsupportedWriteFormat { format }),
        None => Err(IoError::UnknownFormat {
            path: Some(path.to_path_buf()),
        }),
    }
}

fn check_colors(mesh: &TriMesh, colors: Option<&[[u8; 3]]>) -> Result<(), IoError> {
    match colors {
        Some(c) if c.len() != mesh.vertex_count() => Err(IoError::VertexCountMismatch {
            expected: mesh.vertex_count(),
            actual: c.len(),
        }),
        _ => Ok(()),
    }
}

fn encode_ply<W: Write>(
    writer: &mut W,
    mesh: &TriMesh,
    encoding: PlyEncoding,
    colors: Option<&[[u8; 3]]>,
) -> io::Result<()> {
    let format = match encoding {
        PlyEncoding::Ascii => "ascii",
        PlyEncoding::BinaryLittleEndian => "binary_little_endian",
    };
    writeln!(
        writer,
        "ply\nformat {format} 1.0\ncomment written by sphaera-mesh"
    )?;
    writeln!(writer, "element vertex {}", mesh.vertex_count())?;
    writeln!(
        writer,
        "property double x\nproperty double y\nproperty double z"
    )?;
    if colors.is_some() {
        writeln!(
            writer,
            "property uchar red\nproperty uchar green\nproperty uchar blue"
        )?;
    }
    writeln!(writer, "element face {}", mesh.triangle_count())?;
    writeln!(
        writer,
        "property list uchar uint vertex_indices\nend_header"
    )?;
    let color = |i: usize| colors.and_then(|c| c.get(i));
    match encoding {
        PlyEncoding::Ascii => {
            for (i, p) in mesh.positions().iter().enumerate() {
                write!(writer, "{} {} {}", p.x, p.y, p.z)?;
                if let Some([r, g, b]) = color(i) {
                    write!(writer, " {r} {g} {b}")?;
                }
                writeln!(writer)?;
            }
            for [a, b, c] in mesh.triangles() {
                writeln!(writer, "3 {a} {b} {c}")?;
            }
        }
        PlyEncoding::BinaryLittleEndian => {
            for (i, p) in mesh.positions().iter().enumerate() {
                for v in p.to_array() {
                    writer.write_all(&v.to_le_bytes())?;
                }
                if let Some(rgb) = color(i) {
                    writer.write_all(rgb)?;
                }
            }
            for tri in mesh.triangles() {
                writer.write_all(&[3])?;
                for v in tri {
                    writer.write_all(&v.to_le_bytes())?;
                }
            }
        }
    }
    Ok(())
}
