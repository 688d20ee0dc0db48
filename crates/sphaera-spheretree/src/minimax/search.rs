//! The discrete search: which few candidate centres, each expanded to a common reach
//! beyond the surface, cover every representative piece.
//!
//! For a standoff `e`, candidate `c` (centre `x_c`, signed depth `s_c`) covers piece `r`
//! when the sphere about `x_c` of radius `s_c + e` contains the piece's corners, that is
//! when the piece's *threshold* `t(c, r) = max_corner |corner − x_c| − s_c` is at most
//! `e` (the paper's expand step, section 5.3, with eq. 2's error). Whether `k` candidates
//! cover every piece at `e` is a set-cover question; it is answered by a depth-first
//! search that always branches on the uncovered piece with the fewest candidates covering
//! it (the most constrained), trying first the candidates that cover the most uncovered
//! pieces, with a bound on the number of search nodes. The smallest `e` the search
//! answers yes to is found by bisection.
//!
//! The search sees only representatives (a subset of the pieces) and candidates at their
//! own positions; what it returns is a starting point that the continuous refinement
//! ([`super::refine`]) then improves on every piece.

use super::candidates::Candidate;
use super::pieces::{Piece, reach_squared};

/// Bisection steps of the standoff at most (the refinement that follows moves every
/// centre anyway; a finer standoff buys little).
const BISECTION_STEPS: usize = 16;

/// Search nodes per decision at most.
const NODE_BUDGET: usize = 4_000;

/// The thresholds of every candidate on every representative, row by candidate.
pub(crate) struct Thresholds {
    reps: usize,
    cands: usize,
    /// `values[c * reps + r]`.
    values: Vec<f32>,
}

impl Thresholds {
    /// The thresholds of `candidates` on `reps`.
    pub(crate) fn new(reps: &[Piece], candidates: &[Candidate]) -> Self {
        let values = candidates
            .iter()
            .flat_map(|c| {
                reps.iter()
                    .map(move |r| (reach_squared(r, c.center).sqrt() - c.depth) as f32)
            })
            .collect();
        Self {
            reps: reps.len(),
            cands: candidates.len(),
            values,
        }
    }

    fn row(&self, c: usize) -> &[f32] {
        &self.values[c * self.reps..(c + 1) * self.reps]
    }

    /// A standoff below which some representative is covered by no candidate.
    fn lower(&self) -> f32 {
        (0..self.reps)
            .map(|r| {
                (0..self.cands)
                    .map(|c| self.values[c * self.reps + r])
                    .fold(f32::INFINITY, f32::min)
            })
            .fold(f32::NEG_INFINITY, f32::max)
    }

    /// A standoff at which one candidate covers every representative.
    fn upper(&self) -> f32 {
        (0..self.cands)
            .map(|c| {
                self.row(c)
                    .iter()
                    .copied()
                    .fold(f32::NEG_INFINITY, f32::max)
            })
            .fold(f32::INFINITY, f32::min)
    }

    /// At most `k` candidates covering every representative at standoff `e`, if the
    /// search finds them (`beam` options tried per branching, the best first).
    pub(crate) fn cover_at(&self, e: f32, k: usize, beam: usize) -> Option<Vec<usize>> {
        let words = self.reps.div_ceil(64);
        let mut sets = vec![0_u64; self.cands * words];
        let mut counts = vec![0_u32; self.reps];
        for c in 0..self.cands {
            let set = &mut sets[c * words..(c + 1) * words];
            for (w, chunk) in self.row(c).chunks(64).enumerate() {
                let mut word = 0_u64;
                for (b, &t) in chunk.iter().enumerate() {
                    word |= u64::from(t <= e) << b;
                }
                set[w] = word;
            }
            for (r, count) in counts.iter_mut().enumerate() {
                *count += (set[r / 64] >> (r % 64) & 1) as u32;
            }
        }
        if counts.contains(&0) {
            return None;
        }
        let mut uncovered = vec![u64::MAX; words];
        if !self.reps.is_multiple_of(64) {
            uncovered[words - 1] = (1_u64 << (self.reps % 64)) - 1;
        }
        let largest = (0..self.cands)
            .map(|c| {
                sets[c * words..(c + 1) * words]
                    .iter()
                    .map(|w| w.count_ones())
                    .sum::<u32>()
            })
            .max()
            .unwrap_or(0);
        let mut search = Search {
            sets: &sets,
            words,
            largest,
            counts: &counts,
            beam: beam.max(1),
            budget: NODE_BUDGET,
            chosen: Vec::new(),
        };
        search.dfs(&uncovered, k).then_some(search.chosen)
    }

