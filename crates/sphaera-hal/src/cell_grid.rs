//! A grid of cells over a closed ring that answers most point-inclusion queries without
//! the tree: a cell no edge touches is wholly inside or outside (found once, at build);
//! a cell a few edges cross keeps its centre's answer, and a query counts the edges that
//! cross the segment from that centre to it.
//!
//! The answer is exact: cells are closed boxes between stored grid lines, located with
//! coordinate comparisons; an edge is listed in every cell it touches (decided with
//! exact orientations); a crossing is counted only when all four orientations are
//! non-zero; and the centres' answers are found at build by stepping from centre to
//! centre the same way, from one answer of the tree's walk (the walk again wherever a
//! step cannot decide). A crowded cell (more than 8 edges, where coastlines bunch up)
//! gets a grid of its own over its box and its edges, one level deep, from a budget
//! shared over the ring. Anything else (a centre on the outline, a query on an edge's
//! line or a segment through a vertex, a crowded cell of a cell's grid) is left to the
//! walk, so the grid's answer is always the walk's.
//!
//! The idea is a planar form of the cell index of Google's S2 geometry library (cells
//! that keep their edges, clipped, and whether their centre is inside).

use glam::DVec2;

use crate::lens::coord;
use crate::query2::Containment;

/// Grid cells per edge of the ring (the grid's size).
const CELLS_PER_EDGE: usize = 4;

/// The most cells a grid has (16 MiB of cell codes).
pub(crate) const MAX_CELLS: usize = 1 << 22;

/// Rings with fewer edges go straight to the walk.
const MIN_EDGES: usize = 8;

/// Cells with more edges than this get a grid of their own (one level deep).
const SUBDIVIDE_ABOVE: usize = 8;

/// Cells with more edges than this, and no grid of their own, are left to the walk.
const MAX_CELL_EDGES: usize = 32;

/// The most cell–edge incidences per edge (a budget against long diagonal edges); a grid
/// over budget is rebuilt four times coarser, and after a few tries not built at all.
const INCIDENCES_PER_EDGE: usize = 12;

/// The most bytes a grid holds per edge, the crowded cells' grids included (they share
/// one more budget of as many cells and incidences): 4 cells of 4 bytes, 12 incidences of
/// 4 bytes and as many mixed cells of 32 bytes, twice (a bound, far above what outlines
/// need), plus the lines.
#[cfg(test)]
const MAX_BYTES_PER_EDGE: usize =
    2 * (CELLS_PER_EDGE * 4 + INCIDENCES_PER_EDGE * (4 + size_of::<MixedCell>()));

/// Cell codes: no edge touches the cell and it is outside, or inside; or the walk answers;
/// or (with this bit) the cell has a grid of its own, the index in the other bits.
const OUTSIDE: u32 = u32::MAX;
const INSIDE: u32 = u32::MAX - 1;
const WALK: u32 = u32::MAX - 2;
const SUBGRID: u32 = 1 << 31;

/// A cell some edges touch: its centre, the centre's answer, its edges' range.
#[derive(Clone, Copy, Debug, PartialEq)]
struct MixedCell {
    centre: DVec2,
    inside: bool,
    start: u32,
    end: u32,
}

/// The grid of a closed ring (see the module's documentation).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CellGrid {
    /// The grid's vertical lines, left to right (`columns + 1`), and horizontal ones.
    /// Invariant: at least two of each (`shape` gives at least one column and one row),
    /// so `len() - 1`, `len() - 2` and `[0]` below never underflow or go out of bounds.
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Cells per unit, to guess a query's column and row before the exact check.
    per_unit: DVec2,
    /// One code per cell, row-major from the bottom: [`OUTSIDE`], [`INSIDE`], [`WALK`] or
    /// an index into `mixed`.
    cells: Vec<u32>,
    mixed: Vec<MixedCell>,
    /// The edges of the mixed cells: the position `p` of the edge `p → p + 1`.
    edges: Vec<u32>,
    /// The grids of crowded cells (top level only).
    subgrids: Vec<CellGrid>,
}

