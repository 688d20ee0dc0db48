//! A uniform grid of boxes: items (points, spheres, any box) listed in the cells their
//! boxes meet, for "which items can be near here" queries. The workspace's one dense
//! grid (the medial approximation's samples, the coverage certificate's spheres, the
//! experiments' sphere sets); the caller chooses the cell size, as each knows its items.
//!
//! Cells are stored as compressed rows (`starts[c]..starts[c + 1]` of one item list), each
//! cell's items in increasing index. Positions outside the grid fall in the nearest
//! cell: the border cells reach out to infinity, so an item never goes missing.

use glam::DVec3;

use crate::QueryError;

/// The most cells a [`UniformGrid`] may have: 2²⁶ (67 million), about 800 MB of counts
/// and row starts while it is built. More `dims` are refused
/// ([`QueryError::InvalidParameter`] named `"dims"`) before anything is allocated.
pub const MAX_GRID_CELLS: usize = 1 << 26;

/// Items bucketed by the cells of a uniform grid that their boxes meet.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::DVec3;
/// use sphaera_query::grid::UniformGrid;
///
/// let points = [DVec3::ZERO, DVec3::splat(0.9), DVec3::new(0.1, 0.1, 0.0)];
/// let grid = UniformGrid::new(
///     DVec3::ZERO,
///     0.5,
///     [2, 2, 2],
///     points.iter().map(|&p| Some((p, p))),
/// )?;
/// assert_eq!(grid.items_at(DVec3::splat(0.05)), &[0, 2]);
/// let mut near = Vec::new();
/// grid.items_meeting(DVec3::splat(0.6), DVec3::splat(5.0), &mut near);
/// assert_eq!(near, [1]);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Debug)]
pub struct UniformGrid {
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    /// Cell `c`'s items are `items[starts[c]..starts[c + 1]]`, ascending.
    starts: Vec<u32>,
    items: Vec<u32>,
}

