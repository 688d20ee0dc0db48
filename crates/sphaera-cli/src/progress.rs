//! Progress display on stderr (indicatif): spinners and bars, silent with `--quiet` or when
//! stderr is not a terminal.

use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

/// A spinner with a message, for steps whose length is unknown (loading a file).
///
/// Hidden with `--quiet`; indicatif itself hides it when stderr is not a terminal, so
/// scripts and `--json` pipelines see clean output.
pub fn spinner(quiet: bool, message: &str) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new_spinner();
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} ({elapsed})") {
        bar.set_style(style);
    }
    bar.set_message(message.to_owned());
    bar.enable_steady_tick(Duration::from_millis(100));
    bar
}

/// A progress bar of `len` steps with a message, for work whose size is known
/// (simplification reports triangles removed out of triangles to remove).
///
/// Hidden with `--quiet`, and by indicatif when stderr is not a terminal.
pub fn bar(quiet: bool, message: &str, len: u64) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len);
    if let Ok(style) = ProgressStyle::with_template(
        "{msg} [{bar:40}] {percent:>3} % ({elapsed}, about {eta} left)",
    ) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message.to_owned());
    bar
}

/// The simplification hierarchy of `mesh` (the default options), with a bar of the
/// triangles removed.
///
/// # Errors
///
/// As [`sphaera::simplify::Hierarchy::build`].
pub fn hierarchy(
    quiet: bool,
    mesh: &sphaera::mesh::TriMesh,
) -> Result<sphaera::simplify::Hierarchy, sphaera::simplify::SimplifyError> {
    let triangles = mesh.triangle_count();
    let bar = bar(
        quiet,
        &format!(
            "building the hierarchy of {} triangles",
            crate::output::thousands(triangles)
        ),
        triangles as u64,
    );
    let report_progress = |p: &sphaera::simplify::SimplifyProgress| {
        bar.set_length(p.to_remove as u64);
        bar.set_position(p.removed as u64);
    };
    let hierarchy = sphaera::simplify::Hierarchy::build_with_progress(
        mesh,
        &sphaera::simplify::SimplifyOptions::default(),
        &report_progress,
    );
    bar.finish_and_clear();
    hierarchy
}
