//! The planner formats: the spherized URDF, MoveIt's SRDF sphere approximations,
//! cuRobo's collision-sphere YAML, and JSON with the levels and the reports.

use std::path::Path;

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, Event};
use serde::Serialize;
use sphaera_mesh::Sphere;
use sphaera_spheretree::export::{CollisionLink, collision_spheres_yaml};

use crate::RobotError;
use crate::spherize::{LinkReport, RobotSpheres};
use crate::urdf::Urdf;

/// A planner format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PlannerFormat {
    /// The same URDF with each link's collision geometry replaced by its spheres.
    Urdf,
    /// MoveIt's SRDF `<link_sphere_approximation>` elements (a sidecar; the URDF stays).
    Srdf,
    /// cuRobo's `collision_spheres` YAML.
    Curobo,
    /// JSON: per link the spheres, the bounding sphere above them, and the report.
    Json,
}

impl std::fmt::Display for PlannerFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for PlannerFormat {
    type Err = sphaera_mesh::ParseNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == s)
            .ok_or_else(|| {
                sphaera_mesh::ParseNameError::new("planner format", s, "urdf, srdf, curobo or json")
            })
    }
}

impl PlannerFormat {
    /// Every format.
    pub const ALL: [Self; 4] = [Self::Urdf, Self::Srdf, Self::Curobo, Self::Json];

    /// The name users type and reports show (`"urdf"`, `"srdf"`, `"curobo"`, `"json"`), as
    /// [`Display`](std::fmt::Display) writes it and [`FromStr`](std::str::FromStr) reads
    /// it.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_robot::PlannerFormat;
    ///
    /// assert_eq!("curobo".parse(), Ok(PlannerFormat::Curobo));
    /// assert_eq!(PlannerFormat::Srdf.to_string(), "srdf");
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Urdf => "urdf",
            Self::Srdf => "srdf",
            Self::Curobo => "curobo",
            Self::Json => "json",
        }
    }

    /// The format a file name's extension names: `.urdf`, `.srdf`, `.yml`/`.yaml`
    /// (cuRobo) or `.json`.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::path::Path;
    /// use sphaera_robot::PlannerFormat;
    ///
    /// assert_eq!(PlannerFormat::from_path(Path::new("panda_spheres.yml")), Some(PlannerFormat::Curobo));
    /// assert_eq!(PlannerFormat::from_path(Path::new("panda.txt")), None);
    /// ```
    #[must_use]
    pub fn from_path(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "urdf" => Some(Self::Urdf),
            "srdf" => Some(Self::Srdf),
            "yml" | "yaml" => Some(Self::Curobo),
            "json" => Some(Self::Json),
            _ => None,
        }
    }

    /// The text of `robot`'s spheres in this format (`urdf` is the URDF it was made from).
    ///
    /// # Errors
    ///
    /// As [`spherized_urdf`], [`srdf`] and [`curobo_yaml`].
    pub fn render(self, urdf: &Urdf, robot: &RobotSpheres) -> Result<String, RobotError> {
        match self {
            Self::Urdf => spherized_urdf(urdf, robot),
            Self::Srdf => srdf(robot),
            Self::Curobo => curobo_yaml(robot),
            Self::Json => Ok(json(robot)),
        }
    }
}

/// A number as XML attributes carry it: the shortest text that reads back exactly.
fn number(v: f64) -> String {
    format!("{v}")
}

fn triple(v: glam::DVec3) -> String {
    format!("{} {} {}", number(v.x), number(v.y), number(v.z))
}

fn xml_error(e: &std::io::Error) -> RobotError {
    RobotError::Write {
        path: "<memory>".into(),
        message: e.to_string(),
    }
}

