//! JSON: per link its tree of spheres and its report, and the self-collision matrix.

use serde::Serialize;
use sphaera_mesh::Sphere;

use crate::self_collision::SelfCollisionMatrix;
use crate::spherize::{LinkReport, RobotSpheres};

#[derive(Serialize)]
struct JsonRobot<'a> {
    robot: &'a str,
    source: crate::GeometrySource,
    spheres: usize,
    links: Vec<JsonLink<'a>>,
    links_without_geometry: &'a [String],
    #[serde(skip_serializing_if = "Option::is_none")]
    self_collision: Option<&'a SelfCollisionMatrix>,
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
/// may skip them; the last level covers the link (certified). With the robot's
/// self-collision matrix, `self_collision` holds every pair of links with its `reason`
/// (`"Adjacent"`, `"Default"`, `"Always"`, `"Never"`, or `null`: checked) and `contacts`.
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
        self_collision: robot.self_collision.as_ref(),
    };
    serde_json::to_string_pretty(&document).unwrap_or_default() + "\n"
}
