//! Dividing one node's region between its children: the discrete search for a start,
//! Lloyd's iteration on the representatives, then the exact refinement on every piece,
//! from a few starts, keeping the best.

use glam::DVec3;
use sphaera_mesh::Sphere;
use sphaera_query::Surface;

use super::candidates::{Candidate, medial_candidate};
use super::cluster::{BRUTE_FORCE_SPHERES, Cluster, Region, worst};
use super::pieces::{Piece, area, centroid};
use super::polish::Corners;
use super::search::Thresholds;
use crate::evaluate::{EvaluationOptions, sphere_error};
use crate::{Effort, SphereTreeError};

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

/// How hard a division works (see [`divide`]), from the [`Effort`] asked for and where
/// the node stands in the tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Plan {
    /// Starts (different subsets of representatives) tried.
    pub(crate) starts: usize,
    /// The best starts (by their error on the representatives) refined exactly.
    pub(crate) refined: usize,
    /// Rounds of exact refinement per start.
    pub(crate) rounds: usize,
    /// Swaps tried per child after the refinement (0: none; see [`Region::swap`]).
    pub(crate) swaps: usize,
    /// How strongly the children's regions are balanced by area (0: not at all; see
    /// [`balance`]).
    pub(crate) balance: f64,
    /// Representatives at least.
    pub(crate) reps: usize,
    /// Candidates at least.
    pub(crate) candidates: usize,
    /// Pieces a region is split into before it is divided, at least.
    pub(crate) pieces: usize,
    /// Pieces per child at least.
    pub(crate) pieces_per_child: usize,
}

impl Plan {
    /// The plan for dividing one of `parents` nodes of a level into `children` at
    /// `effort` (`last`: no node of the next level will be divided): the fewer the nodes,
    /// the more starts each gets (the root's division shapes every region below it),
    /// swaps for a lone node, and regions balanced unless nothing below them is divided.
    pub(crate) fn for_level(effort: Effort, parents: usize, children: usize, last: bool) -> Self {
        let (root_starts, rounds, reps, candidates, pieces, pieces_per_child) = match effort {
            Effort::Quick => (1, 1, 256, 96, 1_500, 24),
            Effort::Thorough => (16, 6, 2_048, 512, 16_000, 200),
            // `Effort` is non-exhaustive: the default for anything new.
            _ => (8, 4, 1_024, 256, 8_000, 100),
        };
        // Many children are costly to divide, and each matters less.
        let most = if children > MANY_CHILDREN {
            2.min(root_starts)
        } else {
            root_starts
        };
        let starts = (root_starts / parents.max(1)).clamp(1, most);
        let quick = effort == Effort::Quick;
        Self {
            starts,
            refined: starts.min(REFINED_STARTS),
            rounds,
            swaps: if !quick && parents == 1 {
                SWAP_PASSES
            } else {
                0
            },
            balance: if last || quick { 0.0 } else { BALANCE_STRENGTH },
            reps,
            candidates,
            pieces,
            pieces_per_child,
        }
    }
}

/// Divisions into more children than this get at most two starts.
const MANY_CHILDREN: usize = 64;
/// Swaps tried by a lone node's division, per child (see [`Region::swap`]).
const SWAP_PASSES: usize = 2;

/// Starts refined exactly at most.
const REFINED_STARTS: usize = 4;
/// The bias per unit of excess area, in units of the worst child's error
/// ([`balance`]).
const BALANCE_STRENGTH: f64 = 0.1;

/// Relative slack added to every radius: the computed distances to the corners are
/// rounded, and a sphere must contain its pieces.
const RADIUS_SLACK: f64 = 1e-12;

/// Absolute slack added to every radius, in canonical units (coordinates within 1 of the
/// origin): a split midpoint is rounded by a few units in the last place of its
/// coordinates, which a small sphere's relative slack may not cover.
const ABSOLUTE_SLACK: f64 = 16.0 * f64::EPSILON;

