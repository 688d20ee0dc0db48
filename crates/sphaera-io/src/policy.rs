//! Which files may be read when a document names them: the one policy for scene files,
//! glTF buffers and URDF meshes (and for the files a user names directly).
//!
//! A file is read only if it is a **regular file** (not a folder, a device such as
//! `/dev/zero`, a named pipe or a socket: looked at before opening, so a pipe cannot hang
//! the reader, and again on the opened file), **no larger than a cap** (read to at most the
//! length it had when checked), and, when the policy has a **root**, **inside that folder**
//! once every symbolic link and `..` is resolved (a link is followed only if it ends inside
//! the root). glTF buffer files are further confined to the asset's own folder, as the
//! glTF specification reads relative URIs.

use std::fs::{File, Metadata};
use std::io::{Read, Take};
use std::path::{Path, PathBuf};

use crate::IoError;

/// The largest file read by default: 2 GiB. A mesh file larger than this (about
/// 100 million triangles in binary PLY) needs [`FilePolicy::with_max_bytes`].
pub const DEFAULT_MAX_FILE_BYTES: u64 = 1 << 31;

/// Which files may be read, and how much of them.
///
/// # Examples
///
/// ```
/// use sphaera_io::{FilePolicy, FileRefusal, IoError};
///
/// // A service confines the files its documents name to one folder.
/// let folder = std::env::temp_dir().join(format!("sphaera-policy-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&folder)?;
/// std::fs::write(folder.join("part.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")?;
/// let policy = FilePolicy::default().with_root(&folder);
/// assert_eq!(policy.read(&folder.join("part.obj"))?.len(), 32);
///
/// // A path climbing out of the root is refused before the file is opened.
/// let outside = std::env::temp_dir().join(format!("sphaera-policy-doc-{}.obj", std::process::id()));
/// std::fs::write(&outside, "v 0 0 0\n")?;
/// let climbing = folder.join("..").join(outside.file_name().unwrap());
/// assert!(matches!(
///     policy.read(&climbing),
///     Err(IoError::Refused { refusal: FileRefusal::OutsideRoot { .. }, .. })
/// ));
/// std::fs::remove_file(&outside)?;
/// # #[cfg(unix)]
/// assert!(matches!(
///     FilePolicy::default().read("/dev/zero".as_ref()),
///     Err(IoError::Refused { refusal: FileRefusal::NotRegular { .. }, .. })
/// ));
/// std::fs::remove_dir_all(&folder)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct FilePolicy {
    /// Files must lie inside this folder once links and `..` are resolved (default `None`:
    /// anywhere the process may read, as a user's own command line expects).
    pub root: Option<PathBuf>,
    /// The largest file read, in bytes (default [`DEFAULT_MAX_FILE_BYTES`]).
    pub max_bytes: u64,
}

impl Default for FilePolicy {
    fn default() -> Self {
        Self {
            root: None,
            max_bytes: DEFAULT_MAX_FILE_BYTES,
        }
    }
}

/// Why a file was not read although it exists.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum FileRefusal {
    /// It is not a regular file.
    #[error("it is {kind}, not a regular file")]
    NotRegular {
        /// What it is: `"a folder"`, `"a device"`, `"a named pipe"`, `"a socket"`.
        kind: &'static str,
    },
    /// It lies outside the folder files are confined to.
    #[error("it lies outside the allowed folder {}", root.display())]
    OutsideRoot {
        /// The folder.
        root: PathBuf,
    },
    /// It is larger than the cap.
    #[error("it is {bytes} bytes, more than the cap of {cap} bytes")]
    TooLarge {
        /// Its size.
        bytes: u64,
        /// The cap ([`FilePolicy::max_bytes`]).
        cap: u64,
    },
}

impl FilePolicy {
    /// Confines files to `root` (a folder; links are followed only if they end inside it).
    #[must_use]
    pub fn with_root(mut self, root: impl Into<PathBuf>) -> Self {
        self.root = Some(root.into());
        self
    }

    /// Reads files of at most `max_bytes` bytes.
    #[must_use]
    pub fn with_max_bytes(mut self, max_bytes: u64) -> Self {
        self.max_bytes = max_bytes;
        self
    }

    /// Whether `path` names a file this policy reads (it exists, is regular, small enough
    /// and inside the root): for choosing among candidate paths.
    #[must_use]
    pub fn admits(&self, path: &Path) -> bool {
        self.check_file(path).is_ok()
    }

    /// Checks, without opening it, that the policy reads the file at `path`; returns it with
    /// every link and `..` resolved.
    ///
    /// # Errors
    ///
    /// As [`FilePolicy::read`].
    pub fn check_file(&self, path: &Path) -> Result<PathBuf, IoError> {
        self.check(path, None).map(|(resolved, _)| resolved)
    }

    /// The bytes of the file at `path`.
    ///
    /// # Errors
    ///
    /// [`IoError::Io`] when the file (or the root) cannot be found or read;
    /// [`IoError::Refused`] when it is not a regular file, lies outside the root, or is
    /// larger than the cap.
    pub fn read(&self, path: &Path) -> Result<Vec<u8>, IoError> {
        self.read_within(path, None, u64::MAX)
    }

