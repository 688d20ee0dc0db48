//! `robot_vs_morphit`: whole robots spherized by Sphaera and by morphit-rs's robot
//! pipeline (`RobotPackage.pack_all`, PyPI `morphit-rs` 0.2.0, the peer a robotics user
//! compares us with), at equal sphere counts per link.
//!
//! For the Franka Panda and the KUKA iiwa of `shared/data` and N in {8, 20, 40} spheres
//! per link:
//!
//! - **Sphaera**: `sphaera::robot::spherize_geometry` with `SphereBudget::PerLink(N)` on
//!   the links' collision meshes (coverage of every surface point certified), timed as a
//!   whole (links two at a time on two cores);
//! - **morphit raw**: `peers/morphit_robot.py`: `pack_all(num_spheres=N, seed=0,
//!   device="cpu")` with the package's defaults (MorphIt-B, 200 iterations), timed as a
//!   whole (both cores); its spheres, given in each collision mesh's frame, are placed in
//!   the link's frame by the collision's origin and scale;
//! - **morphit grown** ([`crate::sphere_sets::grow_to_cover`]): the raw spheres with every
//!   radius grown until they cover the link's surface (certified), the buffer its users
//!   add by hand.
//!
//! Every set is measured on the link's mesh by `sphaera::spheretree::evaluate_set`: the
//! worst protrusion (certified upper bound) and the uncovered share of 100,000 random
//! surface samples with the largest gap. Skipped with a message when no Python imports
//! `morphit_rs` (`SPHAERA_MORPHIT_PYTHON`). Writes `robot_vs_morphit.csv` (a row per
//! robot, link, method and N, plus a row per robot, method and N for the whole robot:
//! link `(robot)`, the worst over its links and the time) and `robot_vs_morphit.svg`.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use sphaera::mesh::DVec3;
use sphaera::mesh::{Sphere, Surface, TriMesh};
use sphaera::robot::{
    GeometrySource, LinkGeometry, MeshResolver, Origin, SphereBudget, SpherizeOptions, Urdf,
    spherize_geometry,
};
use sphaera::spheretree::{EvaluationOptions, SetEvaluation, evaluate_set};

use crate::chart::{
    ChartSpec, GridLegend, GridLine, GridPanel, Series, line_grid, palette, write_csv,
};
use crate::peers::morphit_python;
use crate::sphere_sets::grow_to_cover;

/// The experiment's name, and its chart's.
pub(in crate::experiments) const NAME: &str = "robot_vs_morphit";

/// The robots: their folder in `shared/data`, the URDF in it, and a short name.
const ROBOTS: [(&str, &str, &str); 2] = [
    ("robots/urdf/franka_panda", "panda.urdf", "panda"),
    ("robots/urdf/kuka_iiwa", "model.urdf", "kuka"),
];

/// Spheres per link.
const COUNTS: [usize; 3] = [8, 20, 40];

const METHODS: [(&str, &str, bool); 3] = [
    ("sphaera", "Sphaera (coverage certified)", false),
    ("morphit_raw", "morphit-rs as returned", true),
    ("morphit_grown", "morphit-rs grown to cover", true),
];

struct Row {
    robot: &'static str,
    link: String,
    method: &'static str,
    n: usize,
    spheres: usize,
    /// Worst protrusion (certified upper bound), metres.
    worst: f64,
    /// Uncovered share of the surface samples, and the largest gap (metres).
    uncovered: f64,
    gap: f64,
    /// The whole robot's time (summary rows only), seconds.
    seconds: Option<f64>,
}

pub(in crate::experiments) fn run(data: &Path, out: &Path) -> Result<()> {
    let Some(python) = morphit_python(NAME) else {
        return Ok(());
    };
    let mut rows = Vec::new();
    for (folder, file, robot) in ROBOTS {
        let dir = data.join(folder);
        if !dir.join(file).is_file() {
            eprintln!("{NAME}: {folder}/{file} not in {}, skipped", data.display());
            continue;
        }
        rows.extend(robot_rows(&python, &dir, file, robot)?);
    }
    if rows.is_empty() {
        eprintln!("{NAME}: no robot found, nothing written");
        return Ok(());
    }
    write_outputs(out, &rows)
}

/// A link with a mesh: its geometry and surface.
struct MeshLink {
    geometry: LinkGeometry,
    mesh: TriMesh,
    surface: Surface,
}

