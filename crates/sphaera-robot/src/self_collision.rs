//! The self-collision matrix: which pairs of links a planner need not test against each
//! other, found as MoveIt's setup assistant finds them, on the link spheres.
//!
//! Every pair of links with spheres gets one verdict, the first rule that holds, in
//! MoveIt's order:
//!
//! 1. **Adjacent**: joined by a joint (a link without spheres between them does not
//!    separate them: every pair of links it joins is adjacent);
//! 2. **Default**: in contact at the default configuration
//!    ([`KinematicChain::default_configuration`]);
//! 3. **Always**: in contact in at least [`SelfCollisionOptions::always_fraction`] of the
//!    sampled configurations;
//! 4. **Never**: in contact in none of them.
//!
//! The rest are checked by the planner. Two links are in contact when a sphere of one
//! meets a sphere of the other (closer than the sum of the radii plus
//! [`SelfCollisionOptions::padding`]). The spheres cover the links, so a pair whose
//! spheres never meet in the sampled configurations has links that never meet in them
//! either; between samples it is the same bet MoveIt makes, with the same default of
//! 10,000 configurations.

use std::collections::{BTreeMap, HashSet};
use std::time::Instant;

use glam::{DAffine3, DVec3};
#[cfg(feature = "parallel")]
use rayon::prelude::*;
use serde::Serialize;

use crate::RobotError;
use crate::chain::KinematicChain;
use crate::spherize::RobotSpheres;
use crate::urdf::Urdf;

/// Why a pair of links is left out of self-collision checks: MoveIt's SRDF reasons.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum DisableReason {
    /// Joined by a joint (through links without geometry).
    Adjacent,
    /// In contact at the default configuration.
    Default,
    /// In contact in (nearly) every sampled configuration.
    Always,
    /// In contact in no sampled configuration.
    Never,
}

impl DisableReason {
    /// Every reason, in the order the rules are applied.
    pub const ALL: [Self; 4] = [Self::Adjacent, Self::Default, Self::Always, Self::Never];

    /// The name MoveIt's SRDF writes in `reason="…"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Adjacent => "Adjacent",
            Self::Default => "Default",
            Self::Always => "Always",
            Self::Never => "Never",
        }
    }
}

impl std::fmt::Display for DisableReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The most configurations [`self_collision_matrix`] samples: ten thousand times MoveIt's
/// default, minutes for a 7-joint arm on two cores. Memory does not grow with the count.
pub const MAX_SELF_COLLISION_SAMPLES: usize = 100_000_000;

/// How the matrix is sampled.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SelfCollisionOptions {
    /// Random configurations sampled (default 10,000, MoveIt's). 0 applies the adjacent
    /// and default rules only.
    pub samples: usize,
    /// The random sequence ([`KinematicChain::sample`]); default 0.
    pub seed: u64,
    /// The share of sampled configurations in contact that makes a pair "Always"
    /// (default 0.95, MoveIt's).
    pub always_fraction: f64,
    /// A distance added to every sum of radii (default 0): pairs that come within it
    /// count as in contact, so "Never" keeps that clearance.
    pub padding: f64,
}

impl Default for SelfCollisionOptions {
    fn default() -> Self {
        Self {
            samples: 10_000,
            seed: 0,
            always_fraction: 0.95,
            padding: 0.0,
        }
    }
}

impl SelfCollisionOptions {
    /// Samples `samples` configurations.
    #[must_use]
    pub fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// Draws them from sequence `seed`.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Calls a pair "Always" when in contact in at least this share of them.
    #[must_use]
    pub fn with_always_fraction(mut self, fraction: f64) -> Self {
        self.always_fraction = fraction;
        self
    }

    /// Counts pairs closer than `padding` as in contact.
    #[must_use]
    pub fn with_padding(mut self, padding: f64) -> Self {
        self.padding = padding;
        self
    }
}

/// One pair of links with spheres, its verdict, and what the sampling saw.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LinkPair {
    /// The link first in URDF order.
    pub first: String,
    /// The other.
    pub second: String,
    /// Why the pair is left out, or `None` when the planner must check it.
    pub reason: Option<DisableReason>,
    /// In how many sampled configurations its spheres met (0 for an adjacent pair, which is
    /// not sampled).
    pub contacts: usize,
}

/// The verdict on every pair of links with spheres ([`self_collision_matrix`] says how).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SelfCollisionMatrix {
    /// Every pair of links with spheres, in URDF order.
    pub pairs: Vec<LinkPair>,
    /// Configurations sampled.
    pub samples: usize,
    /// The random sequence they came from.
    pub seed: u64,
    /// Seconds taken.
    pub seconds: f64,
}