/// What the grids of crowded cells may still spend, over the whole ring: cells and
/// cell–edge pairs.
struct Budget {
    cells: usize,
    incidences: usize,
}

impl CellGrid {
    /// The grid over the ring `ordered` (its first point repeated last), with `walk` the
    /// exact answer at any point; `None` for a ring too small to need one or whose edges
    /// would touch too many cells.
    pub(crate) fn build(ordered: &[DVec2], walk: impl Fn(DVec2) -> Containment) -> Option<Self> {
        let edges = ordered.len().checked_sub(1)?;
        if edges < MIN_EDGES || ordered.iter().any(|p| !p.is_finite()) {
            return None;
        }
        let (lo, hi) = ordered
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let mut budget = Budget {
            cells: CELLS_PER_EDGE * edges,
            incidences: INCIDENCES_PER_EDGE * edges,
        };
        Self::over(ordered, None, (lo, hi), &walk, Some(&mut budget))
    }

    /// The grid over the box `lo..hi` of the edges `subset` (every edge for `None`); the
    /// crowded cells get grids of their own from `budget` (none for `None`).
    fn over(
        ordered: &[DVec2],
        subset: Option<&[u32]>,
        (lo, hi): (DVec2, DVec2),
        walk: &impl Fn(DVec2) -> Containment,
        budget: Option<&mut Budget>,
    ) -> Option<Self> {
        // `build` only calls this for rings of at least `MIN_EDGES` edges.
        let edges = subset.map_or(ordered.len() - 1, <[u32]>::len);
        let mut target = (CELLS_PER_EDGE * edges).min(MAX_CELLS);
        for _ in 0..3 {
            let (columns, rows) = shape(hi - lo, target);
            let xs = lines(lo.x, hi.x, columns);
            let ys = lines(lo.y, hi.y, rows);
            let limit = INCIDENCES_PER_EDGE * edges;
            if let Some(touching) = incidences(ordered, subset, &xs, &ys, limit) {
                return Some(Self::classify(ordered, xs, ys, &touching, walk, budget));
            }
            target /= 4;
        }
        None
    }

    /// The cells' codes from the (cell, edge) pairs sorted by cell.
    fn classify(
        ordered: &[DVec2],
        xs: Vec<f64>,
        ys: Vec<f64>,
        touching: &[(u32, u32)],
        walk: &impl Fn(DVec2) -> Containment,
        mut budget: Option<&mut Budget>,
    ) -> Self {
        let (columns, rows) = (xs.len() - 1, ys.len() - 1);
        let per_unit = DVec2::new(
            per_unit(xs[0], xs[columns], columns),
            per_unit(ys[0], ys[rows], rows),
        );
        let centre = |cell: usize| {
            let (i, j) = (cell % columns, cell / columns);
            DVec2::new(midpoint(xs[i], xs[i + 1]), midpoint(ys[j], ys[j + 1]))
        };
        let answers = centre_answers(ordered, (columns, rows), &centre, touching, walk);
        // Cells no edge touches take their centre's answer (never on the outline).
        let mut cells: Vec<u32> = answers
            .iter()
            .map(|&a| if a == Some(true) { INSIDE } else { OUTSIDE })
            .collect();
        let mut mixed = Vec::new();
        let mut edges = Vec::new();
        let mut subgrids = Vec::new();
        let mut positions = Vec::new();
        for group in touching.chunk_by(|a, b| a.0 == b.0) {
            // `chunk_by` yields non-empty groups.
            let cell = group[0].0 as usize;
            if group.len() > SUBDIVIDE_ABOVE
                && let Some(budget) = budget.as_deref_mut()
                && budget.cells >= CELLS_PER_EDGE * group.len()
                && budget.incidences >= INCIDENCES_PER_EDGE * group.len()
            {
                let (i, j) = (cell % columns, cell / columns);
                let corners = (DVec2::new(xs[i], ys[j]), DVec2::new(xs[i + 1], ys[j + 1]));
                positions.clear();
                positions.extend(group.iter().map(|&(_, p)| p));
                if let Some(grid) = Self::over(ordered, Some(&positions), corners, walk, None) {
                    // A grid's shape may round a few cells past its target.
                    budget.cells = budget.cells.saturating_sub(grid.cells.len());
                    budget.incidences = budget.incidences.saturating_sub(grid.edges.len());
                    cells[cell] = SUBGRID | subgrids.len() as u32;
                    subgrids.push(grid);
                    continue;
                }
            }
            if group.len() > MAX_CELL_EDGES {
                cells[cell] = WALK;
                continue;
            }
            let c = centre(cell);
            let Some(inside) = answers[cell] else {
                // The centre is on the outline.
                cells[cell] = WALK;
                continue;
            };
            let start = edges.len() as u32;
            edges.extend(group.iter().map(|&(_, p)| p));
            cells[cell] = mixed.len() as u32;
            mixed.push(MixedCell {
                centre: c,
                inside,
                start,
                end: edges.len() as u32,
            });
        }
        Self {
            xs,
            ys,
            per_unit,
            cells,
            mixed,
            edges,
            subgrids,
        }
    }

