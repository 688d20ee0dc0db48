//! A uniform spatial hash grid over points, for fixed-radius neighbour searches.
//!
//! Points are renumbered into "slots" sorted by cell, so each occupied cell is a range of
//! slots and a neighbourhood is at most 27 ranges. All outputs are deterministic and the
//! same with or without the `parallel` feature.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

use glam::DVec3;
use smallvec::SmallVec;

/// Integer cell coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct CellKey([i64; 3]);

impl Hash for CellKey {
    fn hash<H: Hasher>(&self, state: &mut H) {
        // One well-mixed word (so the trivial hasher below is enough).
        let [x, y, z] = self.0.map(|c| c as u64);
        let mut h = x.wrapping_mul(0x9e37_79b9_7f4a_7c15)
            ^ y.wrapping_mul(0xc2b2_ae3d_27d4_eb4f)
            ^ z.wrapping_mul(0x1656_67b1_9e37_79f9);
        h = (h ^ (h >> 33)).wrapping_mul(0xff51_afd7_ed55_8ccd);
        state.write_u64(h ^ (h >> 33));
    }
}

/// Passes through the pre-mixed word of [`CellKey`] (falls back to FNV-style mixing for
/// other input, which `CellKey` never produces).
#[derive(Default)]
struct PassThroughHasher(u64);

impl Hasher for PassThroughHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn write_u64(&mut self, value: u64) {
        self.0 = value;
    }
}

/// A grid of cubic cells of a given size over a set of points.
#[derive(Debug)]
pub(super) struct Grid {
    /// `slots[s]` = index of the point in slot `s` (points sorted by cell, then index).
    pub slots: Vec<u32>,
    /// Occupied cells in key order: `(key, first slot, one past the last slot)`.
    cells: Vec<(CellKey, u32, u32)>,
    /// Cell key → position in `cells`.
    lookup: HashMap<CellKey, u32, BuildHasherDefault<PassThroughHasher>>,
}

impl Grid {
    /// The grid of `points` with cells of edge `cell` (finite, positive).
    ///
    /// `points.len()` must fit a `u32` (the samplers cap it far below).
    pub fn new(points: &[DVec3], cell: f64) -> Self {
        let origin = points
            .iter()
            .fold(DVec3::splat(f64::INFINITY), |m, &p| m.min(p));
        let inverse = 1.0 / cell;
        // `as i64` saturates, so far-away points share an extreme cell: still correct
        // (only slower), since neighbour candidates are always distance-checked.
        let key = |p: DVec3| {
            CellKey(
                ((p - origin) * inverse)
                    .floor()
                    .to_array()
                    .map(|c| c as i64),
            )
        };
        let mut keyed: Vec<(CellKey, u32)> = points
            .iter()
            .enumerate()
            .map(|(i, &p)| (key(p), i as u32))
            .collect();
        keyed.sort_unstable();
        let mut cells: Vec<(CellKey, u32, u32)> = Vec::new();
        for (slot, &(k, _)) in keyed.iter().enumerate() {
            let slot = slot as u32;
            match cells.last_mut() {
                Some(last) if last.0 == k => last.2 = slot + 1,
                _ => cells.push((k, slot, slot + 1)),
            }
        }
        let lookup = cells
            .iter()
            .enumerate()
            .map(|(c, &(k, _, _))| (k, c as u32))
            .collect();
        Self {
            slots: keyed.into_iter().map(|(_, i)| i).collect(),
            cells,
            lookup,
        }
    }

    /// Number of occupied cells.
    pub fn cell_count(&self) -> usize {
        self.cells.len()
    }

    /// Slot range of occupied cell `c`.
    pub fn cell_slots(&self, c: usize) -> std::ops::Range<usize> {
        self.cells
            .get(c)
            .map_or(0..0, |&(_, start, end)| start as usize..end as usize)
    }

    /// Slot ranges of the (up to 27) occupied cells around occupied cell `c`, in key order.
    pub fn neighbourhood(&self, c: usize) -> SmallVec<[std::ops::Range<usize>; 27]> {
        let mut ranges = SmallVec::new();
        let Some(&(CellKey([x, y, z]), _, _)) = self.cells.get(c) else {
            return ranges;
        };
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let k = CellKey([
                        x.saturating_add(dx),
                        y.saturating_add(dy),
                        z.saturating_add(dz),
                    ]);
                    if let Some(&n) = self.lookup.get(&k) {
                        ranges.push(self.cell_slots(n as usize));
                    }
                }
            }
        }
        ranges
    }
}

/// `f(i)` for `i` in `0..n`, collected in order; in parallel with the `parallel` feature
/// (the result is the same either way).
pub(super) fn map_indices<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n).into_par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        (0..n).map(f).collect()
    }
}

/// The smallest distance between two of `points` (`f64::INFINITY` for fewer than two).
///
/// Starts with cells of edge `guess` (a good guess of the answer) and doubles the cell
/// until some pair lies within a cell's reach.
pub(super) fn min_distance(points: &[DVec3], guess: f64) -> f64 {
    if points.len() < 2 {
        return f64::INFINITY;
    }
    let mut cell = if guess.is_finite() && guess > 0.0 {
        guess
    } else {
        1.0
    };
    loop {
        let grid = Grid::new(points, cell);
        let per_cell = map_indices(grid.cell_count(), |c| {
            let mut best = f64::INFINITY;
            let ranges = grid.neighbourhood(c);
            for s in grid.cell_slots(c) {
                let p = points[grid.slots[s] as usize];
                for t in ranges.iter().flat_map(Clone::clone).filter(|&t| t > s) {
                    best = best.min(p.distance_squared(points[grid.slots[t] as usize]));
                }
            }
            best
        });
        let best = per_cell.into_iter().fold(f64::INFINITY, f64::min);
        // Every pair closer than `cell` is in neighbouring cells, so a pair found below
        // `cell` is the closest; one cell holding everything also ends the search.
        if best < cell * cell || grid.cell_count() == 1 || !cell.is_finite() {
            return best.sqrt();
        }
        cell *= 2.0;
    }
}
