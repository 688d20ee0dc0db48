//! Label files: [`Labels`] saved with what identifies the mesh they belong to, and read
//! back only for that mesh (the paper's Algorithm 1 computes the labels once and stores
//! them; a later run reads them instead of labelling every view again).
//!
//! The format is versioned ([`LABEL_FILE_VERSION`]), checked by two checksums (a flipped
//! byte anywhere is found), and holds the mesh's counts and fingerprint
//! ([`MeshFingerprint`]), so that labels are never used with another mesh. Files are
//! written atomically and read by a [`FilePolicy`] (regular files only, within a size cap
//! and, with a root, inside a folder); every count is checked against its cap before
//! anything is allocated.
//!
#![doc = include_str!("label_file.md")]

use std::io::{self, BufReader, Read, Write};
use std::path::Path;

use sphaera_io::FilePolicy;
use sphaera_mesh::TriMesh;
use xxhash_rust::xxh3::{Xxh3Default, xxh3_64};

use crate::caps::{check_label_count, check_resolution};
use crate::error::LabelFileProblem;
use crate::{
    Contours, DistanceTransform, LabelOptions, Labels, Projection, SilhouetteError, ViewSet,
};

/// The label file format this library writes and reads (1). A file of another version is
/// refused with [`LabelFileProblem::UnsupportedVersion`], which names both versions.
///
/// The version changes with the layout and with the labels' meaning: when the way labels
/// are computed changes (what the binary image cuts out, how a vertex takes its label),
/// the version goes up too, so that files of the older labelling are refused and
/// computed again rather than silently used.
pub const LABEL_FILE_VERSION: u32 = 1;

/// The first 8 bytes of every label file.
pub const LABEL_FILE_MAGIC: [u8; 8] = *b"SPHLABEL";

/// Bytes of the header's fields, before the header checksum.
const FIELDS: usize = 72;
/// Bytes of the header with its checksum.
const HEADER: usize = FIELDS + 8;
/// Bytes of the checksum that ends the file.
const CHECKSUM: usize = 8;
/// Bytes read or written at a time (even: whole labels).
const CHUNK: usize = 1 << 16;
/// What errors name for a reader or a writer rather than a file.
const STREAM: &str = "<stream>";

/// What identifies a mesh: its vertex and triangle counts and a 128-bit hash of its
/// geometry. Labels carry the fingerprint of the mesh they were computed for, and label
/// files refuse any other mesh.
///
/// The hash is XXH3-128 (seed 0) of the vertex count and the triangle count (`u64`
/// little-endian), then every position's `x`, `y`, `z` (the `f64` bits, little-endian),
/// then every triangle's three indices (`u32` little-endian): stable across runs,
/// platforms and versions. Moving a vertex by one unit in the last place, scaling the
/// mesh or reordering a triangle's corners changes it.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, TriMesh, shapes};
/// use sphaera_silhouette::MeshFingerprint;
///
/// let mesh = shapes::sphere(1.0, 8)?;
/// let fingerprint = MeshFingerprint::of(&mesh);
/// assert_eq!(fingerprint.vertices, mesh.vertex_count());
/// assert_eq!(fingerprint, MeshFingerprint::of(&mesh.clone()));
/// let scaled: Vec<DVec3> = mesh.positions().iter().map(|&p| 2.0 * p).collect();
/// let scaled = TriMesh::new(scaled, mesh.triangles().to_vec())?;
/// assert_ne!(MeshFingerprint::of(&scaled).hash(), fingerprint.hash());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MeshFingerprint {
    /// Vertices of the mesh.
    pub vertices: usize,
    /// Triangles of the mesh.
    pub triangles: usize,
    /// The hash's bytes, little-endian (as in a label file; bytes rather than a `u128`
    /// keep errors holding a fingerprint small).
    digest: [u8; 16],
}

