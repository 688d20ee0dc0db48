//! The joint space of a robot and a forward kinematics over link indices: what the
//! self-collision sampling, the planner files (cuRobo's `cspace`, MJCF's joints) and the
//! robot viewer need, without a map of names per configuration.

use std::collections::HashMap;
use std::f64::consts::PI;

use glam::{DAffine3, DQuat, DVec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::RobotError;
use crate::urdf::{Joint, JointKind, Urdf};

/// A joint a configuration gives a value to: a revolute, continuous or prismatic joint
/// that mimics no other.
#[derive(Clone, Debug, PartialEq)]
pub struct ActiveJoint {
    /// Its name in the URDF.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// The range sampled and written to planner files: the URDF's limits; `[-π, π]` for a
    /// continuous joint or a revolute joint without limits; `[0, 0]` for a prismatic
    /// joint without limits (it cannot be sampled).
    pub lower: f64,
    /// The upper end of the range.
    pub upper: f64,
    /// Whether the URDF gives the limits (`false`: the range above was chosen here).
    pub limited: bool,
}

impl ActiveJoint {
    /// MoveIt's default value: 0 when it lies within the range, else the range's middle.
    #[must_use]
    pub fn default_value(&self) -> f64 {
        if self.lower <= 0.0 && 0.0 <= self.upper {
            0.0
        } else {
            0.5 * (self.lower + self.upper)
        }
    }
}

/// Where a moving joint's value comes from: an active joint (an index into
/// [`KinematicChain::joints`]), scaled and offset (a mimic chain collapsed to the joint that
/// drives it: `value = multiplier · q[joint] + offset`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointSource {
    /// The active joint.
    pub joint: usize,
    /// Its factor.
    pub multiplier: f64,
    /// The offset.
    pub offset: f64,
}

/// How a joint of the tree moves its child.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointMotion {
    /// Not at all (fixed, floating and planar joints, and mimics of joints that do not move).
    Fixed,
    /// A rotation about the axis by the source's value (radians).
    Rotate(JointSource),
    /// A translation along the axis by the source's value.
    Slide(JointSource),
}

/// One joint of the tree, parent before child: `pose[child] = pose[parent] · origin ·
/// motion(value)`.
#[derive(Clone, Debug, PartialEq)]
pub struct JointStep {
    /// The parent link (an index into [`KinematicChain::links`]).
    pub parent: usize,
    /// The child link.
    pub child: usize,
    /// The child's frame at zero motion, in the parent's.
    pub origin: DAffine3,
    /// The unit axis of motion, in the child's frame.
    pub axis: DVec3,
    /// How it moves.
    pub motion: JointMotion,
}

/// A robot's kinematic tree, compiled: links by index (the root first, every link after
/// its parent), the active joints ([`ActiveJoint`]), and link poses for a configuration
/// in one pass.
///
/// Floating and planar joints stay at their origin (as in [`Urdf::link_poses`], which
/// this equals).
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_robot::{KinematicChain, Urdf};
///
/// let urdf = Urdf::parse(r#"
///   <robot name="arm">
///     <link name="base"/><link name="tool"/>
///     <joint name="j1" type="revolute">
///       <parent link="base"/><child link="tool"/>
///       <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="-1" upper="2"/>
///     </joint>
///   </robot>"#, "arm.urdf")?;
/// let chain = KinematicChain::new(&urdf)?;
/// assert_eq!(chain.links(), ["base", "tool"]);
/// assert_eq!((chain.joints()[0].lower, chain.joints()[0].upper), (-1.0, 2.0));
/// let poses = chain.poses(&[std::f64::consts::FRAC_PI_2])?;
/// let tip = poses[chain.link_index("tool").unwrap()].transform_point3(DVec3::X);
/// assert!((tip - DVec3::new(0.0, 1.0, 0.2)).length() < 1e-12);
/// // Configuration 3 of seed 7, the same on every machine and thread count.
/// let q = chain.sample(7, 3);
/// assert!(q[0] >= -1.0 && q[0] <= 2.0);
/// assert_eq!(q, chain.sample(7, 3));
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct KinematicChain {
    links: Vec<String>,
    index: HashMap<String, usize>,
    parents: Vec<Option<usize>>,
    steps: Vec<JointStep>,
    active: Vec<ActiveJoint>,
}

