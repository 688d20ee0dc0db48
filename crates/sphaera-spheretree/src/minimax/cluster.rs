//! Clusters of pieces and the moves that improve them: assignment of every piece to the
//! sphere that covers it with the least error, the best candidate centre for a cluster,
//! splitting a cluster, and the alternation of the two (Lloyd's iteration for the
//! minimax objective), first on the representatives, then exactly on every piece.

use glam::DVec3;
use sphaera_query::Surface;

use super::candidates::Candidate;
use super::pieces::{Piece, centroid, reach_squared};
use super::polish::{Corners, polish};
use crate::SphereTreeError;

/// A sphere being fitted: its centre, signed depth, the pieces it covers (indices, into
/// the representatives or into every piece of the region, as the stage says) and its
/// eq. 2 error over them (`reach − depth`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Cluster {
    pub(crate) center: DVec3,
    pub(crate) depth: f64,
    pub(crate) members: Vec<u32>,
    pub(crate) cost: f64,
    /// Added to the cost of every piece when pieces are assigned: a positive bias shrinks
    /// the cluster's region (region balancing); 0 for the minimax assignment.
    pub(crate) bias: f64,
}

/// The worst error of a set of clusters (`-∞` for none).
pub(crate) fn worst(clusters: &[Cluster]) -> f64 {
    clusters
        .iter()
        .map(|c| c.cost)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Clusters of more than this many spheres assign pieces among neighbouring spheres only.
pub(crate) const BRUTE_FORCE_SPHERES: usize = 24;

/// The region being divided: its pieces, representatives and candidate centres.
pub(crate) struct Region<'a> {
    pub(crate) surface: &'a Surface,
    /// Every piece of the region.
    pub(crate) pieces: &'a [Piece],
    /// The pieces' corners, numbered.
    pub(crate) corners: &'a Corners,
    /// The representatives, as indices into `pieces` (ascending).
    pub(crate) reps: Vec<u32>,
    /// The candidate centres.
    pub(crate) candidates: Vec<Candidate>,
    /// Per candidate, the position in `reps` of the representative it was grown from.
    pub(crate) sources: Vec<u32>,
    /// Per candidate, the piece it was grown from.
    pub(crate) origins: Vec<u32>,
}

