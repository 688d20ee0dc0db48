//! Dividing one node's region between its children: the discrete search for a start,
//! Lloyd's iteration on the representatives, then the exact refinement on every piece,
//! from a few starts, keeping the best.

use glam::DVec3;
use sphaera_mesh::{Sphere, Surface};

use super::candidates::{Candidate, medial_candidate};
use super::cluster::{Cluster, Region, worst};
use super::pieces::{Piece, area, centroid};
use super::search::Thresholds;
use crate::SphereTreeError;
use crate::evaluate::{EvaluationOptions, sphere_error};

/// What a division must reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Goal {
    /// Exactly this many children (fewer only when the region has fewer pieces).
    Count(usize),
    /// The fewest children, at most `most`, whose eq. 2 errors are all at most
    /// `tolerance`; `most` with the least worst error when that many cannot.
    Within {
        /// The error every child should meet.
        tolerance: f64,
        /// Children at most.
        most: usize,
    },
}

impl Goal {
    fn most(self) -> usize {
        match self {
            Self::Count(k) => k,
            Self::Within { most, .. } => most,
        }
    }
}

/// One child of a division: its sphere (containing every corner of its pieces), the
/// signed depth of its centre and its eq. 2 error, and its pieces (indices into the
/// divided region's pieces, ascending).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Child {
    pub(crate) sphere: Sphere,
    pub(crate) depth: f64,
    pub(crate) error: f64,
    pub(crate) members: Vec<u32>,
}

/// How hard a division works (see [`divide`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Effort {
    /// Starts (different subsets of representatives) tried.
    pub(crate) starts: usize,
    /// The best starts (by their error on the representatives) refined exactly.
    pub(crate) refined: usize,
    /// Rounds of exact refinement per start.
    pub(crate) rounds: usize,
    /// Passes of swaps after the refinement (0: none).
    pub(crate) swaps: usize,
    /// How strongly the children's regions are balanced by area (0: not at all; see
    /// [`balance`]).
    pub(crate) balance: f64,
}

impl Effort {
    /// The effort for dividing one of `parents` nodes of a level (`last`: no node of the
    /// next level will be divided): the fewer the nodes, the more starts each gets (the
    /// root's division shapes every region below it), swaps for a lone node, and regions
    /// balanced unless nothing below them is divided.
    pub(crate) fn for_level(parents: usize, last: bool) -> Self {
        let starts = (ROOT_STARTS / parents.max(1)).clamp(1, ROOT_STARTS);
        Self {
            starts,
            refined: starts.min(REFINED_STARTS),
            rounds: REFINE_ROUNDS,
            swaps: usize::from(parents == 1),
            balance: if last { 0.0 } else { BALANCE_STRENGTH },
        }
    }
}

/// Starts of a lone node's division (a level of `n` nodes gives each `8 / n`).
const ROOT_STARTS: usize = 8;
/// Starts refined exactly at most.
const REFINED_STARTS: usize = 4;
/// Rounds of exact refinement.
const REFINE_ROUNDS: usize = 4;
/// The bias per unit of excess area, in units of the worst child's error
/// ([`balance`]).
const BALANCE_STRENGTH: f64 = 0.1;

/// Relative slack added to every radius: the computed distances to the corners are
/// rounded, and a sphere must contain its pieces.
const RADIUS_SLACK: f64 = 1e-12;

/// Representatives at least, and per child.
const REPS_MIN: usize = 1_024;
const REPS_PER_CHILD: usize = 6;
/// Candidates at least, per child, and at most.
const CANDIDATES_MIN: usize = 256;
const CANDIDATES_PER_CHILD: usize = 4;
const CANDIDATES_MAX: usize = 2_400;

