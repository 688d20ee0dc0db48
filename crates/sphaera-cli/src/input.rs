//! Reading the mesh a subcommand works on: a file, or the embedded default mesh.

use std::{path::Path, sync::OnceLock, time::Instant};

use anyhow::{Context, Result};
use sphaera::mesh::io::{self, Format, LoadedMesh};

use crate::progress;

/// The default mesh: the public-domain low-resolution Stanford bunny (npm `bunny` 1.0.1),
/// closed, genus 0, 3,674 triangles.
const EMBEDDED_BUNNY: &[u8] = include_bytes!("../assets/bunny_lowres.obj");

/// The name shown for the embedded mesh.
pub const EMBEDDED_NAME: &str = "<embedded bunny_lowres.obj>";

/// A mesh read for a subcommand, with where it came from and how long reading took.
pub struct Input {
    /// The file name, or [`EMBEDDED_NAME`].
    pub source: String,
    /// The mesh and the reader's report.
    pub loaded: LoadedMesh,
    /// Seconds spent reading and parsing.
    pub seconds: f64,
}

/// Reads `path`, or the embedded bunny when `path` is `None`, with a spinner on stderr.
///
/// # Errors
///
/// When the file cannot be read or parsed; the message names the file and, for malformed
/// data, the line or byte offset.
pub fn read_mesh(path: Option<&Path>, quiet: bool) -> Result<Input> {
    let started = Instant::now();
    let (source, loaded) = match path {
        Some(path) => {
            let source = path.display().to_string();
            let spinner = progress::spinner(quiet, &format!("reading {source}"));
            let loaded = io::read_with(path, &file_policy());
            spinner.finish_and_clear();
            // The error names the file (and the line or byte offset when it is malformed).
            let loaded = loaded?;
            (source, loaded)
        }
        None => (
            EMBEDDED_NAME.to_owned(),
            io::read_from_bytes(EMBEDDED_BUNNY, Format::Obj)
                .context("cannot parse the embedded bunny")?,
        ),
    };
    Ok(Input {
        source,
        loaded,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The cap `--max-file-bytes` set, if it was given.
static MAX_FILE_BYTES: OnceLock<u64> = OnceLock::new();

/// Sets the size cap of every file this run reads (`--max-file-bytes`); the first call wins.
pub fn set_max_file_bytes(bytes: u64) {
    // A second call (there is none: `commands::run` makes the one) keeps the first cap.
    let _ = MAX_FILE_BYTES.set(bytes);
}

/// The policy for every file this run reads, and every file those name: regular files only
/// (a device or a named pipe is refused at once, not read until memory runs out or a writer
/// comes), of at most `--max-file-bytes` (2 GiB by default).
pub fn file_policy() -> io::FilePolicy {
    let policy = io::FilePolicy::default();
    match MAX_FILE_BYTES.get() {
        Some(&bytes) => policy.with_max_bytes(bytes),
        None => policy,
    }
}

/// The text of a file a user names (points, a polygon, a tree), by [`file_policy`], UTF-8.
///
/// # Errors
///
/// When the file cannot be read, the policy refuses it, or it is not UTF-8; `what` names
/// it in the message.
pub fn read_text(path: &Path, what: &str) -> Result<String> {
    file_policy()
        .read_to_string(path)
        .with_context(|| format!("cannot read {what} {}", path.display()))
}
