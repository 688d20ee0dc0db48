//! Shared fixtures for Sphaera's cross-crate tests, benches and experiments.
//!
//! The real meshes live outside the repository, in `../shared/data` beside the checkout
//! (override with `SPHAERA_DATA=/path/to/data`). Tests that need them call [`data_dir`]:
//! when the folder is absent they skip with a message, unless `SPHAERA_REQUIRE_DATA=1`
//! (CI sets it), in which case they fail.

use std::path::{Path, PathBuf};

/// Where the shared meshes are: `$SPHAERA_DATA`, or `../shared/data` beside the workspace.
pub fn data_root() -> PathBuf {
    match std::env::var_os("SPHAERA_DATA") {
        Some(dir) => PathBuf::from(dir),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data"),
    }
}

/// Whether a missing data folder must fail the run (`SPHAERA_REQUIRE_DATA=1`).
pub fn data_required() -> bool {
    std::env::var("SPHAERA_REQUIRE_DATA").is_ok_and(|v| v == "1")
}

/// The shared data folder, or `None` (with a message on stderr) when it is absent and not
/// required.
///
/// # Panics
///
/// When the folder is absent and `SPHAERA_REQUIRE_DATA=1`.
pub fn data_dir(test_name: &str) -> Option<PathBuf> {
    let dir = data_root();
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(
        !data_required(),
        "{test_name}: the shared meshes are required (SPHAERA_REQUIRE_DATA=1) but {} is missing",
        dir.display()
    );
    #[allow(clippy::print_stderr)] // a skipped test says why
    {
        eprintln!(
            "{test_name}: skipped, no shared meshes at {} (set SPHAERA_DATA)",
            dir.display()
        );
    }
    None
}

/// Every mesh file under `dir` (recursively), sorted by path, relative to `dir`.
pub fn mesh_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    collect(dir, dir, &mut files);
    files.sort();
    files
}

fn collect(root: &Path, dir: &Path, files: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(root, &path, files);
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "obj" | "ply" | "stl" | "off"))
        {
            if let Ok(relative) = path.strip_prefix(root) {
                files.push(relative.to_path_buf());
            }
        }
    }
}