impl KinematicChain {
    /// Compiles `urdf`'s tree.
    ///
    /// # Errors
    ///
    /// As [`Urdf::link_poses`]: a robot without exactly one root, a link reached twice, a
    /// mimic naming no joint or a cycle of mimics.
    pub fn new(urdf: &Urdf) -> Result<Self, RobotError> {
        let joints: HashMap<&str, &Joint> =
            urdf.joints.iter().map(|j| (j.name.as_str(), j)).collect();
        let root = urdf.root()?;
        let below = urdf.child_joints();
        let mut links = vec![root.to_owned()];
        let mut index = HashMap::from([(root.to_owned(), 0)]);
        let mut order: Vec<&Joint> = Vec::with_capacity(urdf.joints.len());
        let mut frontier = vec![root];
        while let Some(parent) = frontier.pop() {
            for &joint in below.get(parent).into_iter().flatten() {
                if index.insert(joint.child.clone(), links.len()).is_some() {
                    return Err(urdf.reached_twice(joint));
                }
                links.push(joint.child.clone());
                order.push(joint);
                frontier.push(joint.child.as_str());
            }
        }
        let moves = |j: &Joint| {
            matches!(
                j.kind,
                JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic
            )
        };
        // Active joints in file order, the order users and planner files list them in.
        let active: Vec<ActiveJoint> = urdf
            .joints
            .iter()
            .filter(|j| moves(j) && j.mimic.is_none() && index.contains_key(&j.child))
            .map(active_joint)
            .collect();
        let active_index: HashMap<&str, usize> = active
            .iter()
            .enumerate()
            .map(|(k, j)| (j.name.as_str(), k))
            .collect();
        let mut steps = Vec::with_capacity(order.len());
        for joint in order {
            let motion = if moves(joint) {
                let source = source(joint, &joints, &active_index)?;
                match (joint.kind, source) {
                    (_, None) => JointMotion::Fixed,
                    (JointKind::Prismatic, Some(s)) => JointMotion::Slide(s),
                    (_, Some(s)) => JointMotion::Rotate(s),
                }
            } else {
                JointMotion::Fixed
            };
            // Both ends are indexed: `order` holds only joints reached from the root, whose
            // parent was indexed before the joint was pushed and whose child when it was.
            steps.push(JointStep {
                parent: index[&joint.parent],
                child: index[&joint.child],
                origin: joint.origin.affine(),
                axis: joint.axis,
                motion,
            });
        }
        let mut parents = vec![None; links.len()];
        for step in &steps {
            parents[step.child] = Some(step.parent);
        }
        Ok(Self {
            links,
            index,
            parents,
            steps,
            active,
        })
    }

    /// The links, the root first and every link after its parent.
    #[must_use]
    pub fn links(&self) -> &[String] {
        &self.links
    }