impl Region<'_> {
    fn rep(&self, position: u32) -> &Piece {
        &self.pieces[self.reps[position as usize] as usize]
    }

    /// The eq. 2 error of a sphere about `center` (signed depth `depth`) over the
    /// representatives at `positions`, stopping once it exceeds `stop`.
    fn rep_cost(&self, positions: &[u32], center: DVec3, depth: f64, stop: f64) -> f64 {
        let limit = stop + depth;
        let limit_squared = if limit > 0.0 { limit * limit } else { 0.0 };
        let mut reach_sq = 0.0_f64;
        for &p in positions {
            reach_sq = reach_sq.max(reach_squared(self.rep(p), center));
            if reach_sq > limit_squared && limit.is_finite() {
                break;
            }
        }
        reach_sq.sqrt() - depth
    }

    /// The best candidate centre for the representatives at `positions`: the candidates
    /// grown from them (and `extra`), ranked by a lower bound, measured in that order.
    pub(crate) fn fit(&self, positions: &[u32], extra: &[usize]) -> Cluster {
        let mut mine: Vec<usize> = Vec::new();
        if !positions.is_empty() {
            // Candidates grown from these representatives (sources ascend with positions).
            let sorted = {
                let mut s = positions.to_vec();
                s.sort_unstable();
                s
            };
            for (c, &source) in self.sources.iter().enumerate() {
                if sorted.binary_search(&source).is_ok() {
                    mine.push(c);
                }
            }
        }
        mine.extend_from_slice(extra);
        if mine.is_empty() {
            mine = (0..self.candidates.len()).collect();
        }
        // A few far-apart representatives bound every candidate's reach from below.
        let probes = far_chain(self, positions, 6);
        let mut ranked: Vec<(f64, usize)> = mine
            .iter()
            .map(|&c| {
                let cand = self.candidates[c];
                let lower = probes
                    .iter()
                    .map(|&p| reach_squared(self.rep(p), cand.center))
                    .fold(0.0, f64::max)
                    .sqrt()
                    - cand.depth;
                (lower, c)
            })
            .collect();
        ranked.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut best = (f64::INFINITY, usize::MAX);
        for &(lower, c) in &ranked {
            if lower >= best.0 {
                break;
            }
            let cand = self.candidates[c];
            let cost = self.rep_cost(positions, cand.center, cand.depth, best.0);
            if cost < best.0 {
                best = (cost, c);
            }
        }
        let cand = self.candidates.get(best.1).copied().unwrap_or(Candidate {
            center: DVec3::ZERO,
            depth: f64::NEG_INFINITY,
        });
        Cluster {
            center: cand.center,
            depth: cand.depth,
            members: positions.to_vec(),
            cost: best.0,
            bias: 0.0,
        }
    }

    /// Assigns every representative to the cluster that covers it with the least error.
    pub(crate) fn assign_reps(&self, clusters: &mut [Cluster]) {
        for c in clusters.iter_mut() {
            c.members.clear();
        }
        for r in 0..self.reps.len() as u32 {
            let piece = self.rep(r);
            if let Some(k) = cheapest(clusters, piece, 0..clusters.len()) {
                clusters[k].members.push(r);
            }
        }
    }

    /// Lloyd's iteration on the representatives: assign, then fit every changed cluster,
    /// while the worst error falls (at most `rounds` times). Empty clusters are dropped
    /// (the count is completed on the pieces, [`Region::complete`]).
    pub(crate) fn lloyd(&self, clusters: &mut Vec<Cluster>, rounds: usize) {
        for _ in 0..rounds {
            let before = worst(clusters);
            let snapshot = clusters.clone();
            self.assign_reps(clusters);
            let mut changed = false;
            for (cluster, old) in clusters.iter_mut().zip(&snapshot) {
                if !cluster.members.is_empty() && cluster.members != old.members {
                    changed = true;
                    *cluster = self.fit(&cluster.members, &[]);
                }
            }
            clusters.retain(|c| !c.members.is_empty());
            let after = worst(clusters);
            if after > before {
                *clusters = snapshot;
                return;
            }
            if !changed || after >= before - 1e-12 * before.abs() {
                return;
            }
        }
    }

    /// The clusters with every piece of the region as members (each piece to the cluster
    /// that covers it with the least error), exactly measured.
    pub(crate) fn on_pieces(&self, clusters: &[Cluster]) -> Vec<Cluster> {
        let mut out: Vec<Cluster> = clusters
            .iter()
            .map(|c| Cluster {
                members: Vec::new(),
                ..c.clone()
            })
            .collect();
        if clusters.len() <= BRUTE_FORCE_SPHERES {
            // The members are not looked at: every piece's cluster at once.
            let all = 0..out.len();
            let homes = map_pieces(self.pieces, |piece| cheapest(&out, piece, all.clone()));
            for (i, home) in homes.into_iter().enumerate() {
                if let Some(k) = home {
                    out[k].members.push(i as u32);
                }
            }
        } else {
            // Each piece starts with its representative's cluster (the representative
            // before it in the region's order), then moves among that cluster's
            // neighbours.
            let mut owner = vec![0_u32; self.reps.len()];
            for (k, c) in clusters.iter().enumerate() {
                for &m in &c.members {
                    owner[m as usize] = k as u32;
                }
            }
            let neighbours = neighbours(clusters, |k| {
                clusters[k]
                    .members
                    .iter()
                    .map(|&m| reach_squared(self.rep(m), clusters[k].center))
                    .fold(0.0, f64::max)
                    .sqrt()
            });
            let mut rep = 0_usize;
            for (i, piece) in self.pieces.iter().enumerate() {
                while rep + 1 < self.reps.len() && self.reps[rep + 1] as usize <= i {
                    rep += 1;
                }
                let home = owner.get(rep).copied().unwrap_or(0) as usize;
                let near = neighbours.get(home).map_or(&[][..], Vec::as_slice);
                let k = cheapest(&out, piece, near.iter().map(|&j| j as usize)).unwrap_or(home);
                out[k].members.push(i as u32);
            }
        }
        // A cluster left without pieces takes back its first representative's piece, so
        // that the count asked for is kept.
        for k in 0..out.len() {
            if !out[k].members.is_empty() {
                continue;
            }
            let Some(&first) = clusters[k].members.first() else {
                continue;
            };
            let piece = self.reps[first as usize];
            if let Some(j) = out
                .iter()
                .position(|c| c.members.len() > 1 && c.members.contains(&piece))
            {
                out[j].members.retain(|&m| m != piece);
                out[k].members.push(piece);
            }
        }
        out.retain(|c| !c.members.is_empty());
        for c in &mut out {
            c.cost = exact_reach(self.pieces, &c.members, c.center) - c.depth;
        }
        out
    }

    /// Exact refinement on every piece: polish every sphere's centre (Nelder–Mead with the
    /// exact reach and signed depth), reassign the pieces, and repeat while the worst
    /// error falls (at most `rounds` times). `clusters` hold pieces as members.
    pub(crate) fn refine(
        &self,
        clusters: &mut Vec<Cluster>,
        rounds: usize,
    ) -> Result<(), SphereTreeError> {
        self.polish_all(clusters)?;
        self.refine_polished(clusters, rounds, None)
    }

    /// [`Region::refine`] where only the clusters marked `changed` need their first
    /// polish (the others were polished on the same pieces already).
    pub(crate) fn refine_changed(
        &self,
        clusters: &mut Vec<Cluster>,
        changed: &[bool],
        rounds: usize,
    ) -> Result<(), SphereTreeError> {
        self.polish_changed(clusters, changed)?;
        self.refine_polished(clusters, rounds, Some(changed.to_vec()))
    }

    /// The rounds of [`Region::refine`] after its first polish.
    fn refine_polished(
        &self,
        clusters: &mut Vec<Cluster>,
        rounds: usize,
        mut active: Option<Vec<bool>>,
    ) -> Result<(), SphereTreeError> {
        for _ in 0..rounds {
            let before = worst(clusters);
            let snapshot = clusters.clone();
            let changed = self.reassign_some(clusters, active.as_deref());
            if !changed.contains(&true) {
                return Ok(());
            }
            self.polish_changed(clusters, &changed)?;
            if active.is_some() {
                active = Some(changed);
            }
            let after = worst(clusters);
            if after > before {
                *clusters = snapshot;
                return Ok(());
            }
            if after.is_nan() || after >= before - 1e-12 * before.abs() {
                return Ok(());
            }
        }
        Ok(())
    }

    /// One round of the exact refinement, kept whatever it gives: every piece to its
    /// cheapest neighbouring cluster (biases included), every centre polished.
    pub(crate) fn reassign_and_polish(
        &self,
        clusters: &mut [Cluster],
    ) -> Result<(), SphereTreeError> {
        let changed = self.reassign_pieces(clusters);
        self.polish_changed(clusters, &changed)
    }

    /// Polishes the clusters `these`.
    pub(crate) fn polish_these(
        &self,
        clusters: &mut [Cluster],
        these: &[usize],
    ) -> Result<(), SphereTreeError> {
        let mut flags = vec![false; clusters.len()];
        for &i in these {
            if let Some(f) = flags.get_mut(i) {
                *f = true;
            }
        }
        self.polish_changed(clusters, &flags)
    }

    /// Polishes every cluster's centre (in parallel with the `parallel` feature; each is
    /// independent, so the result is the same).
    fn polish_all(&self, clusters: &mut [Cluster]) -> Result<(), SphereTreeError> {
        self.polish_changed(clusters, &vec![true; clusters.len()])
    }

    /// Polishes the clusters marked `changed` (in parallel with the `parallel` feature;
    /// each is independent, so the result is the same). A cluster whose pieces did not
    /// change since its last polish would polish to the same centre.
    fn polish_changed(
        &self,
        clusters: &mut [Cluster],
        changed: &[bool],
    ) -> Result<(), SphereTreeError> {
        let one = |(c, &changed): (&Cluster, &bool)| -> Result<Cluster, SphereTreeError> {
            if !changed {
                return Ok(c.clone());
            }
            let (center, depth, reach) = polish(
                self.surface,
                self.pieces,
                self.corners,
                &c.members,
                c.center,
            )?;
            Ok(Cluster {
                center,
                depth,
                members: c.members.clone(),
                cost: reach - depth,
                bias: c.bias,
            })
        };
        #[cfg(feature = "parallel")]
        let polished: Result<Vec<Cluster>, SphereTreeError> = {
            use rayon::prelude::*;
            clusters
                .par_iter()
                .zip(changed.par_iter())
                .map(one)
                .collect()
        };
        #[cfg(not(feature = "parallel"))]
        let polished: Result<Vec<Cluster>, SphereTreeError> =
            clusters.iter().zip(changed.iter()).map(one).collect();
        for (slot, c) in clusters.iter_mut().zip(polished?) {
            *slot = c;
        }
        Ok(())
    }

    /// Every piece to the cluster (among its own cluster's neighbours) that covers it with
    /// the least error; costs measured again. No cluster is left empty. Returns, per
    /// cluster, whether its pieces changed.
    fn reassign_pieces(&self, clusters: &mut [Cluster]) -> Vec<bool> {
        self.reassign_some(clusters, None)
    }

    /// [`Region::reassign_pieces`] for the pieces of the clusters marked `active` only
    /// (all with `None`); the others keep theirs (and may take some).
    fn reassign_some(&self, clusters: &mut [Cluster], active: Option<&[bool]>) -> Vec<bool> {
        let reach: Vec<f64> = clusters.iter().map(|c| c.cost + c.depth).collect();
        let neighbours = neighbours(clusters, |k| reach[k]);
        let mut moved: Vec<Vec<u32>> = vec![Vec::new(); clusters.len()];
        for (k, c) in clusters.iter().enumerate() {
            if active.is_some_and(|a| !a[k]) {
                moved[k].extend_from_slice(&c.members);
                continue;
            }
            let near = || neighbours[k].iter().map(|&j| j as usize);
            let targets = map_members(&c.members, |m| {
                cheapest(clusters, &self.pieces[m as usize], near()).unwrap_or(k)
            });
            for (&m, to) in c.members.iter().zip(targets) {
                moved[to].push(m);
            }
        }
        // A cluster left without pieces keeps the one of its own it covers best.
        for k in 0..clusters.len() {
            if !moved[k].is_empty() {
                continue;
            }
            let c = &clusters[k];
            let own = c.members.iter().copied().min_by(|&a, &b| {
                let cost = |m: u32| reach_squared(&self.pieces[m as usize], c.center);
                cost(a).total_cmp(&cost(b)).then(a.cmp(&b))
            });
            let Some(piece) = own else { continue };
            if let Some(j) = moved.iter().position(|m| m.len() > 1 && m.contains(&piece)) {
                moved[j].retain(|&m| m != piece);
                moved[k].push(piece);
            }
        }
        let mut changed = vec![false; clusters.len()];
        for ((c, mut members), changed) in clusters.iter_mut().zip(moved).zip(&mut changed) {
            members.sort_unstable();
            if members != c.members {
                *changed = true;
                c.cost = exact_reach(self.pieces, &members, c.center) - c.depth;
                c.members = members;
            }
        }
        changed
    }
}

