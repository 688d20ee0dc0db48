//! Workspace automation for Sphaera, reached through the `cargo xtask` alias.
//!
//! ```text
//! cargo xtask test          every test: unit, cross-crate (`tests/`), doctests
//! cargo xtask ci            fmt check, clippy -D warnings, tests, docs -D warnings,
//!                           duplicate-glam check, generated-file check
//! cargo xtask bench [ARGS]  the criterion benches (ARGS go to `cargo bench`)
//! cargo xtask charts        run the sphaera-eval experiments, write docs/charts/*.svg + *.csv
//! cargo xtask charts --check  fail if a chart or its CSV is missing, or the CSV misses
//!                           a mesh of ../shared/data the chart must cover
//! ```

// A command-line tool reports on the terminal.
#![allow(clippy::print_stderr, clippy::print_stdout)]

use std::{
    path::{Path, PathBuf},
    process::Command,
    time::Instant,
};

use anyhow::{Context, Result, bail};

const USAGE: &str = "usage: cargo xtask <test | ci | bench [ARGS..] | charts [--check]>";

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let task = args.next().unwrap_or_default();
    let rest: Vec<String> = args.collect();
    let root = project_root();
    std::env::set_current_dir(&root)
        .with_context(|| format!("cannot enter the project root {}", root.display()))?;
    match task.as_str() {
        "test" => test(),
        "ci" => ci(),
        "bench" => bench(&rest),
        "charts" => charts(rest.iter().any(|a| a == "--check")),
        "" | "help" | "--help" | "-h" => {
            eprintln!("{USAGE}");
            Ok(())
        }
        other => bail!("unknown task `{other}`\n{USAGE}"),
    }
}

/// The workspace root: the parent of this crate's manifest directory.
fn project_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Runs `cargo ARGS`, failing with the command line if it fails.
fn cargo(args: &[&str]) -> Result<()> {
    cargo_with_env(args, &[])
}

fn cargo_with_env(args: &[&str], env: &[(&str, &str)]) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    eprintln!("$ cargo {}", args.join(" "));
    let started = Instant::now();
    let status = Command::new(&cargo)
        .args(args)
        .envs(env.iter().copied())
        .status()
        .with_context(|| format!("cannot run {cargo}"))?;
    eprintln!(
        "  ({:.1} s, {})",
        started.elapsed().as_secs_f64(),
        if status.success() { "ok" } else { "FAILED" }
    );
    if !status.success() {
        bail!("`cargo {}` failed ({status})", args.join(" "));
    }
    Ok(())
}

/// Every test: unit and integration tests of every crate, the cross-crate tests in
/// `tests/`, and the doctests (all run by `cargo test`); then the mesh, simplification,
/// medial, sphere-tree and scene crates again without their default `parallel` feature, whose
/// results must be identical (their tests compare digests of their results with the same
/// recorded values both ways),
/// and the sphere-tree's export and awkward-mesh tests with its optional `parry` feature.
fn test() -> Result<()> {
    cargo(&["test", "--workspace", "--locked"])?;
    for crate_name in [
        "sphaera-mesh",
        "sphaera-simplify",
        "sphaera-medial",
        "sphaera-spheretree",
        "sphaera-scene",
    ] {
        cargo(&[
            "test",
            "--locked",
            "-p",
            crate_name,
            "--no-default-features",
            "--lib",
            "--tests",
        ])?;
    }
    // The sphere-tree's parry3d export, behind its optional feature (the awkward meshes
    // write it too).
    cargo(&[
        "test",
        "--locked",
        "-p",
        "sphaera-spheretree",
        "--features",
        "parry",
        "--test",
        "export",
        "--test",
        "awkward",
    ])?;
    Ok(())
}

fn ci() -> Result<()> {
    let started = Instant::now();
    cargo(&["fmt", "--all", "--check"])?;
    check_single_glam()?;
    cargo(&[
        "clippy",
        "--workspace",
        "--all-targets",
        "--locked",
        "--",
        "-D",
        "warnings",
    ])?;
    cargo(&[
        "clippy",
        "-p",
        "sphaera-spheretree",
        "--features",
        "parry",
        "--all-targets",
        "--locked",
        "--",
        "-D",
        "warnings",
    ])?;
    cargo_with_env(
        &["doc", "--workspace", "--no-deps", "--locked"],
        &[("RUSTDOCFLAGS", "-D warnings")],
    )?;
    test()?;
    charts(true)?;
    eprintln!("ci passed in {:.0} s", started.elapsed().as_secs_f64());
    Ok(())
}