fn robot_rows(python: &Path, dir: &Path, file: &str, robot: &'static str) -> Result<Vec<Row>> {
    let urdf = Urdf::read(dir.join(file))?;
    let geometry = LinkGeometry::load_all(
        &urdf,
        GeometrySource::Collision,
        &MeshResolver::new(urdf.folder()),
    )?;
    let mut links = Vec::new();
    for g in geometry {
        let Some(mesh) = g.mesh.clone() else { continue };
        let surface = Surface::solid_or_shell(&mesh).with_context(|| format!("link {}", g.link))?;
        links.push(MeshLink {
            geometry: g,
            mesh,
            surface,
        });
    }
    let peer = morphit_runs(python, dir, file)?;
    let evaluation = EvaluationOptions::default();
    let mut rows = Vec::new();
    for (n, peer) in COUNTS.iter().copied().zip(peer) {
        let started = Instant::now();
        let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(n));
        let ours = spherize_geometry(
            &urdf.name,
            links.iter().map(|l| l.geometry.clone()).collect(),
            &options,
            &|_| {},
        )?;
        let ours_seconds = started.elapsed().as_secs_f64();
        let mut per_method: Vec<Vec<Row>> = vec![Vec::new(), Vec::new(), Vec::new()];
        for (link, spheres) in links.iter().zip(&ours.links) {
            let name = &link.geometry.link;
            let measure = |spheres: &[Sphere]| -> Result<SetEvaluation> {
                evaluate_set(&link.surface, spheres, &evaluation)
                    .with_context(|| format!("evaluating {name}"))
            };
            let row = |method: &'static str, spheres: &[Sphere], fit: &SetEvaluation| Row {
                robot,
                link: name.clone(),
                method,
                n,
                spheres: spheres.len(),
                worst: fit.worst_upper,
                uncovered: fit.coverage.uncovered_fraction,
                gap: fit.coverage.largest_gap,
                seconds: None,
            };
            per_method[0].push(row(
                METHODS[0].0,
                &spheres.spheres,
                &measure(&spheres.spheres)?,
            ));
            let raw = peer.link_spheres(&urdf, name)?;
            if raw.is_empty() {
                eprintln!("{NAME}: morphit gave {name} no spheres at {n}");
                continue;
            }
            per_method[1].push(row(METHODS[1].0, &raw, &measure(&raw)?));
            let grown = grow_to_cover(&link.mesh, &raw, 1e-4 * link.surface.diagonal())?;
            per_method[2].push(row(METHODS[2].0, &grown.spheres, &measure(&grown.spheres)?));
        }
        for (k, method_rows) in per_method.into_iter().enumerate() {
            let seconds = if k == 0 { ours_seconds } else { peer.seconds };
            rows.push(Row {
                robot,
                link: "(robot)".to_owned(),
                method: METHODS[k].0,
                n,
                spheres: method_rows.iter().map(|r| r.spheres).sum(),
                worst: method_rows.iter().map(|r| r.worst).fold(0.0, f64::max),
                uncovered: method_rows.iter().map(|r| r.uncovered).fold(0.0, f64::max),
                gap: method_rows.iter().map(|r| r.gap).fold(0.0, f64::max),
                seconds: Some(seconds),
            });
            eprintln!(
                "{NAME}: {robot} at {n} per link, {:<13} worst {:6.1} mm, most uncovered {:5.1} %, {:.2} s",
                METHODS[k].0,
                1e3 * rows[rows.len() - 1].worst,
                100.0 * rows[rows.len() - 1].uncovered,
                seconds
            );
            rows.extend(method_rows);
        }
    }
    Ok(rows)
}

/// One `pack_all` of morphit: its time and each collision's spheres with its placement.
struct PeerRun {
    seconds: f64,
    collisions: Vec<(String, Vec<Sphere>, Origin, DVec3)>,
}

impl PeerRun {
    /// The spheres of `link`'s collisions, in the link's frame.
    fn link_spheres(&self, urdf: &Urdf, link: &str) -> Result<Vec<Sphere>> {
        if urdf.link(link).is_none() {
            bail!("morphit names a link {link} the URDF does not have");
        }
        Ok(self
            .collisions
            .iter()
            .filter(|(name, ..)| name == link)
            .flat_map(|(_, spheres, origin, scale)| {
                let pose = origin.affine();
                spheres.iter().map(move |s| {
                    Sphere::new(
                        pose.transform_point3(s.center * *scale),
                        s.radius * scale.max_element(),
                    )
                })
            })
            .collect())
    }
}