/// Representatives per child.
const REPS_PER_CHILD: usize = 6;
/// Candidates per child, and at most.
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
    effort: Plan,
) -> Result<Vec<Child>, SphereTreeError> {
    if let Goal::Count(k) = goal
        && k > LARGE_DIVISION
    {
        return divide_in_groups(surface, pieces, k, parent, effort);
    }
    let most = goal.most().max(1);
    let corners = Corners::of(pieces);
    // The region's candidate centres and the pieces they were grown from, the parent's
    // centre last (grown from the middle piece).
    let all_candidates = || -> Result<(Vec<Candidate>, Vec<u32>), SphereTreeError> {
        let (mut candidates, mut origins) =
            candidates(surface, pieces, most, effort.candidates, parent.0.radius)?;
        candidates.push(Candidate {
            center: parent.0.center,
            depth: parent.1,
        });
        origins.push((pieces.len() / 2) as u32);
        Ok((candidates, origins))
    };
    let wanted = effort
        .pieces
        .max(effort.pieces_per_child.saturating_mul(most))
        .max(1);
    let proxied = most <= BRUTE_FORCE_SPHERES && pieces.len() > PROXY_FACTOR.saturating_mul(wanted);
    let (mut clusters, (candidates, origins)) = if proxied {
        // Divided on every `stride`-th piece (each standing for its neighbours in Morton
        // order), then refined on every piece from there.
        let stride = pieces.len().div_ceil(wanted);
        let proxy: Vec<Piece> = pieces.iter().step_by(stride).copied().collect();
        let drafted: Vec<Cluster> = divide(surface, &proxy, goal, parent, effort)?
            .into_iter()
            .map(|child| Cluster {
                center: child.sphere.center,
                depth: child.depth,
                members: Vec::new(),
                cost: child.error,
                bias: 0.0,
            })
            .collect();
        // The exact refinement moves centres off the candidates, and the balancing
        // after it does not look at them: the region's own (the proxy had its) are grown
        // only when children must be added.
        let bare = region(surface, pieces, &corners, most, effort.reps, 0, &[], &[]);
        let mut exact = refined(&bare, &drafted, PROXY_ROUNDS)?;
        let found = if incomplete(&exact, goal) {
            let (candidates, origins) = all_candidates()?;
            let whole = region(
                surface,
                pieces,
                &corners,
                most,
                effort.reps,
                0,
                &candidates,
                &origins,
            );
            complete_to(&whole, goal, &mut exact, PROXY_ROUNDS)?;
            (candidates, origins)
        } else {
            (Vec::new(), Vec::new())
        };
        (exact, found)
    } else {
        let (candidates, origins) = all_candidates()?;
        let starts = if pieces.len() <= effort.reps {
            1
        } else {
            effort.starts.max(1)
        };
        // Every start on the representatives; the best ones refined on every piece.
        let region_from = |start| {
            region(
                surface,
                pieces,
                &corners,
                most,
                effort.reps,
                start,
                &candidates,
                &origins,
            )
        };
        let mut drafts = Vec::with_capacity(starts);
        for start in 0..starts {
            let region = region_from(start);
            let clusters = draft(&region, goal);
            drafts.push((worst(&clusters), start, clusters));
        }
        drafts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut best: Option<Vec<Cluster>> = None;
        for (_, start, clusters) in drafts.into_iter().take(effort.refined.max(1)) {
            let region = region_from(start);
            let refined = finish(&region, goal, &clusters, effort.rounds)?;
            if better(&refined, best.as_deref(), goal) {
                best = Some(refined);
            }
        }
        (best.unwrap_or_default(), (candidates, origins))
    };
    // Without the swaps (only when not proxied), the candidates are not looked at.
    let whole = region(
        surface,
        pieces,
        &corners,
        most,
        effort.reps,
        0,
        &candidates,
        &origins,
    );
    if !proxied && effort.swaps > 0 && matches!(goal, Goal::Count(_)) {
        whole.swap(&mut clusters, effort.swaps, SWAP_ROUNDS)?;
    }
    if effort.balance > 0.0 && clusters.len() > 1 {
        balance(&whole, &mut clusters, effort.balance)?;
    }
    let children: Vec<Child> = clusters
        .into_iter()
        .map(|c| {
            let radius = (c.cost + c.depth) * (1.0 + RADIUS_SLACK) + ABSOLUTE_SLACK;
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

/// A region of more pieces than this many times the plan's (the root of a mesh of a
/// million triangles) is first divided on a proxy, every `stride`-th piece, and then
/// refined on every piece for [`PROXY_ROUNDS`] rounds from there (the proxy's division
/// has had the starts and the swaps). Lower factors save nothing: a region proxied on
/// every second or third piece is refined for the proxy's rounds on its part and then for
/// [`PROXY_ROUNDS`] on every piece, as many centre polishes (the division's main cost,
/// each a few dozen closest-point queries on the whole surface, whatever the pieces) and
/// as many candidates as dividing it directly (the dragon's 64 level-3 regions, 14k–16k
/// pieces once split, all proxied at 1.5: the same levels, no less time).
const PROXY_FACTOR: usize = 2;

/// Rounds of exact refinement on every piece after a proxy's division.
const PROXY_ROUNDS: usize = 2;

/// Divisions into more children than this go in two steps ([`divide_in_groups`]).
const LARGE_DIVISION: usize = 1_024;

/// Children per group of a two-step division, about.
const GROUP_CHILDREN: usize = 256;

/// A division into `k` children, more than [`LARGE_DIVISION`], in two steps: the region
/// is first divided into groups of about [`GROUP_CHILDREN`] children's worth, each group
/// gets a share of the `k` children proportional to its area (largest remainders, at
/// least one each, exactly `k` in all), and each group is divided into its share (in
/// parallel with the `parallel` feature). The groups' boundaries constrain the children
/// a little; the search and the refinement of one division into thousands would cost
/// far more.
fn divide_in_groups(
    surface: &Surface,
    pieces: &[Piece],
    k: usize,
    parent: (Sphere, f64),
    effort: Plan,
) -> Result<Vec<Child>, SphereTreeError> {
    let count = k.div_ceil(GROUP_CHILDREN);
    let groups = divide(surface, pieces, Goal::Count(count), parent, effort)?;
    let areas: Vec<f64> = groups
        .iter()
        .map(|g| g.members.iter().map(|&m| area(&pieces[m as usize])).sum())
        .collect();
    let shares = shares(&areas, k);
    let one = |(group, &share): (&Child, &usize)| -> Result<Vec<Child>, SphereTreeError> {
        let own: Vec<Piece> = group.members.iter().map(|&m| pieces[m as usize]).collect();
        let children = divide(
            surface,
            &own,
            Goal::Count(share),
            (group.sphere, group.depth),
            effort,
        )?;
        // Back to the region's piece indices.
        Ok(children
            .into_iter()
            .map(|mut c| {
                for m in &mut c.members {
                    *m = group.members[*m as usize];
                }
                c.members.sort_unstable();
                c
            })
            .collect())
    };
    #[cfg(feature = "parallel")]
    let divided: Result<Vec<Vec<Child>>, SphereTreeError> = {
        use rayon::prelude::*;
        groups.par_iter().zip(shares.par_iter()).map(one).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let divided: Result<Vec<Vec<Child>>, SphereTreeError> =
        groups.iter().zip(shares.iter()).map(one).collect();
    Ok(divided?.into_iter().flatten().collect())
}

/// `total` split in proportion to `weights` by largest remainders, at least 1 each (when
/// `total` allows), summing to `total` exactly.
fn shares(weights: &[f64], total: usize) -> Vec<usize> {
    let n = weights.len();
    if n == 0 {
        return Vec::new();
    }
    let base = total.saturating_sub(n);
    let sum: f64 = weights.iter().map(|w| w.max(0.0)).sum();
    let exact: Vec<f64> = weights
        .iter()
        .map(|w| {
            if sum > 0.0 {
                base as f64 * w.max(0.0) / sum
            } else {
                base as f64 / n as f64
            }
        })
        .collect();
    let mut out: Vec<usize> = exact.iter().map(|e| 1 + e.floor() as usize).collect();
    let mut left = total.saturating_sub(out.iter().sum());
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        let (fa, fb) = (exact[a] - exact[a].floor(), exact[b] - exact[b].floor());
        fb.total_cmp(&fa).then(a.cmp(&b))
    });
    for &i in order.iter().cycle().take(n * 2) {
        if left == 0 {
            break;
        }
        out[i] += 1;
        left -= 1;
    }
    out
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

/// Rounds of exact refinement after the children were completed to the count.
const COMPLETION_ROUNDS: usize = 2;

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
    minimum: usize,
    scale: f64,
) -> Result<(Vec<Candidate>, Vec<u32>), SphereTreeError> {
    let count = (CANDIDATES_PER_CHILD * most)
        .clamp(minimum, CANDIDATES_MAX.max(minimum))
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
#[allow(clippy::too_many_arguments)]
fn region<'a>(
    surface: &'a Surface,
    pieces: &'a [Piece],
    corners: &'a Corners,
    most: usize,
    minimum: usize,
    start: usize,
    candidates: &[Candidate],
    origins: &[u32],
) -> Region<'a> {
    let wanted = minimum.max(REPS_PER_CHILD * most);
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
        corners,
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
    clusters
}

/// The exact refinement of a draft on every piece; with a tolerance not met, more
/// children while allowed.
fn finish(
    region: &Region<'_>,
    goal: Goal,
    clusters: &[Cluster],
    rounds: usize,
) -> Result<Vec<Cluster>, SphereTreeError> {
    let mut exact = refined(region, clusters, rounds)?;
    complete_to(region, goal, &mut exact, rounds)?;
    Ok(exact)
}

/// The first part of [`finish`]: the draft on every piece, refined exactly (neither looks
/// at the region's candidates).
fn refined(
    region: &Region<'_>,
    clusters: &[Cluster],
    rounds: usize,
) -> Result<Vec<Cluster>, SphereTreeError> {
    let mut exact = region.on_pieces(clusters);
    region.refine(&mut exact, rounds)?;
    Ok(exact)
}

/// Whether [`complete_to`] would add children to `exact` for `goal`.
fn incomplete(exact: &[Cluster], goal: Goal) -> bool {
    match goal {
        Goal::Count(k) => exact.len() < k,
        Goal::Within { tolerance, most } => worst(exact) > tolerance && exact.len() < most,
    }
}

/// The second part of [`finish`]: with fewer children than `goal` asks for, more (grown
/// from the region's candidates), refined again.
fn complete_to(
    region: &Region<'_>,
    goal: Goal,
    exact: &mut Vec<Cluster>,
    rounds: usize,
) -> Result<(), SphereTreeError> {
    match goal {
        Goal::Count(k) => {
            if exact.len() < k {
                region.complete(exact, k)?;
                region.refine(exact, COMPLETION_ROUNDS)?;
            }
        }
        Goal::Within { tolerance, most } => {
            while worst(exact) > tolerance && exact.len() < most {
                let before = exact.len();
                region.complete(exact, before + 1)?;
                if exact.len() == before {
                    break;
                }
                region.refine(exact, rounds)?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::shares;

    #[test]
    fn shares_sum_to_the_total_with_one_each_at_least() {
        for (weights, total) in [
            (vec![1.0, 1.0, 1.0], 10),
            (vec![5.0, 0.1, 0.0, 2.0], 1_025),
            (vec![0.0, 0.0], 3),
            (vec![1e-300, 1e300], 2),
        ] {
            let s = shares(&weights, total);
            assert_eq!(s.iter().sum::<usize>(), total, "{weights:?}");
            assert!(s.iter().all(|&x| x >= 1), "{s:?}");
        }
        assert_eq!(shares(&[3.0, 1.0], 6), vec![4, 2]);
    }
}
