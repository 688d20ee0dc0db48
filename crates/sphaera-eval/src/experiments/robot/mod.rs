//! `robot_protrusion_vs_spheres`: how far a robot's collision spheres reach beyond its
//! links, Sphaera against the volume-sampling baseline planners ship, at the same number
//! of spheres per link.
//!
//! For every link of the Franka Panda with a collision mesh (`shared/data/robots/urdf/
//! franka_panda/panda.urdf`, eleven links) and `N` in {4, 8, 16, 24, 40, 64} spheres per
//! link, and for the KUKA iiwa's links at `N` = 40 (`robots/urdf/kuka_iiwa/model.urdf`, in
//! the CSV only):
//!
//! - **Sphaera**: `sphaera::robot::spherize_geometry` with `SphereBudget::PerLink(N)` and
//!   the default options (a one-level minimax sphere-tree of exactly N spheres per link,
//!   coverage of every point of the surface certified);
//! - **voxel k-means** ([`voxel`]): the link voxelized with 64 cells along its longest
//!   side, the occupied voxels clustered into `N` by k-means (farthest-point seeds, 20
//!   Lloyd iterations), one smallest enclosing sphere per cluster around its voxels'
//!   corners. Its coverage is not certified.
//!
//! Both sets are measured the same way, by `sphaera::spheretree::evaluate_set` with the
//! default options on the link's mesh: the worst protrusion is its `worst_upper` (a
//! certified upper bound of how far any sphere reaches beyond the link's solid, to 10⁻⁴ of
//! the link's diagonal), the coverage is the fraction of its 100,000 random surface
//! samples inside some sphere. Sphaera's own report (`LinkReport::worst_protrusion`, the
//! same evaluator) is recorded beside it. Also recorded: the spheres actually produced
//! and the time — Sphaera's per link from its report (sphere-tree, certification of
//! coverage and protrusion, the 95th-percentile estimate; links two at a time on two
//! cores), the baseline's voxelization plus clustering on one thread, without any
//! evaluation (its voxelization, a winding-number inside test per voxel centre, is most
//! of it; a flood-filling voxelizer would be faster but fails on open meshes such as
//! `link6`, so the times say little about which method is quicker).
//!
//! Writes `robot_protrusion_vs_spheres.svg` (one panel per Panda link: worst protrusion
//! in mm against the spheres produced, Sphaera solid, the baseline dashed) and `.csv`
//! (every row; the first column is the URDF). About 40 s in release on two cores, so
//! every count and the finest usual voxel resolution are kept (at 48 cells the
//! baseline's worst protrusion over the Panda at 40 per link was 39 mm, at 64 cells
//! 34 mm).
//!
//! The chart's x axis is the spheres produced and the CSV has both counts (asked and
//! produced), so that a method giving fewer than asked shows it; Sphaera gives exactly N
//! (fewer only where a link cannot use them, which the report says). The last column is
//! Sphaera's worst protrusion over the baseline's on the same link and count.

pub(super) mod budgets;
pub(super) mod morphit;
pub mod voxel;

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use sphaera::mesh::Surface;
use sphaera::robot::{
    GeometrySource, LinkGeometry, MeshResolver, SphereBudget, SpherizeOptions, Urdf,
    spherize_geometry,
};
use sphaera::spheretree::{EvaluationOptions, SetEvaluation, evaluate_set};

use self::voxel::{VoxelOptions, Voxels};
use crate::chart::{
    ChartSpec, GridLegend, GridLine, GridPanel, Series, line_grid, palette, write_csv,
};

/// The experiment's name, and its chart's.
pub(super) const NAME: &str = "robot_protrusion_vs_spheres";

/// The robots, from `shared/data`, with the sphere counts per link each is run at.
const ROBOTS: [(&str, &[usize]); 2] = [
    (
        "robots/urdf/franka_panda/panda.urdf",
        &[4, 8, 16, 24, 40, 64],
    ),
    ("robots/urdf/kuka_iiwa/model.urdf", &[40]),
];

/// The method names in the CSV.
const SPHAERA: &str = "sphaera";
/// The baseline's name in the CSV.
const BASELINE: &str = "voxel_kmeans";

