//! `sphaera urdf`: whole-robot sphere models for motion planners.

use std::time::Instant;

use anyhow::{Result, bail};
use serde::Serialize;
use sphaera::robot::{
    CuroboOptions, DisableReason, GeometrySource, LinkReport, MeshResolver, MjcfOptions,
    PlannerFormat, RobotSpheres, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf,
    curobo_robot_yaml, curobo_yaml, mjcf, spherize_with_progress, write_atomic,
};

use crate::{
    cli::UrdfArgs,
    output::{check_target, print_report, thousands},
    progress,
};

/// Everything `sphaera urdf` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    urdf: String,
    robot: String,
    /// `collision` or `visual`.
    source: GeometrySource,
    /// `spheres per link N`, `total N` or `tolerance T` / `T%`.
    budget: String,
    /// Spheres over all links.
    spheres: usize,
    /// The spheres asked for over all links (`None` under a tolerance): more than
    /// `spheres` only where a link cannot use them (its `shortfall` says why).
    asked: Option<usize>,
    /// One entry per link with geometry, in URDF order.
    links: Vec<LinkReport>,
    /// Links without geometry of the chosen kind (no spheres).
    links_without_geometry: Vec<String>,
    /// The worst protrusion over all links (certified).
    worst_protrusion: f64,
    /// Which pairs of links a planner need not test, and why.
    self_collision: SelfCollisionSummary,
    /// The file written and its format, if any.
    output: Option<String>,
    format: Option<PlannerFormat>,
    seconds: f64,
}

/// The self-collision matrix in brief (the pairs themselves are in the SRDF, cuRobo, MJCF
/// and JSON outputs).
#[derive(Debug, Serialize)]
struct SelfCollisionSummary {
    /// Pairs of links with spheres.
    pairs: usize,
    /// Pairs left out, by MoveIt's reason.
    adjacent: usize,
    default: usize,
    always: usize,
    never: usize,
    /// Pairs the planner must check.
    checked: usize,
    /// Random configurations sampled, and their seed.
    samples: usize,
    seed: u64,
    seconds: f64,
}

