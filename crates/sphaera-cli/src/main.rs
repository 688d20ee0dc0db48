//! `sphaera`: the command-line tool of the Sphaera workspace.
//!
//! One subcommand per capability; every result prints as text for people or, with
//! `--json`, as one JSON document on stdout for scripts. Errors go to stderr with a
//! non-zero exit code. Long work shows a progress bar on stderr (hidden when stderr is not
//! a terminal or with `--quiet`).

// A command-line tool talks on the terminal.
#![allow(clippy::print_stdout, clippy::print_stderr)]

mod cli;
mod commands;
mod input;
mod output;
mod progress;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    match commands::run(&cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