    /// The answer at `x` (inside the ring's bounding box), or `None` when the walk must
    /// give it.
    #[inline]
    pub(crate) fn containment(&self, ordered: &[DVec2], x: DVec2) -> Option<Containment> {
        let columns = self.xs.len() - 1;
        let i = locate(&self.xs, x.x, (x.x - self.xs[0]) * self.per_unit.x);
        let j = locate(&self.ys, x.y, (x.y - self.ys[0]) * self.per_unit.y);
        let code = self.cells[j * columns + i];
        let cell = match code {
            OUTSIDE => return Some(Containment::Outside),
            INSIDE => return Some(Containment::Inside),
            WALK => return None,
            sub if sub & SUBGRID != 0 => {
                return self.subgrids[(sub & !SUBGRID) as usize].containment(ordered, x);
            }
            m => &self.mixed[m as usize],
        };
        let c = coord(cell.centre);
        let q = coord(x);
        let mut inside = cell.inside;
        for &p in &self.edges[cell.start as usize..cell.end as usize] {
            inside ^= crosses(ordered, p, c, q)?;
        }
        Some(if inside {
            Containment::Inside
        } else {
            Containment::Outside
        })
    }

    /// The bytes the grid holds.
    #[cfg(test)]
    fn bytes(&self) -> usize {
        (self.xs.len() + self.ys.len()) * size_of::<f64>()
            + self.cells.len() * size_of::<u32>()
            + self.mixed.len() * size_of::<MixedCell>()
            + self.edges.len() * size_of::<u32>()
            + self.subgrids.iter().map(CellGrid::bytes).sum::<usize>()
    }
}

/// Whether the edge `p → p + 1` crosses the segment `c → q` (in its interior, at one
/// point), with exact orientations; `None` when that cannot be told so simply: `c` or `q`
/// on the edge's line, or the segment through one of its ends.
#[inline]
fn crosses(
    ordered: &[DVec2],
    p: u32,
    c: robust::Coord<f64>,
    q: robust::Coord<f64>,
) -> Option<bool> {
    let (a, b) = (coord(ordered[p as usize]), coord(ordered[p as usize + 1]));
    let (o1, o2) = (robust::orient2d(a, b, c), robust::orient2d(a, b, q));
    if (o1 > 0.0 && o2 > 0.0) || (o1 < 0.0 && o2 < 0.0) {
        return Some(false);
    }
    let (o3, o4) = (robust::orient2d(c, q, a), robust::orient2d(c, q, b));
    if (o3 > 0.0 && o4 > 0.0) || (o3 < 0.0 && o4 < 0.0) {
        return Some(false);
    }
    if o1 == 0.0 || o2 == 0.0 || o3 == 0.0 || o4 == 0.0 {
        return None;
    }
    Some(true)
}

