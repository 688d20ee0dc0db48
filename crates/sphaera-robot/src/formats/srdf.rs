//! MoveIt's SRDF: the links' sphere approximations and the pairs left out of
//! self-collision checks.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, Event};

use super::{number, triple, xml_error};
use crate::RobotError;
use crate::self_collision::SelfCollisionMatrix;
use crate::spherize::RobotSpheres;

/// MoveIt's SRDF: one `<link_sphere_approximation link="…">` per link with `<sphere
/// center="x y z" radius="r"/>` children in the link's frame, then one
/// `<disable_collisions link1="…" link2="…" reason="…"/>` per pair `matrix` leaves out,
/// with MoveIt's reasons (`Adjacent`, `Default`, `Always`, `Never`). Groups, end effectors
/// and virtual joints are left to MoveIt's setup assistant.
///
/// # Examples
///
/// ```
/// use sphaera_robot::{
///     MeshResolver, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf, spherize, srdf,
/// };
///
/// let urdf = Urdf::parse(r#"
///   <robot name="arm">
///     <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
///     <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><capsule radius="0.04" length="0.3"/></geometry></collision></link>
///     <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
///       <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/><limit lower="-1" upper="1"/></joint>
///   </robot>"#, "arm.urdf")?;
/// let options = SpherizeOptions::default()
///     .with_budget(SphereBudget::PerLink(3))
///     .with_self_collision(SelfCollisionOptions::default().with_samples(100));
/// let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options)?;
/// let text = srdf(&robot, robot.self_collision.as_ref().unwrap())?;
/// assert!(text.contains(r#"<disable_collisions link1="base" link2="upper" reason="Adjacent"/>"#));
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
///
/// # Errors
///
/// Never in practice ([`RobotError::Write`] if the XML writer fails).
pub fn srdf(robot: &RobotSpheres, matrix: &SelfCollisionMatrix) -> Result<String, RobotError> {
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
            for pair in matrix.disabled() {
                let reason = pair.reason.map_or("", |r| r.name());
                w.create_element("disable_collisions")
                    .with_attribute(("link1", pair.first.as_str()))
                    .with_attribute(("link2", pair.second.as_str()))
                    .with_attribute(("reason", reason))
                    .write_empty()?;
            }
            Ok(())
        })
        .map_err(|e| xml_error(&e))?;
    String::from_utf8(writer.into_inner()).map_err(|e| RobotError::Write {
        path: "<memory>".into(),
        message: e.to_string(),
    })
}
