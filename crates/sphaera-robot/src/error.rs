//! Errors of URDF reading, link geometry, spherization and the planner formats.

use std::path::PathBuf;

/// Why a robot could not be read, spherized or written.
///
/// Messages are lowercase without a final period and name the file, the line and the
/// link where there is one.
///
/// # Examples
///
/// ```
/// use sphaera_robot::{RobotError, Urdf};
///
/// let error = Urdf::parse("<robot name='r'><link name='a'>", "broken.urdf").unwrap_err();
/// assert!(matches!(error, RobotError::Xml { .. }));
/// assert!(error.to_string().starts_with("broken.urdf: malformed XML"));
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RobotError {
    /// A file could not be read, or the file policy refuses it.
    #[error("cannot read {}: {source}", path.display())]
    ReadFile {
        /// The file.
        path: PathBuf,
        /// Why: the operating system's error, or the policy's refusal.
        source: Box<sphaera_io::IoError>,
    },
    /// The URDF is not well-formed XML.
    #[error("{}: malformed XML: {message}", path.display())]
    Xml {
        /// The URDF.
        path: PathBuf,
        /// What the XML reader found, with the line and column.
        message: String,
    },
    /// An element or attribute of the URDF is missing or meaningless (a number that does
    /// not parse, a zero scale, a negative radius, a joint naming an unknown link).
    #[error("{}:{line}: {place}: {message}", path.display())]
    Invalid {
        /// The URDF.
        path: PathBuf,
        /// The line of the element.
        line: u32,
        /// The element, e.g. `link "panda_link6" collision[0] mesh`.
        place: String,
        /// What is wrong.
        message: String,
    },
    /// A mesh file named by a link was not found.
    #[error("link \"{link}\": mesh `{uri}` not found (tried {})", list(tried))]
    MeshNotFound {
        /// The link.
        link: String,
        /// The file name as the URDF gives it.
        uri: String,
        /// The paths tried, in order.
        tried: Vec<PathBuf>,
    },
    /// A link's mesh file could not be loaded (an unknown format, a malformed file, no
    /// triangles).
    #[error("link \"{link}\": mesh {}: {source}", path.display())]
    Mesh {
        /// The link.
        link: String,
        /// The mesh file.
        path: PathBuf,
        /// Why it could not be loaded.
        source: Box<sphaera_io::IoError>,
    },
    /// A link's geometry could not be spherized (a closed mesh facing inward, a mesh
    /// without area), with the sphere-tree's or the surface's reason.
    #[error("link \"{link}\": {message}")]
    Spherize {
        /// The link.
        link: String,
        /// Why, from the sphere-tree builder or the surface.
        message: String,
    },
    /// A sphere budget that cannot be honoured: a total too small to give every link
    /// with geometry a sphere, or per-link counts that do not add up to the total.
    #[error("sphere budget: {message}")]
    Budget {
        /// What does not add up.
        message: String,
    },
    /// A link's tolerance cannot be met within the most spheres allowed per link.
    #[error(
        "link \"{link}\": the tolerance {tolerance} cannot be met within {max} spheres: {message} (loosen the tolerance or allow more spheres per link)"
    )]
    ToleranceUnreachable {
        /// The link.
        link: String,
        /// The tolerance, in the link's units.
        tolerance: f64,
        /// The most spheres allowed per link.
        max: usize,
        /// What it would need.
        message: String,
    },
    /// An option names a link the robot does not have, or one without geometry.
    #[error("no link \"{name}\"{}", if *without_geometry { " with geometry" } else { "" })]
    UnknownLink {
        /// The name given.
        name: String,
        /// The link exists but has no geometry of the chosen kind.
        without_geometry: bool,
    },
    /// A parameter is out of its domain.
    #[error("invalid {name} ({value}): must be {requirement}")]
    InvalidParameter {
        /// The parameter.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// A joint configuration names an unknown joint or gives a non-finite value.
    #[error("joint \"{joint}\": {message}")]
    Joint {
        /// The joint.
        joint: String,
        /// What is wrong.
        message: String,
    },
    /// No link of the robot has geometry of the kind asked for: the output would be empty.
    #[error(
        "no link of robot \"{robot}\" has {} geometry, so there is nothing to spherize",
        kind.name()
    )]
    NoGeometry {
        /// The robot's name.
        robot: String,
        /// The kind of geometry asked for.
        kind: crate::GeometrySource,
    },
    /// An output could not be written.
    #[error("cannot write {}: {message}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        message: String,
    },
}

fn list(paths: &[PathBuf]) -> String {
    if paths.is_empty() {
        return "nothing: the URI names no file".to_owned();
    }
    paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}