/// One link, one method, one sphere count.
struct Row {
    robot: &'static str,
    link: String,
    method: &'static str,
    /// Spheres asked for.
    budget: usize,
    /// Spheres produced.
    spheres: usize,
    /// `evaluate_set`'s certified bounds of the worst protrusion.
    fit: SetEvaluation,
    /// Sphaera's own certified worst protrusion (`LinkReport`).
    reported: Option<f64>,
    /// Whether coverage of every point is certified.
    certified: bool,
    seconds: f64,
    diagonal: f64,
    /// Occupied voxels (the baseline).
    voxels: Option<usize>,
}

pub(super) fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    for (file, counts) in ROBOTS {
        let path = data.join(file);
        if !path.is_file() {
            eprintln!("{file}: not in {}, skipped", data.display());
            continue;
        }
        rows.extend(robot_rows(file, &path, counts)?);
    }
    if rows.is_empty() {
        eprintln!("{NAME}: no robot found, nothing written");
        return Ok(());
    }
    write_outputs(out, &rows)
}

/// A link with a mesh and nothing else: its geometry, surface and voxels.
struct MeshLink {
    geometry: LinkGeometry,
    surface: Surface,
    voxels: Voxels,
    voxel_seconds: f64,
}

/// Every row of the robot at `path` (named `file` in the CSV).
fn robot_rows(file: &'static str, path: &Path, counts: &[usize]) -> Result<Vec<Row>> {
    let urdf = Urdf::read(path)?;
    let geometry = LinkGeometry::load_all(
        &urdf,
        GeometrySource::Collision,
        &MeshResolver::new(urdf.folder()),
    )?;
    let voxel_options = VoxelOptions::default();
    let mut links = Vec::new();
    for g in &geometry {
        let Some(mesh) = &g.mesh else { continue };
        if !g.primitives.is_empty() {
            eprintln!(
                "{file}: {} has primitives besides its mesh, skipped",
                g.link
            );
            continue;
        }
        let surface = Surface::new(mesh).with_context(|| format!("link {}", g.link))?;
        let started = Instant::now();
        let voxels =
            Voxels::new(&surface, &voxel_options).with_context(|| format!("link {}", g.link))?;
        let voxel_seconds = started.elapsed().as_secs_f64();
        links.push(MeshLink {
            geometry: g.clone(),
            surface,
            voxels,
            voxel_seconds,
        });
    }
    let evaluation = EvaluationOptions::default();
    let mut rows = Vec::new();
    for &n in counts {
        let started = Instant::now();
        let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(n));
        let robot = spherize_geometry(
            &urdf.name,
            links.iter().map(|l| l.geometry.clone()).collect(),
            &options,
            &|_| {},
        )?;
        eprintln!(
            "{file}: Sphaera at {n} per link in {:.1} s",
            started.elapsed().as_secs_f64()
        );
        for (link, spheres) in links.iter().zip(&robot.links) {
            let fit = evaluate_set(&link.surface, &spheres.spheres, &evaluation)
                .with_context(|| format!("evaluating Sphaera on {}", link.geometry.link))?;
            rows.push(Row {
                robot: file,
                link: link.geometry.link.clone(),
                method: SPHAERA,
                budget: n,
                spheres: spheres.spheres.len(),
                fit,
                reported: Some(spheres.report.worst_protrusion),
                certified: spheres.report.coverage_certified,
                seconds: spheres.report.seconds,
                diagonal: spheres.report.diagonal,
                voxels: None,
            });
        }
        for link in &links {
            let started = Instant::now();
            let spheres = link
                .voxels
                .spheres(n, voxel_options.lloyd_iterations)
                .with_context(|| format!("the baseline on {}", link.geometry.link))?;
            let seconds = link.voxel_seconds + started.elapsed().as_secs_f64();
            let fit = evaluate_set(&link.surface, &spheres, &evaluation)
                .with_context(|| format!("evaluating the baseline on {}", link.geometry.link))?;
            rows.push(Row {
                robot: file,
                link: link.geometry.link.clone(),
                method: BASELINE,
                budget: n,
                spheres: spheres.len(),
                fit,
                reported: None,
                certified: false,
                seconds,
                diagonal: link.geometry.diagonal(),
                voxels: Some(link.voxels.occupied()),
            });
        }
        for pair in rows[rows.len() - 2 * links.len()..].chunks(links.len()) {
            let worst = pair.iter().map(|r| r.fit.worst_upper).fold(0.0, f64::max);
            let coverage = pair
                .iter()
                .map(|r| 1.0 - r.fit.coverage.uncovered_fraction)
                .fold(1.0, f64::min);
            eprintln!(
                "  {:<12} worst protrusion {:6.1} mm over the links, lowest coverage {:.5}",
                pair[0].method,
                1e3 * worst,
                coverage
            );
        }
    }
    Ok(rows)
}

