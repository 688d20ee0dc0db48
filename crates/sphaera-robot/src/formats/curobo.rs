//! cuRobo: the `collision_spheres` block, and the complete robot file.

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;

use sphaera_spheretree::export::{CollisionLink, collision_spheres_yaml, yaml_float};

use crate::RobotError;
use crate::chain::KinematicChain;
use crate::self_collision::SelfCollisionMatrix;
use crate::spherize::RobotSpheres;
use crate::urdf::{Joint, Urdf};

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

/// What a complete cuRobo robot file says beyond the URDF and the spheres.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct CuroboOptions {
    /// `urdf_path` as written (default: the path the URDF was read from).
    pub urdf_path: Option<String>,
    /// `asset_root_path` (default: the URDF's folder).
    pub asset_root_path: Option<String>,
    /// `ee_link` (default: where the main chain ends: from the root, the one child whose
    /// subtree has moving joints is followed while there is exactly one; the Panda's
    /// `panda_hand`, the iiwa's last link). The active joints below it are locked
    /// (`lock_joints`) at their default values.
    pub ee_link: Option<String>,
    /// `collision_sphere_buffer`, added to every sphere by cuRobo (default 0: the spheres
    /// already cover the links, certified).
    pub collision_sphere_buffer: f64,
    /// Every link's `self_collision_buffer` (default 0).
    pub self_collision_buffer: f64,
    /// Instead of the spheres inline, this file named in `collision_spheres` (write it
    /// with [`curobo_yaml`]).
    pub spheres_file: Option<String>,
}

impl CuroboOptions {
    /// With `ee_link` named.
    #[must_use]
    pub fn with_ee_link(mut self, link: impl Into<String>) -> Self {
        self.ee_link = Some(link.into());
        self
    }

    /// With the URDF and asset paths written as given.
    #[must_use]
    pub fn with_paths(
        mut self,
        urdf_path: impl Into<String>,
        asset_root_path: impl Into<String>,
    ) -> Self {
        self.urdf_path = Some(urdf_path.into());
        self.asset_root_path = Some(asset_root_path.into());
        self
    }

    /// With the spheres in `file`, named from the robot file.
    #[must_use]
    pub fn with_spheres_file(mut self, file: impl Into<String>) -> Self {
        self.spheres_file = Some(file.into());
        self
    }

    /// With the given buffers.
    #[must_use]
    pub fn with_buffers(
        mut self,
        collision_sphere_buffer: f64,
        self_collision_buffer: f64,
    ) -> Self {
        self.collision_sphere_buffer = collision_sphere_buffer;
        self.self_collision_buffer = self_collision_buffer;
        self
    }
}

/// A YAML double-quoted string (JSON's escapes, which YAML reads).
fn quoted(text: &str) -> String {
    serde_json::to_string(text).unwrap_or_default()
}

fn flow_strings<'a>(items: impl IntoIterator<Item = &'a str>) -> String {
    let items: Vec<String> = items.into_iter().map(quoted).collect();
    format!("[{}]", items.join(", "))
}

fn flow_floats(items: impl IntoIterator<Item = f64>) -> String {
    let items: Vec<String> = items.into_iter().map(yaml_float).collect();
    format!("[{}]", items.join(", "))
}

/// Where the main chain ends: from the root, follow the one child whose subtree has a
/// moving joint while there is exactly one.
fn end_of_main_chain(urdf: &Urdf) -> Result<String, RobotError> {
    let below = urdf.child_joints();
    let mut moving: HashMap<&str, bool> = HashMap::new();
    // Post-order: a link's subtree moves when a joint below it moves or its subtree does.
    let root = urdf.root()?;
    let mut order = vec![root];
    let mut k = 0;
    while k < order.len() {
        order.extend(
            below
                .get(order[k])
                .into_iter()
                .flatten()
                .map(|j| j.child.as_str()),
        );
        k += 1;
    }
    for &link in order.iter().rev() {
        let moves = below.get(link).into_iter().flatten().any(|j: &&Joint| {
            j.kind != crate::JointKind::Fixed
                || moving.get(j.child.as_str()).copied().unwrap_or(false)
        });
        moving.insert(link, moves);
    }
    let mut at = root;
    loop {
        let children: Vec<&&Joint> = below.get(at).into_iter().flatten().collect();
        let live: Vec<&&Joint> = children
            .iter()
            .copied()
            // Every link reached from the root is in `moving` (filled over `order`, the
            // whole tree from the root).
            .filter(|j| j.kind != crate::JointKind::Fixed || moving[j.child.as_str()])
            .collect();
        match (children.as_slice(), live.as_slice()) {
            ([only], _) | (_, [only]) => at = only.child.as_str(),
            _ => return Ok(at.to_owned()),
        }
    }
}

