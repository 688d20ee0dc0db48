//! Peers that are not Rust crates, run as child processes in the same sitting as Sphaera.
//!
//! - **cascading-upper-bounds** (Sacht & Jacobson, SGP 2024), the certified Hausdorff
//!   distance of its Python package, run by `peers/cub_hausdorff.py`. The `hausdorff`
//!   bench and the `hausdorff_gap_vs_time` experiment both go through [`cub_python`] and
//!   [`run_cub`], so that they time exactly the same calls. The interpreter is
//!   `$SPHAERA_CUB_PYTHON`, else `python3`.
//! - **morphit-rs** (PyPI 0.2.0, the `MorphIt` sphere packer in Rust for Python), run by
//!   `peers/morphit_spheres.py`: a fixed number of spheres per mesh, its default preset
//!   and seed 0. The `spheres_vs_morphit` bench and the `spheres_vs_count` experiment
//!   both go through [`morphit_python`] and [`run_morphit`]. The interpreter is
//!   `$SPHAERA_MORPHIT_PYTHON`, else `python3`.
//! - **libigl** (PyPI `libigl` 2.6), the fast winding number of a triangle mesh (Barill et
//!   al., SIGGRAPH 2018) on one thread, run by `peers/igl_winding.py`: the 3D
//!   point-inclusion peer of the `hal3_vs_parry` bench, through [`igl_python`] and
//!   [`run_igl_winding`]. The interpreter is `$SPHAERA_IGL_PYTHON`, else `python3`.
//!
//! Install them with
//!
//! ```text
//! python3 -m venv env && env/bin/pip install cascading_upper_bounds numpy
//! SPHAERA_CUB_PYTHON=env/bin/python cargo bench -p sphaera-eval --bench hausdorff
//! python3 -m venv env && env/bin/pip install morphit-rs==0.2.0 numpy
//! SPHAERA_MORPHIT_PYTHON=env/bin/python cargo bench -p sphaera-eval --bench spheres_vs_morphit
//! python3 -m venv env && env/bin/pip install libigl numpy
//! SPHAERA_IGL_PYTHON=env/bin/python cargo bench -p sphaera-eval --bench hal3_vs_parry
//! ```

use std::{
    path::{Path, PathBuf},
    process::Command,
};

use anyhow::{Context, Result, bail};
use sphaera::mesh::{DVec3, Sphere};

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
    python_with(
        who,
        "SPHAERA_CUB_PYTHON",
        "cascading_upper_bounds",
        "cascading_upper_bounds numpy",
    )
}

