//! `robot_budgets`: two whole robots spherized as a user asks for them, by spheres per
//! link, by a total for the robot, or by a tolerance: the spheres given, the worst
//! protrusion over the links and the time.
//!
//! The Franka Panda (`shared/data/robots/urdf/franka_panda/panda.urdf`: eleven collision
//! meshes of 32–1,308 triangles, ten of them closed once welded) and the KUKA iiwa
//! (`robots/urdf/kuka_iiwa/model.urdf`: eight open binary STLs of 1,157–3,038
//! triangles), each through `sphaera::robot::spherize` with the default options (minimax,
//! default effort) and one of the [`BUDGETS`]: 8, 16, 32 and 64 spheres per link, 100 and
//! 300 for the whole robot (divided between the links by need), a tolerance of 5 % of each
//! link's diagonal, and 10 mm and 5 mm.
//!
//! Per robot and budget, one CSV row: the spheres asked for (counts) and given, the worst
//! certified protrusion over the links (each link's `LinkReport::worst_protrusion`, in
//! millimetres) and its link, the largest share of a link's bounding-box diagonal any
//! link's worst protrusion reaches (the two may come from different links: a small link
//! has a large share of a few millimetres), the lowest coverage of a link's surface
//! samples (1: certified for every point), and the wall time of the whole call (links two
//! at a time on two cores, every certificate included).
//!
//! Writes `robot_budgets.csv` (the first column is the URDF) and `robot_budgets.svg` (one
//! panel per robot: worst protrusion against spheres given, log-log, each point labelled
//! with its budget and time).

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result};
use sphaera::mesh::Length;
use sphaera::robot::{MeshResolver, SphereBudget, SpherizeOptions, Urdf, spherize};

use crate::chart::{
    ChartSpec, LegendEntry, Marker, Series, Style, StyledPanel, StyledSeries, XAxis, palette,
    styled_panels, write_csv,
};

/// The experiment's name, and its chart's.
pub(in crate::experiments) const NAME: &str = "robot_budgets";

/// The robots, from `shared/data`, with the name the chart gives them.
const ROBOTS: [(&str, &str); 2] = [
    ("robots/urdf/franka_panda/panda.urdf", "Franka Panda"),
    ("robots/urdf/kuka_iiwa/model.urdf", "KUKA iiwa"),
];

/// The budgets: their name in the CSV and the table, and what is asked.
const BUDGETS: [(&str, Budget); 9] = [
    ("8 per link", Budget::PerLink(8)),
    ("16 per link", Budget::PerLink(16)),
    ("32 per link", Budget::PerLink(32)),
    ("64 per link", Budget::PerLink(64)),
    ("100 in all", Budget::Total(100)),
    ("300 in all", Budget::Total(300)),
    ("tolerance 5 %", Budget::Relative(0.05)),
    ("tolerance 10 mm", Budget::Absolute(0.010)),
    ("tolerance 5 mm", Budget::Absolute(0.005)),
];

/// A budget of [`BUDGETS`], made a [`SphereBudget`] on use.
#[derive(Clone, Copy)]
enum Budget {
    PerLink(usize),
    Total(usize),
    /// A share of each link's diagonal.
    Relative(f64),
    /// In the URDF's units (metres).
    Absolute(f64),
}

impl Budget {
    fn of(self) -> SphereBudget {
        match self {
            Self::PerLink(n) => SphereBudget::PerLink(n),
            Self::Total(n) => SphereBudget::Total(n),
            Self::Relative(f) => SphereBudget::Tolerance(Length::RelativeToDiagonal(f)),
            Self::Absolute(d) => SphereBudget::Tolerance(Length::Absolute(d)),
        }
    }

    /// The kind, for the chart's markers and the CSV.
    fn kind(self) -> &'static str {
        match self {
            Self::PerLink(_) => "per_link",
            Self::Total(_) => "total",
            Self::Relative(_) | Self::Absolute(_) => "tolerance",
        }
    }
}

/// One robot at one budget.
struct Row {
    robot: &'static str,
    budget: &'static str,
    kind: &'static str,
    /// Spheres asked for (`None` under a tolerance).
    asked: Option<usize>,
    spheres: usize,
    /// The worst certified protrusion over the links, in metres, and its link.
    worst: f64,
    worst_link: String,
    /// The largest share of a link's diagonal a link's worst protrusion reaches, in %.
    worst_share_pct: f64,
    /// The lowest coverage of a link's samples.
    coverage: f64,
    certified: bool,
    seconds: f64,
}

