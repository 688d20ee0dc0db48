//! Helpers shared by the end-to-end tests: run the binary, parse its JSON.

#![allow(dead_code)]

use std::process::{Command, Output};

/// Runs the `sphaera` binary with `args`.
pub fn sphaera(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sphaera"))
        .args(args)
        .output()
        .expect("the sphaera binary runs")
}

/// The JSON document a successful run printed.
pub fn json(output: &Output) -> serde_json::Value {
    assert!(
        output.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("valid JSON")
}
