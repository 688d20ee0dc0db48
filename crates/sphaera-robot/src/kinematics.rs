//! Forward kinematics: where every link's frame is for given joint values.

use std::collections::{BTreeMap, HashMap};

use glam::DAffine3;

use crate::RobotError;
use crate::chain::KinematicChain;
use crate::urdf::{Joint, Urdf};

impl Urdf {
    /// The pose of every link's frame in the root link's frame, for the joint values in
    /// `positions` (radians or metres, by joint name; a joint not named is at 0, a mimic
    /// joint follows the joint it copies, through a chain of mimics to the joint that drives
    /// it). Floating and planar joints stay at their origin. Linear in links and joints:
    /// a [`KinematicChain`] compiled and posed once (compile it yourself to pose many
    /// configurations).
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
        let chain = KinematicChain::new(self)?;
        let q: Vec<f64> = chain
            .joints()
            .iter()
            .map(|j| positions.get(&j.name).copied().unwrap_or(0.0))
            .collect();
        let poses = chain.poses(&q)?;
        Ok(chain.links().iter().cloned().zip(poses).collect())
    }
}
