//! Reading a URDF: links with their collision and visual geometry, joints with their
//! origins, axes, limits and mimics. Only what spherization and forward kinematics need;
//! inertia, materials and transmissions are skipped.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use glam::{DAffine3, DMat3, DVec3};
use sphaera_io::FilePolicy;

use crate::RobotError;

mod checks;

/// A pose in a parent frame as URDF gives it: a translation and fixed-axis roll, pitch
/// and yaw (about x, then y, then z).
///
/// # Examples
///
/// ```
/// use sphaera_robot::Origin;
/// use glam::DVec3;
///
/// let origin = Origin { xyz: DVec3::new(0.0, 0.0, 0.333), rpy: DVec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2) };
/// let p = origin.affine().transform_point3(DVec3::X);
/// assert!((p - DVec3::new(0.0, 1.0, 0.333)).length() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Origin {
    /// The translation.
    pub xyz: DVec3,
    /// Roll, pitch and yaw in radians.
    pub rpy: DVec3,
}

impl Origin {
    /// The rigid transform: `Rz(yaw) · Ry(pitch) · Rx(roll)`, then the translation.
    #[must_use]
    pub fn affine(&self) -> DAffine3 {
        let rotation = DMat3::from_rotation_z(self.rpy.z)
            * DMat3::from_rotation_y(self.rpy.y)
            * DMat3::from_rotation_x(self.rpy.x);
        DAffine3::from_mat3_translation(rotation, self.xyz)
    }
}

/// The geometry of a collision or visual element.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A box centred on the origin with these side lengths.
    Box {
        /// Side lengths along x, y and z.
        size: DVec3,
    },
    /// A cylinder along z, centred on the origin.
    Cylinder {
        /// Its radius.
        radius: f64,
        /// Its length along z.
        length: f64,
    },
    /// A sphere centred on the origin.
    Sphere {
        /// Its radius.
        radius: f64,
    },
    /// A capsule along z, centred on the origin: a cylinder of this length capped by two
    /// hemispheres (an extension some URDF readers accept).
    Capsule {
        /// Its radius.
        radius: f64,
        /// The distance between the caps' centres.
        length: f64,
    },
    /// A mesh file, scaled per axis.
    Mesh {
        /// The file name as written (`package://…`, `file://…`, relative or absolute).
        filename: String,
        /// The scale per axis (default 1).
        scale: DVec3,
    },
}

impl Geometry {
    /// The kind's name in reports: `box`, `cylinder`, `sphere`, `capsule` or `mesh`.
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Box { .. } => "box",
            Self::Cylinder { .. } => "cylinder",
            Self::Sphere { .. } => "sphere",
            Self::Capsule { .. } => "capsule",
            Self::Mesh { .. } => "mesh",
        }
    }
}

/// A `<collision>` or `<visual>` element: geometry at an origin in the link's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// Its `name` attribute, if any.
    pub name: Option<String>,
    /// Where the geometry sits in the link's frame.
    pub origin: Origin,
    /// The geometry.
    pub geometry: Geometry,
    /// The element's line in the URDF.
    pub line: u32,
    /// The element's byte range in the URDF text.
    pub range: std::ops::Range<usize>,
}

/// A link's mass properties: `<inertial>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertial {
    /// The centre of mass and the inertia's axes, in the link's frame.
    pub origin: Origin,
    /// The mass (at least 0).
    pub mass: f64,
    /// The inertia about the centre of mass, `[ixx, ixy, ixz, iyy, iyz, izz]`.
    pub inertia: [f64; 6],
}

/// A link: its collision and visual elements.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Its name.
    pub name: String,
    /// Its mass properties, when the URDF gives them.
    pub inertial: Option<Inertial>,
    /// Its `<collision>` elements, in file order.
    pub collisions: Vec<Element>,
    /// Its `<visual>` elements, in file order.
    pub visuals: Vec<Element>,
    /// The link's line in the URDF.
    pub line: u32,
    /// The link element's byte range in the URDF text.
    pub range: std::ops::Range<usize>,
}

/// How a joint moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A rotation about the axis, within limits.
    Revolute,
    /// A rotation about the axis, unlimited.
    Continuous,
    /// A translation along the axis.
    Prismatic,
    /// No motion.
    Fixed,
    /// Six degrees of freedom (taken at its origin).
    Floating,
    /// Motion in a plane (taken at its origin).
    Planar,
}