/// Every cell centre's answer (`None`: on the outline), found by stepping from centre to
/// centre — up the first column, then along each row — and counting the edges that cross
/// each step (a step stays inside its two cells, so their edges are all it can cross);
/// the walk answers the first centre, and any centre a step cannot decide simply.
fn centre_answers(
    ordered: &[DVec2],
    (columns, rows): (usize, usize),
    centre: &impl Fn(usize) -> DVec2,
    touching: &[(u32, u32)],
    walk: &impl Fn(DVec2) -> Containment,
) -> Vec<Option<bool>> {
    let count = columns * rows;
    // Each cell's edges: `touching[starts[cell]..starts[cell + 1]]`, sorted by position.
    let mut starts = vec![0_usize; count + 1];
    for &(cell, _) in touching {
        starts[cell as usize + 1] += 1;
    }
    for k in 0..count {
        starts[k + 1] += starts[k];
    }
    let edges_of = |cell: usize| &touching[starts[cell]..starts[cell + 1]];
    let step = |from: usize, to: usize, inside: bool| -> Option<bool> {
        let (c, q) = (coord(centre(from)), coord(centre(to)));
        let (mut x, mut y) = (edges_of(from), edges_of(to));
        let mut inside = inside;
        // The two cells' edges merged, each edge once.
        loop {
            let p = match (x.first(), y.first()) {
                (None, None) => return Some(inside),
                (Some(&(_, p)), None) => {
                    x = &x[1..];
                    p
                }
                (None, Some(&(_, p))) => {
                    y = &y[1..];
                    p
                }
                (Some(&(_, p)), Some(&(_, r))) => {
                    if p <= r {
                        x = &x[1..];
                    }
                    if r <= p {
                        y = &y[1..];
                    }
                    p.min(r)
                }
            };
            inside ^= crosses(ordered, p, c, q)?;
        }
    };
    let mut answers: Vec<Option<bool>> = vec![None; count];
    for cell in 0..count {
        let before = if cell % columns == 0 {
            cell.checked_sub(columns)
        } else {
            Some(cell - 1)
        };
        let stepped = before.and_then(|b| answers[b].and_then(|inside| step(b, cell, inside)));
        answers[cell] = stepped.or_else(|| match walk(centre(cell)) {
            Containment::Inside => Some(true),
            Containment::Outside => Some(false),
            Containment::Boundary => None,
        });
    }
    answers
}

/// Columns and rows for about `target` cells of about square shape over `extent`.
fn shape(extent: DVec2, target: usize) -> (usize, usize) {
    let target = target.max(1) as f64;
    let (w, h) = (extent.x, extent.y);
    if !(w > 0.0 && h > 0.0) {
        // A flat ring: one row or one column.
        return if w > 0.0 {
            (target as usize, 1)
        } else if h > 0.0 {
            (1, target as usize)
        } else {
            (1, 1)
        };
    }
    let columns = (target * w / h).sqrt().round().clamp(1.0, target);
    let rows = (target / columns).round().max(1.0);
    (columns as usize, rows as usize)
}

/// `count + 1` lines from `lo` to `hi` (both exact, never decreasing).
fn lines(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    let mut out: Vec<f64> = (0..=count)
        .map(|i| lo + (hi - lo) * (i as f64 / count as f64))
        .collect();
    out[0] = lo;
    out[count] = hi;
    for i in 1..=count {
        out[i] = out[i].clamp(out[i - 1], hi);
    }
    out
}

fn per_unit(lo: f64, hi: f64, count: usize) -> f64 {
    let per = count as f64 / (hi - lo);
    if per.is_finite() { per } else { 0.0 }
}