impl SelfCollisionMatrix {
    /// The pairs left out, with their reasons.
    pub fn disabled(&self) -> impl Iterator<Item = &LinkPair> {
        self.pairs.iter().filter(|p| p.reason.is_some())
    }

    /// The pairs the planner must check.
    pub fn checked(&self) -> impl Iterator<Item = &LinkPair> {
        self.pairs.iter().filter(|p| p.reason.is_none())
    }

    /// How many pairs `reason` left out.
    #[must_use]
    pub fn count(&self, reason: DisableReason) -> usize {
        self.pairs
            .iter()
            .filter(|p| p.reason == Some(reason))
            .count()
    }

    /// Whether the pair `a`, `b` (either order) is left out.
    #[must_use]
    pub fn is_disabled(&self, a: &str, b: &str) -> bool {
        self.pairs.iter().any(|p| {
            p.reason.is_some()
                && ((p.first == a && p.second == b) || (p.first == b && p.second == a))
        })
    }

    /// cuRobo's `self_collision_ignore`: for each link, the links after it (in URDF order)
    /// it is not checked against.
    #[must_use]
    pub fn ignore_lists(&self) -> BTreeMap<String, Vec<String>> {
        let mut lists: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for pair in self.disabled() {
            lists
                .entry(pair.first.clone())
                .or_default()
                .push(pair.second.clone());
        }
        lists
    }
}

/// A link's spheres in its own frame, and where its posed copies go.
struct LinkBalls {
    /// The link's index in the chain.
    link: usize,
    centers: Vec<DVec3>,
    radii: Vec<f64>,
    bounding: (DVec3, f64),
    /// Where its posed centres start in the flat buffer.
    offset: usize,
}

/// Computes the matrix of `robot`'s spheres on `urdf`'s kinematics.
///
/// Every pair of links with spheres gets one verdict, the first rule that holds, in
/// MoveIt's order: **Adjacent** (joined by a joint; a link without spheres between them
/// does not separate them), **Default** (in contact at
/// [`KinematicChain::default_configuration`]), **Always** (in contact in at least
/// [`SelfCollisionOptions::always_fraction`] of the sampled configurations), **Never** (in
/// contact in none of them); the rest are left for the planner. Two links are in contact
/// when a sphere of one meets a sphere of the other (closer than the sum of the radii plus
/// [`SelfCollisionOptions::padding`]). The spheres cover the links, so a pair whose
/// spheres never meet in the sampled configurations has links that never meet in them
/// either; between samples it is the same bet MoveIt's setup assistant makes, with its
/// default of 10,000 configurations.
///
/// # Examples
///
/// ```
/// use sphaera_robot::{
///     DisableReason, MeshResolver, SelfCollisionOptions, SphereBudget, SpherizeOptions, Urdf,
///     self_collision_matrix, spherize,
/// };
///
/// // A base, a short upper arm on a shoulder, and a forearm on an elbow that cannot
/// // reach back to the base.
/// let urdf = Urdf::parse(r#"
///   <robot name="arm">
///     <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
///     <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><capsule radius="0.03" length="0.3"/></geometry></collision></link>
///     <link name="fore"><collision><origin xyz="0 0 0.15"/><geometry><capsule radius="0.03" length="0.2"/></geometry></collision></link>
///     <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
///       <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-0.5" upper="0.5"/></joint>
///     <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
///       <origin xyz="0 0 0.4"/><axis xyz="0 1 0"/><limit lower="-1" upper="1"/></joint>
///   </robot>"#, "arm.urdf")?;
/// let options = SpherizeOptions::default().with_budget(SphereBudget::PerLink(4));
/// let robot = spherize(&urdf, &MeshResolver::new(urdf.folder()), &options)?;
/// let matrix = self_collision_matrix(&urdf, &robot, &SelfCollisionOptions::default().with_samples(500))?;
/// assert_eq!(matrix.count(DisableReason::Adjacent), 2);
/// assert!(matrix.is_disabled("base", "fore")); // never within reach
/// assert_eq!(matrix.ignore_lists()["base"], ["upper", "fore"]);
/// # Ok::<(), sphaera_robot::RobotError>(())
/// ```
///
/// # Errors
///
/// [`RobotError::InvalidParameter`] for an `always_fraction` outside `(0, 1]`, a
/// `padding` that is negative or not finite, or more than [`MAX_SELF_COLLISION_SAMPLES`]
/// samples; as [`KinematicChain::new`] for the URDF; a
/// link of `robot` the URDF does not have ([`RobotError::UnknownLink`]).
pub fn self_collision_matrix(
    urdf: &Urdf,
    robot: &RobotSpheres,
    options: &SelfCollisionOptions,
) -> Result<SelfCollisionMatrix, RobotError> {
    let started = Instant::now();
    check_options(options)?;
    let chain = KinematicChain::new(urdf)?;
    let links = link_balls(&chain, robot)?;
    let adjacent = adjacent_pairs(&chain, &links);
    let mut pairs: Vec<LinkPair> = Vec::new();
    let mut sampled: Vec<(usize, usize)> = Vec::new();
    for i in 0..links.len() {
        for j in i + 1..links.len() {
            let is_adjacent = adjacent.contains(&(links[i].link, links[j].link));
            pairs.push(LinkPair {
                first: robot.links[i].link.clone(),
                second: robot.links[j].link.clone(),
                reason: is_adjacent.then_some(DisableReason::Adjacent),
                contacts: 0,
            });
            if !is_adjacent {
                sampled.push((i, j));
            }
        }
    }
    let pose = Posed::new(&links);
    // The default configuration.
    let at_default = pose.contacts(
        &chain,
        &links,
        &sampled,
        &chain.default_configuration(),
        options.padding,
    )?;
    // The samples: per pair, in how many the spheres met.
    let counts = count_contacts(&chain, &links, &sampled, options)?;
    let always = |c: usize| {
        options.samples > 0 && c as f64 >= options.always_fraction * options.samples as f64
    };
    let mut k = 0;
    for pair in &mut pairs {
        if pair.reason.is_some() {
            continue;
        }
        let contacts = counts[k];
        pair.contacts = contacts;
        pair.reason = if at_default[k] {
            Some(DisableReason::Default)
        } else if always(contacts) {
            Some(DisableReason::Always)
        } else if options.samples > 0 && contacts == 0 {
            Some(DisableReason::Never)
        } else {
            None
        };
        k += 1;
    }
    Ok(SelfCollisionMatrix {
        pairs,
        samples: options.samples,
        seed: options.seed,
        seconds: started.elapsed().as_secs_f64(),
    })
}