/// MoveIt's SRDF sphere approximations: one `<link_sphere_approximation link="…">` per
/// link with `<sphere center="x y z" radius="r"/>` children, in the link's frame.
///
/// # Errors
///
/// Never in practice ([`RobotError::Write`] if the XML writer fails).
pub fn srdf(robot: &RobotSpheres) -> Result<String, RobotError> {
    let mut writer = Writer::new_with_indent(Vec::new(), b' ', 2);
    writer
        .write_event(Event::Decl(BytesDecl::new("1.0", Some("utf-8"), None)))
        .map_err(|e| xml_error(&e))?;
    writer
        .create_element("robot")
        .with_attribute(("name", robot.robot.as_str()))
        .write_inner_content(|w| {
            for link in &robot.links {
                w.create_element("link_sphere_approximation")
                    .with_attribute(("link", link.link.as_str()))
                    .write_inner_content(|w| {
                        for s in &link.spheres {
                            w.create_element("sphere")
                                .with_attribute(("center", triple(s.center).as_str()))
                                .with_attribute(("radius", number(s.radius).as_str()))
                                .write_empty()?;
                        }
                        Ok(())
                    })?;
            }
            Ok(())
        })
        .map_err(|e| xml_error(&e))?;
    String::from_utf8(writer.into_inner()).map_err(|e| RobotError::Write {
        path: "<memory>".into(),
        message: e.to_string(),
    })
}

/// cuRobo's `collision_spheres` YAML: per link, `center: [x, y, z]` and `radius`.
///
/// # Errors
///
/// [`RobotError::Write`] for a sphere that is not one (never for spherized links).
pub fn curobo_yaml(robot: &RobotSpheres) -> Result<String, RobotError> {
    let links: Vec<CollisionLink> = robot
        .links
        .iter()
        .map(|l| CollisionLink::new(l.link.clone(), l.spheres.clone()))
        .collect();
    collision_spheres_yaml(&links).map_err(|e| RobotError::Write {
        path: "<memory>".into(),
        message: e.to_string(),
    })
}

#[derive(Serialize)]
struct JsonRobot<'a> {
    robot: &'a str,
    source: crate::GeometrySource,
    spheres: usize,
    links: Vec<JsonLink<'a>>,
    links_without_geometry: &'a [String],
}

#[derive(Serialize)]
struct JsonLink<'a> {
    link: &'a str,
    /// The levels of the link's tree, coarsest first (see [`json`]).
    levels: Vec<Vec<JsonSphere>>,
    report: &'a LinkReport,
}

#[derive(Serialize)]
struct JsonSphere {
    center: [f64; 3],
    radius: f64,
    /// Its children in the next level, `[first, end)`; absent at the last level.
    #[serde(skip_serializing_if = "Option::is_none")]
    children: Option<[usize; 2]>,
}

impl JsonSphere {
    fn new(s: &Sphere, children: Option<[usize; 2]>) -> Self {
        Self {
            center: s.center.to_array(),
            radius: s.radius,
            children,
        }
    }
}