/// The midpoint of `a ≤ b`, between them.
fn midpoint(a: f64, b: f64) -> f64 {
    (a + (b - a) / 2.0).clamp(a, b)
}

/// The cell between `lines` holding `v` (within the first and last line), from the guess
/// `guess` (cells from the first line), checked with comparisons.
#[inline]
fn locate(lines: &[f64], v: f64, guess: f64) -> usize {
    let last = lines.len() - 2;
    // A negative or NaN guess saturates to 0.
    let mut i = (guess as usize).min(last);
    while i > 0 && v < lines[i] {
        i -= 1;
    }
    while i < last && v > lines[i + 1] {
        i += 1;
    }
    i
}

/// The first and last cell whose closed interval meets `[lo, hi]` (inside the lines),
/// `per` cells a unit.
fn span(lines: &[f64], per: f64, lo: f64, hi: f64) -> (usize, usize) {
    let last = lines.len() - 2;
    let mut first = locate(lines, lo, (lo - lines[0]) * per);
    while first > 0 && lines[first] >= lo {
        first -= 1;
    }
    let mut end = locate(lines, hi, (hi - lines[0]) * per);
    while end < last && lines[end + 1] <= hi {
        end += 1;
    }
    (first, end.max(first))
}

/// Every (cell, edge) pair whose closed cell the edge touches (of the edges `subset`, or
/// all), sorted; `None` beyond `budget` pairs.
fn incidences(
    ordered: &[DVec2],
    subset: Option<&[u32]>,
    xs: &[f64],
    ys: &[f64],
    budget: usize,
) -> Option<Vec<(u32, u32)>> {
    let (columns, rows) = (xs.len() - 1, ys.len() - 1);
    let per_x = per_unit(xs[0], xs[columns], columns);
    let per_y = per_unit(ys[0], ys[rows], rows);
    let every = 0..ordered.len() as u32 - 1;
    let positions: Box<dyn Iterator<Item = u32>> = match subset {
        Some(subset) => Box::new(subset.iter().copied()),
        None => Box::new(every),
    };
    let mut out = Vec::new();
    for p in positions {
        let (a, b) = (ordered[p as usize], ordered[p as usize + 1]);
        let (lo, hi) = (a.min(b), a.max(b));
        let (i0, i1) = span(xs, per_x, lo.x, hi.x);
        let (j0, j1) = span(ys, per_y, lo.y, hi.y);
        // Rounding in the edge's height over a column, generously bounded.
        let slack = 8.0 * f64::EPSILON * (a.y.abs() + b.y.abs() + (b.y - a.y).abs());
        for i in i0..=i1 {
            // A vertical edge spans its whole height in its one column (exact test).
            #[allow(clippy::float_cmp)]
            let vertical = a.x == b.x;
            let (from, to) = if vertical {
                (lo.y, hi.y)
            } else {
                let at = |x: f64| {
                    let t = ((x - a.x) / (b.x - a.x)).clamp(0.0, 1.0);
                    a.y + t * (b.y - a.y)
                };
                let (y0, y1) = (at(xs[i]), at(xs[i + 1]));
                (y0.min(y1) - slack, y0.max(y1) + slack)
            };
            let from = from.max(lo.y);
            let (r0, r1) = span(ys, per_y, from, to.min(hi.y).max(from));
            for j in r0.max(j0)..=r1.min(j1) {
                let (min, max) = (DVec2::new(xs[i], ys[j]), DVec2::new(xs[i + 1], ys[j + 1]));
                if touches(a, b, min, max) {
                    out.push(((j * columns + i) as u32, p));
                    if out.len() > budget {
                        return None;
                    }
                }
            }
        }
    }
    out.sort_unstable();
    Some(out)
}