fn morphit_runs(python: &Path, dir: &Path, file: &str) -> Result<Vec<PeerRun>> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("peers/morphit_robot.py");
    let counts: Vec<String> = COUNTS.iter().map(usize::to_string).collect();
    let output = Command::new(python)
        .arg(&script)
        .arg(dir)
        .arg(file)
        .arg(counts.join(","))
        .output()
        .with_context(|| format!("cannot run {}", script.display()))?;
    if !output.status.success() {
        bail!(
            "morphit_robot.py failed on {}: {}",
            dir.display(),
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let mut runs = Vec::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let value: serde_json::Value = serde_json::from_str(line)
            .with_context(|| format!("morphit_robot.py printed {line}"))?;
        if let Some(error) = value.get("error") {
            bail!("morphit failed on {}: {error}", dir.display());
        }
        let triple = |v: &serde_json::Value| -> Result<DVec3> {
            let a: Vec<f64> = serde_json::from_value(v.clone())?;
            match a.as_slice() {
                [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
                _ => bail!("not three numbers: {v}"),
            }
        };
        let mut collisions = Vec::new();
        for link in value["links"].as_array().context("no links")? {
            let centers = link["centers"].as_array().context("no centers")?;
            let radii: Vec<f64> = serde_json::from_value(link["radii"].clone())?;
            if centers.len() != radii.len() {
                bail!(
                    "morphit gave {} centres and {} radii",
                    centers.len(),
                    radii.len()
                );
            }
            let spheres = centers
                .iter()
                .zip(&radii)
                .map(|(c, &r)| Ok(Sphere::new(triple(c)?, r)))
                .collect::<Result<Vec<_>>>()?;
            let origin = Origin {
                xyz: triple(&link["origin_xyz"])?,
                rpy: triple(&link["origin_rpy"])?,
            };
            let name = link["link"].as_str().context("no link name")?.to_owned();
            collisions.push((name, spheres, origin, triple(&link["mesh_scale"])?));
        }
        runs.push(PeerRun {
            seconds: value["seconds"].as_f64().context("no seconds")?,
            collisions,
        });
    }
    if runs.len() != COUNTS.len() {
        bail!(
            "morphit_robot.py printed {} runs for {} counts",
            runs.len(),
            COUNTS.len()
        );
    }
    Ok(runs)
}

fn write_outputs(out: &Path, rows: &[Row]) -> Result<()> {
    let header = [
        "robot",
        "link",
        "method",
        "spheres_per_link",
        "spheres",
        "worst_protrusion_mm",
        "uncovered_pct",
        "largest_gap_mm",
        "seconds",
    ];
    let mm = |v: f64| format!("{:.3}", 1e3 * v);
    let lines: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.robot.to_owned(),
                r.link.clone(),
                r.method.to_owned(),
                r.n.to_string(),
                r.spheres.to_string(),
                mm(r.worst),
                format!("{:.3}", 100.0 * r.uncovered),
                mm(r.gap),
                r.seconds.map_or_else(String::new, |s| format!("{s:.3}")),
            ]
        })
        .collect();
    write_csv(&out.join(format!("{NAME}.csv")), &header, &lines)?;
    // Per robot: the worst protrusion over its links, the most uncovered link, the time.
    let robots: Vec<&str> = ROBOTS
        .iter()
        .map(|r| r.2)
        .filter(|r| rows.iter().any(|row| row.robot == *r))
        .collect();
    type Measure = fn(&Row) -> Option<f64>;
    let measures: [(&str, &str, Measure); 3] = [
        ("worst protrusion over the links", "mm", |r| {
            Some(1e3 * r.worst)
        }),
        ("most uncovered link", "% of its surface", |r| {
            Some(100.0 * r.uncovered)
        }),
        ("time for the whole robot", "s", |r| r.seconds),
    ];
    let mut titles = Vec::new();
    let mut lines = Vec::new();
    for robot in &robots {
        for (title, _, measure) in &measures {
            titles.push(format!("{robot}: {title}"));
            lines.push(
                METHODS
                    .iter()
                    .enumerate()
                    .map(|(m, &(method, label, dashed))| {
                        let mut series = Series::new(label);
                        series.points = rows
                            .iter()
                            .filter(|r| {
                                r.robot == *robot && r.link == "(robot)" && r.method == method
                            })
                            .filter_map(|r| Some((r.n as f64, measure(r)?)))
                            .collect();
                        GridLine {
                            series,
                            color: palette(m),
                            dashed,
                        }
                    })
                    .collect::<Vec<_>>(),
            );
        }
    }
    let units: Vec<&str> = robots
        .iter()
        .flat_map(|_| measures.iter().map(|m| m.1))
        .collect();
    let panels: Vec<GridPanel<'_>> = titles
        .iter()
        .zip(&lines)
        .zip(&units)
        .map(|((title, lines), unit)| GridPanel {
            spec: ChartSpec {
                title,
                x_label: "spheres per link",
                y_label: unit,
            },
            lines,
        })
        .collect();
    let legend: Vec<GridLegend> = METHODS
        .iter()
        .enumerate()
        .map(|(m, &(_, label, dashed))| GridLegend {
            label: label.to_owned(),
            color: Some(palette(m)),
            dashed,
        })
        .chain(
            [
                "Sphaera covers every link: 0 % uncovered",
                "(not drawn on the log axis)",
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
        "Whole robots, Sphaera against morphit-rs's RobotPackage at equal spheres per link",
        3,
        &panels,
        &legend,
    )
}