/// A joint that copies another: `value = multiplier · other + offset`.
#[derive(Clone, Debug, PartialEq)]
pub struct Mimic {
    /// The joint copied.
    pub joint: String,
    /// The factor (default 1).
    pub multiplier: f64,
    /// The offset (default 0).
    pub offset: f64,
}

/// A joint between a parent link and a child link.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Its name.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// The parent link.
    pub parent: String,
    /// The child link.
    pub child: String,
    /// The child frame at zero motion, in the parent's frame.
    pub origin: Origin,
    /// The unit axis of motion in the joint frame (default x).
    pub axis: DVec3,
    /// The lower and upper limits, when given.
    pub limits: Option<(f64, f64)>,
    /// The joint it copies, if any.
    pub mimic: Option<Mimic>,
    /// The joint's line in the URDF.
    pub line: u32,
}

/// A robot read from a URDF: its links and joints, and where the file was (mesh paths
/// resolve against it).
///
/// # Examples
///
/// ```
/// use sphaera_robot::{Geometry, Urdf};
///
/// let urdf = Urdf::parse(r#"
///   <robot name="arm">
///     <link name="base">
///       <collision><origin xyz="0 0 0.1"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
///     </link>
///     <link name="tool"/>
///     <joint name="j1" type="revolute">
///       <parent link="base"/><child link="tool"/>
///       <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="-1" upper="1"/>
///     </joint>
///   </robot>"#, "arm.urdf")?;
/// assert_eq!(urdf.name, "arm");
/// assert_eq!(urdf.links.len(), 2);
/// assert!(matches!(urdf.links[0].collisions[0].geometry, Geometry::Box { .. }));
/// assert_eq!(urdf.root()?, "base");
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Urdf {
    /// The robot's name.
    pub name: String,
    /// Its links, in file order.
    pub links: Vec<Link>,
    /// Its joints, in file order.
    pub joints: Vec<Joint>,
    /// The file it was read from (for messages and to resolve mesh paths).
    pub path: PathBuf,
    /// The file's text (the spherized URDF is written from it, element by element).
    pub text: String,
}

impl Urdf {
    /// Reads and parses the URDF at `path` (by the default [`FilePolicy`]: a regular file
    /// of at most [`DEFAULT_MAX_FILE_BYTES`](sphaera_io::DEFAULT_MAX_FILE_BYTES)).
    ///
    /// # Errors
    ///
    /// [`RobotError::ReadFile`], then as [`Urdf::parse`].
    pub fn read(path: impl AsRef<Path>) -> Result<Self, RobotError> {
        Self::read_with(path, &FilePolicy::default())
    }

    /// [`Urdf::read`] by `policy` (a service confines URDFs and their meshes to a root:
    /// give the same policy to [`MeshResolver::with_policy`](crate::MeshResolver::with_policy)).
    ///
    /// # Errors
    ///
    /// As [`Urdf::read`].
    pub fn read_with(path: impl AsRef<Path>, policy: &FilePolicy) -> Result<Self, RobotError> {
        let path = path.as_ref();
        let text = policy
            .read_to_string(path)
            .map_err(|source| RobotError::ReadFile {
                path: path.to_path_buf(),
                source: Box::new(source),
            })?;
        Self::parse(&text, path)
    }

    /// Parses URDF `text`; `path` names it in messages and is where mesh paths resolve
    /// from.
    ///
    /// # Errors
    ///
    /// [`RobotError::Xml`] for malformed XML (with the line and column);
    /// [`RobotError::Invalid`] for a root element other than `<robot>`, a missing or
    /// unparsable attribute, a zero, negative or non-finite size, radius or scale, two
    /// links or joints of one name, a joint naming a link the robot does not have, no
    /// link, or links and joints that are not one tree (more than one root, a link with
    /// two parents, a cycle).
    pub fn parse(text: &str, path: impl AsRef<Path>) -> Result<Self, RobotError> {
        let path = path.as_ref().to_path_buf();
        let document = roxmltree::Document::parse(text).map_err(|e| RobotError::Xml {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(at, _)| at + 1))
            .collect();
        let reader = Reader {
            path: &path,
            line_starts,
        };
        let root = document.root_element();
        if root.tag_name().name() != "robot" {
            return Err(reader.invalid(
                root,
                "document",
                format!(
                    "the root element is <{}>, not <robot>",
                    root.tag_name().name()
                ),
            ));
        }
        let name = root.attribute("name").unwrap_or_default().to_owned();
        let mut links: Vec<Link> = Vec::new();
        let mut joints: Vec<Joint> = Vec::new();
        for node in root.children().filter(roxmltree::Node::is_element) {
            match node.tag_name().name() {
                "link" => links.push(reader.link(node)?),
                "joint" => joints.push(reader.joint(node)?),
                _ => {}
            }
        }
        let urdf = Self {
            name,
            links,
            joints,
            path,
            text: text.to_owned(),
        };
        urdf.check_names()?;
        urdf.check_tree()?;
        Ok(urdf)
    }