/// Whether the closed segment `a–b` touches the closed box `min..max` (exact): the boxes
/// overlap and the box's corners are not all strictly on one side of the segment's line.
fn touches(a: DVec2, b: DVec2, min: DVec2, max: DVec2) -> bool {
    if a.x.max(b.x) < min.x || a.x.min(b.x) > max.x || a.y.max(b.y) < min.y || a.y.min(b.y) > max.y
    {
        return false;
    }
    let side = |x: f64, y: f64| robust::orient2d(coord(a), coord(b), coord(DVec2::new(x, y)));
    let corners = [
        side(min.x, min.y),
        side(max.x, min.y),
        side(max.x, max.y),
        side(min.x, max.y),
    ];
    !(corners.iter().all(|&s| s > 0.0) || corners.iter().all(|&s| s < 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_exact_at_the_ends_and_never_decrease() {
        let l = lines(0.1, 0.7, 7);
        assert_eq!((l[0], l[7]), (0.1, 0.7));
        assert!(l.windows(2).all(|w| w[0] <= w[1]));
        let tiny = lines(1.0, 1.0 + f64::EPSILON, 5);
        assert!(tiny.windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn locate_and_span_use_closed_cells() {
        let l = [0.0, 1.0, 2.0, 3.0];
        assert_eq!(locate(&l, 1.0, 1.0), 1);
        assert_eq!(locate(&l, 1.0, 0.0), 0);
        assert_eq!(locate(&l, 3.0, 9.0), 2);
        assert_eq!(locate(&l, 0.0, f64::NAN), 0);
        // A value on a line touches both cells beside it.
        assert_eq!(span(&l, 1.0, 1.0, 1.0), (0, 1));
        assert_eq!(span(&l, 1.0, 0.5, 2.0), (0, 2));
        assert_eq!(span(&l, 1.0, 3.0, 3.0), (2, 2));
        assert_eq!(span(&l, 1.0, 0.0, 0.0), (0, 0));
    }

    #[test]
    fn a_segment_touching_a_corner_touches_the_box() {
        let (min, max) = (DVec2::ZERO, DVec2::ONE);
        assert!(touches(
            DVec2::new(1.0, 1.0),
            DVec2::new(2.0, 3.0),
            min,
            max
        ));
        assert!(touches(
            DVec2::new(2.0, 0.0),
            DVec2::new(0.0, 2.0),
            min,
            max
        ));
        assert!(!touches(
            DVec2::new(2.0, 0.0),
            DVec2::new(0.0, 2.0 + 1e-15),
            DVec2::new(0.0, 0.0),
            DVec2::new(0.99, 0.99)
        ));
        assert!(!touches(
            DVec2::new(1.5, 0.0),
            DVec2::new(3.0, 1.0),
            min,
            max
        ));
    }

    use crate::{HalTree2, Polyline2, contains_brute};

    /// The points where a grid is most fragile: every line crossing, cell centre and
    /// side midpoint, every vertex and edge midpoint, each also an ulp away.
    fn probes(grid: &CellGrid, ordered: &[DVec2]) -> Vec<DVec2> {
        let mut out = Vec::new();
        let (xs, ys) = (&grid.xs, &grid.ys);
        for i in 0..xs.len() {
            for j in 0..ys.len() {
                out.push(DVec2::new(xs[i], ys[j]));
                if i + 1 < xs.len() {
                    out.push(DVec2::new(midpoint(xs[i], xs[i + 1]), ys[j]));
                }
                if j + 1 < ys.len() {
                    out.push(DVec2::new(xs[i], midpoint(ys[j], ys[j + 1])));
                }
                if i + 1 < xs.len() && j + 1 < ys.len() {
                    out.push(DVec2::new(
                        midpoint(xs[i], xs[i + 1]),
                        midpoint(ys[j], ys[j + 1]),
                    ));
                }
            }
        }
        for sub in &grid.subgrids {
            out.extend(probes(sub, &[]));
        }
        for pair in ordered.windows(2) {
            out.push(pair[0]);
            out.push(0.5 * (pair[0] + pair[1]));
        }
        let near: Vec<DVec2> = out
            .iter()
            .flat_map(|&p| {
                [
                    DVec2::new(p.x.next_up(), p.y),
                    DVec2::new(p.x, p.y.next_down()),
                    DVec2::new(p.x.next_down(), p.y.next_up()),
                ]
            })
            .collect();
        out.extend(near);
        out
    }

    /// Builds the tree of `points` and checks the grid's answers (and the tree's) at
    /// every probe against brute force; returns how many probes the grid answered.
    fn check(points: Vec<DVec2>) -> (usize, usize) {
        let outline = Polyline2::polygon(points).expect("a polygon");
        let tree = HalTree2::build(&outline).expect("a tree");
        let grid = tree.grid().expect("a grid");
        let probes = probes(grid, tree.ordered());
        let mut answered = 0;
        for &x in &probes {
            let truth = contains_brute(&outline, x).expect("closed");
            if let Some(answer) = grid.containment(tree.ordered(), x) {
                assert_eq!(answer, truth, "the grid at {x:?}");
                answered += 1;
            }
            assert_eq!(
                tree.contains(x).expect("closed"),
                truth,
                "the tree at {x:?}"
            );
        }
        (answered, probes.len())
    }

    /// Sixteen edges over `[0, 8]²`: an 8 × 8 grid on the integers. Edges along grid
    /// lines, through cell centres (half-integers) and vertices on line crossings.
    #[test]
    fn a_comb_on_the_grid_lines_and_centres() {
        let comb = [
            (0.0, 0.0),
            (8.0, 0.0),
            (8.0, 8.0),
            (6.5, 8.0),
            (6.5, 2.5),
            (5.5, 2.5),
            (5.5, 8.0),
            (4.0, 8.0),
            (4.0, 3.0),
            (3.0, 3.0),
            (3.0, 8.0),
            (1.5, 8.0),
            (1.5, 4.5),
            (0.5, 4.5),
            (0.5, 8.0),
            (0.0, 8.0),
        ];
        let points: Vec<DVec2> = comb.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
        let outline = Polyline2::polygon(points.clone()).expect("a polygon");
        let tree = HalTree2::build(&outline).expect("a tree");
        let grid = tree.grid().expect("a grid");
        assert_eq!(grid.xs, (0..=8).map(f64::from).collect::<Vec<_>>());
        assert_eq!(grid.ys, grid.xs);
        // Centres on an edge are left to the walk.
        assert!(grid.cells.contains(&WALK));
        let (answered, probes) = check(points);
        assert!(2 * answered > probes, "{answered} of {probes}");
    }

    /// Far from the origin, tiny, flat-ish and with repeated vertices: the grid agrees
    /// with brute force everywhere it answers.
    #[test]
    fn awkward_rings_agree_with_brute_force() {
        let star = |n: usize, scale: f64, offset: DVec2| -> Vec<DVec2> {
            (0..n)
                .map(|i| {
                    let r = if i % 2 == 0 {
                        1.0
                    } else {
                        0.3 + 0.01 * (i % 7) as f64
                    };
                    offset
                        + scale * r * DVec2::from_angle(std::f64::consts::TAU * i as f64 / n as f64)
                })
                .collect()
        };
        for (scale, offset) in [
            (1.0, DVec2::ZERO),
            (2f64.powi(-40), DVec2::ZERO),
            (1e-3, DVec2::new(3e9, -3e9)),
            (1e6, DVec2::new(1e3, 0.0)),
        ] {
            check(star(40, scale, offset));
        }
        // Repeated vertices and a zero-length edge, a long thin sliver.
        let mut repeated = star(20, 1.0, DVec2::ZERO);
        repeated.insert(5, repeated[5]);
        repeated.insert(12, repeated[12]);
        check(repeated);
        let sliver: Vec<DVec2> = (0..30)
            .map(|i| DVec2::new(f64::from(i), if i % 2 == 0 { 0.0 } else { 1e-9 }))
            .chain([DVec2::new(29.0, 1.0), DVec2::new(0.0, 1.0)])
            .collect();
        check(sliver);
    }

    /// A spiral crowding many edges into few cells: crowded cells get grids of their own,
    /// whose crowded cells go to the walk; the answers stay right.
    #[test]
    fn crowded_cells_get_grids_of_their_own() {
        // Turns packed ever closer towards the centre, out and back.
        let (turns, n) = (30.0, 600);
        let out: Vec<DVec2> = (0..n)
            .map(|i| {
                let t = f64::from(i) / f64::from(n);
                DVec2::from_angle(std::f64::consts::TAU * turns * t) * t.powi(4)
            })
            .collect();
        let back: Vec<DVec2> = out.iter().rev().map(|&p| p * 1.05).collect();
        let points: Vec<DVec2> = out.into_iter().chain(back).collect();
        let outline = Polyline2::polygon(points.clone()).expect("a polygon");
        let tree = HalTree2::build(&outline).expect("a tree");
        let grid = tree.grid().expect("a grid");
        assert!(!grid.subgrids.is_empty());
        assert!(grid.subgrids.iter().any(|sub| sub.cells.contains(&WALK)));
        check(points);
    }

    /// Long edges across the whole box (a star of thin spikes) overflow the incidence
    /// budget: the grid is rebuilt coarser or not at all, and the tree still answers.
    #[test]
    fn long_crossing_edges_keep_the_grid_within_budget() {
        let n = 400;
        let points: Vec<DVec2> = (0..n)
            .map(|i| {
                let r = if i % 2 == 0 { 1.0 } else { 1e-3 };
                DVec2::from_angle(std::f64::consts::TAU * f64::from(i) / f64::from(n)) * r
            })
            .collect();
        let outline = Polyline2::polygon(points).expect("a polygon");
        let tree = HalTree2::build(&outline).expect("a tree");
        if let Some(grid) = tree.grid() {
            assert!(grid.edges.len() <= INCIDENCES_PER_EDGE * n as usize);
            assert!(grid.cells.len() <= MAX_CELLS);
        }
        for k in 0..200 {
            let x = DVec2::from_angle(f64::from(k) * 0.7) * (f64::from(k) / 150.0);
            assert_eq!(
                tree.contains(x).expect("closed"),
                contains_brute(&outline, x).expect("closed")
            );
        }
    }

    /// The grid stays within its documented size: at most 4 cells and 12 cell–edge
    /// pairs per edge, a mixed cell for each pair at most.
    #[test]
    fn the_grid_is_a_few_dozen_bytes_per_edge() {
        let n = 1_000;
        let points: Vec<DVec2> = (0..n)
            .map(|i| {
                let angle = std::f64::consts::TAU * f64::from(i) / f64::from(n);
                DVec2::from_angle(angle) * (1.0 + 0.2 * (angle * 17.0).sin())
            })
            .collect();
        let outline = Polyline2::polygon(points).expect("a polygon");
        let tree = HalTree2::build(&outline).expect("a tree");
        let grid = tree.grid().expect("a grid");
        let per_edge = grid.bytes() as f64 / f64::from(n);
        assert!(per_edge <= MAX_BYTES_PER_EDGE as f64, "{per_edge}");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(
            sphaera_tests::cases(64)
        ))]

        /// Random polygons on a coarse lattice (collinear runs, repeated vertices, edges
        /// crossing and overlapping): the grid agrees with brute force at every probe.
        #[test]
        fn lattice_polygons_agree_with_brute_force_at_every_probe(
            raw in proptest::collection::vec((0i32..10, 0i32..10), 8..40),
            scale in -3i32..4,
        ) {
            // Off the origin: an ulp beside 0 is subnormal, where the exact orientation
            // of the `robust` crate underflows (and brute force with it).
            let k = 2f64.powi(scale * 7);
            check(raw.iter().map(|&(x, y)| DVec2::new(f64::from(x + 1), f64::from(y + 1)) * k).collect());
        }
    }
}
