//! `cargo xtask test` and `cargo xtask ci`: every test, and every check CI runs.

use std::{process::Command, sync::OnceLock, time::Instant};

use anyhow::{Context, Result, bail};

use crate::{browser, cargo, cargo_with_env, charts, doc, package, print_steps, python, tables};

/// The property-test cases of the sequential (no `parallel`) run of [`test()`].
const SEQUENTIAL_CASES: &str = "8";

/// The integration tests that compare results with recorded digests, run again by the
/// sequential run of [`test()`]: `parallel_fingerprints` (query), `order` (simplify),
/// `medial`, `build` (sphere-tree), `collide` and `detail` (scene; the sphere-tree's
/// `collide` runs too, having the same name), `properties` (robot).
const SEQUENTIAL_DIGEST_TESTS: [&str; 7] = [
    "parallel_fingerprints",
    "order",
    "medial",
    "build",
    "collide",
    "detail",
    "properties",
];

/// Every test: unit and integration tests of every crate, the cross-crate tests in
/// `tests/`, and the doctests (all run by `cargo test`); then the unit tests and the
/// digest tests ([`SEQUENTIAL_DIGEST_TESTS`]) of the query, simplification, medial,
/// sphere-tree, scene and robot crates again without their default `parallel` feature, whose
/// results must be identical (the digests are compared with the same recorded values both
/// ways). The sphere-tree's optional `parry` export is tested in the
/// first run: `sphaera-tests` asks for it, so the workspace's one build has it. The
/// first run also has `sphaera-eval`'s `geos` feature when GEOS is installed
/// ([`geos_features`]): the test of 2D point inclusion against GEOS.
pub fn test() -> Result<()> {
    let mut args = vec!["test", "--workspace", "--locked"];
    args.extend(geos_features());
    cargo(&args)?;
    // One invocation for all of them: one build, its crates compiled in parallel. No
    // dev-dependency of theirs asks for `parallel`, so none of them gets it
    // (`cargo tree -e features` confirms).
    let mut args = vec!["test", "--locked"];
    for crate_name in [
        "sphaera-query",
        "sphaera-simplify",
        "sphaera-medial",
        "sphaera-spheretree",
        "sphaera-scene",
        "sphaera-robot",
    ] {
        args.extend(["-p", crate_name]);
    }
    // The unit tests, and the integration tests that compare a recorded digest of the
    // results (the same values both ways); the others check properties the first run
    // checked already, and compiling their 30 binaries again cost minutes on 2 cores.
    args.extend(["--no-default-features", "--lib"]);
    for digest_test in SEQUENTIAL_DIGEST_TESTS {
        args.extend(["--test", digest_test]);
    }
    // The properties were checked at their full counts in the first run; here they only
    // need to show that the sequential build behaves alike, so each runs a few cases
    // (unless `PROPTEST_CASES` asks for a deep run), which halves this run.
    match std::env::var("PROPTEST_CASES") {
        Ok(_) => cargo(&args)?,
        Err(_) => cargo_with_env(&args, &[("PROPTEST_CASES", SEQUENTIAL_CASES)])?,
    }
    // The Python bindings, built with maturin into a virtual environment and tested with
    // pytest against the CLI's numbers.
    python::python_test()?;
    Ok(())
}

pub fn ci() -> Result<()> {
    let started = Instant::now();
    cargo(&["fmt", "--all", "--check"])?;
    check_single_glam()?;
    // With the GEOS peer when GEOS is installed: its bench, test and module are linted
    // too (the feature adds only `geos` and `geos-sys` to the build, a few seconds).
    let mut args = vec!["clippy", "--workspace", "--all-targets", "--locked"];
    args.extend(geos_features());
    args.extend(["--", "-D", "warnings"]);
    cargo(&args)?;
    // The published crates as docs.rs documents them (every feature), then the whole
    // workspace with default features, as a user's `cargo doc` builds it: a link that
    // resolves only with an optional feature on fails there, and the CLI, the evaluation
    // crate, the test helpers and this tool are documented too.
    doc()?;
    cargo_with_env(
        &["doc", "--workspace", "--no-deps", "--locked"],
        &[("RUSTDOCFLAGS", "-D warnings")],
    )?;
    package()?;
    test()?;
    charts(true, &[])?;
    tables::tables(true)?;
    browser::browser_test(false)?;
    print_steps();
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

/// `--features sphaera-eval/geos` when GEOS is installed, else nothing (said once): the
/// same-run GEOS peer of 2D point inclusion (the `hal2_vs_geos` bench and test) links the
/// system's libgeos, which a machine without it cannot build. GEOS counts as installed
/// when `pkg-config --exists geos` succeeds: the `geos-sys` build script looks for it
/// with pkg-config (and fails without pkg-config), so `geos-config` alone is not enough.
/// `.ci/run` installs both (Debian's `libgeos-dev` and `pkg-config`).
pub fn geos_features() -> &'static [&'static str] {
    static FEATURES: OnceLock<&'static [&'static str]> = OnceLock::new();
    FEATURES.get_or_init(|| {
        let found = Command::new("pkg-config")
            .args(["--exists", "geos"])
            .status()
            .is_ok_and(|status| status.success());
        if found {
            &["--features", "sphaera-eval/geos"]
        } else {
            eprintln!(
                "GEOS not found (`pkg-config --exists geos` failed): building and testing \
                 without sphaera-eval's `geos` feature (install libgeos-dev and pkg-config \
                 for the GEOS peer of 2D point inclusion)"
            );
            &[]
        }
    })
}