    /// The smallest standoff (to the bisection's resolution) at which the search finds at
    /// most `k` candidates covering every representative, and those candidates.
    pub(crate) fn smallest_cover(&self, k: usize, beam: usize) -> (f32, Vec<usize>) {
        let (mut lo, mut hi) = (self.lower(), self.upper());
        let single = (0..self.cands)
            .min_by(|&a, &b| {
                let worst = |c| {
                    self.row(c)
                        .iter()
                        .copied()
                        .fold(f32::NEG_INFINITY, f32::max)
                };
                worst(a).total_cmp(&worst(b)).then(a.cmp(&b))
            })
            .map_or_else(Vec::new, |c| vec![c]);
        if k == 0 || self.cands == 0 || self.reps == 0 {
            return (hi, single);
        }
        let mut best = (hi, single);
        if let Some(found) = self.cover_at(lo, k, beam) {
            return (lo, found);
        }
        for _ in 0..BISECTION_STEPS {
            let gap = hi - lo;
            if gap.is_nan() || gap <= 2e-3 * hi.abs().max(lo.abs()) {
                break;
            }
            let mid = 0.5 * (lo + hi);
            match self.cover_at(mid, k, beam) {
                Some(found) => {
                    hi = mid;
                    best = (mid, found);
                }
                None => lo = mid,
            }
        }
        best
    }

    /// The fewest candidates (at most `k`) the search finds covering every representative
    /// at standoff `e`, or `None` when it finds no cover of `k`.
    pub(crate) fn fewest_at(&self, e: f32, k: usize, beam: usize) -> Option<Vec<usize>> {
        (1..=k).find_map(|n| self.cover_at(e, n, beam))
    }
}

/// The depth-first search of one decision.
struct Search<'a> {
    sets: &'a [u64],
    words: usize,
    /// The most representatives one candidate covers.
    largest: u32,
    counts: &'a [u32],
    beam: usize,
    budget: usize,
    chosen: Vec<usize>,
}

impl Search<'_> {
    fn set(&self, c: usize) -> &[u64] {
        &self.sets[c * self.words..(c + 1) * self.words]
    }

    /// Whether `left` more candidates cover `uncovered` (then [`Search::chosen`] holds
    /// the whole cover).
    fn dfs(&mut self, uncovered: &[u64], left: usize) -> bool {
        let remaining: u32 = uncovered.iter().map(|w| w.count_ones()).sum();
        if remaining == 0 {
            return true;
        }
        if left == 0 || self.budget == 0 {
            return false;
        }
        self.budget -= 1;
        // The most constrained uncovered representative.
        let mut pick = (u32::MAX, usize::MAX);
        for (w, &word) in uncovered.iter().enumerate() {
            let mut bits = word;
            while bits != 0 {
                let r = w * 64 + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                if self.counts[r] < pick.0 {
                    pick = (self.counts[r], r);
                }
            }
        }
        if pick.1 == usize::MAX {
            return false;
        }
        let (word, bit) = (pick.1 / 64, pick.1 % 64);
        let cands = self.sets.len() / self.words.max(1);
        let mut ranked: Vec<(u32, usize)> = (0..cands)
            .filter(|&c| self.set(c)[word] >> bit & 1 == 1)
            .map(|c| {
                let gain = self
                    .set(c)
                    .iter()
                    .zip(uncovered)
                    .map(|(s, u)| (s & u).count_ones())
                    .sum();
                (gain, c)
            })
            .collect();
        ranked.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        // Even the largest set `left` times cannot cover what remains: no cover.
        if (self.largest as usize).saturating_mul(left) < remaining as usize {
            return false;
        }
        for &(_, c) in ranked.iter().take(self.beam) {
            let next: Vec<u64> = uncovered
                .iter()
                .zip(self.set(c))
                .map(|(u, s)| u & !s)
                .collect();
            self.chosen.push(c);
            if self.dfs(&next, left - 1) {
                return true;
            }
            self.chosen.pop();
            if self.budget == 0 {
                return false;
            }
        }
        false
    }
}