fn write_outputs(out: &Path, rows: &[Row]) -> Result<()> {
    let header = [
        "robot",
        "link",
        "method",
        "spheres_per_link",
        "spheres",
        "worst_protrusion_mm",
        "worst_protrusion_lower_mm",
        "reported_protrusion_mm",
        "protrusion_pct_of_diagonal",
        "coverage",
        "coverage_certified",
        "largest_gap_mm",
        "seconds",
        "diagonal_mm",
        "occupied_voxels",
        "worst_vs_baseline",
    ];
    let mm = |v: f64| format!("{:.3}", 1e3 * v);
    // Sphaera's worst protrusion over the baseline's, on the same link and count.
    let ratio = |r: &Row| {
        if r.method != SPHAERA {
            return String::new();
        }
        rows.iter()
            .find(|b| {
                b.method == BASELINE
                    && b.robot == r.robot
                    && b.link == r.link
                    && b.budget == r.budget
            })
            .map_or_else(String::new, |b| {
                format!("{:.3}", r.fit.worst_upper / b.fit.worst_upper)
            })
    };
    let lines: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.robot.to_owned(),
                r.link.clone(),
                r.method.to_owned(),
                r.budget.to_string(),
                r.spheres.to_string(),
                mm(r.fit.worst_upper),
                mm(r.fit.worst_lower),
                r.reported.map_or_else(String::new, mm),
                format!("{:.3}", 100.0 * r.fit.worst_upper / r.diagonal),
                format!("{:.6}", 1.0 - r.fit.coverage.uncovered_fraction),
                r.certified.to_string(),
                mm(r.fit.coverage.largest_gap),
                format!("{:.4}", r.seconds),
                mm(r.diagonal),
                r.voxels.map_or_else(String::new, |v| v.to_string()),
                ratio(r),
            ]
        })
        .collect();
    write_csv(&out.join(format!("{NAME}.csv")), &header, &lines)?;

    // One panel per link of the first robot (the Panda).
    let Some(first) = rows.first().map(|r| r.robot) else {
        return Ok(());
    };
    let mut names: Vec<&str> = Vec::new();
    for r in rows.iter().filter(|r| r.robot == first) {
        if !names.contains(&r.link.as_str()) {
            names.push(&r.link);
        }
    }
    let methods = [
        (SPHAERA, "Sphaera (coverage certified)", false),
        (BASELINE, "voxel k-means (not certified)", true),
    ];
    let lines: Vec<Vec<GridLine>> = names
        .iter()
        .map(|name| {
            methods
                .iter()
                .enumerate()
                .map(|(m, &(method, label, dashed))| {
                    let mut series = Series::new(label);
                    series.points = rows
                        .iter()
                        .filter(|r| r.robot == first && r.link == *name && r.method == method)
                        .map(|r| (r.spheres as f64, 1e3 * r.fit.worst_upper))
                        .collect();
                    GridLine {
                        series,
                        color: palette(m),
                        dashed,
                    }
                })
                .collect()
        })
        .collect();
    let panels: Vec<GridPanel<'_>> = names
        .iter()
        .zip(&lines)
        .map(|(name, lines)| GridPanel {
            spec: ChartSpec {
                title: name,
                x_label: "spheres",
                y_label: "worst protrusion (mm)",
            },
            lines,
        })
        .collect();
    let legend: Vec<GridLegend> = methods
        .iter()
        .enumerate()
        .map(|(m, &(_, label, dashed))| GridLegend {
            label: label.to_owned(),
            color: Some(palette(m)),
            dashed,
        })
        .chain(
            [
                "both measured by evaluate_set:",
                "certified upper bound of the",
                "farthest reach beyond the link;",
                "x: spheres produced (asked for:",
                "4, 8, 16, 24, 40, 64 per link)",
            ]
            .map(|text| GridLegend {
                label: text.to_owned(),
                color: None,
                dashed: false,
            }),
        )
        .collect();
    line_grid(
        &out.join(format!("{NAME}.svg")),
        "Franka Panda collision links: certified worst protrusion against spheres per link",
        4,
        &panels,
        &legend,
    )
}
