//! Workspace automation for Sphaera, reached through the `cargo xtask` alias.
//!
//! ```text
//! cargo xtask test          every test: unit, cross-crate (`tests/`), doctests
//! cargo xtask ci            fmt check, duplicate-glam check, clippy -D warnings, the
//!                           API reference as docs.rs builds it and the whole
//!                           workspace's docs with default features (-D warnings),
//!                           package dry run, tests, generated-file checks (charts
//!                           and tables)
//! cargo xtask doc           the API reference of every published library crate as
//!                           docs.rs builds it: all features, `--cfg docsrs`, -D warnings
//! cargo xtask package       `cargo package` dry run of every crate meant for crates.io,
//!                           and a check of what each package holds
//! cargo xtask bench [ARGS]  the criterion benches (ARGS go to `cargo bench`)
//! cargo xtask charts [--only NAME]...
//!                           run the sphaera-eval experiments (or only those named),
//!                           write docs/charts/*.svg + *.csv
//! cargo xtask browser-test [--update-images]
//!                           `sphaera view` pages in headless Chromium (console errors,
//!                           spheres drawn per level, certified errors shown, canvas not
//!                           blank); `--update-images` refreshes the README's screenshots
//! cargo xtask charts --check  fail if a chart or its CSV is missing, or the CSV misses
//!                           a mesh of ../shared/data the chart must cover
//! cargo xtask tables        regenerate the markdown tables marked `<!-- table: NAME -->`
//!                           in the docs from docs/charts/NAME.csv (format: `tables/mod.rs`)
//! cargo xtask tables --check  fail if a generated table differs from its CSV, or a typed
//!                           table of docs/benchmarks.md is not a dated snapshot naming
//!                           its command (`<!-- snapshot: YYYY-MM-DD; COMMAND -->`)
//! ```
//!
//! `test`, `ci` and `bench` turn on sphaera-eval's `geos` feature (the GEOS peer of 2D
//! point inclusion) when `pkg-config --exists geos` finds GEOS, and say so when not.

// A command-line tool reports on the terminal.
#![allow(clippy::print_stderr, clippy::print_stdout)]

mod browser;
mod charts;
mod ci;
mod publish;
mod python;
mod tables;

use std::{
    path::{Path, PathBuf},
    process::Command,
    time::Instant,
};

use anyhow::{Context, Result, bail};

use charts::{charts, only};
use ci::{ci, test};
use publish::{doc, package};

const USAGE: &str = "usage: cargo xtask <test | ci | doc | package | bench [ARGS..] | charts [--check | --only NAME...] | tables [--check] | browser-test [--update-images] | python-test>";

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
        "python-test" => python::python_test(),
        "ci" => ci(),
        "doc" => doc(),
        "package" => package(),
        "bench" => bench(&rest),
        "charts" => charts(rest.iter().any(|a| a == "--check"), &only(&rest)?),
        "tables" => tables::tables(rest.iter().any(|a| a == "--check")),
        "browser-test" => browser::browser_test(rest.iter().any(|a| a == "--update-images")),
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

/// The workspace's target directory as cargo resolves it (`CARGO_TARGET_DIR`,
/// `build.target-dir` in a cargo configuration, or `target/`), from `cargo metadata`.
fn target_dir() -> Result<PathBuf> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    let output = Command::new(&cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .output()
        .with_context(|| format!("cannot run {cargo} metadata"))?;
    if !output.status.success() {
        bail!(
            "`cargo metadata` failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let metadata: serde_json::Value =
        serde_json::from_slice(&output.stdout).context("`cargo metadata` is not JSON")?;
    metadata["target_directory"]
        .as_str()
        .map(PathBuf::from)
        .context("`cargo metadata` names no target directory")
}

/// The `sphaera` binary of the dev profile as the workspace's tests build it: `cargo test
/// --workspace --no-run` (nothing to do after `cargo xtask test`'s first run). A `cargo
/// build -p sphaera-cli` would resolve the dependencies' features without the test
/// helpers' and compile the CLI's whole stack again (90 s on 2 cores), replacing the
/// binary the tests ran.
fn built_cli() -> Result<PathBuf> {
    // The features of `cargo xtask test`'s first run, or sphaera-eval is compiled again.
    let mut args = vec!["test", "--workspace", "--locked", "--no-run"];
    args.extend(ci::geos_features());
    cargo(&args)?;
    debug_cli()
}

/// The `sphaera` binary of the dev profile, as last built.
fn debug_cli() -> Result<PathBuf> {
    let cli = target_dir()?.join("debug").join("sphaera");
    std::fs::canonicalize(&cli).with_context(|| format!("cannot find {}", cli.display()))
}

/// Every command run so far with its time in seconds, for [`ci::ci`]'s summary.
static STEPS: std::sync::Mutex<Vec<(String, f64)>> = std::sync::Mutex::new(Vec::new());

/// Records a step's time for the summary.
fn record_step(command: &str, seconds: f64) {
    if let Ok(mut steps) = STEPS.lock() {
        steps.push((command.to_owned(), seconds));
    }
}

/// Prints every step's time, longest first.
fn print_steps() {
    let Ok(mut steps) = STEPS.lock() else {
        return;
    };
    steps.sort_by(|a, b| b.1.total_cmp(&a.1));
    eprintln!("time per step:");
    for (command, seconds) in steps.iter() {
        let shown: String = command.chars().take(100).collect();
        eprintln!("  {seconds:>7.1} s  {shown}");
    }
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
    let seconds = started.elapsed().as_secs_f64();
    eprintln!(
        "  ({seconds:.1} s, {})",
        if status.success() { "ok" } else { "FAILED" }
    );
    record_step(&format!("cargo {}", args.join(" ")), seconds);
    if !status.success() {
        bail!("`cargo {}` failed ({status})", args.join(" "));
    }
    Ok(())
}
fn bench(args: &[String]) -> Result<()> {
    let mut full = vec!["bench", "--workspace", "--locked"];
    // The GEOS peer's bench too when GEOS is installed.
    full.extend(ci::geos_features());
    full.extend(args.iter().map(String::as_str));
    cargo(&full)
}