/// `$variable` (else `python3`) when it can import `module`; else `None`, said on the
/// terminal with `who` and the command that installs `packages`.
fn python_with(who: &str, variable: &str, module: &str, packages: &str) -> Option<PathBuf> {
    let python = std::env::var_os(variable).map_or_else(|| "python3".into(), PathBuf::from);
    let works = Command::new(&python)
        .args(["-c", &format!("import {module}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if !works {
        #[allow(clippy::print_stderr)] // a skipped peer is said where the figures appear
        {
            eprintln!(
                "{who}: skipped {module}: `{}` cannot import it \
                 (`python3 -m venv env && env/bin/pip install {packages}`, \
                 then {variable}=env/bin/python)",
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

/// One sphere count of morphit-rs, as `peers/morphit_spheres.py` reports it.
#[derive(Clone, Debug, PartialEq)]
pub struct MorphitRun {
    /// The spheres asked for.
    pub requested: usize,
    /// The spheres it returned (at most `requested`: its final prune drops spheres whose
    /// centre left the mesh), or why `pack` failed on this count.
    pub spheres: std::result::Result<Vec<Sphere>, String>,
    /// The shortest time of `pack` over the runs, in seconds (0 when it failed).
    pub seconds: f64,
    /// The median time of `pack` over the runs, in seconds (0 when it failed).
    pub seconds_median: f64,
    /// Every run's time of `pack`, in seconds (empty when it failed).
    pub seconds_all: Vec<f64>,
}

/// The Python interpreter that imports `morphit_rs`, or `None`, said on the terminal
/// with `who` (the bench or experiment skipping the peer) and how to install it.
#[must_use]
pub fn morphit_python(who: &str) -> Option<PathBuf> {
    python_with(
        who,
        "SPHAERA_MORPHIT_PYTHON",
        "morphit_rs",
        "morphit-rs==0.2.0 numpy",
    )
}

/// Runs morphit-rs's default preset (`MorphIt-B`, seed 0, the package's default threads)
/// on the mesh file `mesh` (OBJ, STL or PLY) for each of `counts`, `runs` times each,
/// timing only `pack`: one [`MorphitRun`] per count, in order.
///
/// # Errors
///
/// When the script cannot start, fails (e.g. the mesh does not load), or prints
/// something other than one JSON object per count.
pub fn run_morphit(
    python: &Path,
    mesh: &Path,
    counts: &[usize],
    runs: usize,
) -> Result<Vec<MorphitRun>> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("peers/morphit_spheres.py");
    let list: Vec<String> = counts.iter().map(usize::to_string).collect();
    let output = Command::new(python)
        .arg(&script)
        .arg(mesh)
        .arg(list.join(","))
        .arg(runs.to_string())
        .output()
        .with_context(|| format!("cannot run {}", script.display()))?;
    if !output.status.success() {
        bail!(
            "morphit_spheres.py failed on {}: {}",
            mesh.display(),
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let mut out = Vec::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        out.push(parse_morphit(line)?);
    }
    if out.len() != counts.len() {
        bail!(
            "morphit_spheres.py reported {} counts of {}",
            out.len(),
            counts.len()
        );
    }
    Ok(out)
}

/// One JSON line of `morphit_spheres.py`.
fn parse_morphit(line: &str) -> Result<MorphitRun> {
    let run: serde_json::Value = serde_json::from_str(line)
        .with_context(|| format!("morphit_spheres.py printed {line:?}"))?;
    let number = |k: &str| {
        run[k]
            .as_f64()
            .with_context(|| format!("morphit_spheres.py printed no {k:?}"))
    };
    let requested = run["n"]
        .as_u64()
        .and_then(|n| usize::try_from(n).ok())
        .context("morphit_spheres.py printed no count")?;
    if let Some(error) = run["error"].as_str() {
        return Ok(MorphitRun {
            requested,
            spheres: Err(error.to_owned()),
            seconds: 0.0,
            seconds_median: 0.0,
            seconds_all: Vec::new(),
        });
    }
    let (Some(centers), Some(radii)) = (run["centers"].as_array(), run["radii"].as_array()) else {
        bail!("morphit_spheres.py printed no spheres for {requested}");
    };
    if centers.len() != radii.len() {
        bail!(
            "morphit_spheres.py printed {} centers and {} radii",
            centers.len(),
            radii.len()
        );
    }
    let mut spheres = Vec::with_capacity(radii.len());
    for (c, r) in centers.iter().zip(radii) {
        let xyz: Vec<f64> = c
            .as_array()
            .map(|a| a.iter().filter_map(serde_json::Value::as_f64).collect())
            .unwrap_or_default();
        let (&[x, y, z], Some(radius)) = (xyz.as_slice(), r.as_f64()) else {
            bail!("morphit_spheres.py printed a malformed sphere {c} {r}");
        };
        spheres.push(Sphere::new(DVec3::new(x, y, z), radius));
    }
    Ok(MorphitRun {
        requested,
        spheres: Ok(spheres),
        seconds: number("seconds")?,
        seconds_median: number("seconds_median")?,
        seconds_all: run["seconds_all"]
            .as_array()
            .map(|a| a.iter().filter_map(serde_json::Value::as_f64).collect())
            .unwrap_or_default(),
    })
}

/// One run of libigl's fast winding number, as `peers/igl_winding.py` reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IglRun {
    /// Seconds spent on the queries alone: the call on every point less the call on one
    /// point (libigl builds its hierarchy in each call, and its Python binding keeps none).
    pub seconds: f64,
    /// Seconds of the call on every point (the build included).
    pub seconds_all: f64,
    /// Seconds of the call on the first point alone (the build and the call's overhead).
    pub seconds_one: f64,
    /// The queries answered in `seconds_all`: the file's points times the repeats.
    pub points: u64,
    /// How many of the file's points have a winding number above 1/2.
    pub inside: u64,
}

/// The Python interpreter that imports `igl` (PyPI `libigl`), or `None`, said on the
/// terminal with `who` (the bench or experiment skipping the peer) and how to install it.
#[must_use]
pub fn igl_python(who: &str) -> Option<PathBuf> {
    python_with(who, "SPHAERA_IGL_PYTHON", "igl", "libigl numpy")
}

/// Writes `points` to `path` for `peers/igl_winding.py`: one point a line, three numbers
/// printed so that they read back exactly.
///
/// # Errors
///
/// When the file cannot be written.
pub fn write_points(path: &Path, points: &[DVec3]) -> Result<()> {
    let text: String = points
        .iter()
        .map(|p| format!("{:?} {:?} {:?}\n", p.x, p.y, p.z))
        .collect();
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}

/// Runs libigl's fast winding number on one thread on the mesh file `mesh` (OBJ) at the
/// points of `points` (written by [`write_points`]) repeated `repeats` times, `runs`
/// times: one [`IglRun`] per run.
///
/// # Errors
///
/// When the script cannot start, fails (e.g. a file does not load), or prints something
/// other than one JSON object per run.
pub fn run_igl_winding(
    python: &Path,
    mesh: &Path,
    points: &Path,
    repeats: u64,
    runs: u64,
) -> Result<Vec<IglRun>> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("peers/igl_winding.py");
    let output = Command::new(python)
        .arg(&script)
        .arg(mesh)
        .arg(points)
        .arg(repeats.to_string())
        .arg(runs.to_string())
        .output()
        .with_context(|| format!("cannot run {}", script.display()))?;
    if !output.status.success() {
        bail!(
            "igl_winding.py failed on {}: {}",
            mesh.display(),
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let mut out = Vec::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let run: serde_json::Value = serde_json::from_str(line)
            .with_context(|| format!("igl_winding.py printed {line:?}"))?;
        let number = |k: &str| {
            run[k]
                .as_f64()
                .with_context(|| format!("igl_winding.py printed no {k:?} in {line:?}"))
        };
        let count = |k: &str| {
            run[k]
                .as_u64()
                .with_context(|| format!("igl_winding.py printed no {k:?} in {line:?}"))
        };
        out.push(IglRun {
            seconds: number("seconds")?,
            seconds_all: number("seconds_all")?,
            seconds_one: number("seconds_one")?,
            points: count("points")?,
            inside: count("inside")?,
        });
    }
    if out.len() as u64 != runs {
        bail!("igl_winding.py reported {} runs of {runs}", out.len());
    }
    Ok(out)
}
