//! Swaps: leaving a local optimum of the exact refinement by giving one child's place to
//! the worst. A child is removed (its pieces go to its neighbours), the worst child is
//! split in two, and the result is refined; the swap is kept when the worst error falls.

use glam::DVec3;

use super::cluster::{Cluster, Region, worst};
use super::pieces::centroid;
use super::polish::Reach;
use crate::SphereTreeError;

impl Region<'_> {
    /// Swaps (every other child removed in turn while the worst is split), kept while the
    /// worst error falls, for at most `passes` passes over the children. `clusters` hold
    /// pieces as members.
    pub(crate) fn swap(
        &self,
        clusters: &mut Vec<Cluster>,
        passes: usize,
        rounds: usize,
    ) -> Result<(), SphereTreeError> {
        if clusters.len() < 3 {
            return Ok(());
        }
        for _ in 0..passes {
            let mut improved = false;
            let mut removed = 0;
            while removed < clusters.len() {
                let before = worst(clusters);
                let w = (0..clusters.len())
                    .max_by(|&a, &b| {
                        clusters[a]
                            .cost
                            .total_cmp(&clusters[b].cost)
                            .then(b.cmp(&a))
                    })
                    .unwrap_or(0);
                if removed == w {
                    removed += 1;
                    continue;
                }
                let Some([a, b]) = self.split_pieces(&clusters[w]) else {
                    return Ok(());
                };
                let mut trial: Vec<Cluster> = clusters
                    .iter()
                    .enumerate()
                    .filter(|&(i, _)| i != w && i != removed)
                    .map(|(_, c)| c.clone())
                    .collect();
                trial.push(a);
                trial.push(b);
                self.hand_out(&mut trial, &clusters[removed].members);
                self.refine(&mut trial, rounds)?;
                if worst(&trial) < before - 1e-9 * before.abs() && trial.len() == clusters.len() {
                    *clusters = trial;
                    improved = true;
                } else {
                    removed += 1;
                }
            }
            if !improved {
                break;
            }
        }
        Ok(())
    }

    /// Gives each of `pieces` to the cluster that covers it with the least error.
    fn hand_out(&self, clusters: &mut [Cluster], pieces: &[u32]) {
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
            }
        }
        for c in clusters.iter_mut() {
            c.members.sort_unstable();
            c.cost = super::cluster::exact_reach(self.pieces, &c.members, c.center) - c.depth;
        }
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
        Some([self.fit_pieces(left), self.fit_pieces(right)])
    }

    /// The best candidate centre for a set of pieces (ascending), among the candidates
    /// grown from them (all candidates when none was), with its exact cost.
    fn fit_pieces(&self, members: Vec<u32>) -> Cluster {
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
        let reach = Reach::new(self.pieces, &members, origin);
        let mut best = (f64::INFINITY, 0);
        for c in pool {
            let cand = self.candidates[c];
            let cost = reach.at(cand.center) - cand.depth;
            if cost < best.0 {
                best = (cost, c);
            }
        }
        let cand = self.candidates[best.1];
        Cluster {
            center: cand.center,
            depth: cand.depth,
            members,
            cost: best.0,
            bias: 0.0,
        }
    }
}
