//! Mesh mapping (section 3.1.1): every face rasterized conservatively onto a square grid
//! over the image of the bounding sphere, each cell recording the faces that touch it.

use glam::DVec2;

use crate::SilhouetteError;
use crate::caps::{MAX_FACE_GRID_ENTRIES, check_resolution};

/// A square grid of `resolution²` cells over `[−1, 1]²`, cell `(i, j)` (column, row from
/// the bottom) at index `j · resolution + i`, with the faces touching each cell.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaceGrid {
    resolution: usize,
    /// Cell `c`'s faces are `faces[start[c]..start[c + 1]]`, ascending.
    start: Vec<u32>,
    faces: Vec<u32>,
}

/// A clamped cell coordinate (in `[0, resolution − 1]`, or NaN) as an index.
fn index(x: f64) -> usize {
    // Invariant: `x` is clamped to `[0, resolution − 1]` (or NaN, which gives 0, as a
    // cast to `usize` would), so it fits an `i64` and is not negative.
    x as i64 as usize
}

/// The cell span `[lo, hi]` (clamped) that the interval `[a, b]` of image coordinates
/// touches.
fn span(a: f64, b: f64, resolution: usize) -> Option<(usize, usize)> {
    let scale = resolution as f64 / 2.0;
    let (lo, hi) = ((a + 1.0) * scale, (b + 1.0) * scale);
    let last = resolution as f64 - 1.0;
    if hi < 0.0 || lo > resolution as f64 {
        return None;
    }
    Some((index(lo.clamp(0.0, last)), index(hi.clamp(0.0, last))))
}

/// One edge of a triangle, from `a` to `b`, set up for crossing horizontal lines.
#[derive(Clone, Copy)]
struct Edge {
    a: DVec2,
    /// `b − a`.
    delta: DVec2,
    /// The edge's y-range.
    low: f64,
    high: f64,
    /// Not horizontal (a horizontal edge adds only its ends, taken as corners).
    sloped: bool,
}

impl Edge {
    fn new(a: DVec2, b: DVec2) -> Self {
        let delta = DVec2::new(b.x - a.x, b.y - a.y);
        Self {
            a,
            delta,
            low: a.y.min(b.y),
            high: a.y.max(b.y),
            sloped: delta.y.abs() > 0.0,
        }
    }

    /// Where the edge crosses the line at height `y`, if it does.
    fn crossing(&self, y: f64) -> Option<f64> {
        (self.sloped && y >= self.low && y <= self.high)
            .then(|| self.a.x + (y - self.a.y) * self.delta.x / self.delta.y)
    }
}

/// The x-extent of the closed triangle with corners `t` and edges `edges` within the
/// horizontal band `[lo, hi]` (`None` when it misses the band): the triangle's part in
/// the band is convex, so it covers every x between the extremes of its corners in the
/// band and its edges' crossings of the band's two lines.
#[inline]
fn extent_in_band(t: &[DVec2; 3], edges: &[Edge; 3], lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    // As `f64::min` and `f64::max` (a NaN is skipped; the sign of a zero extreme does not
    // change the cells), without their NaN handling.
    let mut take = |x: f64| {
        if x < min {
            min = x;
        }
        if x > max {
            max = x;
        }
    };
    for corner in t {
        if corner.y >= lo && corner.y <= hi {
            take(corner.x);
        }
    }
    for edge in edges {
        for y in [lo, hi] {
            if let Some(x) = edge.crossing(y) {
                take(x);
            }
        }
    }
    (min <= max).then_some((min, max))
}

/// The cell of image point `p` on a `resolution²` grid over `[−1, 1]²` (clamped).
pub(crate) fn cell_index(p: DVec2, resolution: usize) -> usize {
    let scale = resolution as f64 / 2.0;
    // Clamped first, so truncation is the floor.
    let index = |x: f64| ((x + 1.0) * scale).clamp(0.0, resolution as f64 - 1.0) as usize;
    index(p.y) * resolution + index(p.x)
}

/// The cells a projected triangle touches (conservatively), row by row from the bottom:
/// `row(j, a, b)` for the cells `a..=b` (never empty) of row `j`.
pub(crate) fn rows_of_triangle(
    t: [DVec2; 3],
    resolution: usize,
    mut row: impl FnMut(usize, usize, usize),
) {
    let Some(bounds) = Bounds::new(t, resolution) else {
        return;
    };
    let rows = Rows::new(t, bounds, resolution);
    for j in bounds.j0..=bounds.j1 {
        if let Some((a, b)) = rows.row(j) {
            row(j, a, b);
        }
    }
}

