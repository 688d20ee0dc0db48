//! The Python bindings' tests: `crates/sphaera-py` built into a virtual environment that
//! this creates (`python-venv` in the target directory, packages from PyPI pinned in
//! `crates/sphaera-py/requirements-test.txt`) with `maturin develop`, then its pytest
//! suite, which checks the numbers against the `sphaera` binary's (`SPHAERA_CLI`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};

/// The virtual environment's folder in the target directory.
const VENV: &str = "python-venv";
const REQUIREMENTS: &str = "crates/sphaera-py/requirements-test.txt";

/// Runs `program` with `args` (and `envs`), echoing the command, failing on failure.
fn run(program: &Path, args: &[&str], envs: &[(&str, &std::ffi::OsStr)]) -> Result<()> {
    eprintln!("$ {} {}", program.display(), args.join(" "));
    let started = Instant::now();
    let status = Command::new(program)
        .args(args)
        .envs(envs.iter().copied())
        .status()
        .with_context(|| format!("cannot run {}", program.display()))?;
    let seconds = started.elapsed().as_secs_f64();
    eprintln!(
        "  ({seconds:.1} s, {})",
        if status.success() { "ok" } else { "FAILED" }
    );
    crate::record_step(
        &format!("{} {}", program.display(), args.join(" ")),
        seconds,
    );
    if !status.success() {
        bail!(
            "`{} {}` failed ({status})",
            program.display(),
            args.join(" ")
        );
    }
    Ok(())
}

/// The virtual environment's Python, created (with the pinned packages) in `venv` when
/// missing.
fn python_in(venv: &Path) -> Result<PathBuf> {
    let python = venv.join("bin/python");
    if !python.exists() {
        let system = ["python3", "python"]
            .into_iter()
            .find(|name| {
                Command::new(name)
                    .arg("--version")
                    .output()
                    .is_ok_and(|o| o.status.success())
            })
            .context(
                "the Python bindings' tests need Python 3.9 or later with `venv` \
                 (on Debian or Ubuntu: `sudo apt-get install python3 python3-venv`)",
            )?;
        let folder = venv.to_string_lossy();
        run(Path::new(system), &["-m", "venv", &folder], &[])?;
    }
    run(
        &python,
        &[
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
            "-r",
            REQUIREMENTS,
        ],
        &[],
    )?;
    Ok(python)
}

pub fn python_test() -> Result<()> {
    let folder = crate::target_dir()?.join(VENV);
    let python = python_in(&folder)?;
    let venv = std::fs::canonicalize(&folder)
        .with_context(|| format!("cannot find {}", folder.display()))?;
    let bin = venv.join("bin");
    let path = std::env::join_paths(std::iter::once(bin.clone()).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .context("a PATH with the virtual environment")?;
    let envs: Vec<(&str, &std::ffi::OsStr)> = vec![
        ("VIRTUAL_ENV", venv.as_os_str()),
        ("PATH", path.as_os_str()),
    ];
    // The extension in the workspace's dev profile, sharing the target directory.
    run(
        &bin.join("maturin"),
        &[
            "develop",
            "--quiet",
            "--locked",
            "--manifest-path",
            "crates/sphaera-py/Cargo.toml",
        ],
        &envs,
    )?;
    // The CLI the suite compares against (built by the Rust tests already).
    let cli = crate::built_cli()?;
    let mut envs = envs;
    envs.push(("SPHAERA_CLI", cli.as_os_str()));
    run(
        &python,
        &["-m", "pytest", "-q", "crates/sphaera-py/tests"],
        &envs,
    )
}