pub fn run(args: &UrdfArgs, quiet: bool) -> Result<()> {
    let format = match (args.format, &args.output) {
        (Some(f), _) => Some(f),
        (None, Some(path)) => match PlannerFormat::from_path(path) {
            Some(f) => Some(f),
            None => bail!(
                "cannot write {}: the extension is not .urdf, .srdf, .yml/.yaml (cuRobo), .xml/.mjcf (MuJoCo) or .json (or give --format)",
                path.display()
            ),
        },
        (None, None) => None,
    };
    if let Some(path) = &args.output {
        check_target(path)?;
        let same = |a: &std::path::Path, b: &std::path::Path| matches!((a.canonicalize(), b.canonicalize()), (Ok(a), Ok(b)) if a == b);
        if same(path, &args.urdf) {
            bail!(
                "cannot write {}: it is the input URDF, which the output would replace (give another -o)",
                path.display()
            );
        }
    }
    if let Some(spheres) = &args.curobo_spheres {
        check_target(spheres)?;
    }
    let started = Instant::now();
    let policy = crate::input::file_policy();
    let urdf = Urdf::read_with(&args.urdf, &policy)?;
    let mut resolver = MeshResolver::new(urdf.folder()).with_policy(policy);
    for (name, folder) in &args.packages {
        resolver = resolver.with_package(name.clone(), folder.clone());
    }
    let (budget, budget_text) = match (args.budget, args.spheres_per_link, args.tolerance) {
        (Some(total), _, _) => (SphereBudget::Total(total), format!("total {total}")),
        (None, _, Some(t)) => (
            SphereBudget::Tolerance(t),
            match t {
                sphaera::mesh::Length::Absolute(v) => format!("tolerance {v}"),
                sphaera::mesh::Length::RelativeToDiagonal(f) => {
                    format!("tolerance {}%", f * 100.0)
                }
            },
        ),
        (None, n, None) => {
            let n = n.unwrap_or(16);
            (SphereBudget::PerLink(n), format!("spheres per link {n}"))
        }
    };
    let mut options = SpherizeOptions::default()
        .with_budget(budget)
        .with_source(if args.visual {
            GeometrySource::Visual
        } else {
            GeometrySource::Collision
        })
        .with_effort(args.effort)
        .with_max_spheres_per_link(args.max_spheres_per_link)
        .with_self_collision(
            SelfCollisionOptions::default()
                .with_samples(args.self_collision_samples)
                .with_seed(args.seed)
                .with_padding(args.self_collision_padding),
        );
    for (name, count) in &args.per_link {
        options = options.with_link(name.clone(), *count);
    }
    let robot = spherize_robot(&urdf, &resolver, &options, quiet)?;
    let Some(matrix) = &robot.self_collision else {
        bail!("the self-collision matrix was asked for and not computed");
    };
    if let (Some(path), Some(format)) = (&args.output, format) {
        let text = match format {
            PlannerFormat::Curobo => {
                let mut curobo = CuroboOptions::default();
                if let Some(link) = &args.ee_link {
                    curobo = curobo.with_ee_link(link.clone());
                }
                if let Some(spheres) = &args.curobo_spheres {
                    write_atomic(spheres, &curobo_yaml(&robot)?)?;
                    curobo = curobo.with_spheres_file(spheres.display().to_string());
                }
                curobo_robot_yaml(&urdf, &robot, matrix, &curobo)?
            }
            PlannerFormat::Mjcf => {
                let mut options = MjcfOptions::default();
                if args.mjcf_meshes {
                    options = options.with_meshes(options_source(args), resolver.clone());
                }
                mjcf(&urdf, &robot, matrix, &options)?
            }
            other => other.render(&urdf, &robot)?,
        };
        write_atomic(path, &text)?;
    }
    let self_collision = SelfCollisionSummary {
        pairs: matrix.pairs.len(),
        adjacent: matrix.count(DisableReason::Adjacent),
        default: matrix.count(DisableReason::Default),
        always: matrix.count(DisableReason::Always),
        never: matrix.count(DisableReason::Never),
        checked: matrix.checked().count(),
        samples: matrix.samples,
        seed: matrix.seed,
        seconds: matrix.seconds,
    };
    let report = Report {
        urdf: args.urdf.display().to_string(),
        robot: robot.robot.clone(),
        source: robot.source,
        budget: budget_text,
        spheres: robot.sphere_count(),
        asked: robot
            .links
            .iter()
            .map(|l| l.report.budget)
            .sum::<Option<usize>>(),
        worst_protrusion: robot
            .links
            .iter()
            .map(|l| l.report.worst_protrusion)
            .fold(0.0, f64::max),
        links: robot.links.iter().map(|l| l.report.clone()).collect(),
        links_without_geometry: robot.links_without_geometry.clone(),
        self_collision,
        output: args.output.as_ref().map(|p| p.display().to_string()),
        format,
        seconds: started.elapsed().as_secs_f64(),
    };
    print_report(&report, args.print.json)
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![
            format!("urdf            {} (robot \"{}\")", self.urdf, self.robot),
            format!(
                "geometry        {}, {} links with geometry{}",
                match self.source {
                    GeometrySource::Collision => "collision",
                    GeometrySource::Visual => "visual",
                },
                self.links.len(),
                if self.links_without_geometry.is_empty() {
                    String::new()
                } else {
                    format!(", {} without", self.links_without_geometry.len())
                }
            ),
            format!("budget          {}", self.budget),
            "link                       spheres   triangles  worst protrusion   p95 protrusion  coverage  seconds"
                .to_owned(),
        ];
        for l in &self.links {
            lines.push(format!(
                "  {:<24} {:>7}  {:>10}  {:>16.6}  {:>15.6}  {:>7.3}{}  {:>7.3}",
                l.link,
                l.spheres,
                thousands(l.triangles),
                l.worst_protrusion,
                l.p95_protrusion,
                l.coverage,
                if l.coverage_certified { "✓" } else { " " },
                l.seconds
            ));
        }
        for l in &self.links {
            if let Some(why) = &l.shortfall {
                lines.push(format!(
                    "                ! {} has {} of its {} spheres: {why}",
                    l.link,
                    l.spheres,
                    l.budget.unwrap_or(l.spheres)
                ));
            }
        }
        lines.push(format!(
            "spheres         {} in all{}; worst protrusion {:.6} (certified; ✓: coverage of every surface point certified)",
            thousands(self.spheres),
            match self.asked {
                Some(asked) if asked != self.spheres => format!(" of {} asked", thousands(asked)),
                _ => String::new(),
            },
            self.worst_protrusion
        ));
        let c = &self.self_collision;
        lines.push(format!(
            "self-collision  {} pairs: {} adjacent, {} default, {} always, {} never left out; {} to check ({} random configurations, seed {}, {:.3} s)",
            c.pairs, c.adjacent, c.default, c.always, c.never, c.checked, thousands(c.samples), c.seed, c.seconds
        ));
        if let Some(output) = &self.output {
            lines.push(format!(
                "wrote           {output} ({})",
                match self.format {
                    Some(PlannerFormat::Urdf) => "spherized URDF",
                    Some(PlannerFormat::Srdf) =>
                        "SRDF: sphere approximations and disabled collisions",
                    Some(PlannerFormat::Curobo) => "cuRobo robot file",
                    Some(PlannerFormat::CuroboSpheres) => "cuRobo collision_spheres YAML",
                    Some(PlannerFormat::Mjcf) => "MuJoCo MJCF",
                    Some(PlannerFormat::Json) | None => "JSON",
                }
            ));
        }
        lines.push(format!("time            {:.3} s", self.seconds));
        lines.join("\n") + "\n"
    }
}

/// The geometry `sphaera urdf` spherizes, as the arguments choose it.
fn options_source(args: &UrdfArgs) -> GeometrySource {
    if args.visual {
        GeometrySource::Visual
    } else {
        GeometrySource::Collision
    }
}

/// `urdf` spherized by `options` with a progress bar over its links with geometry (hidden
/// when `quiet`).
///
/// # Errors
///
/// As `sphaera::robot::spherize`.
pub(crate) fn spherize_robot(
    urdf: &Urdf,
    resolver: &MeshResolver,
    options: &SpherizeOptions,
    quiet: bool,
) -> Result<RobotSpheres> {
    let links_with_geometry = urdf
        .links
        .iter()
        .filter(|l| !options.source.elements(l).is_empty())
        .count();
    let bar = progress::bar(
        quiet,
        &format!("spherizing {links_with_geometry} links of {}", urdf.name),
        links_with_geometry as u64,
    );
    let robot = spherize_with_progress(urdf, resolver, options, &|p| {
        bar.set_position(p.done as u64);
    });
    bar.finish_and_clear();
    Ok(robot?)
}
