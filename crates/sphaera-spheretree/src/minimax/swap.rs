//! Swaps: leaving a local optimum of the exact refinement by giving one child's place to
//! the worst. A child is removed (its pieces go to its neighbours), the worst child is
//! split in two, and the result is refined; the swap is kept when the worst error falls.

use glam::DVec3;

use super::cluster::{Cluster, Region, worst};
use super::pieces::centroid;
use super::polish::Reach;
use crate::SphereTreeError;

/// The clusters `of` and those that could take pieces from them or give them pieces (the
/// neighbour condition of [`super::cluster`], both ways), ascending.
fn near(clusters: &[Cluster], of: &[usize]) -> Vec<usize> {
    let reach = |c: &Cluster| c.cost + c.depth;
    (0..clusters.len())
        .filter(|&j| {
            of.iter().any(|&s| {
                let (cs, cj) = (&clusters[s], &clusters[j]);
                let apart = cs.center.distance(cj.center);
                j == s
                    || apart <= reach(cs) + cs.cost.max(0.0) + cj.depth
                    || apart <= reach(cj) + cj.cost.max(0.0) + cs.depth
            })
        })
        .collect()
}

/// Removals tried in a row without lowering the worst error before the swaps stop: the
/// first in [`Region::removal_order`] nearly always succeeds while any does.
const SWAP_PATIENCE: usize = 6;

/// Children whose centres are nearest a removed child's, to which [`Region::removal_order`]
/// offers its pieces.
const RANKING_NEIGHBOURS: usize = 12;