impl MeshFingerprint {
    /// The fingerprint of `mesh`.
    ///
    /// # Performance
    ///
    /// Linear: one pass over the positions and the triangles (a few milliseconds for a
    /// million vertices).
    #[must_use]
    pub fn of(mesh: &TriMesh) -> Self {
        let (vertices, triangles) = (mesh.vertex_count(), mesh.triangle_count());
        let mut hasher = Xxh3Default::new();
        hasher.update(&(vertices as u64).to_le_bytes());
        hasher.update(&(triangles as u64).to_le_bytes());
        let mut buffer = Vec::with_capacity(CHUNK);
        for p in mesh.positions() {
            for c in p.to_array() {
                buffer.extend_from_slice(&c.to_le_bytes());
            }
            if buffer.len() + 24 > CHUNK {
                hasher.update(&buffer);
                buffer.clear();
            }
        }
        for t in mesh.triangles() {
            for v in t {
                buffer.extend_from_slice(&v.to_le_bytes());
            }
            if buffer.len() + 12 > CHUNK {
                hasher.update(&buffer);
                buffer.clear();
            }
        }
        hasher.update(&buffer);
        Self {
            vertices,
            triangles,
            digest: hasher.digest128().to_le_bytes(),
        }
    }

    /// The hash: XXH3-128 of the counts, the positions and the triangles.
    #[must_use]
    pub fn hash(&self) -> u128 {
        u128::from_le_bytes(self.digest)
    }
}

impl std::fmt::Display for MeshFingerprint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} vertices, {} triangles, fingerprint {:032x}",
            self.vertices,
            self.triangles,
            self.hash()
        )
    }
}

/// A projection as users read it: `orthographic` or `perspective at D radii`.
fn projection_name(projection: Projection) -> String {
    match projection {
        Projection::Orthographic => "orthographic".to_owned(),
        Projection::Perspective { distance } => format!("perspective at {distance} radii"),
    }
}

fn file_error(path: &Path, problem: LabelFileProblem) -> SilhouetteError {
    SilhouetteError::LabelFile {
        path: path.to_owned(),
        problem,
    }
}