/// The links in `link`'s subtree, itself included.
fn subtree(urdf: &Urdf, link: &str) -> HashSet<String> {
    let below = urdf.child_joints();
    let mut seen = HashSet::from([link.to_owned()]);
    let mut stack = vec![link];
    while let Some(at) = stack.pop() {
        for joint in below.get(at).into_iter().flatten() {
            seen.insert(joint.child.clone());
            stack.push(joint.child.as_str());
        }
    }
    seen
}

/// A complete cuRobo robot file (`robot_cfg: kinematics:` as cuRobo's template holds it):
/// the URDF and asset paths, `base_link` (the URDF's root), `ee_link`, the collision
/// links and their spheres (inline, or the file named in
/// [`CuroboOptions::spheres_file`]), the buffers, `self_collision_ignore` from `matrix`
/// (for each link, the links after it left out), `self_collision_buffer`, the links with
/// meshes, and the joint space: every active joint, the default configuration as
/// `retract_config` (MoveIt's: 0 where the limits allow, else their middle), unit
/// weights, cuRobo's default jerk and acceleration limits, and the URDF's position limits
/// as comments (cuRobo reads them from the URDF).
///
/// # Examples
///
/// ```
/// use sphaera_robot::{
///     CuroboOptions, MeshResolver, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf,
///     curobo_robot_yaml, self_collision_matrix, spherize,
/// };
///
/// let urdf = Urdf::parse(r#"
///   <robot name="arm">
///     <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
///     <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><capsule radius="0.04" length="0.3"/></geometry></collision></link>
///     <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
///       <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/><limit lower="-1" upper="1"/></joint>
///   </robot>"#, "arm.urdf")?;
/// let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(3));
/// let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options)?;
/// let matrix = self_collision_matrix(&urdf, &robot, &SelfCollisionOptions::default().with_samples(100))?;
/// let yaml = curobo_robot_yaml(&urdf, &robot, &matrix, &CuroboOptions::default())?;
/// assert!(yaml.contains("    base_link: \"base\"\n    ee_link: \"upper\"\n"));
/// assert!(yaml.contains("      \"base\": [\"upper\"]\n"));
/// assert!(yaml.contains("      joint_names: [\"shoulder\"]\n      retract_config: [0.0]\n"));
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
///
/// # Errors
///
/// [`RobotError::UnknownLink`] for an `ee_link` the URDF does not have; as
/// [`KinematicChain::new`]; [`RobotError::Write`] for a sphere that is not one.
pub fn curobo_robot_yaml(
    urdf: &Urdf,
    robot: &RobotSpheres,
    matrix: &SelfCollisionMatrix,
    options: &CuroboOptions,
) -> Result<String, RobotError> {
    let chain = KinematicChain::new(urdf)?;
    let ee_link = match &options.ee_link {
        Some(link) if urdf.link(link).is_some() => link.clone(),
        Some(link) => {
            return Err(RobotError::UnknownLink {
                name: link.clone(),
                without_geometry: false,
            });
        }
        None => end_of_main_chain(urdf)?,
    };
    let below_ee = subtree(urdf, &ee_link);
    let joint_child: HashMap<&str, &str> = urdf
        .joints
        .iter()
        .map(|j| (j.name.as_str(), j.child.as_str()))
        .collect();
    let locked: Vec<(&str, f64)> = chain
        .joints()
        .iter()
        .filter(|j| {
            joint_child
                .get(j.name.as_str())
                .is_some_and(|c| below_ee.contains(*c) && *c != ee_link)
        })
        .map(|j| (j.name.as_str(), j.default_value()))
        .collect();
    let urdf_path = options
        .urdf_path
        .clone()
        .unwrap_or_else(|| urdf.path.display().to_string());
    let asset_root = options
        .asset_root_path
        .clone()
        .unwrap_or_else(|| urdf.folder().display().to_string());
    let links: Vec<&str> = robot.links.iter().map(|l| l.link.as_str()).collect();
    let mut out = String::new();
    let w = &mut out;
    let _ = writeln!(
        w,
        "# cuRobo robot file for {}, written by sphaera",
        quoted(&robot.robot)
    );
    let _ = writeln!(
        w,
        "robot_cfg:\n  kinematics:\n    use_usd_kinematics: false"
    );
    let _ = writeln!(w, "    urdf_path: {}", quoted(&urdf_path));
    let _ = writeln!(w, "    asset_root_path: {}", quoted(&asset_root));
    let _ = writeln!(w, "    base_link: {}", quoted(urdf.root()?));
    let _ = writeln!(w, "    ee_link: {}", quoted(&ee_link));
    let _ = writeln!(w, "    link_names: null");
    if locked.is_empty() {
        let _ = writeln!(w, "    lock_joints: null");
    } else {
        let entries: Vec<String> = locked
            .iter()
            .map(|(name, v)| format!("{}: {}", quoted(name), yaml_float(*v)))
            .collect();
        let _ = writeln!(w, "    lock_joints: {{{}}}", entries.join(", "));
    }
    let _ = writeln!(w, "    extra_links: null");
    let _ = writeln!(
        w,
        "    collision_link_names: {}",
        flow_strings(links.iter().copied())
    );
    match &options.spheres_file {
        Some(file) => {
            let _ = writeln!(w, "    collision_spheres: {}", quoted(file));
        }
        None => {
            for line in curobo_yaml(robot)?.lines() {
                let _ = writeln!(w, "    {line}");
            }
        }
    }
    let _ = writeln!(
        w,
        "    collision_sphere_buffer: {}",
        yaml_float(options.collision_sphere_buffer)
    );
    let _ = writeln!(w, "    extra_collision_spheres: {{}}");
    let ignore = matrix.ignore_lists();
    if ignore.is_empty() {
        let _ = writeln!(w, "    self_collision_ignore: {{}}");
    } else {
        let _ = writeln!(w, "    self_collision_ignore:");
        // In the robot's link order, as cuRobo's own files list them.
        for link in &links {
            if let Some(others) = ignore.get(*link) {
                let _ = writeln!(
                    w,
                    "      {}: {}",
                    quoted(link),
                    flow_strings(others.iter().map(String::as_str))
                );
            }
        }
    }
    let _ = writeln!(w, "    self_collision_buffer:");
    for link in &links {
        let _ = writeln!(
            w,
            "      {}: {}",
            quoted(link),
            yaml_float(options.self_collision_buffer)
        );
    }
    let _ = writeln!(w, "    use_global_cumul: true");
    let with_meshes = robot
        .links
        .iter()
        .filter(|l| l.report.triangles > 0)
        .map(|l| l.link.as_str());
    let _ = writeln!(w, "    mesh_link_names: {}", flow_strings(with_meshes));
    let joints = chain.joints();
    let _ = writeln!(w, "    cspace:");
    for j in joints {
        let source = if j.limited {
            "the URDF's limits"
        } else {
            "no limits in the URDF; range sampled"
        };
        let _ = writeln!(
            w,
            "      # {}: [{}, {}] ({source})",
            j.name,
            yaml_float(j.lower),
            yaml_float(j.upper)
        );
    }
    let _ = writeln!(
        w,
        "      joint_names: {}",
        flow_strings(joints.iter().map(|j| j.name.as_str()))
    );
    let _ = writeln!(
        w,
        "      retract_config: {}",
        flow_floats(chain.default_configuration())
    );
    let ones = || joints.iter().map(|_| 1.0);
    let _ = writeln!(w, "      null_space_weight: {}", flow_floats(ones()));
    let _ = writeln!(w, "      cspace_distance_weight: {}", flow_floats(ones()));
    let _ = writeln!(w, "      max_jerk: 500.0\n      max_acceleration: 15.0");
    Ok(out)
}