pub(in crate::experiments) fn run(data: &Path, out: &Path) -> Result<()> {
    let mut rows = Vec::new();
    for (file, _) in ROBOTS {
        let path = data.join(file);
        if !path.is_file() {
            eprintln!("{file}: not in {}, skipped", data.display());
            continue;
        }
        let urdf = Urdf::read(&path).with_context(|| format!("cannot read {file}"))?;
        let resolver = MeshResolver::new(urdf.folder());
        for (name, budget) in BUDGETS {
            let options = SpherizeOptions::default().with_budget(budget.of());
            let started = Instant::now();
            let robot = spherize(&urdf, &resolver, &options)
                .with_context(|| format!("{file} at {name}"))?;
            let seconds = started.elapsed().as_secs_f64();
            let reports = || robot.links.iter().map(|l| &l.report);
            let worst_report = reports()
                .max_by(|a, b| a.worst_protrusion.total_cmp(&b.worst_protrusion))
                .context("a robot without links")?;
            let row = Row {
                robot: file,
                budget: name,
                kind: budget.kind(),
                asked: reports().map(|r| r.budget).sum(),
                spheres: robot.sphere_count(),
                worst: worst_report.worst_protrusion,
                worst_link: worst_report.link.clone(),
                worst_share_pct: reports()
                    .map(|r| 100.0 * r.worst_protrusion / r.diagonal)
                    .fold(0.0, f64::max),
                coverage: reports().map(|r| r.coverage).fold(1.0, f64::min),
                certified: reports().all(|r| r.coverage_certified),
                seconds,
            };
            eprintln!(
                "{file} {name:>15}: {:>5} spheres, worst {:6.2} mm ({}), at most {:5.2} % of a link's diagonal, {seconds:.2} s",
                row.spheres,
                1e3 * row.worst,
                row.worst_link,
                row.worst_share_pct
            );
            rows.push(row);
        }
    }
    if rows.is_empty() {
        eprintln!("{NAME}: no robot found, nothing written");
        return Ok(());
    }
    write_outputs(out, &rows)
}

fn write_outputs(out: &Path, rows: &[Row]) -> Result<()> {
    let header = [
        "robot",
        "budget",
        "kind",
        "asked",
        "spheres",
        "worst_protrusion_mm",
        "worst_link",
        "worst_share_pct",
        "lowest_coverage",
        "coverage_certified",
        "seconds",
    ];
    let lines: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.robot.to_owned(),
                r.budget.to_owned(),
                r.kind.to_owned(),
                r.asked.map_or_else(String::new, |n| n.to_string()),
                r.spheres.to_string(),
                format!("{:.2}", 1e3 * r.worst),
                r.worst_link.clone(),
                format!("{:.2}", r.worst_share_pct),
                format!("{:.6}", r.coverage),
                r.certified.to_string(),
                format!("{:.2}", r.seconds),
            ]
        })
        .collect();
    write_csv(&out.join(format!("{NAME}.csv")), &header, &lines)?;

    let kinds = [
        (
            "per_link",
            "spheres per link (8, 16, 32, 64)",
            Marker::Circle,
        ),
        ("total", "spheres for the robot (100, 300)", Marker::Square),
        (
            "tolerance",
            "a tolerance (5 %, 10 mm, 5 mm)",
            Marker::Triangle,
        ),
    ];
    let style = |k: usize, marker| Style {
        color: palette(k),
        marker,
        filled: true,
        line: k == 0,
    };
    let series: Vec<(&str, Vec<StyledSeries>)> = ROBOTS
        .iter()
        .filter(|(file, _)| rows.iter().any(|r| r.robot == *file))
        .map(|&(file, title)| {
            let series = kinds
                .iter()
                .enumerate()
                .map(|(k, &(kind, label, marker))| {
                    let chosen: Vec<&Row> = rows
                        .iter()
                        .filter(|r| r.robot == file && r.kind == kind)
                        .collect();
                    let mut points = Series::new(label);
                    points.points = chosen
                        .iter()
                        .map(|r| (r.spheres as f64, 1e3 * r.worst))
                        .collect();
                    StyledSeries::new(points, style(k, marker)).with_labels(
                        chosen
                            .iter()
                            .map(|r| format!("{} ({:.1} s)", r.budget, r.seconds))
                            .collect(),
                    )
                })
                .collect();
            (title, series)
        })
        .collect();
    let panels: Vec<StyledPanel<'_>> = series
        .iter()
        .map(|(title, series)| StyledPanel {
            spec: ChartSpec {
                title,
                x_label: "spheres given (whole robot)",
                y_label: "worst certified protrusion over the links (mm)",
            },
            x_axis: XAxis::Log,
            series,
            notes: &[],
        })
        .collect();
    let legend: Vec<LegendEntry> = kinds
        .iter()
        .enumerate()
        .map(|(k, &(_, label, marker))| LegendEntry {
            label: label.to_owned(),
            style: style(k, marker),
        })
        .collect();
    styled_panels(&out.join(format!("{NAME}.svg")), &panels, &legend)
}