    /// The link named `name`.
    #[must_use]
    pub fn link(&self, name: &str) -> Option<&Link> {
        self.links.iter().find(|l| l.name == name)
    }

    /// The root link: the one link that is no joint's child.
    ///
    /// # Errors
    ///
    /// [`RobotError::Invalid`] when there is no link, or more than one root.
    pub fn root(&self) -> Result<&str, RobotError> {
        let children: HashSet<&str> = self.joints.iter().map(|j| j.child.as_str()).collect();
        let roots: Vec<&str> = self
            .links
            .iter()
            .filter(|l| !children.contains(l.name.as_str()))
            .map(|l| l.name.as_str())
            .collect();
        match roots.as_slice() {
            [root] => Ok(root),
            _ => Err(RobotError::Invalid {
                path: self.path.clone(),
                line: 1,
                place: "robot".to_owned(),
                message: format!(
                    "a robot needs exactly one root link (one that is no joint's child); found {}",
                    if roots.is_empty() {
                        "none".to_owned()
                    } else {
                        roots.join(", ")
                    }
                ),
            }),
        }
    }

    /// The joints below each link, by the link's name, in file order.
    pub(crate) fn child_joints(&self) -> HashMap<&str, Vec<&Joint>> {
        let mut below: HashMap<&str, Vec<&Joint>> = HashMap::with_capacity(self.links.len());
        for joint in &self.joints {
            below.entry(joint.parent.as_str()).or_default().push(joint);
        }
        below
    }

    /// The folder the URDF is in (mesh paths resolve against it).
    #[must_use]
    pub fn folder(&self) -> &Path {
        self.path.parent().unwrap_or_else(|| Path::new(""))
    }
}

struct Reader<'a> {
    path: &'a Path,
    /// The byte offset where each line of the text starts: a node's line by binary
    /// search (roxmltree's `text_pos_at` scans from the start, quadratic over a file).
    line_starts: Vec<usize>,
}

