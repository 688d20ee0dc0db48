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
mod measure;
mod output;
mod progress;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    quiet_on_closed_stdout();
    let cli = cli::Cli::parse();
    match commands::run(&cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {}", error_message(&error));
            ExitCode::FAILURE
        }
    }
}

/// A reader that stops early (`sphaera hal … --json | head`) closes the pipe, and the next
/// `println!` panics with "failed printing to stdout: Broken pipe". That is not an error of
/// ours: leave quietly, with the shell's status for a process the pipe's closing ended
/// (128 + SIGPIPE), instead of printing a panic. Every other panic goes to the default hook.
fn quiet_on_closed_stdout() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(141);
        }
        default(info);
    }));
}

/// The error and its causes on one line, skipping a cause whose text an outer message
/// already quotes (library errors often include their source's text).
fn error_message(error: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in error.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    message
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_causes_are_printed_once() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "no such file");
        let error = anyhow::Error::new(io).context("cannot access a.obj: no such file");
        assert_eq!(error_message(&error), "cannot access a.obj: no such file");
        let error = anyhow::anyhow!("inner").context("outer");
        assert_eq!(error_message(&error), "outer: inner");
    }
}
