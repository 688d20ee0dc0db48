//! Peers that are not Rust crates, run as child processes in the same sitting as Sphaera.
//!
//! Today one: **cascading-upper-bounds** (Sacht & Jacobson, SGP 2024), the certified
//! Hausdorff distance of its Python package, run by `peers/cub_hausdorff.py`. The
//! `hausdorff` bench and the `hausdorff_gap_vs_time` experiment both go through
//! [`cub_python`] and [`run_cub`], so that they time exactly the same calls.
//!
//! The interpreter is `$SPHAERA_CUB_PYTHON`, else `python3`; install the peer with
//!
//! ```text
//! python3 -m venv env && env/bin/pip install cascading_upper_bounds numpy
//! SPHAERA_CUB_PYTHON=env/bin/python cargo bench -p sphaera-eval --bench hausdorff
//! ```

use std::{
    path::{Path, PathBuf},
    process::Command,
};

use anyhow::{Context, Result, bail};

/// One run of the peer: both one-sided distances to a tolerance, as the script reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubRun {
    /// Seconds spent in the two one-sided calls (loading excluded).
    pub seconds: f64,
    /// Certified lower bound of the symmetric distance.
    pub lower: f64,
    /// Certified upper bound of the symmetric distance.
    pub upper: f64,
}

/// The Python interpreter that imports `cascading_upper_bounds`, or `None`, said on the
/// terminal with `who` (the bench or experiment skipping the peer) and how to install it.
#[must_use]
pub fn cub_python(who: &str) -> Option<PathBuf> {
    let python =
        std::env::var_os("SPHAERA_CUB_PYTHON").map_or_else(|| "python3".into(), PathBuf::from);
    let works = Command::new(&python)
        .args(["-c", "import cascading_upper_bounds"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !works {
        #[allow(clippy::print_stderr)] // a skipped peer is said where the figures appear
        {
            eprintln!(
                "{who}: skipped cascading_upper_bounds: `{}` cannot import it \
                 (`python3 -m venv env && env/bin/pip install cascading_upper_bounds numpy`, \
                 then SPHAERA_CUB_PYTHON=env/bin/python)",
                python.display()
            );
        }
    }
    works.then_some(python)
}

/// Runs the peer `runs` times on the OBJ files `a` and `b` to `tolerance`, relative to the
/// bounding-box diagonal of both meshes together, one [`CubRun`] per run.
///
/// # Errors
///
/// When the script cannot start, fails, or prints something other than one JSON object
/// per run.
pub fn run_cub(
    python: &Path,
    a: &Path,
    b: &Path,
    tolerance: f64,
    runs: u64,
) -> Result<Vec<CubRun>> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("peers/cub_hausdorff.py");
    let output = Command::new(python)
        .arg(&script)
        .arg(a)
        .arg(b)
        .arg(tolerance.to_string())
        .arg(runs.to_string())
        .output()
        .with_context(|| format!("cannot run {}", script.display()))?;
    if !output.status.success() {
        bail!(
            "cub_hausdorff.py failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let mut out = Vec::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let run: serde_json::Value = serde_json::from_str(line)
            .with_context(|| format!("cub_hausdorff.py printed {line:?}"))?;
        let field = |k: &str| {
            run[k]
                .as_f64()
                .with_context(|| format!("cub_hausdorff.py printed no {k:?} in {line:?}"))
        };
        out.push(CubRun {
            seconds: field("seconds")?,
            lower: field("lower")?,
            upper: field("upper")?,
        });
    }
    if out.is_empty() {
        bail!("cub_hausdorff.py printed no run");
    }
    Ok(out)
}