/// The levels of one link's tree, coarsest first: its bounding sphere (grown to enclose
/// the next level where needed); with more than
/// eight spheres, about `√n` groups of nearby spheres, each the smallest ball enclosing
/// its group; then the spheres, ordered group by group. Each sphere names its children's
/// range in the next level and encloses them, so a planner that finds a sphere clear of
/// an obstacle may skip its children.
fn link_levels(link: &crate::LinkSpheres) -> Vec<Vec<JsonSphere>> {
    let spheres = &link.spheres;
    // The bounding sphere, grown where needed to enclose the next level (a group's
    // smallest ball may reach past the smallest ball of all the spheres).
    let root = |next: &[JsonSphere]| {
        let b = &link.bounding_sphere;
        let radius = next
            .iter()
            .map(|s| b.center.distance(glam::DVec3::from_array(s.center)) + s.radius)
            .fold(b.radius, f64::max);
        vec![JsonSphere::new(
            &Sphere::new(b.center, radius),
            Some([0, next.len()]),
        )]
    };
    let leaves = |order: &[usize]| -> Vec<JsonSphere> {
        order
            .iter()
            .map(|&i| JsonSphere::new(&spheres[i], None))
            .collect()
    };
    let groups = group_spheres(spheres);
    let enclosing: Option<Vec<Sphere>> = groups
        .iter()
        .map(|g| {
            let members: Vec<Sphere> = g.iter().map(|&i| spheres[i]).collect();
            let ball = sphaera_mesh::geometry::minimum_enclosing_ball_of_balls(&members).ok()?;
            // Enclosing as a planner computes it, whatever the solver's rounding.
            let radius = members
                .iter()
                .map(|m| ball.center.distance(m.center) + m.radius)
                .fold(ball.radius, f64::max);
            Some(Sphere::new(ball.center, radius))
        })
        .collect();
    match enclosing {
        Some(enclosing) if groups.len() > 1 => {
            let mut middle = Vec::with_capacity(groups.len());
            let mut order = Vec::with_capacity(spheres.len());
            for (group, ball) in groups.iter().zip(&enclosing) {
                middle.push(JsonSphere::new(
                    ball,
                    Some([order.len(), order.len() + group.len()]),
                ));
                order.extend_from_slice(group);
            }
            vec![root(&middle), middle, leaves(&order)]
        }
        _ => {
            let order: Vec<usize> = (0..spheres.len()).collect();
            let last = leaves(&order);
            vec![root(&last), last]
        }
    }
}

/// About `√n` groups of nearby spheres (indices, ascending within a group), by k-means on
/// their centres from a farthest-point start; one group for eight spheres or fewer.
/// Deterministic: ties go to the lower index.
fn group_spheres(spheres: &[Sphere]) -> Vec<Vec<usize>> {
    let n = spheres.len();
    if n <= 8 {
        return vec![(0..n).collect()];
    }
    let k = (n as f64).sqrt().round() as usize;
    let nearest = |p: glam::DVec3, centers: &[glam::DVec3]| -> usize {
        let mut best = 0;
        for (j, c) in centers.iter().enumerate() {
            if p.distance_squared(*c) < p.distance_squared(centers[best]) {
                best = j;
            }
        }
        best
    };
    let mut centers = vec![spheres[0].center];
    while centers.len() < k {
        let mut far = (0, -1.0);
        for (i, s) in spheres.iter().enumerate() {
            let d = s
                .center
                .distance_squared(centers[nearest(s.center, &centers)]);
            if d > far.1 {
                far = (i, d);
            }
        }
        centers.push(spheres[far.0].center);
    }
    let mut assignment = vec![0; n];
    for _ in 0..20 {
        for (a, s) in assignment.iter_mut().zip(spheres) {
            *a = nearest(s.center, &centers);
        }
        let mut sums = vec![(glam::DVec3::ZERO, 0usize); k];
        for (&a, s) in assignment.iter().zip(spheres) {
            sums[a].0 += s.center;
            sums[a].1 += 1;
        }
        for (c, (sum, count)) in centers.iter_mut().zip(sums) {
            if count > 0 {
                *c = sum / count as f64;
            }
        }
    }
    let mut groups = vec![Vec::new(); k];
    for (i, &a) in assignment.iter().enumerate() {
        groups[a].push(i);
    }
    groups.retain(|g| !g.is_empty());
    groups
}

/// JSON: the robot, then per link its `levels` and its `report`. The levels are the
/// link's tree, coarsest first, each a list of `{"center": [x, y, z], "radius": r,
/// "children": [first, end]}`: the bounding sphere (grown where needed to enclose the
/// groups); with more than eight spheres, about `√n` groups of nearby spheres, each the
/// smallest ball enclosing its group; then the spheres themselves (without `children`),
/// ordered group by group. Every sphere encloses its children, checked as a planner
/// computes it (`|c − c'| + r' ≤ r`), so a planner that finds one clear of an obstacle
/// may skip them; the last level covers the link (certified).
#[must_use]
pub fn json(robot: &RobotSpheres) -> String {
    let document = JsonRobot {
        robot: &robot.robot,
        source: robot.source,
        spheres: robot.sphere_count(),
        links: robot
            .links
            .iter()
            .map(|l| JsonLink {
                link: &l.link,
                levels: link_levels(l),
                report: &l.report,
            })
            .collect(),
        links_without_geometry: &robot.links_without_geometry,
    };
    serde_json::to_string_pretty(&document).unwrap_or_default() + "\n"
}

