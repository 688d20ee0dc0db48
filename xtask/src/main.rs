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
//!                           in the docs from docs/charts/NAME.csv (format: `tables.rs`)
//! cargo xtask tables --check  fail if a generated table differs from its CSV
//! ```

// A command-line tool reports on the terminal.
#![allow(clippy::print_stderr, clippy::print_stdout)]

use std::{
    path::{Path, PathBuf},
    process::Command,
    time::Instant,
};

use anyhow::{Context, Result, bail};

mod browser;
mod python;
mod tables;

const USAGE: &str = "usage: cargo xtask <test | ci | doc | package | bench [ARGS..] | charts [--check | --only NAME...] | tables [--check] | browser-test [--update-images] | python-test>";

/// The crates meant for crates.io, each after the crates it depends on. Every other
/// workspace member must say `publish = false` ([`check_publish_settings`]).
const PUBLISHED: &[&str] = &[
    "sphaera-mesh",
    "sphaera-io",
    "sphaera-query",
    "sphaera-simplify",
    "sphaera-sweep",
    "sphaera-medial",
    "sphaera-spheretree",
    "sphaera-hal",
    "sphaera-silhouette",
    "sphaera-scene",
    "sphaera-robot",
    "sphaera",
    "sphaera-cli",
];

/// The published crates without a library target. docs.rs builds library documentation
/// only, so [`doc`] leaves them out (`ci` still checks their docs).
const BINARY_ONLY: &[&str] = &["sphaera-cli"];

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

/// The `sphaera` binary of the dev profile, built by the tests (`cargo build -p
/// sphaera-cli`).
fn debug_cli() -> Result<PathBuf> {
    let cli = target_dir()?.join("debug").join("sphaera");
    std::fs::canonicalize(&cli).with_context(|| format!("cannot find {}", cli.display()))
}

/// Every command run so far with its time in seconds, for [`ci`]'s summary.
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

/// Every test: unit and integration tests of every crate, the cross-crate tests in
/// `tests/`, and the doctests (all run by `cargo test`); then the query, simplification,
/// medial, sphere-tree and scene crates again without their default `parallel` feature, whose
/// results must be identical (their tests compare digests of their results with the same
/// recorded values both ways),
/// and the sphere-tree's export and awkward-mesh tests with its optional `parry` feature.
fn test() -> Result<()> {
    cargo(&["test", "--workspace", "--locked"])?;
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
    // The every-shared-mesh build (the 871k dragon among them) checks no digest: once,
    // in parallel, is enough.
    args.extend([
        "--no-default-features",
        "--lib",
        "--tests",
        "--",
        "--skip",
        "every_shared_mesh_builds_and_writes_every_format",
    ]);
    cargo(&args)?;
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
        // The tests that write the compound.
        "--",
        "parry",
        "every_method_and_format_on_every_awkward_mesh",
    ])?;
    // The Python bindings, built with maturin into a virtual environment and tested with
    // pytest against the CLI's numbers.
    python::python_test()?;
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

/// The API reference as docs.rs builds it: every published library crate with all its
/// features (`all-features = true` in each crate's `package.metadata.docs.rs`) and
/// `--cfg docsrs` (its `rustdoc-args`), warnings denied, without the dependencies' docs.
///
/// docs.rs documents with a nightly rustdoc; the toolchain here is stable (1.95). The
/// only difference that could matter is a nightly feature switched on under
/// `cfg(docsrs)`, the usual one being `#![cfg_attr(docsrs, feature(doc_cfg))]` for the
/// "available on crate feature X only" badges. We decided against it: no crate uses
/// `cfg(docsrs)` for anything nightly (feature-gated items say in their docs which
/// feature they need, and every crate's docs list its features), so passing
/// `--cfg docsrs` to the stable rustdoc through `RUSTDOCFLAGS` gives docs.rs's
/// configuration exactly, with no `RUSTC_BOOTSTRAP=1` (which would also change the
/// compiler's fingerprint of every dependency and rebuild them between this step and
/// clippy). A crate that wants `doc_cfg` later must set `RUSTC_BOOTSTRAP=1` here too,
/// since stable rustdoc refuses `#![feature]` (E0554).
///
/// The CLI has no library target, and docs.rs does not document binaries, so it is left
/// out; `cargo xtask ci` documents it with the rest of the workspace.
fn doc() -> Result<()> {
    let mut args = vec!["doc", "--no-deps", "--all-features", "--locked"];
    for name in PUBLISHED.iter().filter(|name| !BINARY_ONLY.contains(name)) {
        args.extend(["-p", name]);
    }
    cargo_with_env(&args, &[("RUSTDOCFLAGS", "--cfg docsrs -D warnings")])
}

