//! Sets of points for expand-select's greedy covers: points are numbered in space-filling
//! (Morton) order, so a sphere's cover is a short run of words and a set stores only the
//! words between its first and last member.

use glam::DVec3;

/// Bits per word.
const WORD: usize = 64;

/// A set of point positions stored over the words between its first and last member.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct WindowBits {
    first: usize,
    words: Vec<u64>,
}

impl WindowBits {
    /// The set of `positions` (any order; at least one).
    pub fn new(positions: &[u32]) -> Self {
        let low = positions.iter().min().map_or(0, |&p| p as usize / WORD);
        let high = positions.iter().max().map_or(0, |&p| p as usize / WORD);
        let mut words = vec![0; high + 1 - low];
        for &p in positions {
            let p = p as usize;
            words[p / WORD - low] |= 1 << (p % WORD);
        }
        Self { first: low, words }
    }

    /// The set of a full-length set's members, its window not trimmed (fine as the
    /// `other` of [`Self::is_subset_of`]).
    pub fn from_full(full: &[u64]) -> Self {
        Self {
            first: 0,
            words: full.to_vec(),
        }
    }

    /// The window's words with their indices.
    fn indexed(&self) -> impl Iterator<Item = (usize, u64)> + '_ {
        self.words
            .iter()
            .enumerate()
            .map(|(k, &bits)| (self.first + k, bits))
    }

    /// The members also in `full` (a full-length set), the window trimmed to them; `None`
    /// when there are none.
    pub fn masked(&self, full: &[u64]) -> Option<Self> {
        let word = |k: usize| self.words[k] & full.get(self.first + k).copied().unwrap_or(0);
        let start = (0..self.words.len()).position(|k| word(k) != 0)?;
        let end = (start..self.words.len()).rev().find(|&k| word(k) != 0)? + 1;
        Some(Self {
            first: self.first + start,
            words: (start..end).map(word).collect(),
        })
    }

    /// Members in all.
    /// The first word index the set can touch.
    pub fn first_word(&self) -> usize {
        self.first
    }

    /// One past the last word index the set can touch.
    pub fn end_word(&self) -> usize {
        self.first + self.words.len()
    }

    pub fn count(&self) -> u32 {
        self.words.iter().map(|w| w.count_ones()).sum()
    }

    /// Whether every member is in `other`. Windows are trimmed to their first and last
    /// members ([`Self::new`] and [`Self::masked`] leave them so), so a window reaching
    /// outside `other`'s has a member outside it.
    pub fn is_subset_of(&self, other: &Self) -> bool {
        let Some(offset) = self.first.checked_sub(other.first) else {
            return false;
        };
        let Some(theirs) = other.words.get(offset..offset + self.words.len()) else {
            return false;
        };
        self.words
            .iter()
            .zip(theirs)
            .all(|(mine, their)| mine & !their == 0)
    }

    /// Removes the set's members from `full`.
    pub fn remove_from(&self, full: &mut [u64]) {
        for (w, bits) in self.indexed() {
            if let Some(slot) = full.get_mut(w) {
                *slot &= !bits;
            }
        }
    }

    /// Adds the set's members to `full`.
    pub fn add_to(&self, full: &mut [u64]) {
        for (w, bits) in self.indexed() {
            if let Some(slot) = full.get_mut(w) {
                *slot |= bits;
            }
        }
    }
}

/// A full-length set of `n` positions, all members.
pub(super) fn all_of(n: usize) -> Vec<u64> {
    let mut words = vec![u64::MAX; n.div_ceil(WORD)];
    if let Some(last) = words.last_mut()
        && !n.is_multiple_of(WORD)
    {
        *last = (1 << (n % WORD)) - 1;
    }
    words
}

/// For each point, its position in Morton (Z) order of the points' bounding box, ties by
/// index: nearby points get nearby positions.
pub(super) fn morton_positions(points: &[DVec3]) -> Vec<u32> {
    let (low, high) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let extent = (high - low).max_element();
    let scale = if extent > 0.0 && extent.is_finite() {
        f64::from((1u32 << 21) - 1) / extent
    } else {
        0.0
    };
    let code = |p: DVec3| {
        let q = ((p - low) * scale).max(DVec3::ZERO);
        // In range by construction; `as` saturates anything rounding pushed past it.
        spread(q.x as u64) | spread(q.y as u64) << 1 | spread(q.z as u64) << 2
    };
    let mut order: Vec<(u64, u32)> = points
        .iter()
        .enumerate()
        .map(|(i, &p)| (code(p), i as u32))
        .collect();
    order.sort_unstable();
    let mut positions = vec![0; points.len()];
    for (position, &(_, i)) in order.iter().enumerate() {
        positions[i as usize] = position as u32;
    }
    positions
}

/// The low 21 bits of `v`, two zero bits after each.
fn spread(v: u64) -> u64 {
    let mut x = v.min((1 << 21) - 1);
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn full_of(n: usize, members: &[u32]) -> Vec<u64> {
        let mut full = vec![0; n.div_ceil(WORD)];
        WindowBits::new(members).add_to(&mut full);
        full
    }

    proptest! {
        /// The window operations agree with plain sets.
        #[test]
        fn window_sets_match_plain_sets(
            a in prop::collection::btree_set(0u32..300, 1..40),
            b in prop::collection::btree_set(0u32..300, 1..40),
            mask in prop::collection::btree_set(0u32..300, 0..200),
        ) {
            let n: usize = 300;
            let (va, vb, vm): (Vec<u32>, Vec<u32>, Vec<u32>) = (
                a.iter().copied().collect(),
                b.iter().copied().collect(),
                mask.iter().copied().collect(),
            );
            let (wa, wb) = (WindowBits::new(&va), WindowBits::new(&vb));
            prop_assert_eq!(wa.is_subset_of(&wb), a.is_subset(&b));
            let full_mask = if vm.is_empty() { vec![0; n.div_ceil(WORD)] } else { full_of(n, &vm) };
            let subset = a.intersection(&mask).all(|p| b.contains(p));
            match wa.masked(&full_mask) {
                Some(m) => {
                    prop_assert_eq!(m.count() as usize, a.intersection(&mask).count());
                    prop_assert_eq!(m.is_subset_of(&wb), subset);
                }
                None => prop_assert_eq!(a.intersection(&mask).count(), 0),
            }
            let mut removed = full_mask.clone();
            wa.remove_from(&mut removed);
            let left = mask.difference(&a).count();
            prop_assert_eq!(removed.iter().map(|w| w.count_ones() as usize).sum::<usize>(), left);
        }
    }

    #[test]
    fn all_of_has_exactly_n_members() {
        for n in [1, 63, 64, 65, 130] {
            assert_eq!(
                all_of(n)
                    .iter()
                    .map(|w| w.count_ones() as usize)
                    .sum::<usize>(),
                n
            );
        }
    }

    #[test]
    fn morton_positions_are_a_permutation_and_local() {
        let points: Vec<DVec3> = (0..512)
            .map(|i| DVec3::new(f64::from(i % 8), f64::from((i / 8) % 8), f64::from(i / 64)))
            .collect();
        let positions = morton_positions(&points);
        let mut sorted = positions.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..512).collect::<Vec<u32>>());
        // The 2×2×2 block at the origin takes the first eight positions.
        let block: Vec<u32> = points
            .iter()
            .zip(&positions)
            .filter(|(p, _)| p.max_element() < 2.0)
            .map(|(_, &k)| k)
            .collect();
        assert!(block.iter().all(|&k| k < 8), "{block:?}");
    }
}
