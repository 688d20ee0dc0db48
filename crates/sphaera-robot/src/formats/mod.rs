//! The planner formats: the spherized URDF, MoveIt's SRDF, cuRobo's robot file (or its
//! `collision_spheres` block alone), MuJoCo's MJCF, and JSON with the levels, the reports
//! and the self-collision matrix.

mod curobo;
mod json;
mod mjcf;
mod srdf;
mod urdf_out;

use std::borrow::Cow;
use std::path::Path;

use serde::Serialize;

pub use curobo::{CuroboOptions, curobo_robot_yaml, curobo_yaml};
pub use json::json;
pub use mjcf::{MjcfOptions, mjcf};
pub use srdf::srdf;
pub use urdf_out::spherized_urdf;

use crate::RobotError;
use crate::self_collision::{SelfCollisionMatrix, SelfCollisionOptions, self_collision_matrix};
use crate::spherize::RobotSpheres;
use crate::urdf::Urdf;

/// A planner format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlannerFormat {
    /// The same URDF with each link's collision geometry replaced by its spheres.
    Urdf,
    /// MoveIt's SRDF: `<link_sphere_approximation>` per link and `<disable_collisions>`
    /// per pair of links left out of self-collision checks (a sidecar; the URDF stays).
    Srdf,
    /// A complete cuRobo robot file: the URDF, base and end-effector links, the collision
    /// links and their spheres, buffers, the self-collision ignore lists and the joint
    /// space ([`curobo_robot_yaml`]).
    Curobo,
    /// cuRobo's `collision_spheres` block alone ([`curobo_yaml`]), for a robot file that
    /// names it.
    CuroboSpheres,
    /// MuJoCo's MJCF: the body tree with its joints and limits, the spheres as geoms,
    /// and the pairs left out as `<exclude>` ([`mjcf`]).
    Mjcf,
    /// JSON: per link the spheres, the bounding sphere above them, and the report; the
    /// self-collision matrix when computed.
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
                sphaera_mesh::ParseNameError::new(
                    "planner format",
                    s,
                    "urdf, srdf, curobo, curobo-spheres, mjcf or json",
                )
            })
    }
}

impl PlannerFormat {
    /// Every format.
    pub const ALL: [Self; 6] = [
        Self::Urdf,
        Self::Srdf,
        Self::Curobo,
        Self::CuroboSpheres,
        Self::Mjcf,
        Self::Json,
    ];

    /// The name users type and reports show (`"urdf"`, `"srdf"`, `"curobo"`,
    /// `"curobo-spheres"`, `"mjcf"`, `"json"`), as [`Display`](std::fmt::Display) writes it
    /// and [`FromStr`](std::str::FromStr) reads it.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_robot::PlannerFormat;
    ///
    /// assert_eq!("curobo".parse(), Ok(PlannerFormat::Curobo));
    /// assert_eq!(PlannerFormat::CuroboSpheres.to_string(), "curobo-spheres");
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Urdf => "urdf",
            Self::Srdf => "srdf",
            Self::Curobo => "curobo",
            Self::CuroboSpheres => "curobo-spheres",
            Self::Mjcf => "mjcf",
            Self::Json => "json",
        }
    }

    /// The format a file name's extension names: `.urdf`, `.srdf`, `.yml`/`.yaml` (the
    /// complete cuRobo file), `.xml`/`.mjcf` (MJCF) or `.json`.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::path::Path;
    /// use sphaera_robot::PlannerFormat;
    ///
    /// assert_eq!(PlannerFormat::from_path(Path::new("panda.yml")), Some(PlannerFormat::Curobo));
    /// assert_eq!(PlannerFormat::from_path(Path::new("panda.xml")), Some(PlannerFormat::Mjcf));
    /// assert_eq!(PlannerFormat::from_path(Path::new("panda.txt")), None);
    /// ```
    #[must_use]
    pub fn from_path(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "urdf" => Some(Self::Urdf),
            "srdf" => Some(Self::Srdf),
            "yml" | "yaml" => Some(Self::Curobo),
            "xml" | "mjcf" => Some(Self::Mjcf),
            "json" => Some(Self::Json),
            _ => None,
        }
    }

    /// Whether the format writes which pairs of links are left out of self-collision
    /// checks (and so needs the matrix: [`PlannerFormat::render`] computes it when the
    /// robot has none).
    #[must_use]
    pub fn writes_self_collision(self) -> bool {
        matches!(self, Self::Srdf | Self::Curobo | Self::Mjcf)
    }

    /// The text of `robot`'s spheres in this format (`urdf` is the URDF it was made
    /// from), with default [`CuroboOptions`] and [`MjcfOptions`]. The formats that write
    /// the pairs left out of self-collision checks use `robot.self_collision`, or compute
    /// the matrix with [`SelfCollisionOptions::default`] when it is `None`.
    ///
    /// # Errors
    ///
    /// As [`spherized_urdf`], [`srdf`], [`curobo_robot_yaml`], [`curobo_yaml`] and
    /// [`mjcf`], and [`self_collision_matrix`].
    pub fn render(self, urdf: &Urdf, robot: &RobotSpheres) -> Result<String, RobotError> {
        let matrix = || matrix_of(urdf, robot);
        match self {
            Self::Urdf => spherized_urdf(urdf, robot),
            Self::Srdf => srdf(robot, &*matrix()?),
            Self::Curobo => curobo_robot_yaml(urdf, robot, &*matrix()?, &CuroboOptions::default()),
            Self::CuroboSpheres => curobo_yaml(robot),
            Self::Mjcf => mjcf(urdf, robot, &*matrix()?, &MjcfOptions::default()),
            Self::Json => Ok(json(robot)),
        }
    }
}

/// The robot's self-collision matrix, or one computed with the default options.
fn matrix_of<'a>(
    urdf: &Urdf,
    robot: &'a RobotSpheres,
) -> Result<Cow<'a, SelfCollisionMatrix>, RobotError> {
    match &robot.self_collision {
        Some(matrix) => Ok(Cow::Borrowed(matrix)),
        None => Ok(Cow::Owned(self_collision_matrix(
            urdf,
            robot,
            &SelfCollisionOptions::default(),
        )?)),
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