impl UniformGrid {
    /// `dims` cells of edge `cell` from `origin`; item `i` (the `i`-th box, `(lo, hi)`) is
    /// listed in every cell its box meets, clamped into the grid. A `None` box is listed
    /// nowhere (an item the caller leaves out, a non-finite one).
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidParameter`] for a cell edge that is not finite and positive,
    /// a zero dimension or more than [`MAX_GRID_CELLS`] cells (checked before anything is
    /// allocated); [`QueryError::TooManyItems`] for more item listings than 32-bit indices
    /// address.
    pub fn new(
        origin: DVec3,
        cell: f64,
        dims: [usize; 3],
        boxes: impl IntoIterator<Item = Option<(DVec3, DVec3)>>,
    ) -> Result<Self, QueryError> {
        if !(cell.is_finite() && cell > 0.0 && origin.is_finite()) {
            return Err(QueryError::InvalidParameter {
                name: "cell",
                value: cell,
                requirement: "finite and positive, from a finite origin",
            });
        }
        let cells = dims
            .iter()
            .try_fold(1_usize, |n, &d| n.checked_mul(d))
            .filter(|&n| n > 0 && n <= MAX_GRID_CELLS)
            .ok_or(QueryError::InvalidParameter {
                name: "dims",
                value: dims.iter().map(|&d| d as f64).product(),
                requirement: "at least one cell per axis, at most `grid::MAX_GRID_CELLS` \
                              (2^26) cells in all",
            })?;
        let mut grid = Self {
            origin,
            cell,
            dims,
            starts: Vec::new(),
            items: Vec::new(),
        };
        // Each item's cell range, then two passes: count, then fill in item order (so each
        // cell's items ascend).
        let ranges: Vec<Option<([usize; 3], [usize; 3])>> = boxes
            .into_iter()
            .map(|b| b.map(|(lo, hi)| (grid.cell_of(lo), grid.cell_of(hi))))
            .collect();
        let mut counts = vec![0_u64; cells + 1];
        for &(a, b) in ranges.iter().flatten() {
            grid.for_cells(a, b, |c| counts[c + 1] += 1);
        }
        for c in 0..cells {
            counts[c + 1] += counts[c];
        }
        let total = counts[cells];
        if total > u64::from(u32::MAX) || ranges.len() > u32::MAX as usize {
            return Err(QueryError::TooManyItems {
                operation: "uniform grid",
                count: usize::try_from(total).unwrap_or(usize::MAX),
            });
        }
        // Both fit a u32: checked above.
        grid.starts = counts.iter().map(|&c| c as u32).collect();
        let mut next = grid.starts.clone();
        grid.items = vec![0; total as usize];
        for (i, range) in ranges.iter().enumerate() {
            if let Some((a, b)) = *range {
                let (items, next) = (&mut grid.items, &mut next);
                Self::cells(dims, a, b, |c| {
                    items[next[c] as usize] = i as u32;
                    next[c] += 1;
                });
            }
        }
        Ok(grid)
    }

    /// Cells per axis.
    #[must_use]
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The cell of `p`, clamped into the grid (a NaN coordinate to the first cell).
    #[must_use]
    pub fn cell_of(&self, p: DVec3) -> [usize; 3] {
        let q = ((p - self.origin) / self.cell).to_array();
        // Saturating float-to-integer conversion: negative values and NaN give 0.
        std::array::from_fn(|axis| (q[axis].floor().max(0.0) as usize).min(self.dims[axis] - 1))
    }

    /// The items listed in the cell of `p`, ascending: every item whose box contains `p`
    /// is among them.
    #[must_use]
    pub fn items_at(&self, p: DVec3) -> &[u32] {
        let c = self.index(self.cell_of(p));
        &self.items[self.starts[c] as usize..self.starts[c + 1] as usize]
    }

    /// Appends to `out` the items listed in the cells the box `[lo, hi]` meets, ascending
    /// and once each: every item whose box meets `[lo, hi]` is among them.
    pub fn items_meeting(&self, lo: DVec3, hi: DVec3, out: &mut Vec<u32>) {
        let start = out.len();
        let (a, b) = (self.cell_of(lo), self.cell_of(hi));
        self.for_cells(a, b, |c| {
            out.extend_from_slice(
                &self.items[self.starts[c] as usize..self.starts[c + 1] as usize],
            );
        });
        out[start..].sort_unstable();
        let mut kept = start;
        for k in start..out.len() {
            if k == start || out[k] != out[kept - 1] {
                out[kept] = out[k];
                kept += 1;
            }
        }
        out.truncate(kept);
    }

    /// Calls `f` with every item listed in the cells the box `[lo, hi]` meets, cell by
    /// cell, ascending within a cell (an item whose box spans several of those cells comes
    /// once per cell): the unsorted, cheaper form of [`UniformGrid::items_meeting`].
    pub fn visit_meeting(&self, lo: DVec3, hi: DVec3, mut f: impl FnMut(u32)) {
        let (a, b) = (self.cell_of(lo), self.cell_of(hi));
        self.for_cells(a, b, |c| {
            for &i in &self.items[self.starts[c] as usize..self.starts[c + 1] as usize] {
                f(i);
            }
        });
    }

    /// The number of cells the box `[lo, hi]` meets (clamped into the grid): the cost of
    /// a visit, to choose a scan instead when it is larger than the items.
    #[must_use]
    pub fn cells_meeting(&self, lo: DVec3, hi: DVec3) -> usize {
        let (a, b) = (self.cell_of(lo), self.cell_of(hi));
        (0..3).map(|axis| b[axis] - a[axis] + 1).product()
    }

    /// The number of item listings (an item once per cell it is listed in).
    #[must_use]
    pub fn listings(&self) -> usize {
        self.items.len()
    }

    fn index(&self, [x, y, z]: [usize; 3]) -> usize {
        (z * self.dims[1] + y) * self.dims[0] + x
    }

    /// Calls `f` with the index of every cell from `a` to `b` (inclusive, per axis).
    fn for_cells(&self, a: [usize; 3], b: [usize; 3], f: impl FnMut(usize)) {
        Self::cells(self.dims, a, b, f);
    }

    fn cells(dims: [usize; 3], a: [usize; 3], b: [usize; 3], mut f: impl FnMut(usize)) {
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                for x in a[0]..=b[0] {
                    f((z * dims[1] + y) * dims[0] + x);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::UniformGrid;
    use glam::DVec3;

    /// A small seeded generator (no dependency).
    fn points(n: usize, seed: u64) -> Vec<DVec3> {
        let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        let mut unit = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1_u64 << 53) as f64
        };
        (0..n)
            .map(|_| DVec3::new(unit(), unit(), unit()) * 3.0 - DVec3::ONE)
            .collect()
    }

    /// Every item whose box meets a query box is listed, against a scan of all items,
    /// for boxes inside, across and outside the grid.
    #[test]
    fn every_box_meeting_a_query_is_listed() {
        let centers = points(300, 3);
        let radii: Vec<f64> = (0..300)
            .map(|i| 0.01 + 0.3 * f64::from(i % 7) / 7.0)
            .collect();
        let grid = UniformGrid::new(
            DVec3::ZERO,
            0.125,
            [8, 4, 2],
            centers
                .iter()
                .zip(&radii)
                .map(|(&c, &r)| Some((c - DVec3::splat(r), c + DVec3::splat(r)))),
        )
        .expect("a grid");
        let corners = points(400, 5);
        for pair in corners.chunks(2) {
            let (lo, hi) = (pair[0].min(pair[1]), pair[0].max(pair[1]));
            let mut listed = Vec::new();
            grid.items_meeting(lo, hi, &mut listed);
            assert!(listed.windows(2).all(|w| w[0] < w[1]));
            for (i, (&c, &r)) in centers.iter().zip(&radii).enumerate() {
                let (a, b) = (c - DVec3::splat(r), c + DVec3::splat(r));
                if a.cmple(hi).all() && lo.cmple(b).all() {
                    assert!(listed.binary_search(&(i as u32)).is_ok(), "item {i}");
                }
            }
            for &p in pair {
                let at = grid.items_at(p);
                for (i, (&c, &r)) in centers.iter().zip(&radii).enumerate() {
                    if (p - c).abs().cmple(DVec3::splat(r)).all() {
                        assert!(at.binary_search(&(i as u32)).is_ok(), "item {i} at {p}");
                    }
                }
            }
        }
    }

    #[test]
    fn bad_cells_are_refused_and_left_out_items_listed_nowhere() {
        let none = std::iter::empty::<Option<(DVec3, DVec3)>>;
        assert!(UniformGrid::new(DVec3::ZERO, 0.0, [1, 1, 1], none()).is_err());
        assert!(UniformGrid::new(DVec3::ZERO, f64::NAN, [1, 1, 1], none()).is_err());
        assert!(UniformGrid::new(DVec3::ZERO, 1.0, [0, 1, 1], none()).is_err());
        assert!(UniformGrid::new(DVec3::ZERO, 1.0, [usize::MAX, 2, 1], none()).is_err());
        let grid = UniformGrid::new(
            DVec3::ZERO,
            1.0,
            [1, 1, 1],
            [None, Some((DVec3::ZERO, DVec3::ZERO))],
        )
        .expect("a grid");
        assert_eq!(grid.items_at(DVec3::splat(f64::NAN)), &[1]);
    }
}
