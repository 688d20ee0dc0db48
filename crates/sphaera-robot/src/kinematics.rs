//! Forward kinematics: where every link's frame is for given joint values.

use std::collections::BTreeMap;

use glam::{DAffine3, DQuat};

use crate::RobotError;
use crate::urdf::{JointKind, Urdf};

impl Urdf {
    /// The pose of every link's frame in the root link's frame, for the joint values in
    /// `positions` (radians or metres, by joint name; a joint not named is at 0, a mimic
    /// joint follows the joint it copies). Floating and planar joints stay at their
    /// origin.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::collections::BTreeMap;
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
        for (name, value) in positions {
            if !self.joints.iter().any(|j| &j.name == name) {
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
        let value = |name: &str| -> f64 {
            let joint = self.joints.iter().find(|j| j.name == name);
            match joint.and_then(|j| j.mimic.as_ref()) {
                Some(m) => {
                    m.multiplier * positions.get(&m.joint).copied().unwrap_or(0.0) + m.offset
                }
                None => positions.get(name).copied().unwrap_or(0.0),
            }
        };
        let root = self.root()?;
        let mut poses = BTreeMap::from([(root.to_owned(), DAffine3::IDENTITY)]);
        let mut frontier = vec![root.to_owned()];
        while let Some(parent) = frontier.pop() {
            let parent_pose = poses[&parent];
            for joint in self.joints.iter().filter(|j| j.parent == parent) {
                let q = value(&joint.name);
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
                frontier.push(joint.child.clone());
            }
        }
        Ok(poses)
    }
}