/// Fails if the dependency graph holds two versions of glam: our `DVec3` must be the one
/// parry3d-f64 uses, or values cannot cross between the crates.
fn check_single_glam() -> Result<()> {
    eprintln!("$ cargo tree --workspace -d -e normal,build,dev --depth 0 --locked");
    let output = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned()))
        .args([
            "tree",
            "--workspace",
            "-d",
            "-e",
            "normal,build,dev",
            "--depth",
            "0",
            "--locked",
        ])
        .output()
        .context("cannot run cargo tree")?;
    if !output.status.success() {
        bail!(
            "cargo tree failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let tree = String::from_utf8_lossy(&output.stdout);
    let glams: Vec<&str> = tree
        .lines()
        .filter(|line| line.starts_with("glam v"))
        .collect();
    if !glams.is_empty() {
        bail!(
            "two versions of glam in the dependency graph ({}): pin `glam` in the root \
             Cargo.toml to the version parry3d-f64 uses",
            glams.join(", ")
        );
    }
    eprintln!("  (one glam: ok)");
    Ok(())
}

fn bench(args: &[String]) -> Result<()> {
    let mut full = vec!["bench", "--workspace", "--locked"];
    full.extend(args.iter().map(String::as_str));
    cargo(&full)
}

/// Which meshes of `../shared/data` a chart's CSV must list in its first column.
enum Coverage {
    /// Every mesh file of the folder (a chart over the whole collection).
    EveryMesh,
    /// These files (relative to the folder), when present: a chart that covers chosen
    /// meshes by design.
    Only(&'static [&'static str]),
}

/// The charts `cargo xtask charts` must produce, each as `docs/charts/NAME.svg` with the
/// data behind it in `docs/charts/NAME.csv`, and the meshes its CSV must cover.
const CHARTS: &[(&str, Coverage)] = &[
    ("load_topology_time", Coverage::EveryMesh),
    (
        "simplify_error_vs_time",
        Coverage::Only(&["stanford-bunny.obj", "dragon_vrip.ply"]),
    ),
    (
        "sweep_throughput",
        Coverage::Only(&[
            "bunny_lowres.obj",
            "dragon_vrip_res4.ply",
            "dragon_vrip_res3.ply",
            "stanford-bunny.obj",
            "dragon_vrip_res2.ply",
            "dragon_vrip.ply",
        ]),
    ),
    (
        "sweep_speedup_vs_step",
        Coverage::Only(&["stanford-bunny.obj", "dragon_vrip_res2.ply"]),
    ),
    (
        "hausdorff_gap_vs_time",
        Coverage::Only(&["stanford-bunny.obj", "bunny_lowres.obj"]),
    ),
    (
        "medial_static_vs_adaptive",
        Coverage::Only(&["stanford-bunny.obj", "dragon_vrip.ply"]),
    ),
    (
        "spheretree_error_vs_level",
        Coverage::Only(&[
            "bunny_lowres.obj",
            "dragon_vrip_res4.ply",
            "robots/franka_panda/collision/link3.obj",
        ]),
    ),
    (
        "spheretree_error_vs_time",
        Coverage::Only(&[
            "bunny_lowres.obj",
            "dragon_vrip_res4.ply",
            "robots/franka_panda/collision/link3.obj",
        ]),
    ),
    (
        "hal_width_vs_size",
        Coverage::Only(&[
            "polygons/netherlands.txt",
            "polygons/norway.txt",
            "polygons/americas.txt",
            "spot.obj",
            "bunny_lowres.obj",
            "fandisk.obj",
        ]),
    ),
    (
        "hal_query_speed",
        Coverage::Only(&[
            "polygons/luxembourg.txt",
            "polygons/netherlands.txt",
            "polygons/belgium.txt",
            "polygons/united-kingdom.txt",
            "polygons/norway.txt",
            "polygons/afro-eurasia.txt",
            "polygons/americas.txt",
        ]),
    ),
    (
        "hal_vs_strip_tree",
        Coverage::Only(&["polygons/netherlands.txt", "polygons/norway.txt"]),
    ),
    (
        "hal_vs_simplify",
        Coverage::Only(&["spot.obj", "bunny_lowres.obj", "fandisk.obj"]),
    ),
    (
        "silhouette_error_vs_triangles",
        Coverage::Only(&["stanford-bunny.obj", "dragon_vrip_res2.ply"]),
    ),
    (
        "silhouette_time_vs_faces",
        Coverage::Only(&[
            "dragon_vrip_res4.ply",
            "dragon_vrip_res3.ply",
            "stanford-bunny.obj",
            "dragon_vrip_res2.ply",
            "dragon_vrip.ply",
        ]),
    ),
];