impl Labels {
    /// `Ok` when `mesh` is the mesh these labels were computed for: the same counts and
    /// the same [`MeshFingerprint`].
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::LabelsOfOtherMesh`], whose message gives both meshes' counts,
    /// or says that the counts agree and the positions or triangles do not.
    pub fn check_mesh(&self, mesh: &TriMesh) -> Result<(), SilhouetteError> {
        let given = MeshFingerprint::of(mesh);
        if given == self.mesh_fingerprint() {
            Ok(())
        } else {
            Err(SilhouetteError::LabelsOfOtherMesh {
                labels: self.mesh_fingerprint(),
                mesh: given,
            })
        }
    }

    /// `Ok` when these labels are the ones [`Labels::compute`] gives for `views` and
    /// `options`: the same view step and projection, resolution, distance transform and
    /// contours. For labels read from a file, before using them in place of computing.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_silhouette::{Contours, LabelOptions, Labels, SilhouetteError, ViewSet};
    ///
    /// let mesh = shapes::sphere(1.0, 8)?;
    /// let views = ViewSet::regular(90.0)?;
    /// let options = LabelOptions::default().with_resolution(16);
    /// let labels = Labels::compute(&mesh, &views, &options)?;
    /// assert!(labels.check_settings(&views, &options).is_ok());
    /// let other = labels.check_settings(&ViewSet::regular(45.0)?, &options).unwrap_err();
    /// assert_eq!(other.to_string(), "the labels were computed with step 90°, not 45°");
    /// let all = options.with_contours(Contours::All);
    /// assert!(matches!(
    ///     labels.check_settings(&views, &all),
    ///     Err(SilhouetteError::LabelSettingsMismatch { setting: "contours", .. })
    /// ));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::LabelSettingsMismatch`] naming the first setting that differs
    /// (`"step"`, `"projection"`, `"resolution"`, `"transform"`, `"contours"`) with both
    /// values.
    pub fn check_settings(
        &self,
        views: &ViewSet,
        options: &LabelOptions,
    ) -> Result<(), SilhouetteError> {
        let mismatch = |setting, labels: String, asked: String| {
            Err(SilhouetteError::LabelSettingsMismatch {
                setting,
                labels,
                asked,
            })
        };
        let (mine, theirs) = (self.views(), views);
        if mine.step_degrees().to_bits() != theirs.step_degrees().to_bits() {
            let degrees = |v: &ViewSet| format!("{}°", v.step_degrees());
            return mismatch("step", degrees(mine), degrees(theirs));
        }
        if mine.projection() != theirs.projection() {
            return mismatch(
                "projection",
                projection_name(mine.projection()),
                projection_name(theirs.projection()),
            );
        }
        if self.resolution() != options.resolution {
            return mismatch(
                "resolution",
                self.resolution().to_string(),
                options.resolution.to_string(),
            );
        }
        if self.transform() != options.transform {
            return mismatch(
                "transform",
                self.transform().to_string(),
                options.transform.to_string(),
            );
        }
        if self.contours() != options.contours {
            return mismatch(
                "contours",
                self.contours().to_string(),
                options.contours.to_string(),
            );
        }
        Ok(())
    }

    /// Writes the labels, the settings they were computed with and `mesh`'s
    /// [`MeshFingerprint`] to `writer` in the label file format (version
    /// [`LABEL_FILE_VERSION`]; the layout is in the crate docs' *Label files* section).
    /// `writer` is written in chunks of 64 KiB and flushed at the end.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::LabelsOfOtherMesh`] when `mesh` is not the mesh the labels were
    /// computed for (nothing is written); [`SilhouetteError::LabelFile`] with
    /// [`LabelFileProblem::Io`] (the path `<stream>`) when `writer` fails.
    ///
    /// # Performance
    ///
    /// Linear in the labels (2 bytes per vertex per view), plus the mesh's fingerprint.
    pub fn write_to(&self, mesh: &TriMesh, mut writer: impl Write) -> Result<(), SilhouetteError> {
        self.check_mesh(mesh)?;
        self.encode(&mut writer)
            .map_err(|source| file_error(Path::new(STREAM), LabelFileProblem::Io { source }))
    }

    /// Saves the labels to `path` as [`Labels::write_to`] writes them, atomically
    /// (a temporary file beside it, renamed over it: an interrupted save never leaves
    /// half a file).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_silhouette::{LabelOptions, Labels, ViewSet};
    ///
    /// let mesh = shapes::torus(1.0, 0.3, 16)?;
    /// let views = ViewSet::regular(45.0)?.with_perspective(3.0)?;
    /// let labels = Labels::compute(&mesh, &views, &LabelOptions::default().with_resolution(32))?;
    /// let dir = tempfile::tempdir()?;
    /// let path = dir.path().join("torus.labels");
    /// labels.save(&mesh, &path)?;
    /// assert_eq!(Labels::load(&path, &mesh)?, labels);
    ///
    /// // Another mesh is refused, and the message says why.
    /// let other = shapes::torus(1.0, 0.25, 16)?;
    /// let refused = Labels::load(&path, &other).unwrap_err();
    /// assert!(refused.to_string().contains("another mesh"), "{refused}");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::LabelsOfOtherMesh`] as [`Labels::write_to`] (nothing is
    /// written); [`SilhouetteError::LabelFile`] naming `path`, with
    /// [`LabelFileProblem::Io`], when the file cannot be written (its folder is missing or
    /// read-only, the disk is full).
    pub fn save(&self, mesh: &TriMesh, path: impl AsRef<Path>) -> Result<(), SilhouetteError> {
        let path = path.as_ref();
        self.check_mesh(mesh)?;
        sphaera_io::write_atomic(path, |w| self.encode(w))
            .map_err(|error| file_error(path, LabelFileProblem::from_io(error)))
    }

    /// Reads labels in the label file format from `reader`, for `mesh`: the file's mesh
    /// must be `mesh` (the same counts and [`MeshFingerprint`]). `reader` is read in
    /// chunks (wrap a slow reader in a [`BufReader`]) to its end: bytes after the labels
    /// are an error.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::LabelFile`] with the path `<stream>` and the
    /// [`LabelFileProblem`]: not a label file, another version, a header checksum that
    /// does not match, an invalid header value or a count beyond its cap (checked before
    /// anything is allocated), another mesh, a truncated stream, a checksum that does not
    /// match, trailing bytes, or the reader's own error.
    ///
    /// # Performance
    ///
    /// Linear in the labels; memory grows with the bytes read (never with what a header
    /// claims), to the labels' size.
    pub fn read_from(reader: impl Read, mesh: &TriMesh) -> Result<Self, SilhouetteError> {
        decode(reader, mesh, None).map_err(|problem| file_error(Path::new(STREAM), problem))
    }

    /// Loads the labels of `mesh` from the label file at `path`, by the default
    /// [`FilePolicy`] (a regular file of at most 2 GiB, anywhere the process may read):
    /// [`Labels::load_with`] names another policy. See [`Labels::save`] for an example.
    ///
    /// # Errors
    ///
    /// As [`Labels::load_with`].
    pub fn load(path: impl AsRef<Path>, mesh: &TriMesh) -> Result<Self, SilhouetteError> {
        Self::load_with(path, mesh, &FilePolicy::default())
    }

    /// Loads the labels of `mesh` from the label file at `path` if `policy` admits the
    /// file (a file named by a document or a user: not a folder, a device or a pipe,
    /// within the size cap and the root). The file's length is checked against its header
    /// before the labels are read.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_io::FilePolicy;
    /// use sphaera_mesh::shapes;
    /// use sphaera_silhouette::Labels;
    ///
    /// let mesh = shapes::sphere(1.0, 8)?;
    /// let dir = tempfile::tempdir()?;
    /// // A folder is refused at once, not read.
    /// let refused = Labels::load_with(dir.path(), &mesh, &FilePolicy::default()).unwrap_err();
    /// assert!(refused.to_string().contains("not a regular file"), "{refused}");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::LabelFile`] naming `path`: with [`LabelFileProblem::Refused`] when
    /// the policy refuses the file, [`LabelFileProblem::Io`] when it cannot be opened (it
    /// does not exist); else as [`Labels::read_from`] ([`LabelFileProblem::Truncated`] or
    /// [`LabelFileProblem::TrailingBytes`] as soon as the header is read when the file's
    /// length does not match it).
    pub fn load_with(
        path: impl AsRef<Path>,
        mesh: &TriMesh,
        policy: &FilePolicy,
    ) -> Result<Self, SilhouetteError> {
        let path = path.as_ref();
        let file = policy
            .open(path)
            .map_err(|error| file_error(path, LabelFileProblem::from_io(error)))?;
        let length = file.limit();
        decode(BufReader::with_capacity(CHUNK, file), mesh, Some(length))
            .map_err(|problem| file_error(path, problem))
    }

    /// The header: the fields and their checksum.
    fn header(&self) -> [u8; HEADER] {
        let mut header = [0_u8; HEADER];
        let mut put = |offset: usize, bytes: &[u8]| {
            header[offset..offset + bytes.len()].copy_from_slice(bytes);
        };
        let views = self.views();
        let (projection, distance) = match views.projection() {
            Projection::Orthographic => (0_u8, 0.0_f64),
            Projection::Perspective { distance } => (1, distance),
        };
        let transform = match self.transform() {
            DistanceTransform::Euclidean => 0_u8,
            DistanceTransform::Chamfer => 1,
        };
        let contours = match self.contours() {
            Contours::External => 0_u8,
            Contours::All => 1,
        };
        let fingerprint = self.mesh_fingerprint();
        put(0, &LABEL_FILE_MAGIC);
        put(8, &LABEL_FILE_VERSION.to_le_bytes());
        // At most `MAX_RESOLUTION` and `MAX_VIEWS`: both fit a `u32`.
        put(12, &(self.resolution() as u32).to_le_bytes());
        put(16, &views.step_degrees().to_le_bytes());
        put(24, &distance.to_le_bytes());
        put(32, &[projection, transform, contours, 0]);
        put(36, &(views.len() as u32).to_le_bytes());
        put(40, &(fingerprint.vertices as u64).to_le_bytes());
        put(48, &(fingerprint.triangles as u64).to_le_bytes());
        put(56, &fingerprint.digest);
        let checksum = xxh3_64(&header[..FIELDS]);
        header[FIELDS..].copy_from_slice(&checksum.to_le_bytes());
        header
    }

    /// Writes the file's bytes to `writer`.
    fn encode(&self, writer: &mut impl Write) -> io::Result<()> {
        let header = self.header();
        let mut hasher = Xxh3Default::new();
        hasher.update(&header);
        writer.write_all(&header)?;
        let mut buffer = Vec::with_capacity(CHUNK);
        for chunk in self.values().chunks(CHUNK / 2) {
            buffer.clear();
            for &label in chunk {
                buffer.extend_from_slice(&label.to_le_bytes());
            }
            hasher.update(&buffer);
            writer.write_all(&buffer)?;
        }
        writer.write_all(&hasher.digest().to_le_bytes())?;
        writer.flush()
    }
}