/// Pieces from which a pass over a region's pieces runs on every core (with `parallel`).
#[cfg(feature = "parallel")]
const PARALLEL_PIECES: usize = 1 << 15;

/// `f` of every piece, in order (on every core with `parallel` for many pieces; the
/// same results either way).
fn map_pieces<T: Send>(pieces: &[Piece], f: impl Fn(&Piece) -> T + Sync) -> Vec<T> {
    #[cfg(feature = "parallel")]
    if pieces.len() >= PARALLEL_PIECES {
        use rayon::prelude::*;
        return pieces.par_iter().with_min_len(4096).map(&f).collect();
    }
    pieces.iter().map(f).collect()
}

/// `f` of every member, in order (as [`map_pieces`]).
fn map_members<T: Send>(members: &[u32], f: impl Fn(u32) -> T + Sync) -> Vec<T> {
    #[cfg(feature = "parallel")]
    if members.len() >= PARALLEL_PIECES {
        use rayon::prelude::*;
        return members
            .par_iter()
            .with_min_len(4096)
            .map(|&m| f(m))
            .collect();
    }
    members.iter().map(|&m| f(m)).collect()
}

/// The largest distance from `center` to a corner of the pieces `members`.
pub(crate) fn exact_reach(pieces: &[Piece], members: &[u32], center: DVec3) -> f64 {
    members
        .iter()
        .map(|&m| reach_squared(&pieces[m as usize], center))
        .fold(0.0, f64::max)
        .sqrt()
}

