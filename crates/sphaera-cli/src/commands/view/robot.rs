//! `sphaera view ROBOT.urdf`: the robot's link meshes and spheres on one page, posed by
//! the robot's forward kinematics as its joint sliders move, links coloured by their
//! certified protrusion, the self-collision pairs listed.
//!
//! Lengths go in page units: the robot's divided by `scale` (the robot's reach from its
//! root at the first configuration), not moved, so that the page's kinematics composes
//! the same transforms as the CLI's; the page writes the posed first sphere of every link
//! back in the robot's units (`data-probe`), and the report holds the CLI's values.

use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use serde::Serialize;
use sphaera::mesh::io::colormap;
use sphaera::mesh::{DVec3, Sphere};
use sphaera::robot::{
    DisableReason, GeometrySource, JointMotion, KinematicChain, LinkGeometry, MeshResolver,
    SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf,
};

use super::page::{STAGE_JS, THREE_JS, base64_of, f32_base64, fill, html_escape, script_json};
use crate::cli::ViewArgs;
use crate::output::{check_target, print_report, thousands};

/// The robot page around the data and the scripts.
const TEMPLATE: &str = include_str!("../../../assets/view/robot.html");
/// The robot page's script.
const ROBOT_JS: &str = include_str!("../../../assets/view/robot.js");

/// Everything `sphaera view ROBOT.urdf` reports; also its JSON schema.
#[derive(Debug, Serialize)]
struct Report {
    urdf: String,
    robot: String,
    /// Per link with spheres: its spheres and certified worst protrusion.
    links: Vec<LinkReport>,
    /// The active joints and the values the page opens at.
    joints: BTreeMap<String, f64>,
    spheres: usize,
    /// Pairs of links with spheres left out of self-collision checks, by reason, and left.
    disabled: BTreeMap<&'static str, usize>,
    checked: usize,
    /// Where each link's first sphere is at the joints above, in the robot's units (the
    /// page shows the same: its `data-probe`).
    probes: BTreeMap<String, [f64; 3]>,
    output: String,
    bytes: usize,
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct LinkReport {
    link: String,
    spheres: usize,
    worst_protrusion: f64,
    coverage_certified: bool,
}

#[derive(Serialize)]
struct PageLink {
    name: String,
    /// Its index among the chain's links.
    index: usize,
    colour: String,
    worst_protrusion: f64,
    /// `x, y, z, r` per sphere, f32, base64, in the link's frame.
    spheres: String,
    mesh: Option<PageMesh>,
}

#[derive(Serialize)]
struct PageMesh {
    positions: String,
    triangles: String,
}

#[derive(Serialize)]
struct PageStep {
    parent: usize,
    child: usize,
    /// The origin as a column-major 4 × 4 matrix, translation in page units.
    origin: Vec<f64>,
    axis: [f64; 3],
    /// `rotate`, `slide` or `fixed`.
    kind: &'static str,
    source: Option<PageSource>,
}

#[derive(Serialize)]
struct PageSource {
    joint: usize,
    multiplier: f64,
    offset: f64,
}

#[derive(Serialize)]
struct PageJoint {
    name: String,
    lower: f64,
    upper: f64,
    value: f64,
}

#[derive(Serialize)]
struct PagePair<'a> {
    first: &'a str,
    second: &'a str,
    reason: Option<&'static str>,
}

/// The joint values the page opens at: the default configuration with `--joint`s set.
fn configuration(chain: &KinematicChain, asked: &[(String, f64)]) -> Result<Vec<f64>> {
    let mut q = chain.default_configuration();
    for (name, value) in asked {
        let Some(k) = chain.joints().iter().position(|j| &j.name == name) else {
            let names: Vec<&str> = chain.joints().iter().map(|j| j.name.as_str()).collect();
            bail!(
                "--joint {name}: the robot has no moving joint of this name (it has {})",
                names.join(", ")
            );
        };
        if !value.is_finite() {
            bail!("--joint {name}={value}: the value must be finite");
        }
        q[k] = *value;
    }
    Ok(q)
}