/// Fills `buffer` from `reader` as far as it goes: the bytes read, fewer at the end.
fn read_full(reader: &mut impl Read, buffer: &mut [u8]) -> Result<usize, LabelFileProblem> {
    let mut filled = 0;
    while filled < buffer.len() {
        match reader.read(&mut buffer[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(source) => return Err(LabelFileProblem::Io { source }),
        }
    }
    Ok(filled)
}

/// The little-endian number of `N` bytes at `offset` of the header.
fn bytes_at<const N: usize>(header: &[u8; HEADER], offset: usize) -> [u8; N] {
    let mut out = [0_u8; N];
    out.copy_from_slice(&header[offset..offset + N]);
    out
}

/// Reads a label file for `mesh` from `reader`, whose length is `length` when known.
fn decode(
    mut reader: impl Read,
    mesh: &TriMesh,
    length: Option<u64>,
) -> Result<Labels, LabelFileProblem> {
    let truncated = |found: usize, needed: usize| LabelFileProblem::Truncated {
        found: found as u64,
        needed: needed as u64,
    };
    let mut header = [0_u8; HEADER];
    let got = read_full(&mut reader, &mut header)?;
    let magic = got.min(LABEL_FILE_MAGIC.len());
    if header[..magic] != LABEL_FILE_MAGIC[..magic] {
        return Err(LabelFileProblem::NotLabelFile);
    }
    if got < 12 {
        return Err(truncated(got, HEADER));
    }
    let version = u32::from_le_bytes(bytes_at(&header, 8));
    if version != LABEL_FILE_VERSION {
        return Err(LabelFileProblem::UnsupportedVersion {
            found: version,
            supported: LABEL_FILE_VERSION,
        });
    }
    if got < HEADER {
        return Err(truncated(got, HEADER));
    }
    let stored = u64::from_le_bytes(bytes_at(&header, FIELDS));
    let computed = xxh3_64(&header[..FIELDS]);
    if stored != computed {
        return Err(LabelFileProblem::Checksum {
            part: "header",
            stored,
            computed,
        });
    }
    let (views, options, file_mesh) = parse_fields(&header)?;
    let given = MeshFingerprint::of(mesh);
    if file_mesh != given {
        return Err(LabelFileProblem::OtherMesh {
            labels: file_mesh,
            mesh: given,
        });
    }
    // At most `MAX_LABELS` (checked): no overflow.
    let count = file_mesh.vertices * views.len();
    let total = HEADER + 2 * count + CHECKSUM;
    if let Some(length) = length {
        if length < total as u64 {
            return Err(LabelFileProblem::Truncated {
                found: length,
                needed: total as u64,
            });
        }
        if length > total as u64 {
            return Err(LabelFileProblem::TrailingBytes {
                expected: total as u64,
            });
        }
    }
    let mut hasher = Xxh3Default::new();
    hasher.update(&header);
    // The labels grow as bytes arrive: a header's claim allocates nothing by itself.
    let mut values: Vec<u16> = Vec::new();
    let mut buffer = vec![0_u8; CHUNK.min(2 * count)];
    let mut read = HEADER;
    let mut remaining = 2 * count;
    while remaining > 0 {
        let want = remaining.min(CHUNK);
        let chunk = &mut buffer[..want];
        let got = read_full(&mut reader, chunk)?;
        read += got;
        if got < want {
            return Err(truncated(read, total));
        }
        hasher.update(chunk);
        values.extend(
            chunk
                .chunks_exact(2)
                .map(|pair| u16::from_le_bytes([pair[0], pair[1]])),
        );
        remaining -= want;
    }
    let mut checksum = [0_u8; CHECKSUM];
    let got = read_full(&mut reader, &mut checksum)?;
    if got < CHECKSUM {
        return Err(truncated(read + got, total));
    }
    let stored = u64::from_le_bytes(checksum);
    let computed = hasher.digest();
    if stored != computed {
        return Err(LabelFileProblem::Checksum {
            part: "file",
            stored,
            computed,
        });
    }
    if read_full(&mut reader, &mut [0_u8; 1])? > 0 {
        return Err(LabelFileProblem::TrailingBytes {
            expected: total as u64,
        });
    }
    Ok(Labels::from_parts(views, options, file_mesh, values))
}

/// The header's view set, options and mesh, each value checked (the counts against their
/// caps).
fn parse_fields(
    header: &[u8; HEADER],
) -> Result<(ViewSet, LabelOptions, MeshFingerprint), LabelFileProblem> {
    let refused = |source: SilhouetteError| LabelFileProblem::Header {
        source: Box::new(source),
    };
    let invalid = |name: &'static str, value: f64, requirement: &'static str| {
        refused(SilhouetteError::InvalidParameter {
            name,
            value,
            requirement,
        })
    };
    let resolution = u32::from_le_bytes(bytes_at(header, 12)) as usize;
    check_resolution(resolution).map_err(refused)?;
    let step = f64::from_le_bytes(bytes_at(header, 16));
    let distance = f64::from_le_bytes(bytes_at(header, 24));
    let [projection, transform, contours, reserved] = bytes_at(header, 32);
    let transform = match transform {
        0 => DistanceTransform::Euclidean,
        1 => DistanceTransform::Chamfer,
        code => {
            return Err(invalid(
                "transform",
                f64::from(code),
                "0 (euclidean) or 1 (chamfer)",
            ));
        }
    };
    let contours = match contours {
        0 => Contours::External,
        1 => Contours::All,
        code => {
            return Err(invalid(
                "contours",
                f64::from(code),
                "0 (outline) or 1 (all)",
            ));
        }
    };
    if reserved != 0 {
        return Err(invalid("reserved byte", f64::from(reserved), "0"));
    }
    let mut views = ViewSet::regular(step).map_err(refused)?;
    match projection {
        0 if distance.to_bits() == 0 => {}
        0 => {
            return Err(invalid(
                "perspective distance",
                distance,
                "0 for orthographic views",
            ));
        }
        1 => views = views.with_perspective(distance).map_err(refused)?,
        code => {
            return Err(invalid(
                "projection",
                f64::from(code),
                "0 (orthographic) or 1 (perspective)",
            ));
        }
    }
    let view_count = u32::from_le_bytes(bytes_at(header, 36));
    if view_count as usize != views.len() {
        return Err(invalid(
            "views",
            f64::from(view_count),
            "the number of views of the file's step",
        ));
    }
    let count = |offset| usize::try_from(u64::from_le_bytes(bytes_at(header, offset)));
    let vertices = count(40).unwrap_or(usize::MAX);
    check_label_count(vertices, views.len()).map_err(refused)?;
    let triangles = count(48).unwrap_or(usize::MAX);
    let mesh = MeshFingerprint {
        vertices,
        triangles,
        digest: bytes_at(header, 56),
    };
    let options = LabelOptions {
        resolution,
        transform,
        contours,
    };
    Ok((views, options, mesh))
}