/// The URDF it was read from with every spherized link's `<collision>` elements replaced
/// by one `<collision>` per sphere (`<sphere>` geometry at an `<origin>`); everything else
/// is kept byte for byte. A link spherized from its visual geometry without collision
/// elements gets the spheres before its closing tag.
///
/// # Errors
///
/// [`RobotError::Write`] when a link of `robot` is not in `urdf` (spheres of another
/// robot).
pub fn spherized_urdf(urdf: &Urdf, robot: &RobotSpheres) -> Result<String, RobotError> {
    let text = &urdf.text;
    // (start, end, replacement), in text order.
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    let by_name: std::collections::HashMap<&str, &crate::urdf::Link> =
        urdf.links.iter().map(|l| (l.name.as_str(), l)).collect();
    for spheres in &robot.links {
        let link = by_name
            .get(spheres.link.as_str())
            .ok_or_else(|| RobotError::Write {
                path: urdf.path.clone(),
                message: format!("link \"{}\" is not in the URDF", spheres.link),
            })?;
        let indent = |at: usize| -> String {
            let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
            text[line_start..at]
                .chars()
                .take_while(|c| c.is_whitespace())
                .collect()
        };
        match link.collisions.split_first() {
            Some((first, rest)) => {
                let block = collisions(&spheres.link, &spheres.spheres, &indent(first.range.start));
                edits.push((first.range.start, first.range.end, block));
                for element in rest {
                    // Remove the element with the indentation before it.
                    let start = text[..element.range.start]
                        .rfind(|c: char| !c.is_whitespace())
                        .map_or(element.range.start, |i| i + 1);
                    edits.push((start, element.range.end, String::new()));
                }
            }
            None => {
                let inner = &text[link.range.clone()];
                let Some(close) = inner.rfind("</") else {
                    continue;
                };
                let at = link.range.start + close;
                let inner_indent = format!("{}  ", indent(link.range.start));
                let block = collisions(&spheres.link, &spheres.spheres, &inner_indent);
                edits.push((at, at, format!("  {block}\n{}", indent(link.range.start))));
            }
        }
    }
    edits.sort_by_key(|e| e.0);
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (start, end, replacement) in edits {
        out.push_str(&text[at..start]);
        out.push_str(&replacement);
        at = end;
    }
    out.push_str(&text[at..]);
    Ok(out)
}

/// One `<collision>` per sphere, joined by newlines at `indent`.
fn collisions(link: &str, spheres: &[Sphere], indent: &str) -> String {
    let name = quick_xml::escape::escape(link);
    spheres
        .iter()
        .enumerate()
        .map(|(i, s)| {
            format!(
                "<collision name=\"{name}_sphere_{i}\"><origin xyz=\"{}\" rpy=\"0 0 0\"/><geometry><sphere radius=\"{}\"/></geometry></collision>",
                triple(s.center),
                number(s.radius)
            )
        })
        .collect::<Vec<_>>()
        .join(&format!("\n{indent}"))
}

/// Writes `text` to `path` atomically (a temporary file renamed over it).
///
/// # Errors
///
/// [`RobotError::Write`] naming the file.
pub fn write_atomic(path: &Path, text: &str) -> Result<(), RobotError> {
    sphaera_io::write_atomic(path, |w| std::io::Write::write_all(w, text.as_bytes())).map_err(|e| {
        RobotError::Write {
            path: path.to_path_buf(),
            message: e.to_string(),
        }
    })
}
