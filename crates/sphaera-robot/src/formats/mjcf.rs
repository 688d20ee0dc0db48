//! MuJoCo's MJCF: the robot as a body tree with its joints, the link spheres as geoms,
//! and the self-collision matrix as contact exclusions.

use std::collections::HashMap;

use glam::{DAffine3, DMat3, DQuat, DVec3};
use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};

use super::{number, triple, xml_error};
use crate::RobotError;
use crate::geometry::{GeometrySource, MeshResolver};
use crate::self_collision::SelfCollisionMatrix;
use crate::spherize::RobotSpheres;
use crate::urdf::{Geometry, Joint, JointKind, Urdf};

/// What the MJCF holds beyond the spheres.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct MjcfOptions {
    /// Also the links' meshes as visual geoms (no contacts, group 1), from this geometry
    /// and resolved by this resolver; only the formats MuJoCo reads (STL, OBJ) are
    /// written, the others are skipped. `None` (the default): spheres only.
    pub meshes: Option<(GeometrySource, MeshResolver)>,
}

impl MjcfOptions {
    /// With the links' meshes of `source`, resolved by `resolver`, as visual geoms.
    #[must_use]
    pub fn with_meshes(mut self, source: GeometrySource, resolver: MeshResolver) -> Self {
        self.meshes = Some((source, resolver));
        self
    }
}

fn quat(q: DQuat) -> String {
    format!(
        "{} {} {} {}",
        number(q.w),
        number(q.x),
        number(q.y),
        number(q.z)
    )
}

fn rotation(pose: &DAffine3) -> DQuat {
    DQuat::from_mat3(&pose.matrix3).normalize()
}

/// One `<mesh>` asset and where its geom sits in the link's frame.
struct MeshGeom {
    name: String,
    file: String,
    scale: DVec3,
    pose: DAffine3,
}

/// The meshes of every link, by link name (only STL and OBJ files).
fn mesh_geoms(
    urdf: &Urdf,
    options: &MjcfOptions,
) -> Result<HashMap<String, Vec<MeshGeom>>, RobotError> {
    let mut by_link: HashMap<String, Vec<MeshGeom>> = HashMap::new();
    let Some((source, resolver)) = &options.meshes else {
        return Ok(by_link);
    };
    for link in &urdf.links {
        for (k, element) in source.elements(link).iter().enumerate() {
            let Geometry::Mesh { filename, scale } = &element.geometry else {
                continue;
            };
            let path = resolver.resolve(&link.name, filename)?;
            let readable = path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("stl") || e.eq_ignore_ascii_case("obj"));
            if !readable {
                continue;
            }
            by_link
                .entry(link.name.clone())
                .or_default()
                .push(MeshGeom {
                    name: format!("{}/mesh{k}", link.name),
                    // MuJoCo resolves relative names against the model's folder, which may
                    // not be the URDF's: absolute names work wherever the MJCF is written.
                    file: std::path::absolute(&path)
                        .unwrap_or(path)
                        .display()
                        .to_string(),
                    scale: *scale,
                    pose: element.origin.affine(),
                });
        }
    }
    Ok(by_link)
}

