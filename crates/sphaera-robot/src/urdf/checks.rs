//! The checks of a parsed URDF: unique names, joints naming links, mimics naming joints
//! without cycles, links and joints forming one tree. Linear in links and joints.

use std::collections::{HashMap, HashSet};

use super::{Joint, Urdf};
use crate::RobotError;

impl Urdf {
    /// Refuses a robot whose links and joints are not one tree: no link, more than one
    /// root, a link with two parents, or links cut off from the root by a cycle.
    pub(super) fn check_tree(&self) -> Result<(), RobotError> {
        if self.links.is_empty() {
            return Err(RobotError::Invalid {
                path: self.path.clone(),
                line: 1,
                place: "robot".to_owned(),
                message: "the robot has no <link>".to_owned(),
            });
        }
        let root = self.root()?;
        let below = self.child_joints();
        let mut reached = HashSet::from([root]);
        let mut frontier = vec![root];
        while let Some(parent) = frontier.pop() {
            for joint in below.get(parent).into_iter().flatten() {
                if !reached.insert(joint.child.as_str()) {
                    return Err(self.reached_twice(joint));
                }
                frontier.push(joint.child.as_str());
            }
        }
        if let Some(link) = self
            .links
            .iter()
            .find(|l| !reached.contains(l.name.as_str()))
        {
            return Err(RobotError::Invalid {
                path: self.path.clone(),
                line: link.line,
                place: format!("link \"{}\"", link.name),
                message: format!(
                    "it is not connected to the root link \"{root}\": the joints above it form a cycle"
                ),
            });
        }
        Ok(())
    }

    /// The error for a link reached a second time, through `joint`, walking down from
    /// the root.
    pub(crate) fn reached_twice(&self, joint: &Joint) -> RobotError {
        RobotError::Invalid {
            path: self.path.clone(),
            line: joint.line,
            place: format!("joint \"{}\"", joint.name),
            message: format!(
                "link \"{}\" is reached twice: it has two parents, or the joints form a cycle",
                joint.child
            ),
        }
    }

    /// Refuses two links or two joints of one name, a joint naming a link the robot does
    /// not have, and a mimic naming no joint or a chain of mimics that comes back to
    /// itself. Linear in links and joints.
    pub(super) fn check_names(&self) -> Result<(), RobotError> {
        let invalid = |line: u32, place: String, message: String| RobotError::Invalid {
            path: self.path.clone(),
            line,
            place,
            message,
        };
        let mut links = HashSet::with_capacity(self.links.len());
        for link in &self.links {
            if !links.insert(link.name.as_str()) {
                return Err(invalid(
                    link.line,
                    format!("link \"{}\"", link.name),
                    "a second link of this name".to_owned(),
                ));
            }
        }
        let mut joints = HashMap::with_capacity(self.joints.len());
        for joint in &self.joints {
            let place = format!("joint \"{}\"", joint.name);
            if joints.insert(joint.name.as_str(), joint).is_some() {
                return Err(invalid(
                    joint.line,
                    place,
                    "a second joint of this name".to_owned(),
                ));
            }
            for (role, link) in [("parent", &joint.parent), ("child", &joint.child)] {
                if !links.contains(link.as_str()) {
                    return Err(invalid(
                        joint.line,
                        place,
                        format!("its {role} link \"{link}\" is not a link of the robot"),
                    ));
                }
            }
        }
        for joint in &self.joints {
            if let Some(mimic) = &joint.mimic
                && !joints.contains_key(mimic.joint.as_str())
            {
                return Err(invalid(
                    joint.line,
                    format!("joint \"{}\"", joint.name),
                    format!("it mimics \"{}\", which is not a joint", mimic.joint),
                ));
            }
        }
        // Mimic chains (a mimics b mimics c) are followed to the joint that drives them;
        // one that comes back to a joint of its own has no driver.
        let mut state: HashMap<&str, bool> = HashMap::new(); // false: on the path, true: done
        for start in &self.joints {
            let mut path = Vec::new();
            let mut at = start;
            while let Some(mimic) = &at.mimic {
                match state.get(at.name.as_str()) {
                    Some(true) => break,
                    Some(false) => {
                        return Err(invalid(
                            at.line,
                            format!("joint \"{}\"", at.name),
                            "its mimics form a cycle: no joint drives them".to_owned(),
                        ));
                    }
                    None => {}
                }
                state.insert(at.name.as_str(), false);
                path.push(at.name.as_str());
                // Every mimic names a joint: checked just above.
                at = joints[mimic.joint.as_str()];
            }
            for name in path {
                state.insert(name, true);
            }
        }
        Ok(())
    }
}