/// The cluster among `among` that covers `piece` with the least eq. 2 error (the first
/// on ties), or `None` when `among` is empty.
fn cheapest(
    clusters: &[Cluster],
    piece: &Piece,
    among: impl Iterator<Item = usize>,
) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for k in among {
        let Some(c) = clusters.get(k) else { continue };
        let cost = reach_squared(piece, c.center).sqrt() - c.depth + c.bias;
        let better = |(b, j): (f64, usize)| match cost.total_cmp(&b) {
            std::cmp::Ordering::Less => true,
            std::cmp::Ordering::Equal => k < j,
            std::cmp::Ordering::Greater => false,
        };
        if best.is_none_or(better) {
            best = Some((cost, k));
        }
    }
    best.map(|(_, k)| k)
}

/// Per cluster, itself and every cluster that could cover one of its pieces with a
/// smaller error than it does: `j` is a neighbour of `k` when
/// `|c_k − c_j| ≤ reach_k + cost_k + depth_j` (a piece within `reach_k` of `c_k` costs at
/// most `cost_k` there, and costs less at `j` only within `cost_k + depth_j` of `c_j`).
fn neighbours(clusters: &[Cluster], reach: impl Fn(usize) -> f64) -> Vec<Vec<u32>> {
    (0..clusters.len())
        .map(|k| {
            let ck = &clusters[k];
            let limit = reach(k) + ck.cost.max(0.0) + ck.bias;
            (0..clusters.len())
                .filter(|&j| {
                    j == k
                        || ck.center.distance(clusters[j].center)
                            <= (limit + clusters[j].depth - clusters[j].bias) * (1.0 + 1e-9)
                })
                .map(|j| j as u32)
                .collect()
        })
        .collect()
}

/// Up to `n` representatives of `positions` far from each other (each the farthest from
/// the previous), for lower bounds of reaches.
fn far_chain(region: &Region<'_>, positions: &[u32], n: usize) -> Vec<u32> {
    let Some(&first) = positions.first() else {
        return Vec::new();
    };
    let mut chain = vec![first];
    let mut from = centroid(region.rep(first));
    for _ in 0..n {
        let next = positions.iter().copied().max_by(|&a, &b| {
            centroid(region.rep(a))
                .distance_squared(from)
                .total_cmp(&centroid(region.rep(b)).distance_squared(from))
                .then(b.cmp(&a))
        });
        let Some(next) = next else { break };
        if chain.contains(&next) {
            break;
        }
        chain.push(next);
        from = centroid(region.rep(next));
    }
    chain
}