impl Reader<'_> {
    /// The 1-based line of `node`'s start.
    fn line(&self, node: roxmltree::Node<'_, '_>) -> u32 {
        let at = node.range().start;
        let line = self.line_starts.partition_point(|&start| start <= at);
        u32::try_from(line).unwrap_or(u32::MAX)
    }

    fn invalid(
        &self,
        node: roxmltree::Node<'_, '_>,
        place: &str,
        message: impl Into<String>,
    ) -> RobotError {
        RobotError::Invalid {
            path: self.path.to_path_buf(),
            line: self.line(node),
            place: place.to_owned(),
            message: message.into(),
        }
    }

    fn required<'n>(
        &self,
        node: roxmltree::Node<'n, '_>,
        attribute: &str,
        place: &str,
    ) -> Result<&'n str, RobotError> {
        node.attribute(attribute).ok_or_else(|| {
            self.invalid(
                node,
                place,
                format!(
                    "<{}> has no `{attribute}` attribute",
                    node.tag_name().name()
                ),
            )
        })
    }

    /// Whitespace-separated finite numbers, exactly `N` of them.
    fn numbers<const N: usize>(
        &self,
        node: roxmltree::Node<'_, '_>,
        attribute: &str,
        text: &str,
        place: &str,
    ) -> Result<[f64; N], RobotError> {
        let values: Vec<f64> = text
            .split_whitespace()
            .map(str::parse::<f64>)
            .collect::<Result<_, _>>()
            .map_err(|_| {
                self.invalid(
                    node,
                    place,
                    format!("`{attribute}=\"{text}\"` is not {N} numbers"),
                )
            })?;
        let array: [f64; N] = values.try_into().map_err(|v: Vec<f64>| {
            self.invalid(
                node,
                place,
                format!("`{attribute}=\"{text}\"` has {} numbers, not {N}", v.len()),
            )
        })?;
        if array.iter().any(|v| !v.is_finite()) {
            return Err(self.invalid(
                node,
                place,
                format!("`{attribute}=\"{text}\"` is not finite"),
            ));
        }
        Ok(array)
    }

    fn number(
        &self,
        node: roxmltree::Node<'_, '_>,
        attribute: &str,
        place: &str,
    ) -> Result<f64, RobotError> {
        let text = self.required(node, attribute, place)?;
        Ok(self.numbers::<1>(node, attribute, text, place)?[0])
    }

    fn positive(
        &self,
        node: roxmltree::Node<'_, '_>,
        attribute: &str,
        place: &str,
    ) -> Result<f64, RobotError> {
        let value = self.number(node, attribute, place)?;
        if value > 0.0 {
            Ok(value)
        } else {
            Err(self.invalid(
                node,
                place,
                format!("`{attribute}` is {value}; it must be positive"),
            ))
        }
    }

    fn origin(&self, parent: roxmltree::Node<'_, '_>, place: &str) -> Result<Origin, RobotError> {
        let Some(node) = child(parent, "origin") else {
            return Ok(Origin::default());
        };
        let vector = |attribute: &str| -> Result<DVec3, RobotError> {
            node.attribute(attribute).map_or(Ok(DVec3::ZERO), |text| {
                Ok(DVec3::from_array(
                    self.numbers::<3>(node, attribute, text, place)?,
                ))
            })
        };
        Ok(Origin {
            xyz: vector("xyz")?,
            rpy: vector("rpy")?,
        })
    }

    fn link(&self, node: roxmltree::Node<'_, '_>) -> Result<Link, RobotError> {
        let name = self.required(node, "name", "link")?.to_owned();
        let mut collisions = Vec::new();
        let mut visuals = Vec::new();
        for element in node.children().filter(roxmltree::Node::is_element) {
            let (list, kind) = match element.tag_name().name() {
                "collision" => (&mut collisions, "collision"),
                "visual" => (&mut visuals, "visual"),
                _ => continue,
            };
            let place = format!("link \"{name}\" {kind}[{}]", list.len());
            list.push(self.element(element, &place)?);
        }
        let inertial = match child(node, "inertial") {
            Some(inertial) => Some(self.inertial(inertial, &format!("link \"{name}\" inertial"))?),
            None => None,
        };
        Ok(Link {
            name,
            inertial,
            collisions,
            visuals,
            line: self.line(node),
            range: node.range(),
        })
    }

    fn inertial(&self, node: roxmltree::Node<'_, '_>, place: &str) -> Result<Inertial, RobotError> {
        let origin = self.origin(node, place)?;
        let mass_node =
            child(node, "mass").ok_or_else(|| self.invalid(node, place, "it has no <mass>"))?;
        // Zero occurs in real files (the KUKA iiwa's base, fixed to the world).
        let mass = self.number(mass_node, "value", place)?;
        if mass < 0.0 {
            return Err(self.invalid(mass_node, place, format!("the mass {mass} is negative")));
        }
        let inertia_node = child(node, "inertia")
            .ok_or_else(|| self.invalid(node, place, "it has no <inertia>"))?;
        let mut inertia = [0.0; 6];
        for (value, name) in inertia
            .iter_mut()
            .zip(["ixx", "ixy", "ixz", "iyy", "iyz", "izz"])
        {
            *value = self.number(inertia_node, name, place)?;
        }
        Ok(Inertial {
            origin,
            mass,
            inertia,
        })
    }

    fn element(&self, node: roxmltree::Node<'_, '_>, place: &str) -> Result<Element, RobotError> {
        let origin = self.origin(node, place)?;
        let geometry_node = child(node, "geometry")
            .ok_or_else(|| self.invalid(node, place, "it has no <geometry>"))?;
        let shape = geometry_node
            .children()
            .find(roxmltree::Node::is_element)
            .ok_or_else(|| self.invalid(geometry_node, place, "its <geometry> is empty"))?;
        let place = format!("{place} {}", shape.tag_name().name());
        let geometry = match shape.tag_name().name() {
            "box" => {
                let text = self.required(shape, "size", &place)?;
                let size = DVec3::from_array(self.numbers::<3>(shape, "size", text, &place)?);
                if size.min_element() <= 0.0 {
                    return Err(self.invalid(
                        shape,
                        &place,
                        format!("`size=\"{text}\"`: every side must be positive"),
                    ));
                }
                Geometry::Box { size }
            }
            "cylinder" => Geometry::Cylinder {
                radius: self.positive(shape, "radius", &place)?,
                length: self.positive(shape, "length", &place)?,
            },
            "capsule" => {
                let radius = self.positive(shape, "radius", &place)?;
                // A length of 0 is a sphere; a negative one is a mistake.
                let length = self.number(shape, "length", &place)?;
                if length < 0.0 {
                    return Err(self.invalid(
                        shape,
                        &place,
                        format!("`length=\"{length}\"` must not be negative"),
                    ));
                }
                Geometry::Capsule { radius, length }
            }
            "sphere" => Geometry::Sphere {
                radius: self.positive(shape, "radius", &place)?,
            },
            "mesh" => {
                let filename = self.required(shape, "filename", &place)?.to_owned();
                let scale = match shape.attribute("scale") {
                    None => DVec3::ONE,
                    Some(text) => {
                        let scale =
                            DVec3::from_array(self.numbers::<3>(shape, "scale", text, &place)?);
                        if scale.x * scale.y * scale.z == 0.0 {
                            return Err(self.invalid(
                                shape,
                                &place,
                                format!(
                                    "`scale=\"{text}\"` flattens the mesh of `{filename}` (a scale of zero)"
                                ),
                            ));
                        }
                        scale
                    }
                };
                Geometry::Mesh { filename, scale }
            }
            other => {
                return Err(self.invalid(
                    shape,
                    &place,
                    format!(
                        "unknown geometry <{other}> (expected box, cylinder, sphere, capsule or mesh)"
                    ),
                ));
            }
        };
        Ok(Element {
            name: node.attribute("name").map(str::to_owned),
            origin,
            geometry,
            line: self.line(node),
            range: node.range(),
        })
    }

    fn joint(&self, node: roxmltree::Node<'_, '_>) -> Result<Joint, RobotError> {
        let name = self.required(node, "name", "joint")?.to_owned();
        let place = format!("joint \"{name}\"");
        let kind = match self.required(node, "type", &place)? {
            "revolute" => JointKind::Revolute,
            "continuous" => JointKind::Continuous,
            "prismatic" => JointKind::Prismatic,
            "fixed" => JointKind::Fixed,
            "floating" => JointKind::Floating,
            "planar" => JointKind::Planar,
            other => {
                return Err(self.invalid(node, &place, format!("unknown joint type `{other}`")));
            }
        };
        let link_of = |tag: &str| -> Result<String, RobotError> {
            let element = child(node, tag)
                .ok_or_else(|| self.invalid(node, &place, format!("it has no <{tag}>")))?;
            Ok(self.required(element, "link", &place)?.to_owned())
        };
        let axis = match child(node, "axis").and_then(|a| a.attribute("xyz").map(|t| (a, t))) {
            None => DVec3::X,
            Some((a, text)) => {
                let axis = DVec3::from_array(self.numbers::<3>(a, "xyz", text, &place)?);
                match axis.try_normalize() {
                    Some(axis) => axis,
                    // A fixed joint's axis means nothing (exporters write `0 0 0`).
                    None if matches!(
                        kind,
                        JointKind::Fixed | JointKind::Floating | JointKind::Planar
                    ) =>
                    {
                        DVec3::X
                    }
                    None => {
                        return Err(self.invalid(
                            a,
                            &place,
                            format!("axis `{text}` has no direction"),
                        ));
                    }
                }
            }
        };
        let limits = match child(node, "limit") {
            Some(limit) if matches!(kind, JointKind::Revolute | JointKind::Prismatic) => {
                let read = |attribute: &str| {
                    limit.attribute(attribute).map_or(Ok(0.0), |text| {
                        Ok::<f64, RobotError>(self.numbers::<1>(limit, attribute, text, &place)?[0])
                    })
                };
                Some((read("lower")?, read("upper")?))
            }
            _ => None,
        };
        let mimic = match child(node, "mimic") {
            None => None,
            Some(m) => {
                let optional = |attribute: &str, default: f64| {
                    m.attribute(attribute).map_or(Ok(default), |text| {
                        Ok::<f64, RobotError>(self.numbers::<1>(m, attribute, text, &place)?[0])
                    })
                };
                Some(Mimic {
                    joint: self.required(m, "joint", &place)?.to_owned(),
                    multiplier: optional("multiplier", 1.0)?,
                    offset: optional("offset", 0.0)?,
                })
            }
        };
        Ok(Joint {
            kind,
            parent: link_of("parent")?,
            child: link_of("child")?,
            origin: self.origin(node, &place)?,
            axis,
            limits,
            mimic,
            line: self.line(node),
            name,
        })
    }
}

fn child<'a, 'input>(
    node: roxmltree::Node<'a, 'input>,
    tag: &str,
) -> Option<roxmltree::Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == tag)
}