/// Files every package must hold.
const PACKAGE_REQUIRED: &[&str] = &["Cargo.toml", "README.md", "LICENSE-MIT", "LICENSE-APACHE"];

/// Files a package may hold besides its `src/**.rs`: the manifest (as published and as
/// written), the lock file and VCS note cargo adds, the readme and the licence texts.
const PACKAGE_ALLOWED: &[&str] = &[
    "Cargo.toml",
    "Cargo.toml.orig",
    "Cargo.lock",
    ".cargo_vcs_info.json",
    "README.md",
    "LICENSE-MIT",
    "LICENSE-APACHE",
];

/// Data files a package may hold because its code embeds them (`include_bytes!`,
/// `include_str!`): the CLI's demo mesh (the low-resolution Stanford bunny, 112 KB, public
/// domain) and the `sphaera view` page (its template and script, and three.js 0.160.1
/// with its MIT licence, 670 KB: the one file allowed over the size limit, see
/// [`PACKAGE_LARGE_ASSETS`]).
const PACKAGE_ASSETS: &[(&str, &str)] = &[
    ("sphaera-cli", "assets/bunny_lowres.obj"),
    ("sphaera-cli", "assets/three/three.module.min.js"),
    ("sphaera-cli", "assets/three/LICENSE"),
    ("sphaera-cli", "assets/view/view.html"),
    ("sphaera-cli", "assets/view/view.js"),
    // Included into the crate docs (its table generated by `cargo xtask tables`).
    ("sphaera-spheretree", "src/performance.md"),
    ("sphaera-robot", "src/performance.md"),
];

/// Embedded files allowed over [`PACKAGE_MAX_FILE_BYTES`]: the vendored three.js (minified,
/// inlined into every `sphaera view` page so that it opens offline).
const PACKAGE_LARGE_ASSETS: &[(&str, &str)] =
    &[("sphaera-cli", "assets/three/three.module.min.js")];

/// The largest file a package may hold: a larger one is data, not code.
const PACKAGE_MAX_FILE_BYTES: u64 = 256 * 1024;