pub(crate) fn check_options(options: &SelfCollisionOptions) -> Result<(), RobotError> {
    let f = options.always_fraction;
    if !(f > 0.0 && f <= 1.0) {
        return Err(RobotError::InvalidParameter {
            name: "always_fraction",
            value: f,
            requirement: "a share in (0, 1]",
        });
    }
    if options.samples > MAX_SELF_COLLISION_SAMPLES {
        return Err(RobotError::InvalidParameter {
            name: "self-collision samples",
            value: options.samples as f64,
            requirement: "at most 100,000,000 (MAX_SELF_COLLISION_SAMPLES)",
        });
    }
    let p = options.padding;
    if !(p.is_finite() && p >= 0.0) {
        return Err(RobotError::InvalidParameter {
            name: "padding",
            value: p,
            requirement: "a finite distance, at least 0",
        });
    }
    Ok(())
}

fn link_balls(chain: &KinematicChain, robot: &RobotSpheres) -> Result<Vec<LinkBalls>, RobotError> {
    let mut offset = 0;
    robot
        .links
        .iter()
        .map(|l| {
            let link = chain
                .link_index(&l.link)
                .ok_or_else(|| RobotError::UnknownLink {
                    name: l.link.clone(),
                    without_geometry: false,
                })?;
            let balls = LinkBalls {
                link,
                centers: l.spheres.iter().map(|s| s.center).collect(),
                radii: l.spheres.iter().map(|s| s.radius).collect(),
                bounding: (l.bounding_sphere.center, l.bounding_sphere.radius),
                offset,
            };
            offset += l.spheres.len();
            Ok(balls)
        })
        .collect()
}

/// Pairs of chain link indices (smaller first) joined by a joint, through links without
/// spheres: every pair of sphered links that meet across a run of links without them.
fn adjacent_pairs(chain: &KinematicChain, links: &[LinkBalls]) -> HashSet<(usize, usize)> {
    let sphered: HashSet<usize> = links.iter().map(|l| l.link).collect();
    let n = chain.links().len();
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    for child in 0..n {
        if let Some(parent) = chain.parent(child) {
            neighbours[child].push(parent);
            neighbours[parent].push(child);
        }
    }
    let mut pairs = HashSet::new();
    let mut add = |a: usize, b: usize| {
        if a != b {
            pairs.insert((a.min(b), a.max(b)));
        }
    };
    for a in 0..n {
        if !sphered.contains(&a) {
            continue;
        }
        // Every sphered link reached from `a` through links without spheres.
        let mut seen = HashSet::from([a]);
        let mut stack: Vec<usize> = neighbours[a].clone();
        while let Some(b) = stack.pop() {
            if !seen.insert(b) {
                continue;
            }
            if sphered.contains(&b) {
                add(a, b);
            } else {
                stack.extend(neighbours[b].iter().copied());
            }
        }
    }
    // Order the pairs by the sphered links' order, as the caller looks them up.
    let order: BTreeMap<usize, usize> =
        links.iter().enumerate().map(|(k, l)| (l.link, k)).collect();
    pairs
        .into_iter()
        .map(|(a, b)| {
            // Both are sphered links (only those are added), and `order` holds every one.
            if order[&a] < order[&b] {
                (a, b)
            } else {
                (b, a)
            }
        })
        .collect()
}