    /// The text of the file at `path` (UTF-8).
    ///
    /// # Errors
    ///
    /// As [`FilePolicy::read`]; [`IoError::Io`] (of kind `InvalidData`) when the file is
    /// not UTF-8.
    pub fn read_to_string(&self, path: &Path) -> Result<String, IoError> {
        let bytes = self.read(path)?;
        String::from_utf8(bytes).map_err(|e| IoError::Io {
            path: path.to_owned(),
            source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error()),
        })
    }

    /// The file at `path`, opened for reading if the policy admits it, to be read as a
    /// stream (a large file need not be held in memory at once): reading stops at the
    /// length the file had when it was checked, which [`Take::limit`] gives.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::io::Read;
    /// use sphaera_io::FilePolicy;
    ///
    /// let dir = tempfile::tempdir()?;
    /// let path = dir.path().join("note.txt");
    /// std::fs::write(&path, "hello")?;
    /// let mut file = FilePolicy::default().open(&path)?;
    /// assert_eq!(file.limit(), 5);
    /// let mut text = String::new();
    /// file.read_to_string(&mut text)?;
    /// assert_eq!(text, "hello");
    /// assert!(FilePolicy::default().open(dir.path()).is_err()); // a folder
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`FilePolicy::read`] (the reading's own errors come from the stream).
    pub fn open(&self, path: &Path) -> Result<Take<File>, IoError> {
        self.open_within(path, None)
    }

    /// [`FilePolicy::open`], the file also confined to `folder`.
    fn open_within(&self, path: &Path, folder: Option<&Path>) -> Result<Take<File>, IoError> {
        let (resolved, length) = self.check(path, folder)?;
        let io = |source| IoError::Io {
            path: path.to_owned(),
            source,
        };
        let file = open_without_blocking(&resolved).map_err(io)?;
        // Checked again on the file opened: it may have been replaced since.
        let metadata = file.metadata().map_err(io)?;
        self.check_metadata(path, &metadata)?;
        Ok(file.take(length))
    }

    /// [`FilePolicy::read`], the file also confined to `folder` (a glTF asset's folder),
    /// and read to at most `limit` bytes (a glTF buffer's length).
    pub(crate) fn read_within(
        &self,
        path: &Path,
        folder: Option<&Path>,
        limit: u64,
    ) -> Result<Vec<u8>, IoError> {
        let mut file = self.open_within(path, folder)?;
        let length = file.limit().min(limit);
        file.set_limit(length);
        let io = |source| IoError::Io {
            path: path.to_owned(),
            source,
        };
        let mut bytes = Vec::new();
        // `length` is at most the cap: a file that grew is read to its checked length.
        bytes
            .try_reserve_exact(usize::try_from(length).unwrap_or(usize::MAX))
            .map_err(|_| IoError::Io {
                path: path.to_owned(),
                source: std::io::Error::from(std::io::ErrorKind::OutOfMemory),
            })?;
        file.read_to_end(&mut bytes).map_err(io)?;
        Ok(bytes)
    }

    /// The resolved path and length of a file this policy reads, or why not.
    fn check(&self, path: &Path, folder: Option<&Path>) -> Result<(PathBuf, u64), IoError> {
        let io = |at: &Path, source| IoError::Io {
            path: at.to_owned(),
            source,
        };
        let resolved = path.canonicalize().map_err(|e| io(path, e))?;
        let roots = self.root.as_deref().into_iter().chain(folder);
        for root in roots {
            let root_resolved = root.canonicalize().map_err(|e| io(root, e))?;
            if !resolved.starts_with(&root_resolved) {
                return Err(IoError::Refused {
                    path: path.to_owned(),
                    refusal: FileRefusal::OutsideRoot {
                        root: root.to_owned(),
                    },
                });
            }
        }
        let metadata = std::fs::metadata(&resolved).map_err(|e| io(path, e))?;
        let length = self.check_metadata(path, &metadata)?;
        Ok((resolved, length))
    }

    /// The length of a regular file within the cap, or why it is refused.
    fn check_metadata(&self, path: &Path, metadata: &Metadata) -> Result<u64, IoError> {
        let refused = |refusal| IoError::Refused {
            path: path.to_owned(),
            refusal,
        };
        if !metadata.is_file() {
            return Err(refused(FileRefusal::NotRegular {
                kind: kind_of(metadata),
            }));
        }
        if metadata.len() > self.max_bytes {
            return Err(refused(FileRefusal::TooLarge {
                bytes: metadata.len(),
                cap: self.max_bytes,
            }));
        }
        Ok(metadata.len())
    }
}

/// What a file that is not regular is, in words.
fn kind_of(metadata: &Metadata) -> &'static str {
    let file_type = metadata.file_type();
    if file_type.is_dir() {
        return "a folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a named pipe";
        }
        if file_type.is_socket() {
            return "a socket";
        }
        if file_type.is_block_device() || file_type.is_char_device() {
            return "a device";
        }
    }
    "a special file"
}

/// Opens `path` for reading without waiting for a writer, should it have become a named
/// pipe since it was checked.
fn open_without_blocking(path: &Path) -> std::io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options.open(path)
}