/// Dry run of `cargo package` for every crate meant for crates.io.
///
/// First what each package holds, from `cargo package --list`: the readme, both licence
/// texts (symbolic links in each crate's folder to the root's `LICENSE-MIT` and
/// `LICENSE-APACHE`, which cargo packages as files), the sources, nothing else (no tests,
/// benches, examples, proptest regressions or meshes: the `include` list of each
/// manifest), and no file over 256 KiB. Then each manifest's crates.io fields
/// (description, keywords, categories, readme; the docs.rs table of the libraries), and
/// that every other workspace member says `publish = false`.
///
/// Then the packages themselves, built together (`cargo package --no-verify -p …`), so
/// that each published manifest is written and each path dependency on a sibling
/// resolves against the sibling's package (cargo's local overlay) rather than crates.io,
/// where none of them is yet (cargo reads the crates.io index for the other
/// dependencies: about 15 s here). The packages are not verified (built from the
/// `.crate` alone): that rebuilds every dependency without the workspace's profiles, 4.5
/// minutes on the two cores (measured once on 2026-11-27, every package built), for what
/// `ci`'s clippy and tests already compile from the same sources. Their tests, benches
/// and examples are not packaged: most need the unpublished `sphaera-tests` helpers or
/// the shared meshes.
fn package() -> Result<()> {
    check_publish_settings()?;
    let cargo_bin = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    for name in PUBLISHED {
        let dir = Path::new("crates").join(name);
        eprintln!("$ cargo package --list --allow-dirty --locked -p {name}");
        let output = Command::new(&cargo_bin)
            .args(["package", "--list", "--allow-dirty", "--locked", "-p", name])
            .output()
            .context("cannot run cargo package --list")?;
        if !output.status.success() {
            bail!(
                "cargo package --list -p {name} failed: {}",
                String::from_utf8_lossy(&output.stderr)
            );
        }
        let listing = String::from_utf8_lossy(&output.stdout);
        let files: Vec<&str> = listing.lines().filter(|line| !line.is_empty()).collect();
        let mut problems = Vec::new();
        for required in PACKAGE_REQUIRED {
            if !files.contains(required) {
                problems.push(format!("{required} is missing"));
            }
        }
        for file in &files {
            let allowed = PACKAGE_ALLOWED.contains(file)
                || (file.starts_with("src/") && file.ends_with(".rs"))
                || PACKAGE_ASSETS.contains(&(name, file));
            if !allowed {
                problems.push(format!("{file} should not be packaged"));
            }
            // Files cargo writes itself are not in the crate's folder.
            if let Ok(metadata) = std::fs::metadata(dir.join(file))
                && metadata.len() > PACKAGE_MAX_FILE_BYTES
                && !PACKAGE_LARGE_ASSETS.contains(&(name, file))
            {
                problems.push(format!("{file} is {} bytes", metadata.len()));
            }
        }
        let manifest_path = dir.join("Cargo.toml");
        let manifest = std::fs::read_to_string(&manifest_path)
            .with_context(|| format!("cannot read {}", manifest_path.display()))?;
        let mut fields = vec!["description", "keywords", "categories", "readme"];
        if !BINARY_ONLY.contains(name) {
            fields.extend(["[package.metadata.docs.rs]", "all-features = true"]);
            fields.push(r#"rustdoc-args = ["--cfg", "docsrs"]"#);
        }
        for field in fields {
            if !manifest
                .lines()
                .any(|line| line.trim_start().starts_with(field))
            {
                problems.push(format!("Cargo.toml lacks `{field}`"));
            }
        }
        if !problems.is_empty() {
            bail!(
                "the package of {name} is not ready for crates.io: {}; fix `include`, the \
                 licence links or the manifest in crates/{name}",
                problems.join(", ")
            );
        }
        eprintln!("  ({} files: ok)", files.len());
    }
    let mut args = vec!["package", "--no-verify", "--allow-dirty", "--locked"];
    for name in PUBLISHED {
        args.extend(["-p", name]);
    }
    eprintln!("$ cargo {}", args.join(" "));
    let started = Instant::now();
    let output = Command::new(&cargo_bin)
        .args(&args)
        .output()
        .context("cannot run cargo package")?;
    // Cargo names every test, bench and example that `include` leaves out; that is the
    // intent, so those lines are counted rather than printed.
    let stderr = String::from_utf8_lossy(&output.stderr);
    let (left_out, rest): (Vec<&str>, Vec<&str>) = stderr.lines().partition(|line| {
        line.starts_with("warning: ignoring ")
            && line.ends_with("is not included in the published package")
    });
    for line in rest {
        eprintln!("{line}");
    }
    eprintln!(
        "  ({:.1} s, {}; {} tests, benches and examples left out as `include` says)",
        started.elapsed().as_secs_f64(),
        if output.status.success() {
            "ok"
        } else {
            "FAILED"
        },
        left_out.len()
    );
    if !output.status.success() {
        bail!("`cargo {}` failed ({})", args.join(" "), output.status);
    }
    Ok(())
}

/// Fails unless every workspace member is either in [`PUBLISHED`] or says
/// `publish = false`, and no published crate says `publish = false`.
fn check_publish_settings() -> Result<()> {
    let root = std::fs::read_to_string("Cargo.toml").context("cannot read Cargo.toml")?;
    let members_start = root
        .find("members = [")
        .context("no `members = [` in the root Cargo.toml")?;
    let members_end = root[members_start..]
        .find(']')
        .context("the root Cargo.toml's members list is not closed")?;
    let members = root[members_start + "members = [".len()..members_start + members_end]
        .split(',')
        .map(|member| member.trim().trim_matches('"'))
        .filter(|member| !member.is_empty());
    for member in members {
        let path = Path::new(member).join("Cargo.toml");
        let manifest = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let name = manifest
            .lines()
            .find_map(|line| line.strip_prefix("name = "))
            .map(|name| name.trim().trim_matches('"'))
            .with_context(|| format!("no package name in {}", path.display()))?;
        let unpublished = manifest
            .lines()
            .any(|line| line.trim() == "publish = false");
        match (PUBLISHED.contains(&name), unpublished) {
            (true, true) => bail!("{name} says `publish = false` but xtask publishes it"),
            (false, false) => bail!(
                "{name} is neither in xtask's PUBLISHED list nor `publish = false` in {}",
                path.display()
            ),
            _ => {}
        }
    }
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
    (
        "robot_protrusion_vs_spheres",
        Coverage::Only(&[
            "robots/urdf/franka_panda/panda.urdf",
            "robots/urdf/kuka_iiwa/model.urdf",
        ]),
    ),
    (
        "robot_budgets",
        Coverage::Only(&[
            "robots/urdf/franka_panda/panda.urdf",
            "robots/urdf/kuka_iiwa/model.urdf",
        ]),
    ),
    (
        "spheretree_similarity",
        Coverage::Only(&["bunny_lowres.obj", "fandisk.obj"]),
    ),
    // Its rows are colliders (four shared meshes in one simulation), not meshes.
    ("scene_time_vs_error", Coverage::Only(&[])),
    ("spheres_vs_count", Coverage::Only(SPHERES_VS_COUNT)),
    ("spheres_vs_count_time", Coverage::Only(SPHERES_VS_COUNT)),
    (
        "spheres_vs_count_uncovered",
        Coverage::Only(SPHERES_VS_COUNT),
    ),
    (
        "main_job",
        Coverage::Only(&["bunny_lowres.obj", "stanford-bunny.obj", "dragon_vrip.ply"]),
    ),
    (
        "tolerance_trees",
        Coverage::Only(&["bunny_lowres.obj", "spot.obj", "fandisk.obj"]),
    ),
];

/// The meshes of the `spheres_vs_count` charts, besides the procedural animal (a link
/// without an inside would be skipped by the experiment; none is today).
const SPHERES_VS_COUNT: &[&str] = &[
    "bunny_lowres.obj",
    "spot.obj",
    "fandisk.obj",
    "robots/franka_panda/collision/link1.obj",
    "robots/franka_panda/collision/link2.obj",
    "robots/franka_panda/collision/link3.obj",
    "robots/franka_panda/collision/link4.obj",
    "robots/franka_panda/collision/link5.obj",
    "robots/franka_panda/collision/link6.obj",
    "robots/franka_panda/collision/link7.obj",
    "robots/franka_panda/collision/hand.obj",
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

/// The experiments named by `--only NAME` arguments (none: every experiment).
fn only(args: &[String]) -> Result<Vec<String>> {
    let mut names = Vec::new();
    let mut args = args.iter();
    while let Some(arg) = args.next() {
        if arg == "--only" {
            names.push(
                args.next()
                    .context("--only needs an experiment name")?
                    .clone(),
            );
        }
    }
    Ok(names)
}

fn charts(check: bool, only: &[String]) -> Result<()> {
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
    let run = [
        "run",
        "--release",
        "--locked",
        "-p",
        "sphaera-eval",
        "--",
        "--out",
        "docs/charts",
    ];
    if only.is_empty() {
        return cargo(&run);
    }
    for name in only {
        let mut args = run.to_vec();
        args.extend(["--only", name.as_str()]);
        cargo(&args)?;
    }
    Ok(())
}