impl Region<'_> {
    /// Swaps, kept while the worst error falls: the worst child is split in two and
    /// another child removed (its pieces handed to the others), then the changed children
    /// are refined. The children to remove are tried in the order of
    /// [`Region::removal_order`] (the likeliest first), until one lowers the worst error
    /// (then again from the new children) or [`SWAP_PATIENCE`] in a row do not, and at most
    /// `per_child` times the children's count in all. `clusters` hold pieces as members.
    pub(crate) fn swap(
        &self,
        clusters: &mut Vec<Cluster>,
        per_child: usize,
        rounds: usize,
    ) -> Result<(), SphereTreeError> {
        if clusters.len() < 3 {
            return Ok(());
        }
        let mut budget = per_child.saturating_mul(clusters.len());
        'configurations: while budget > 0 {
            let before = worst(clusters);
            let w = (0..clusters.len())
                .max_by(|&a, &b| {
                    clusters[a]
                        .cost
                        .total_cmp(&clusters[b].cost)
                        .then(b.cmp(&a))
                })
                .unwrap_or(0);
            let Some([a, b]) = self.split_pieces(&clusters[w]) else {
                return Ok(());
            };
            let order = self.removal_order(clusters, w, [&a, &b]);
            for (tried, &(_, removed)) in order.iter().enumerate() {
                if tried >= SWAP_PATIENCE || budget == 0 {
                    break 'configurations;
                }
                budget -= 1;
                let mut trial: Vec<Cluster> = clusters
                    .iter()
                    .enumerate()
                    .filter(|&(i, _)| i != w && i != removed)
                    .map(|(_, c)| c.clone())
                    .collect();
                trial.push(a.clone());
                trial.push(b.clone());
                let mut changed = self.hand_out(&mut trial, &clusters[removed].members);
                let len = changed.len();
                changed[len - 2..].fill(true);
                self.refine_changed(&mut trial, &changed, rounds)?;
                if worst(&trial) < before - 1e-9 * before.abs() && trial.len() == clusters.len() {
                    *clusters = trial;
                    continue 'configurations;
                }
            }
            break;
        }
        Ok(())
    }

    /// The children other than the worst `w`, in the order their removal is tried: by the
    /// worst error right after their pieces are handed to the others (the split halves
    /// `halves` in the worst's place, and each piece offered to the [`RANKING_NEIGHBOURS`]
    /// centres nearest its child's), before any centre moves; the least first.
    fn removal_order(
        &self,
        clusters: &[Cluster],
        w: usize,
        halves: [&Cluster; 2],
    ) -> Vec<(f64, usize)> {
        let cost = |c: &Cluster, m: u32| {
            super::pieces::reach_squared(&self.pieces[m as usize], c.center).sqrt() - c.depth
        };
        // The errors of the children that stay (and of the halves), largest first: a
        // removal leaves the largest of them but its own.
        let mut kept: Vec<(f64, usize)> = clusters
            .iter()
            .enumerate()
            .filter(|&(i, _)| i != w)
            .map(|(i, c)| (c.cost, i))
            .chain(halves.iter().map(|h| (h.cost, usize::MAX)))
            .collect();
        kept.sort_by(|a, b| b.0.total_cmp(&a.0));
        let mut order: Vec<(f64, usize)> = (0..clusters.len())
            .filter(|&r| r != w)
            .map(|r| {
                let mut score = kept
                    .iter()
                    .find(|&&(_, i)| i != r)
                    .map_or(f64::NEG_INFINITY, |k| k.0);
                let center = clusters[r].center;
                let mut near: Vec<(f64, usize)> = (0..clusters.len())
                    .filter(|&i| i != w && i != r)
                    .map(|i| (clusters[i].center.distance_squared(center), i))
                    .collect();
                let count = RANKING_NEIGHBOURS.min(near.len());
                if count < near.len() {
                    near.select_nth_unstable_by(count, |a, b| {
                        a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))
                    });
                    near.truncate(count);
                }
                let others: Vec<&Cluster> = near
                    .iter()
                    .map(|&(_, i)| &clusters[i])
                    .chain(halves)
                    .collect();
                for &m in &clusters[r].members {
                    let least = others
                        .iter()
                        .map(|c| cost(c, m))
                        .fold(f64::INFINITY, f64::min);
                    score = score.max(least);
                }
                (score, r)
            })
            .collect();
        order.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        order
    }

    /// Adds children until there are `k` (or none can be split): the worst child with two
    /// pieces or more is split in two, and the pieces of the two halves and their
    /// neighbours are reassigned among them; that is kept only when it does not raise the
    /// worst error over the split alone, whose halves reach no farther than the child
    /// did. So the worst error never rises, and a count asked for is a count given.
    pub(crate) fn complete(
        &self,
        clusters: &mut Vec<Cluster>,
        k: usize,
    ) -> Result<(), SphereTreeError> {
        while clusters.len() < k {
            let Some(w) = (0..clusters.len())
                .filter(|&i| clusters[i].members.len() > 1)
                .max_by(|&a, &b| {
                    clusters[a]
                        .cost
                        .total_cmp(&clusters[b].cost)
                        .then(b.cmp(&a))
                })
            else {
                return Ok(());
            };
            let Some([a, b]) = self.split_pieces(&clusters[w]) else {
                return Ok(());
            };
            clusters[w] = a;
            clusters.push(b);
            let halves = [w, clusters.len() - 1];
            self.polish_these(clusters, &halves)?;
            let plain = worst(clusters);
            let near = near(clusters, &halves);
            let saved: Vec<Cluster> = near.iter().map(|&j| clusters[j].clone()).collect();
            self.exchange(clusters, halves, &near);
            if worst(clusters) > plain {
                for (&j, c) in near.iter().zip(saved) {
                    clusters[j] = c;
                }
            }
        }
        Ok(())
    }

    /// After a split into `halves`: each of their pieces to the cheapest of `near` (the
    /// halves and their neighbours), and each piece of a neighbour to a half that covers
    /// it with less error than its own cluster does (the others were already assigned
    /// among themselves). No cluster is left empty; the costs of the changed ones are
    /// measured again (their centres stay: the refinement that follows moves them).
    fn exchange(&self, clusters: &mut [Cluster], halves: [usize; 2], near: &[usize]) {
        let cost = |c: &Cluster, m: u32| {
            super::pieces::reach_squared(&self.pieces[m as usize], c.center).sqrt() - c.depth
        };
        let mut changed = vec![false; clusters.len()];
        let mut moves: Vec<(u32, usize, usize)> = Vec::new();
        for &from in near {
            let from_half = halves.contains(&from);
            for &m in &clusters[from].members {
                let here = cost(&clusters[from], m);
                let targets: &[usize] = if from_half { near } else { &halves };
                let mut best = (here, from);
                for &to in targets {
                    let there = cost(&clusters[to], m);
                    if there < best.0 {
                        best = (there, to);
                    }
                }
                if best.1 != from {
                    moves.push((m, from, best.1));
                }
            }
        }
        for (m, from, to) in moves {
            if clusters[from].members.len() <= 1 {
                continue;
            }
            if let Ok(slot) = clusters[from].members.binary_search(&m) {
                clusters[from].members.remove(slot);
                let at = clusters[to].members.partition_point(|&x| x < m);
                clusters[to].members.insert(at, m);
                changed[from] = true;
                changed[to] = true;
            }
        }
        for (c, &changed) in clusters.iter_mut().zip(&changed) {
            if changed {
                c.cost = super::cluster::exact_reach(self.pieces, &c.members, c.center) - c.depth;
            }
        }
    }

    /// Gives each of `pieces` to the cluster that covers it with the least error; returns,
    /// per cluster, whether it took any.
    fn hand_out(&self, clusters: &mut [Cluster], pieces: &[u32]) -> Vec<bool> {
        let mut took = vec![false; clusters.len()];
        for &m in pieces {
            let piece = &self.pieces[m as usize];
            let mut best = (f64::INFINITY, 0);
            for (k, c) in clusters.iter().enumerate() {
                let cost = super::pieces::reach_squared(piece, c.center).sqrt() - c.depth;
                if cost < best.0 {
                    best = (cost, k);
                }
            }
            if let Some(c) = clusters.get_mut(best.1) {
                c.members.push(m);
                took[best.1] = true;
            }
        }
        for (c, _) in clusters.iter_mut().zip(&took).filter(|(_, t)| **t) {
            c.members.sort_unstable();
            c.cost = super::cluster::exact_reach(self.pieces, &c.members, c.center) - c.depth;
        }
        took
    }

    /// The two halves of a cluster of pieces (two-means on the pieces' centroids, seeded
    /// by a far pair), each with the best candidate centre grown from its own pieces (or
    /// its centroid's neighbourhood), polished.
    fn split_pieces(&self, cluster: &Cluster) -> Option<[Cluster; 2]> {
        let members = &cluster.members;
        if members.len() < 2 {
            return None;
        }
        let at = |m: u32| centroid(&self.pieces[m as usize]);
        let farthest_from = |x: DVec3| {
            members
                .iter()
                .copied()
                .max_by(|&a, &b| {
                    at(a)
                        .distance_squared(x)
                        .total_cmp(&at(b).distance_squared(x))
                        .then(b.cmp(&a))
                })
                .map_or(x, at)
        };
        let first = farthest_from(cluster.center);
        let (mut a, mut b) = (first, farthest_from(first));
        let (mut left, mut right) = (Vec::new(), Vec::new());
        for _ in 0..6 {
            left.clear();
            right.clear();
            for &m in members {
                let p = at(m);
                if p.distance_squared(a) <= p.distance_squared(b) {
                    left.push(m);
                } else {
                    right.push(m);
                }
            }
            if left.is_empty() || right.is_empty() {
                return None;
            }
            a = left.iter().map(|&m| at(m)).sum::<DVec3>() / left.len() as f64;
            b = right.iter().map(|&m| at(m)).sum::<DVec3>() / right.len() as f64;
        }
        let own = Some((cluster.center, cluster.depth));
        Some([self.fit_pieces(left, own), self.fit_pieces(right, own)])
    }

    /// The best candidate centre for a set of pieces (ascending), among the candidates
    /// grown from them (all candidates when none was) and `fallback` (a centre with its
    /// signed depth), with its exact cost.
    fn fit_pieces(&self, members: Vec<u32>, fallback: Option<(DVec3, f64)>) -> Cluster {
        let mine: Vec<usize> = (0..self.candidates.len())
            .filter(|&c| members.binary_search(&self.origins[c]).is_ok())
            .collect();
        let pool: Vec<usize> = if mine.is_empty() {
            (0..self.candidates.len()).collect()
        } else {
            mine
        };
        let origin = members
            .iter()
            .map(|&m| centroid(&self.pieces[m as usize]))
            .sum::<DVec3>()
            / members.len().max(1) as f64;
        let reach = Reach::new(self.pieces, self.corners, &members, origin);
        let mut best = (f64::INFINITY, 0);
        for c in pool {
            let cand = self.candidates[c];
            let cost = reach.at(cand.center) - cand.depth;
            if cost < best.0 {
                best = (cost, c);
            }
        }
        let cand = self.candidates[best.1];
        let (mut center, mut depth, mut cost) = (cand.center, cand.depth, best.0);
        // The split cluster's own centre covers these pieces too.
        if let Some((own, own_depth)) = fallback {
            let own_cost = reach.at(own) - own_depth;
            if own_cost < cost {
                (center, depth, cost) = (own, own_depth, own_cost);
            }
        }
        drop(reach);
        Cluster {
            center,
            depth,
            members,
            cost,
            bias: 0.0,
        }
    }
}