/// Divides the region `pieces` (in Morton order) between children meeting `goal`.
/// `parent` is the sphere that covers the whole region (the parent node's) with its
/// signed depth: its centre is a candidate too, and a child that would reach farther
/// beyond the surface than it takes its sphere instead (dividing a region never makes it
/// looser). Its radius is where the medial candidates start shrinking.
///
/// # Errors
///
/// A closest-point query that fails (non-finite data).
pub(crate) fn divide(
    surface: &Surface,
    pieces: &[Piece],
    goal: Goal,
    parent: (Sphere, f64),
    effort: Effort,
) -> Result<Vec<Child>, SphereTreeError> {
    let most = goal.most().max(1);
    let (mut candidates, mut origins) = candidates(surface, pieces, most, parent.0.radius)?;
    // The parent's centre, grown from the middle piece.
    candidates.push(Candidate {
        center: parent.0.center,
        depth: parent.1,
    });
    origins.push((pieces.len() / 2) as u32);
    let starts = if pieces.len() <= REPS_MIN {
        1
    } else {
        effort.starts.max(1)
    };
    // Every start on the representatives; the best ones refined on every piece.
    let mut drafts = Vec::with_capacity(starts);
    for start in 0..starts {
        let region = region(surface, pieces, most, start, &candidates, &origins);
        let clusters = draft(&region, goal);
        drafts.push((worst(&clusters), start, clusters));
    }
    drafts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut best: Option<Vec<Cluster>> = None;
    for (_, start, clusters) in drafts.into_iter().take(effort.refined.max(1)) {
        let region = region(surface, pieces, most, start, &candidates, &origins);
        let refined = finish(&region, goal, clusters, effort.rounds)?;
        if better(&refined, best.as_deref(), goal) {
            best = Some(refined);
        }
    }
    let mut clusters = best.unwrap_or_default();
    let whole = region(surface, pieces, most, 0, &candidates, &origins);
    if effort.swaps > 0 && matches!(goal, Goal::Count(_)) {
        whole.swap(&mut clusters, effort.swaps, SWAP_ROUNDS)?;
    }
    if effort.balance > 0.0 && clusters.len() > 1 {
        balance(&whole, &mut clusters, effort.balance)?;
    }
    let children: Vec<Child> = clusters
        .into_iter()
        .map(|c| {
            let radius = (c.cost + c.depth) * (1.0 + RADIUS_SLACK);
            Child {
                sphere: Sphere::new(c.center, radius.max(f64::MIN_POSITIVE)),
                depth: c.depth,
                error: super::eq2(radius, c.depth),
                members: c.members,
            }
        })
        .collect();
    no_looser_than_parent(surface, children, parent)
}

/// The children with every child that could reach farther beyond the surface than its
/// parent does replaced by the parent's sphere (which covers its pieces too): dividing a
/// region never makes it looser.
///
/// A child's eq. 2 error bounds its certified error from above; the parent's certified
/// error is bounded from below by one probe of its sphere, and by its certified
/// evaluation when that is not enough. A child above that bound is evaluated itself, and
/// kept when its certified error is not above it.
fn no_looser_than_parent(
    surface: &Surface,
    mut children: Vec<Child>,
    parent: (Sphere, f64),
) -> Result<Vec<Child>, SphereTreeError> {
    let parent_error = super::eq2(parent.0.radius, parent.1);
    let worst_child = children.iter().map(|c| c.error).fold(0.0, f64::max);
    if worst_child <= parent_error.min(crate::build::probe_error(surface, &parent.0)) {
        return Ok(children);
    }
    let options = EvaluationOptions::default();
    let fit = sphere_error(surface, &parent.0, &options)?;
    let limit = fit.lower.max(crate::build::probe_error(surface, &parent.0));
    for child in &mut children {
        if child.error <= limit {
            continue;
        }
        let own = sphere_error(surface, &child.sphere, &options)?;
        if own.upper <= limit {
            child.error = child.error.min(own.upper);
            continue;
        }
        child.sphere = parent.0;
        child.depth = parent.1;
        child.error = parent_error.min(fit.upper);
    }
    Ok(children)
}

/// Rounds of exact refinement after each swap.
const SWAP_ROUNDS: usize = 2;

/// Rounds of region balancing.
const BALANCE_ROUNDS: usize = 8;

/// Balances the children's regions by area without raising the worst child's error: a
/// cluster whose region is larger than the mean gets a bias (added to the error of every
/// piece when pieces are assigned) proportional to the excess, so that its neighbours take
/// its edge pieces where they can without becoming the worst; then the exact refinement,
/// which keeps a change only when the worst error does not rise. A child's region is what
/// its own children will divide: the deepest level's error follows the largest regions.
fn balance(
    region: &Region<'_>,
    clusters: &mut Vec<Cluster>,
    strength: f64,
) -> Result<(), SphereTreeError> {
    let unit = worst(clusters).abs();
    let limit = worst(clusters);
    let mut strength = strength;
    for _ in 0..BALANCE_ROUNDS {
        let areas: Vec<f64> = clusters
            .iter()
            .map(|c| {
                c.members
                    .iter()
                    .map(|&m| area(&region.pieces[m as usize]))
                    .sum()
            })
            .collect();
        let mean = areas.iter().sum::<f64>() / areas.len().max(1) as f64;
        if mean.is_nan() || mean <= 0.0 {
            break;
        }
        let mut trial = clusters.clone();
        for (c, a) in trial.iter_mut().zip(&areas) {
            c.bias = strength * unit * (a / mean - 1.0).max(0.0);
        }
        region.reassign_and_polish(&mut trial)?;
        if worst(&trial) <= limit {
            *clusters = trial;
        } else {
            strength *= 0.5;
        }
    }
    for c in clusters.iter_mut() {
        c.bias = 0.0;
    }
    Ok(())
}

/// Whether `candidate` is a better division than `incumbent` for `goal`: fewer children
/// meeting the tolerance, else a smaller worst error.
fn better(candidate: &[Cluster], incumbent: Option<&[Cluster]>, goal: Goal) -> bool {
    let Some(incumbent) = incumbent else {
        return true;
    };
    if let Goal::Within { tolerance, .. } = goal {
        let meets = |c: &[Cluster]| worst(c) <= tolerance;
        match (meets(candidate), meets(incumbent)) {
            (true, false) => return true,
            (false, true) => return false,
            (true, true) if candidate.len() != incumbent.len() => {
                return candidate.len() < incumbent.len();
            }
            _ => {}
        }
    }
    worst(candidate) < worst(incumbent)
}

