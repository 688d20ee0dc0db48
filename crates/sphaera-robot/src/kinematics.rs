//! Forward kinematics: where every link's frame is for given joint values.

use std::collections::{BTreeMap, HashMap};

use glam::{DAffine3, DQuat};

use crate::RobotError;
use crate::urdf::{Joint, JointKind, Urdf};

impl Urdf {
    /// The pose of every link's frame in the root link's frame, for the joint values in
    /// `positions` (radians or metres, by joint name; a joint not named is at 0, a mimic
    /// joint follows the joint it copies, through a chain of mimics to the joint that drives
    /// it). Floating and planar joints stay at their origin. Linear in links and joints.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::collections::{BTreeMap, HashMap};
    /// use glam::DVec3;
    /// use sphaera_robot::Urdf;
    ///
    /// let urdf = Urdf::parse(r#"
    ///   <robot name="arm">
    ///     <link name="base"/><link name="tool"/>
    ///     <joint name="j1" type="revolute">
    ///       <parent link="base"/><child link="tool"/>
    ///       <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>
    ///     </joint>
    ///   </robot>"#, "arm.urdf")?;
    /// let poses = urdf.link_poses(&BTreeMap::from([("j1".to_owned(), std::f64::consts::FRAC_PI_2)]))?;
    /// let tip = poses["tool"].transform_point3(DVec3::X);
    /// assert!((tip - DVec3::new(0.0, 1.0, 0.2)).length() < 1e-12);
    /// # Ok::<(), sphaera_robot::RobotError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`RobotError::Joint`] for a name that is no joint or a value that is not finite;
    /// [`RobotError::Invalid`] for a robot without exactly one root, or with a cycle.
    pub fn link_poses(
        &self,
        positions: &BTreeMap<String, f64>,
    ) -> Result<BTreeMap<String, DAffine3>, RobotError> {
        let joints: HashMap<&str, &Joint> =
            self.joints.iter().map(|j| (j.name.as_str(), j)).collect();
        for (name, value) in positions {
            if !joints.contains_key(name.as_str()) {
                return Err(RobotError::Joint {
                    joint: name.clone(),
                    message: "the robot has no joint of this name".to_owned(),
                });
            }
            if !value.is_finite() {
                return Err(RobotError::Joint {
                    joint: name.clone(),
                    message: format!("its value {value} is not finite"),
                });
            }
        }
        let values = joint_values(&joints, positions)?;
        let root = self.root()?;
        let below = self.child_joints();
        let mut poses = BTreeMap::from([(root.to_owned(), DAffine3::IDENTITY)]);
        let mut frontier = vec![(root, DAffine3::IDENTITY)];
        while let Some((parent, parent_pose)) = frontier.pop() {
            for &joint in below.get(parent).into_iter().flatten() {
                let q = values.get(joint.name.as_str()).copied().unwrap_or(0.0);
                let motion = match joint.kind {
                    JointKind::Revolute | JointKind::Continuous => {
                        DAffine3::from_quat(DQuat::from_axis_angle(joint.axis, q))
                    }
                    JointKind::Prismatic => DAffine3::from_translation(joint.axis * q),
                    JointKind::Fixed | JointKind::Floating | JointKind::Planar => {
                        DAffine3::IDENTITY
                    }
                };
                let pose = parent_pose * joint.origin.affine() * motion;
                if poses.insert(joint.child.clone(), pose).is_some() {
                    return Err(self.reached_twice(joint));
                }
                frontier.push((joint.child.as_str(), pose));
            }
        }
        Ok(poses)
    }
}

/// Every joint's value: as given (0 when not), a mimic joint's from the joint that drives
/// its chain (`a` mimics `b` mimics `c`: `a = m_a (m_b c + o_b) + o_a`). Linear in the
/// joints: each chain is walked once, its values kept.
fn joint_values<'a>(
    joints: &HashMap<&'a str, &'a Joint>,
    positions: &BTreeMap<String, f64>,
) -> Result<HashMap<&'a str, f64>, RobotError> {
    let mut values: HashMap<&'a str, f64> = HashMap::with_capacity(joints.len());
    for (&name, &joint) in joints {
        let mut chain = Vec::new();
        let mut at = joint;
        let base = loop {
            if let Some(&known) = values.get(at.name.as_str()) {
                break known;
            }
            let Some(mimic) = &at.mimic else {
                break positions.get(&at.name).copied().unwrap_or(0.0);
            };
            if chain.len() > joints.len() {
                return Err(RobotError::Joint {
                    joint: name.to_owned(),
                    message: "its mimics form a cycle: no joint drives them".to_owned(),
                });
            }
            chain.push(at);
            at = joints
                .get(mimic.joint.as_str())
                .ok_or_else(|| RobotError::Joint {
                    joint: at.name.clone(),
                    message: format!("it mimics \"{}\", which is not a joint", mimic.joint),
                })?;
        };
        if at.mimic.is_none() {
            values.insert(at.name.as_str(), base);
        }
        let mut value = base;
        for link in chain.iter().rev() {
            if let Some(mimic) = &link.mimic {
                value = mimic.multiplier * value + mimic.offset;
            }
            values.insert(link.name.as_str(), value);
        }
    }
    Ok(values)
}