/// Raises every cell of `marks` (a `resolution²` grid of 0, 1 and 2) that the projected
/// triangle `t` touches to at least `mark` (1 or 2): as [`rows_of_triangle`] with `max`,
/// but a row whose cells in the triangle's bounding box are all at least `mark` already
/// is left alone, unrasterized (the triangle's cells in a row lie in its bounding box).
pub(crate) fn mark_triangle(t: [DVec2; 3], resolution: usize, marks: &mut [u8], mark: u8) {
    debug_assert!(mark == 1 || mark == 2, "marks are 0, 1 and 2");
    let Some(bounds) = Bounds::new(t, resolution) else {
        return;
    };
    let width = bounds.i1 - bounds.i0 + 1;
    let covered = |j: usize, marks: &[u8]| at_least(marks, j * resolution + bounds.i0, width, mark);
    // Set up the edges only for a triangle with some row left to mark.
    let Some(first) = (bounds.j0..=bounds.j1).find(|&j| !covered(j, marks)) else {
        return;
    };
    let rows = Rows::new(t, bounds, resolution);
    for j in first..=bounds.j1 {
        if j > first && covered(j, marks) {
            continue;
        }
        if let Some((a, b)) = rows.row(j) {
            raise(marks, j * resolution + a, b - a + 1, mark);
        }
    }
}

/// 1 in each byte from byte `len` (below 8) on: the bytes past a run of `len` cells, which
/// pass a test and which an update leaves alone.
fn beyond(len: usize) -> u64 {
    ONES << (8 * len)
}

/// 1 in every byte of a word.
const ONES: u64 = 0x0101_0101_0101_0101;

/// Bit 0 of each byte of `word` (bytes 0, 1 or 2): whether it is at least `mark` (1: either
/// bit; 2: bit 1).
fn passes(word: u64, mark: u8) -> u64 {
    (if mark == 1 {
        word | (word >> 1)
    } else {
        word >> 1
    }) & ONES
}

/// Whether the `len` cells of `marks` (0, 1 or 2 each) from `start` are all at least
/// `mark` (1 or 2). Up to 7 cells are tested at once, as the bytes of a word.
#[inline]
fn at_least(marks: &[u8], start: usize, len: usize, mark: u8) -> bool {
    if len < 8
        && let Some(word) = marks.get(start..).and_then(<[u8]>::first_chunk::<8>)
    {
        return passes(u64::from_le_bytes(*word), mark) | beyond(len) == ONES;
    }
    marks[start..start + len].iter().all(|&m| m >= mark)
}

/// Raises the `len` cells of `marks` (0, 1 or 2 each) from `start` to at least `mark` (1
/// or 2). Up to 7 cells are raised at once, as the bytes of a word.
#[inline]
fn raise(marks: &mut [u8], start: usize, len: usize, mark: u8) {
    if len < 8
        && let Some(bytes) = marks
            .get_mut(start..)
            .and_then(<[u8]>::first_chunk_mut::<8>)
    {
        let word = u64::from_le_bytes(*bytes);
        // 1 in each of the `len` bytes below `mark`, 0 elsewhere.
        let low = (passes(word, mark) | beyond(len)) ^ ONES;
        // Bytes below 2 are 0 or 1 and become 2; bytes below 1 are 0 and become 1.
        let raised = if mark == 2 {
            (word & !(low * 0xff)) | (low * 2)
        } else {
            word | low
        };
        *bytes = raised.to_le_bytes();
        return;
    }
    for m in &mut marks[start..start + len] {
        *m = (*m).max(mark);
    }
}

/// The cell spans `i0..=i1` (columns) and `j0..=j1` (rows) of a projected triangle's
/// bounding box, and the box.
#[derive(Clone, Copy)]
struct Bounds {
    lo: DVec2,
    hi: DVec2,
    i0: usize,
    i1: usize,
    j0: usize,
    j1: usize,
}

impl Bounds {
    /// `None` when the box misses the grid.
    #[inline]
    fn new(t: [DVec2; 3], resolution: usize) -> Option<Self> {
        let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
        let (i0, i1) = span(lo.x, hi.x, resolution)?;
        let (j0, j1) = span(lo.y, hi.y, resolution)?;
        Some(Self {
            lo,
            hi,
            i0,
            i1,
            j0,
            j1,
        })
    }
}

/// A projected triangle set up for conservative rasterization row by row: its bounding
/// box, its edges and the margin of touching.
struct Rows {
    t: [DVec2; 3],
    resolution: usize,
    bounds: Bounds,
    /// Within one cell's span: it touches that cell.
    single: bool,
    edges: [Edge; 3],
    /// A relative margin by which each row's band and extent are widened, on the side of
    /// touching.
    margin: f64,
}

impl Rows {
    #[inline]
    fn new(t: [DVec2; 3], bounds: Bounds, resolution: usize) -> Self {
        let (lo, hi) = (bounds.lo, bounds.hi);
        Self {
            t,
            resolution,
            bounds,
            single: bounds.i0 == bounds.i1 && bounds.j0 == bounds.j1,
            edges: [0, 1, 2].map(|k| Edge::new(t[k], t[(k + 1) % 3])),
            margin: 1e-12 * (1.0 + hi.abs().max(lo.abs()).max_element()),
        }
    }