    /// The index of the link named `name` in [`KinematicChain::links`].
    #[must_use]
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.index.get(name).copied()
    }

    /// The parent of link `link` (an index), `None` for the root.
    #[must_use]
    pub fn parent(&self, link: usize) -> Option<usize> {
        self.parents.get(link).copied().flatten()
    }

    /// The joints of the tree, parent before child (what [`KinematicChain::poses`] walks).
    #[must_use]
    pub fn steps(&self) -> &[JointStep] {
        &self.steps
    }

    /// The joints a configuration gives values to, in URDF order.
    #[must_use]
    pub fn joints(&self) -> &[ActiveJoint] {
        &self.active
    }

    /// MoveIt's default configuration: every joint at [`ActiveJoint::default_value`].
    #[must_use]
    pub fn default_configuration(&self) -> Vec<f64> {
        self.active.iter().map(ActiveJoint::default_value).collect()
    }

    /// Configuration `index` of the random sequence `seed`: every joint uniform in its range.
    /// Each configuration has its own ChaCha8 stream, so a configuration does not depend on
    /// which others were drawn, or on which thread.
    #[must_use]
    pub fn sample(&self, seed: u64, index: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(index);
        self.active
            .iter()
            .map(|j| j.lower + (j.upper - j.lower) * rng.random::<f64>())
            .collect()
    }

    /// The pose of every link's frame in the root's frame (by index, as
    /// [`KinematicChain::links`]), for the active joints' values `q`.
    ///
    /// # Errors
    ///
    /// [`RobotError::Joint`] when `q` does not hold one value per active joint, or holds
    /// one that is not finite.
    pub fn poses(&self, q: &[f64]) -> Result<Vec<DAffine3>, RobotError> {
        let mut poses = Vec::new();
        self.poses_into(q, &mut poses)?;
        Ok(poses)
    }

    /// [`KinematicChain::poses`] into `poses` (cleared first), for loops that pose many
    /// configurations without allocating.
    ///
    /// # Errors
    ///
    /// As [`KinematicChain::poses`].
    pub fn poses_into(&self, q: &[f64], poses: &mut Vec<DAffine3>) -> Result<(), RobotError> {
        if q.len() != self.active.len() {
            return Err(RobotError::Joint {
                joint: "(configuration)".to_owned(),
                message: format!(
                    "{} values given for {} active joints",
                    q.len(),
                    self.active.len()
                ),
            });
        }
        if let Some((k, v)) = q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(RobotError::Joint {
                joint: self.active[k].name.clone(),
                message: format!("its value {v} is not finite"),
            });
        }
        poses.clear();
        poses.resize(self.links.len(), DAffine3::IDENTITY);
        for step in &self.steps {
            let value = |s: &JointSource| s.multiplier * q[s.joint] + s.offset;
            let motion = match &step.motion {
                JointMotion::Fixed => DAffine3::IDENTITY,
                JointMotion::Rotate(s) => {
                    DAffine3::from_quat(DQuat::from_axis_angle(step.axis, value(s)))
                }
                JointMotion::Slide(s) => DAffine3::from_translation(step.axis * value(s)),
            };
            poses[step.child] = poses[step.parent] * step.origin * motion;
        }
        Ok(())
    }
}

fn active_joint(joint: &Joint) -> ActiveJoint {
    let (lower, upper, limited) = match (joint.kind, joint.limits) {
        (JointKind::Continuous, _) => (-PI, PI, false),
        (_, Some((lo, hi))) if lo <= hi => (lo, hi, true),
        (JointKind::Prismatic, _) => (0.0, 0.0, false),
        _ => (-PI, PI, false),
    };
    ActiveJoint {
        name: joint.name.clone(),
        kind: joint.kind,
        lower,
        upper,
        limited,
    }
}

/// The active joint that drives `joint` and the linear map from its value, following a
/// chain of mimics (`a` mimics `b` mimics `c`: `a = m_a (m_b c + o_b) + o_a`); `None` when
/// the chain ends at a joint that does not move.
fn source(
    joint: &Joint,
    joints: &HashMap<&str, &Joint>,
    active: &HashMap<&str, usize>,
) -> Result<Option<JointSource>, RobotError> {
    let (mut multiplier, mut offset) = (1.0, 0.0);
    let mut at = joint;
    for _ in 0..=joints.len() {
        let Some(mimic) = &at.mimic else {
            return Ok(active.get(at.name.as_str()).map(|&k| JointSource {
                joint: k,
                multiplier,
                offset,
            }));
        };
        // value(at) = m · value(next) + o, and value(joint) = multiplier · value(at) + offset.
        offset += multiplier * mimic.offset;
        multiplier *= mimic.multiplier;
        at = joints
            .get(mimic.joint.as_str())
            .ok_or_else(|| RobotError::Joint {
                joint: at.name.clone(),
                message: format!("it mimics \"{}\", which is not a joint", mimic.joint),
            })?;
    }
    Err(RobotError::Joint {
        joint: joint.name.clone(),
        message: "its mimics form a cycle: no joint drives them".to_owned(),
    })
}