/// MuJoCo's MJCF of the robot: `<worldbody>` holds the URDF's root link as a body fixed to
/// the world (a root without geometry or mass is the world itself: its children are the
/// top-level bodies), and every joint becomes a child `<body>` at the joint's origin with a
/// `hinge` (revolute, continuous) or `slide` (prismatic) `<joint>` on the URDF's axis and
/// limits (`limited="false"` for a continuous joint); a fixed joint a body without a joint.
/// A floating joint out of a root link without geometry makes its child a free body
/// (`<freejoint/>`); any other floating or planar joint is written as fixed (as
/// [`Urdf::link_poses`] takes them). A mimic joint is tied to the joint it copies by an
/// `<equality><joint polycoef="offset multiplier 0 0 0"/>`. Each link's spheres are
/// `sphere` geoms in its body; its `<inertial>` is the URDF's (the compiler bounds masses
/// and inertias from below, so a massless link still loads). The pairs `matrix` leaves
/// out are `<contact><exclude>` pairs. Angles in radians.
///
/// # Examples
///
/// ```
/// use sphaera_robot::{
///     MeshResolver, MjcfOptions, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf,
///     mjcf, self_collision_matrix, spherize,
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
/// let xml = mjcf(&urdf, &robot, &matrix, &MjcfOptions::default())?;
/// assert!(xml.contains(r#"<joint name="shoulder" type="hinge" axis="0 1 0" limited="true" range="-1 1"/>"#));
/// assert!(xml.contains(r#"<exclude body1="base" body2="upper"/>"#));
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
///
/// # Errors
///
/// As [`Urdf::root`] for a robot without one root; a mesh that cannot be resolved
/// ([`RobotError::MeshNotFound`]) when meshes are asked for.
pub fn mjcf(
    urdf: &Urdf,
    robot: &RobotSpheres,
    matrix: &SelfCollisionMatrix,
    options: &MjcfOptions,
) -> Result<String, RobotError> {
    let root = urdf.root()?;
    let below = urdf.child_joints();
    let meshes = mesh_geoms(urdf, options)?;
    let spheres: HashMap<&str, &crate::LinkSpheres> =
        robot.links.iter().map(|l| (l.link.as_str(), l)).collect();
    let joints: HashMap<&str, &Joint> = urdf.joints.iter().map(|j| (j.name.as_str(), j)).collect();
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    let e = |e: std::io::Error| xml_error(&e);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("utf-8"), None)))
        .map_err(e)?;
    w.write_event(Event::Start(
        BytesStart::new("mujoco").with_attributes([("model", robot.robot.as_str())]),
    ))
    .map_err(e)?;
    w.create_element("compiler")
        .with_attributes([
            ("angle", "radian"),
            ("balanceinertia", "true"),
            ("boundmass", "1e-6"),
            ("boundinertia", "1e-9"),
        ])
        .write_empty()
        .map_err(e)?;
    if !meshes.is_empty() {
        w.write_event(Event::Start(BytesStart::new("asset")))
            .map_err(e)?;
        for m in meshes.values().flatten() {
            w.create_element("mesh")
                .with_attributes([
                    ("name", m.name.as_str()),
                    ("file", m.file.as_str()),
                    ("scale", triple(m.scale).as_str()),
                ])
                .write_empty()
                .map_err(e)?;
        }
        w.write_event(Event::End(BytesEnd::new("asset")))
            .map_err(e)?;
    }
    w.write_event(Event::Start(BytesStart::new("worldbody")))
        .map_err(e)?;
    // Depth first, without recursion (a chain may be long): `None` closes a body.
    let mut stack: Vec<Option<(&str, Option<&Joint>)>> = vec![Some((root, None))];
    let root_is_bare =
        !spheres.contains_key(root) && urdf.link(root).is_some_and(|l| l.inertial.is_none());
    while let Some(entry) = stack.pop() {
        let Some((link, joint)) = entry else {
            w.write_event(Event::End(BytesEnd::new("body")))
                .map_err(e)?;
            continue;
        };
        if joint.is_none() && root_is_bare {
            // A root without geometry or mass (a "world" link) is the world itself: its
            // children are top-level bodies.
            for &child in below.get(link).into_iter().flatten().rev() {
                stack.push(Some((child.child.as_str(), Some(child))));
            }
            continue;
        }
        let free = joint
            .is_some_and(|j| j.kind == JointKind::Floating && j.parent == root && root_is_bare);
        let mut body = BytesStart::new("body").with_attributes([("name", link)]);
        if let Some(j) = joint {
            let pose = j.origin.affine();
            body.push_attribute(("pos", triple(pose.translation).as_str()));
            body.push_attribute(("quat", quat(rotation(&pose)).as_str()));
        }
        w.write_event(Event::Start(body)).map_err(e)?;
        if free {
            w.create_element("freejoint").write_empty().map_err(e)?;
        }
        if let Some(j) = joint {
            write_joint(&mut w, j)?;
        }
        if let Some(inertial) = urdf.link(link).and_then(|l| l.inertial) {
            // MJCF takes `fullinertia` or a `quat`, not both: the URDF's tensor, given in
            // the inertial frame, turned into the body's axes (R I Rᵀ).
            let pose = inertial.origin.affine();
            let [ixx, ixy, ixz, iyy, iyz, izz] = inertial.inertia;
            let tensor = DMat3::from_cols_array(&[ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz]);
            let r = pose.matrix3;
            let turned = r * tensor * r.transpose();
            let [ixx, iyy, izz] = [turned.x_axis.x, turned.y_axis.y, turned.z_axis.z].map(number);
            let [ixy, ixz, iyz] = [turned.y_axis.x, turned.z_axis.x, turned.z_axis.y].map(number);
            w.create_element("inertial")
                .with_attributes([
                    ("pos", triple(pose.translation).as_str()),
                    ("mass", number(inertial.mass).as_str()),
                    (
                        "fullinertia",
                        format!("{ixx} {iyy} {izz} {ixy} {ixz} {iyz}").as_str(),
                    ),
                ])
                .write_empty()
                .map_err(e)?;
        }
        if let Some(l) = spheres.get(link) {
            for (k, s) in l.spheres.iter().enumerate() {
                w.create_element("geom")
                    .with_attributes([
                        ("name", format!("{link}/sphere{k}").as_str()),
                        ("type", "sphere"),
                        ("size", number(s.radius).as_str()),
                        ("pos", triple(s.center).as_str()),
                        ("rgba", "0.2 0.6 0.9 0.5"),
                    ])
                    .write_empty()
                    .map_err(e)?;
            }
        }
        for m in meshes.get(link).into_iter().flatten() {
            w.create_element("geom")
                .with_attributes([
                    ("name", m.name.as_str()),
                    ("type", "mesh"),
                    ("mesh", m.name.as_str()),
                    ("pos", triple(m.pose.translation).as_str()),
                    ("quat", quat(rotation(&m.pose)).as_str()),
                    ("contype", "0"),
                    ("conaffinity", "0"),
                    ("group", "1"),
                    ("rgba", "0.8 0.8 0.8 1"),
                ])
                .write_empty()
                .map_err(e)?;
        }
        stack.push(None);
        // Children in file order: pushed in reverse.
        for &child in below.get(link).into_iter().flatten().rev() {
            stack.push(Some((child.child.as_str(), Some(child))));
        }
    }
    w.write_event(Event::End(BytesEnd::new("worldbody")))
        .map_err(e)?;
    let mimics: Vec<&Joint> = urdf
        .joints
        .iter()
        .filter(|j| j.mimic.is_some() && moves(j))
        .collect();
    if !mimics.is_empty() {
        w.write_event(Event::Start(BytesStart::new("equality")))
            .map_err(e)?;
        for j in mimics {
            let Some(m) = &j.mimic else { continue };
            if !joints.get(m.joint.as_str()).is_some_and(|d| moves(d)) {
                continue;
            }
            w.create_element("joint")
                .with_attributes([
                    ("joint1", j.name.as_str()),
                    ("joint2", m.joint.as_str()),
                    (
                        "polycoef",
                        format!("{} {} 0 0 0", number(m.offset), number(m.multiplier)).as_str(),
                    ),
                ])
                .write_empty()
                .map_err(e)?;
        }
        w.write_event(Event::End(BytesEnd::new("equality")))
            .map_err(e)?;
    }
    let mut excluded = matrix.disabled().peekable();
    if excluded.peek().is_some() {
        w.write_event(Event::Start(BytesStart::new("contact")))
            .map_err(e)?;
        for pair in excluded {
            w.create_element("exclude")
                .with_attributes([
                    ("body1", pair.first.as_str()),
                    ("body2", pair.second.as_str()),
                ])
                .write_empty()
                .map_err(e)?;
        }
        w.write_event(Event::End(BytesEnd::new("contact")))
            .map_err(e)?;
    }
    w.write_event(Event::End(BytesEnd::new("mujoco")))
        .map_err(e)?;
    let mut text = String::from_utf8(w.into_inner()).map_err(|e| RobotError::Write {
        path: "<memory>".into(),
        message: e.to_string(),
    })?;
    text.push('\n');
    Ok(text)
}

fn moves(joint: &Joint) -> bool {
    matches!(
        joint.kind,
        JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic
    )
}

/// The `<joint>` of a moving URDF joint (nothing for a fixed, floating or planar one).
fn write_joint(w: &mut Writer<Vec<u8>>, joint: &Joint) -> Result<(), RobotError> {
    let kind = match joint.kind {
        JointKind::Revolute | JointKind::Continuous => "hinge",
        JointKind::Prismatic => "slide",
        JointKind::Fixed | JointKind::Floating | JointKind::Planar => return Ok(()),
    };
    let axis = triple(joint.axis);
    let mut attributes = vec![
        ("name", joint.name.clone()),
        ("type", kind.to_owned()),
        ("axis", axis),
    ];
    match (joint.kind, joint.limits) {
        (JointKind::Continuous, _) | (_, None) => attributes.push(("limited", "false".to_owned())),
        (_, Some((lo, hi))) => {
            attributes.push(("limited", "true".to_owned()));
            attributes.push(("range", format!("{} {}", number(lo), number(hi))));
        }
    }
    w.create_element("joint")
        .with_attributes(attributes.iter().map(|(k, v)| (*k, v.as_str())))
        .write_empty()
        .map_err(|e| xml_error(&e))?;
    Ok(())
}