pub fn run(args: &ViewArgs, path: &Path, quiet: bool) -> Result<()> {
    let started = Instant::now();
    for (given, flag) in [
        (args.tree.is_some(), "--tree"),
        (args.simplify.is_some(), "--simplify"),
        (args.hausdorff.is_some(), "--hausdorff"),
        (args.hal.is_some(), "--hal"),
        (args.silhouette, "--silhouette"),
    ] {
        if given {
            bail!("{flag} applies to a mesh, not to a robot's URDF");
        }
    }
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| std::path::PathBuf::from("view.html"));
    check_target(&output)?;
    let policy = crate::input::file_policy();
    let urdf = Urdf::read_with(path, &policy)?;
    let resolver = MeshResolver::new(urdf.folder()).with_policy(policy);
    let chain = KinematicChain::new(&urdf)?;
    let q = configuration(&chain, &args.joints)?;
    let options = SpherizeOptions::default()
        .with_budget(SphereBudget::PerLink(args.spheres_per_link))
        .with_self_collision(SelfCollisionOptions::default());
    let robot = crate::commands::urdf::spherize_robot(&urdf, &resolver, &options, quiet)?;
    let Some(matrix) = &robot.self_collision else {
        bail!("the self-collision matrix was asked for and not computed");
    };
    let geometry = LinkGeometry::load_all(&urdf, GeometrySource::Collision, &resolver)?;
    let meshes: BTreeMap<&str, &sphaera::mesh::TriMesh> = geometry
        .iter()
        .filter_map(|g| Some((g.link.as_str(), g.mesh.as_ref()?)))
        .collect();
    let poses = chain.poses(&q)?;
    let index = |name: &str| {
        chain
            .link_index(name)
            .with_context(|| format!("link {name} is not in the robot's tree"))
    };
    // The robot's reach from its root at this configuration: page radius 1.
    let mut reach: f64 = 0.0;
    for link in &robot.links {
        let pose = poses[index(&link.link)?];
        for s in &link.spheres {
            reach = reach.max(pose.transform_point3(s.center).length() + s.radius);
        }
    }
    let scale = if reach > 0.0 && reach.is_finite() {
        reach
    } else {
        1.0
    };
    let worst_of_all = robot
        .links
        .iter()
        .map(|l| l.report.worst_protrusion)
        .fold(0.0, f64::max);
    let mut page_links = Vec::new();
    let mut probes = BTreeMap::new();
    let (mut low, mut high) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for link in &robot.links {
        let k = index(&link.link)?;
        let [r, g, b] = colormap::blue_to_red(if worst_of_all > 0.0 {
            link.report.worst_protrusion / worst_of_all
        } else {
            0.0
        });
        let spheres = |s: &Sphere| {
            [
                s.center.x / scale,
                s.center.y / scale,
                s.center.z / scale,
                s.radius / scale,
            ]
        };
        let mesh = meshes.get(link.link.as_str()).map(|mesh| PageMesh {
            positions: f32_base64(
                mesh.positions()
                    .iter()
                    .flat_map(|p| (*p / scale).to_array()),
            ),
            triangles: base64_of(
                &mesh
                    .triangles()
                    .iter()
                    .flatten()
                    .flat_map(|i| i.to_le_bytes())
                    .collect::<Vec<u8>>(),
            ),
        });
        for s in &link.spheres {
            let c = poses[k].transform_point3(s.center);
            low = low.min(c - DVec3::splat(s.radius));
            high = high.max(c + DVec3::splat(s.radius));
        }
        if let Some(first) = link.spheres.first() {
            probes.insert(
                link.link.clone(),
                poses[k].transform_point3(first.center).to_array(),
            );
        }
        page_links.push(PageLink {
            name: link.link.clone(),
            index: k,
            colour: format!("#{r:02x}{g:02x}{b:02x}"),
            worst_protrusion: link.report.worst_protrusion,
            spheres: f32_base64(link.spheres.iter().flat_map(spheres)),
            mesh,
        });
    }
    let steps: Vec<PageStep> = chain
        .steps()
        .iter()
        .map(|step| {
            let mut origin = step.origin;
            origin.translation /= scale;
            let (kind, source) = match step.motion {
                JointMotion::Fixed => ("fixed", None),
                JointMotion::Rotate(s) => ("rotate", Some(s)),
                JointMotion::Slide(s) => ("slide", Some(s)),
            };
            PageStep {
                parent: step.parent,
                child: step.child,
                origin: sphaera::mesh::glam::DMat4::from(origin)
                    .to_cols_array()
                    .to_vec(),
                axis: step.axis.to_array(),
                kind,
                source: source.map(|s| PageSource {
                    joint: s.joint,
                    multiplier: s.multiplier,
                    offset: s.offset,
                }),
            }
        })
        .collect();
    let joints: Vec<PageJoint> = chain
        .joints()
        .iter()
        .zip(&q)
        .map(|(j, &value)| PageJoint {
            name: j.name.clone(),
            lower: j.lower.min(value),
            upper: j.upper.max(value),
            value,
        })
        .collect();
    let counts: BTreeMap<&'static str, usize> = DisableReason::ALL
        .iter()
        .map(|&r| (r.name(), matrix.count(r)))
        .collect();
    let pairs: Vec<PagePair<'_>> = matrix
        .pairs
        .iter()
        .map(|p| PagePair {
            first: &p.first,
            second: &p.second,
            reason: p.reason.map(DisableReason::name),
        })
        .collect();
    let checked = matrix.checked().count();
    let data = serde_json::json!({
        "name": urdf.name,
        "scale": scale,
        "link_count": chain.links().len(),
        "target": (0.5 * (low + high) / scale).to_array(),
        "links": page_links,
        "steps": steps,
        "joints": joints,
        "self_collision": {
            "pairs": pairs,
            "counts": counts,
            "checked": checked,
            "samples": matrix.samples,
        },
    });
    let page = fill(
        TEMPLATE,
        &[
            (
                "SPHAERA_TITLE",
                &html_escape(&format!("sphaera view: {}", urdf.name)),
            ),
            ("SPHAERA_THREE_BASE64", &base64_of(THREE_JS.as_bytes())),
            ("SPHAERA_DATA", &script_json(&data.to_string())),
            ("SPHAERA_VIEW_JS", &format!("{STAGE_JS}\n{ROBOT_JS}")),
        ],
    );
    sphaera::mesh::io::write_atomic(&output, |w| std::io::Write::write_all(w, page.as_bytes()))
        .with_context(|| format!("cannot write {}", output.display()))?;
    let report = Report {
        urdf: path.display().to_string(),
        robot: urdf.name.clone(),
        links: robot
            .links
            .iter()
            .map(|l| LinkReport {
                link: l.link.clone(),
                spheres: l.spheres.len(),
                worst_protrusion: l.report.worst_protrusion,
                coverage_certified: l.report.coverage_certified,
            })
            .collect(),
        joints: chain
            .joints()
            .iter()
            .map(|j| j.name.clone())
            .zip(q)
            .collect(),
        spheres: robot.sphere_count(),
        disabled: counts,
        checked,
        probes,
        output: output.display().to_string(),
        bytes: page.len(),
        seconds: started.elapsed().as_secs_f64(),
    };
    print_report(&report, args.print.json)
}

impl crate::output::Report for Report {
    fn to_text(&self) -> String {
        let mut lines = vec![format!(
            "urdf            {} (robot \"{}\")",
            self.urdf, self.robot
        )];
        for l in &self.links {
            lines.push(format!(
                "  {:<24} {:>4} spheres, worst protrusion {:.6}{}",
                l.link,
                l.spheres,
                l.worst_protrusion,
                if l.coverage_certified {
                    " (coverage certified)"
                } else {
                    ""
                }
            ));
        }
        let disabled: Vec<String> = self
            .disabled
            .iter()
            .map(|(r, n)| format!("{n} {}", r.to_lowercase()))
            .collect();
        lines.push(format!(
            "self-collision  {} pairs left out, {} to check",
            disabled.join(", "),
            self.checked
        ));
        lines.push(format!(
            "wrote           {} ({} KB, {} spheres, a slider per joint for {} joints; opens offline in any browser)",
            self.output,
            self.bytes / 1024,
            thousands(self.spheres),
            self.joints.len()
        ));
        lines.push(format!("time            {:.3} s", self.seconds));
        lines.join("\n") + "\n"
    }
}
