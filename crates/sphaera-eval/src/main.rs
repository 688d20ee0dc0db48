//! The `sphaera-eval` binary: runs the experiments of the `sphaera_eval` library and
//! writes their charts.
//!
//! ```text
//! cargo run --release -p sphaera-eval -- --out docs/charts [--only NAME]
//! ```
//!
//! `cargo xtask charts` runs it with `--out docs/charts`; `--help` lists the experiments.

// An experiment runner reports on the terminal.
#![allow(clippy::print_stdout, clippy::print_stderr)]

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use sphaera_eval::experiments;

fn main() -> Result<()> {
    let mut out = PathBuf::from("docs/charts");
    let mut only: Option<String> = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--out" => out = args.next().context("--out needs a folder")?.into(),
            "--only" => only = Some(args.next().context("--only needs an experiment name")?),
            "--help" | "-h" => {
                println!("usage: sphaera-eval [--out DIR] [--only NAME]");
                println!("experiments: {}", experiments::NAMES.join(", "));
                return Ok(());
            }
            other => bail!("unknown argument `{other}` (try --help)"),
        }
    }
    let Some(data) = sphaera_tests::data_dir("sphaera-eval") else {
        bail!("the experiments need the shared meshes (set SPHAERA_DATA)");
    };
    for name in experiments::NAMES {
        if only.as_deref().is_none_or(|o| o == *name) {
            eprintln!("== {name}");
            experiments::run(name, &data, &out)?;
        }
    }
    Ok(())
}
