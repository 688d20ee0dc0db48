//! `cargo xtask charts [--check | --only NAME...]`: runs the experiments that write
//! `docs/charts`, or checks that every chart is there and covers the meshes it must.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::cargo;

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
    // Countries kept in the repository (`tests/data/countries`), not in the shared data.
    ("hal_multipolygon_speed", Coverage::Only(&[])),
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
    // Its rows are robots (the two shared URDFs), not meshes.
    ("robot_vs_morphit", Coverage::Only(&[])),
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
pub fn only(args: &[String]) -> Result<Vec<String>> {
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

/// `cargo xtask charts`: re-runs the experiments (or those named) into `docs/charts`, then
/// rewrites the markdown tables generated from their CSVs; with `check`, only checks that
/// every chart and CSV is there.
pub fn charts(check: bool, only: &[String]) -> Result<()> {
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
        cargo(&run)?;
    } else {
        for name in only {
            let mut args = run.to_vec();
            args.extend(["--only", name.as_str()]);
            cargo(&args)?;
        }
    }
    // The markdown tables of the CSVs just written.
    crate::tables::tables(false)
}