/// Buffers for posing every sphere.
struct Posed {
    poses: Vec<DAffine3>,
    centers: Vec<DVec3>,
    bounding: Vec<DVec3>,
}

impl Posed {
    fn new(links: &[LinkBalls]) -> Self {
        let total = links.iter().map(|l| l.centers.len()).sum();
        Self {
            poses: Vec::new(),
            centers: Vec::with_capacity(total),
            bounding: Vec::with_capacity(links.len()),
        }
    }

    fn place(
        &mut self,
        chain: &KinematicChain,
        links: &[LinkBalls],
        q: &[f64],
    ) -> Result<(), RobotError> {
        chain.poses_into(q, &mut self.poses)?;
        self.centers.clear();
        self.bounding.clear();
        for l in links {
            let pose = self.poses[l.link];
            self.centers
                .extend(l.centers.iter().map(|&c| pose.transform_point3(c)));
            self.bounding.push(pose.transform_point3(l.bounding.0));
        }
        Ok(())
    }

    /// Whether links `i` and `j` (indices into `links`) have spheres that meet.
    fn meet(&self, links: &[LinkBalls], i: usize, j: usize, padding: f64) -> bool {
        let (a, b) = (&links[i], &links[j]);
        let reach = a.bounding.1 + b.bounding.1 + padding;
        if self.bounding[i].distance_squared(self.bounding[j]) > reach * reach {
            return false;
        }
        let b_center = self.bounding[j];
        let b_centers = &self.centers[b.offset..b.offset + b.centers.len()];
        for (k, &ra) in a.radii.iter().enumerate() {
            let ca = self.centers[a.offset + k];
            let reach = ra + b.bounding.1 + padding;
            if ca.distance_squared(b_center) > reach * reach {
                continue;
            }
            for (&cb, &rb) in b_centers.iter().zip(&b.radii) {
                let reach = ra + rb + padding;
                if ca.distance_squared(cb) <= reach * reach {
                    return true;
                }
            }
        }
        false
    }

    /// Which of `pairs` meet at configuration `q`.
    fn contacts(
        mut self,
        chain: &KinematicChain,
        links: &[LinkBalls],
        pairs: &[(usize, usize)],
        q: &[f64],
        padding: f64,
    ) -> Result<Vec<bool>, RobotError> {
        self.place(chain, links, q)?;
        Ok(pairs
            .iter()
            .map(|&(i, j)| self.meet(links, i, j, padding))
            .collect())
    }
}

/// Per pair, in how many of the sampled configurations its spheres meet. Summed over
/// chunks of samples: the same counts whatever the thread count.
fn count_contacts(
    chain: &KinematicChain,
    links: &[LinkBalls],
    pairs: &[(usize, usize)],
    options: &SelfCollisionOptions,
) -> Result<Vec<usize>, RobotError> {
    const CHUNK: usize = 256;
    let chunks = options.samples.div_ceil(CHUNK);
    let run = |chunk: usize| -> Result<Vec<usize>, RobotError> {
        let mut posed = Posed::new(links);
        let mut counts = vec![0_usize; pairs.len()];
        let end = ((chunk + 1) * CHUNK).min(options.samples);
        for index in chunk * CHUNK..end {
            let q = chain.sample(options.seed, index as u64);
            posed.place(chain, links, &q)?;
            for (count, &(i, j)) in counts.iter_mut().zip(pairs) {
                if posed.meet(links, i, j, options.padding) {
                    *count += 1;
                }
            }
        }
        Ok(counts)
    };
    // Summed as they come (integers: any order gives the same sums), so memory does not
    // grow with the number of samples.
    let add = |mut a: Vec<usize>, b: Vec<usize>| {
        for (x, y) in a.iter_mut().zip(b) {
            *x += y;
        }
        a
    };
    #[cfg(feature = "parallel")]
    let counts = (0..chunks)
        .into_par_iter()
        .map(run)
        .try_reduce(|| vec![0; pairs.len()], |a, b| Ok(add(a, b)));
    #[cfg(not(feature = "parallel"))]
    let counts = (0..chunks)
        .map(run)
        .try_fold(vec![0; pairs.len()], |a, b| Ok::<_, RobotError>(add(a, b?)));
    counts
}