/// The region's candidate centres (medial balls of evenly spread pieces, on every core
/// with the `parallel` feature), and the piece each was grown from.
fn candidates(
    surface: &Surface,
    pieces: &[Piece],
    most: usize,
    scale: f64,
) -> Result<(Vec<Candidate>, Vec<u32>), SphereTreeError> {
    let count = (CANDIDATES_PER_CHILD * most)
        .clamp(CANDIDATES_MIN, CANDIDATES_MAX)
        .min(pieces.len());
    let every = pieces.len().div_ceil(count.max(1)).max(1);
    let origins: Vec<u32> = (0..pieces.len() as u32)
        .skip(every / 2)
        .step_by(every)
        .collect();
    let one = |&origin: &u32| -> Result<Candidate, SphereTreeError> {
        let piece = &pieces[origin as usize];
        let normal = (piece[1] - piece[0])
            .cross(piece[2] - piece[0])
            .try_normalize()
            .unwrap_or(DVec3::ZERO);
        Ok(medial_candidate(surface, centroid(piece), normal, scale)?.0)
    };
    #[cfg(feature = "parallel")]
    let found: Result<Vec<Candidate>, SphereTreeError> = {
        use rayon::prelude::*;
        origins.par_iter().map(one).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let found: Result<Vec<Candidate>, SphereTreeError> = origins.iter().map(one).collect();
    Ok((found?, origins))
}

/// The region with the representatives of start number `start` (every `n`-th piece
/// from another offset); each candidate belongs to the representative at or before the
/// piece it was grown from.
fn region<'a>(
    surface: &'a Surface,
    pieces: &'a [Piece],
    most: usize,
    start: usize,
    candidates: &[Candidate],
    origins: &[u32],
) -> Region<'a> {
    let wanted = REPS_MIN.max(REPS_PER_CHILD * most);
    let stride = pieces.len().div_ceil(wanted).max(1);
    let reps: Vec<u32> = (0..pieces.len() as u32)
        .skip(start % stride)
        .step_by(stride)
        .collect();
    let sources = origins
        .iter()
        .map(|&o| reps.partition_point(|&r| r <= o).saturating_sub(1) as u32)
        .collect();
    Region {
        surface,
        pieces,
        reps,
        candidates: candidates.to_vec(),
        sources,
        origins: origins.to_vec(),
    }
}

/// One start on the representatives: search, Lloyd, fill up to the count asked.
fn draft(region: &Region<'_>, goal: Goal) -> Vec<Cluster> {
    let reps: Vec<Piece> = region
        .reps
        .iter()
        .map(|&r| region.pieces[r as usize])
        .collect();
    let thresholds = Thresholds::new(&reps, &region.candidates);
    let most = goal.most().max(1);
    let chosen = match goal {
        Goal::Count(k) => thresholds.smallest_cover(k, 1).1,
        Goal::Within { tolerance, most } => thresholds
            .fewest_at(tolerance as f32, most, 1)
            .unwrap_or_else(|| thresholds.smallest_cover(most, 1).1),
    };
    let mut clusters: Vec<Cluster> = chosen
        .iter()
        .filter_map(|&c| region.candidates.get(c))
        .map(|c| Cluster {
            center: c.center,
            depth: c.depth,
            members: Vec::new(),
            cost: f64::INFINITY,
            bias: 0.0,
        })
        .collect();
    if clusters.is_empty() {
        let all: Vec<u32> = (0..region.reps.len() as u32).collect();
        clusters.push(region.fit(&all, &[]));
    }
    region.assign_reps(&mut clusters);
    clusters.retain(|c| !c.members.is_empty());
    for c in &mut clusters {
        *c = region.fit(&c.members, &[]);
    }
    region.lloyd(&mut clusters, 12);
    if matches!(goal, Goal::Count(_)) {
        region.fill(&mut clusters, most);
    }
    clusters
}

/// The exact refinement of a draft on every piece; with a tolerance not met, more
/// children while allowed.
fn finish(
    region: &Region<'_>,
    goal: Goal,
    mut clusters: Vec<Cluster>,
    rounds: usize,
) -> Result<Vec<Cluster>, SphereTreeError> {
    let mut exact = region.on_pieces(&clusters);
    region.refine(&mut exact, rounds)?;
    if let Goal::Within { tolerance, most } = goal {
        while worst(&exact) > tolerance && clusters.len() < most {
            let before = clusters.len();
            region.fill(&mut clusters, before + 1);
            if clusters.len() == before {
                break;
            }
            exact = region.on_pieces(&clusters);
            region.refine(&mut exact, rounds)?;
        }
    }
    Ok(exact)
}