/// Fails if a mesh of `../shared/data` that the chart must cover is missing from its CSV
/// (first column): the chart is stale and must be regenerated. Skipped when the data
/// folder is absent.
fn check_chart_coverage(csv: &Path, coverage: &Coverage) -> Result<()> {
    let data = std::env::var_os("SPHAERA_DATA").map_or_else(
        || Path::new("..").join("shared").join("data"),
        PathBuf::from,
    );
    if !data.is_dir() {
        eprintln!("  (no {}: chart coverage not checked)", data.display());
        return Ok(());
    }
    let text =
        std::fs::read_to_string(csv).with_context(|| format!("cannot read {}", csv.display()))?;
    let charted: Vec<&str> = text
        .lines()
        .skip(1)
        .filter_map(|line| line.split(',').next())
        .collect();
    let required = match coverage {
        Coverage::EveryMesh => mesh_files(&data)?,
        Coverage::Only(files) => files
            .iter()
            .filter(|file| data.join(file).is_file())
            .map(|file| (*file).to_owned())
            .collect(),
    };
    let mut missing: Vec<String> = required
        .into_iter()
        .filter(|name| !charted.contains(&name.as_str()))
        .collect();
    if !missing.is_empty() {
        missing.sort();
        bail!(
            "{} does not chart {}; run `cargo xtask charts` and commit",
            csv.display(),
            missing.join(", ")
        );
    }
    Ok(())
}

/// Every mesh file under `data` (OBJ, PLY, STL, OFF), relative to it, with `/` separators,
/// except the robot descriptions' assets under `robots/urdf/` (as `sphaera_tests::mesh_files`).
fn mesh_files(data: &Path) -> Result<Vec<String>> {
    let mut files = Vec::new();
    let mut folders = vec![data.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder)
            .with_context(|| format!("cannot list {}", folder.display()))?
        {
            let path = entry?.path();
            let is_mesh = path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                matches!(
                    e.to_ascii_lowercase().as_str(),
                    "obj" | "ply" | "stl" | "off"
                )
            });
            if path.is_dir() {
                if !path.ends_with("robots/urdf") {
                    folders.push(path);
                }
            } else if is_mesh {
                let relative = path.strip_prefix(data).unwrap_or(&path);
                files.push(relative.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    Ok(files)
}

fn charts(check: bool) -> Result<()> {
    let dir = Path::new("docs/charts");
    if check {
        let missing: Vec<String> = CHARTS
            .iter()
            .flat_map(|(name, _)| [format!("{name}.svg"), format!("{name}.csv")])
            .filter(|file| !dir.join(file).is_file())
            .collect();
        if !missing.is_empty() {
            bail!(
                "missing generated files in docs/charts: {}; run `cargo xtask charts` and commit",
                missing.join(", ")
            );
        }
        for (name, coverage) in CHARTS {
            check_chart_coverage(&dir.join(format!("{name}.csv")), coverage)?;
        }
        eprintln!("  (charts present: ok)");
        return Ok(());
    }
    cargo(&[
        "run",
        "--release",
        "--locked",
        "-p",
        "sphaera-eval",
        "--",
        "--out",
        "docs/charts",
    ])
}