    /// The cells `a..=b` the triangle touches in row `j` (of `j0..=j1`): those its extent
    /// in the row's band reaches.
    #[inline]
    fn row(&self, j: usize) -> Option<(usize, usize)> {
        let Bounds { i0, i1, .. } = self.bounds;
        if self.single {
            return Some((i0, i0));
        }
        let (size, margin) = (2.0 / self.resolution as f64, self.margin);
        let band = -1.0 + j as f64 * size;
        let (x0, x1) = extent_in_band(&self.t, &self.edges, band - margin, band + size + margin)?;
        let (a, b) = span(x0 - margin, x1 + margin, self.resolution)?;
        let (a, b) = (a.max(i0), b.min(i1));
        (a <= b).then_some((a, b))
    }
}

impl FaceGrid {
    /// The grid of the projected triangles `triangles` (image coordinates).
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::InvalidResolution`] for a zero resolution;
    /// [`SilhouetteError::InvalidParameter`] for a resolution above
    /// [`MAX_RESOLUTION`](crate::MAX_RESOLUTION) (named `"resolution"`) or more (face,
    /// cell) pairs than [`MAX_FACE_GRID_ENTRIES`] (named `"faces × cells"`), both before
    /// the grid is allocated.
    pub fn new(triangles: &[[DVec2; 3]], resolution: usize) -> Result<Self, SilhouetteError> {
        Self::with_cap(triangles, resolution, MAX_FACE_GRID_ENTRIES)
    }

    /// [`FaceGrid::new`] with at most `cap` (face, cell) pairs.
    fn with_cap(
        triangles: &[[DVec2; 3]],
        resolution: usize,
        cap: usize,
    ) -> Result<Self, SilhouetteError> {
        check_resolution(resolution)?;
        // At most 4,096² cells: checked above.
        let cells = resolution * resolution;
        // Two passes over the faces: count each cell's faces, then fill them in face order
        // (so each cell's faces ascend). The count stops as soon as it passes the cap, so
        // that the list is never allocated beyond it.
        let mut count = vec![0_u32; cells + 1];
        let mut total = 0_usize;
        for &t in triangles {
            rows_of_triangle(t, resolution, |j, a, b| {
                total += b - a + 1;
                let row = j * resolution;
                for n in &mut count[row + a + 1..=row + b + 1] {
                    *n += 1;
                }
            });
            // A face adds at most `cells` pairs, so `total` (and every count) stays far
            // below 2³² until this check refuses it.
            if total > cap {
                return Err(SilhouetteError::InvalidParameter {
                    name: "faces × cells",
                    value: total as f64,
                    requirement: "at most `MAX_FACE_GRID_ENTRIES` (2^28 face–cell pairs): \
                                  use a coarser resolution or fewer faces",
                });
            }
        }
        for c in 0..cells {
            count[c + 1] += count[c];
        }
        let mut fill = count.clone();
        let mut faces = vec![0_u32; total];
        for (f, &t) in triangles.iter().enumerate() {
            rows_of_triangle(t, resolution, |j, a, b| {
                let row = j * resolution;
                for next in &mut fill[row + a..=row + b] {
                    faces[*next as usize] = f as u32;
                    *next += 1;
                }
            });
        }
        Ok(Self {
            resolution,
            start: count,
            faces,
        })
    }

    /// Cells a side.
    #[must_use]
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// The faces touching cell `c`, ascending.
    #[must_use]
    pub fn faces(&self, c: usize) -> &[u32] {
        &self.faces[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The cell holding image point `p` (clamped to the grid).
    #[must_use]
    pub fn cell_of(&self, p: DVec2) -> usize {
        cell_index(p, self.resolution)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_face_cell_pairs_are_capped_before_the_list_is_allocated() {
        // A triangle over the whole grid touches all of its 16 cells.
        let whole = [
            DVec2::splat(-3.0),
            DVec2::new(3.0, -3.0),
            DVec2::new(0.0, 6.0),
        ];
        let grid = FaceGrid::with_cap(&[whole, whole], 4, 32).expect("at the cap");
        assert_eq!(grid.faces(5), &[0, 1]);
        let error = FaceGrid::with_cap(&[whole, whole, whole], 4, 32).expect_err("past the cap");
        assert!(
            matches!(
                error,
                SilhouetteError::InvalidParameter {
                    name: "faces × cells",
                    ..
                }
            ),
            "{error}"
        );
        assert!(
            error.to_string().contains("MAX_FACE_GRID_ENTRIES"),
            "{error}"
        );
    }
}
