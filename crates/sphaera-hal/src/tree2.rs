//! The 2D HAL tree (section 3 of the paper): construction (Algorithm 1), approximation at
//! a level, adaptive approximation by widths.

use glam::{DVec2, DVec3};
use sphaera_mesh::geometry::minimum_enclosing_ball_with_support;

use crate::cell_grid::CellGrid;
use crate::lens::{Lens, vertex_bulge};
use crate::{HalError, Polyline2};

/// A child that is an original edge, not a node.
pub(crate) const EDGE: u32 = u32::MAX;

/// Relative tolerance for a vertex to count as lying on the smallest bounding disc.
const ON_DISC: f64 = 1e-12;

/// One node of a [`HalTree2`]: a polyline of the input from position `first` to `last`
/// (at least one vertex between), its bounding area, and the vertex it is split at.
///
/// Positions run along the outline from the tree's start vertex
/// ([`HalTree2::vertex_at`] maps a position to a vertex index): for a polygon the start
/// is one of the two vertices of the level-0 chord, and position `n` is the start again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node2 {
    /// Position of the polyline's first vertex (`v_p`).
    pub first: u32,
    /// Position of its last vertex (`v_s`).
    pub last: u32,
    /// Position of the vertex the node adds to the approximation (`v_q` or `v_r`).
    pub split: u32,
    /// Level: the polylines of level-0 chords are at level 1.
    pub level: u32,
    /// The bounding area over the chord `v_p → v_s` (Definition 3).
    pub lens: Lens,
    /// The largest width `max(w₁, w₂)` (Definition 4).
    pub width: f64,
    children: [u32; 2],
}

impl Node2 {
    /// The node of the part before the split and after it (`None`: that part is one
    /// original edge).
    #[must_use]
    pub fn children(&self) -> [Option<usize>; 2] {
        self.children.map(|c| (c != EDGE).then_some(c as usize))
    }
}

/// One polyline a level-0 chord stands for: positions `first` to `last`, with its node
/// (`None` when it is one edge).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chain {
    /// Position of the first vertex.
    pub first: u32,
    /// Position of the last vertex.
    pub last: u32,
    /// The node over it, if it has vertices between its ends.
    pub node: Option<usize>,
}

/// A hierarchical approximation and localization tree of a polygon or polyline.
///
/// The root is the smallest disc containing every vertex (polygons) and the level-0
/// approximation the chord between the two vertices on it farthest apart; each node splits
/// its polyline at the vertex whose disc is larger (Algorithm 1), so that the in-order
/// traversal gives the outline back. Storage is `Θ(N)`: one node per vertex not in the
/// level-0 chord (Theorem 3). Beside the paper's bounding areas each node keeps the
/// bounding box of its part (32 bytes), and the tree keeps the vertices in outline order
/// (16 bytes each): point inclusion and intersection test the box first, with coordinate
/// comparisons only, and use the lens where the box cannot decide. A closed ring of at
/// least 8 edges also gets a cell grid for [`HalTree2::contains`] (about 4 cells per
/// edge, at most 2²² cells and 12 cell–edge pairs per edge, and as many again for the
/// grids of crowded cells: a few dozen bytes per edge, built in time linear in the cells
/// and pairs, with one walk of the tree per grid and per degenerate step).
///
/// # Examples
///
/// ```
/// use glam::DVec2;
/// use sphaera_hal::{HalTree2, Containment, Polyline2};
///
/// // An L-shaped hexagon.
/// let polygon = Polyline2::polygon(vec![
///     DVec2::new(0.0, 0.0), DVec2::new(2.0, 0.0), DVec2::new(2.0, 1.0),
///     DVec2::new(1.0, 1.0), DVec2::new(1.0, 2.0), DVec2::new(0.0, 2.0),
/// ])?;
/// let tree = HalTree2::build(&polygon)?;
/// assert_eq!(tree.nodes().len(), 6 - 2);
/// assert_eq!(tree.level(0).len(), 2);
/// assert_eq!(tree.level(tree.depth()).len(), 6);
/// assert_eq!(tree.contains(DVec2::new(0.5, 0.5))?, Containment::Inside);
/// assert_eq!(tree.contains(DVec2::new(1.5, 1.5))?, Containment::Outside);
/// assert_eq!(tree.contains(DVec2::new(1.0, 1.5))?, Containment::Boundary);
/// # Ok::<(), sphaera_hal::HalError>(())
/// ```
#[derive(Clone, Debug)]
pub struct HalTree2 {
    polyline: Polyline2,
    /// Vertex index at position 0.
    start: usize,
    /// The smallest bounding disc (polygons only): centre and radius.
    root_disc: Option<(DVec2, f64)>,
    chains: Vec<Chain>,
    nodes: Vec<Node2>,
    /// Per node, what point inclusion reads, in one cache line.
    walk: Vec<Walk2>,
    /// The vertices by position (a polygon's start repeated at position `n`).
    ordered: Vec<DVec2>,
    /// The bounding box of every vertex.
    bounds: Box2,
    /// The cell grid that answers most point-inclusion queries (closed rings).
    grid: Option<CellGrid>,
}

/// What point inclusion reads of a node, packed in one cache line: its part's bounding
/// box, its lens, its split position and its children ([`EDGE`] for an original edge).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(align(64))]
pub(crate) struct Walk2 {
    pub(crate) bounds: Box2,
    pub(crate) lens: Lens,
    pub(crate) split: u32,
    pub(crate) children: [u32; 2],
}

/// An axis-aligned box: `min` and `max` corners, closed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Box2 {
    pub(crate) min: DVec2,
    pub(crate) max: DVec2,
}

impl Box2 {
    /// The empty box (the identity of [`Box2::grow`]).
    pub(crate) const EMPTY: Self = Self {
        min: DVec2::splat(f64::INFINITY),
        max: DVec2::splat(f64::NEG_INFINITY),
    };

    /// The box around `self` and `p`.
    pub(crate) fn grow(self, p: DVec2) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The box around both.
    pub(crate) fn union(&self, other: &Self) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Whether `p` lies in the closed box.
    pub(crate) fn holds(&self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// Whether the closed boxes share no point.
    pub(crate) fn apart(&self, other: &Self) -> bool {
        self.max.x < other.min.x
            || other.max.x < self.min.x
            || self.max.y < other.min.y
            || other.max.y < self.min.y
    }

    /// The distance from `p` to the box (0 inside).
    pub(crate) fn distance(&self, p: DVec2) -> f64 {
        (self.min - p).max(p - self.max).max(DVec2::ZERO).length()
    }
}

impl HalTree2 {
    /// Builds the complete tree of `polyline` (Algorithm 1).
    ///
    /// Ties are broken by position along the outline: among vertices equally far from
    /// their chord's disc, the first; among vertices on the smallest disc equally far
    /// apart, the pair with the lowest indices. A polyline whose vertices all lie on its
    /// chord is split at its middle position.
    ///
    /// # Errors
    ///
    /// [`HalError::Mesh`] when the smallest bounding disc cannot be computed
    /// (coordinates near the ends of the `f64` range).
    ///
    /// # Performance
    ///
    /// Each node scans its polyline once: `O(N log N)` when splits are balanced, `O(N²)`
    /// in the worst case (Theorem 2).
    pub fn build(polyline: &Polyline2) -> Result<Self, HalError> {
        let points = polyline.points();
        let n = points.len();
        let (start, root_disc, ends) = if polyline.is_closed() {
            let (i, j, disc) = level_zero(points)?;
            (i, Some(disc), vec![0, (j + n - i) % n, n])
        } else {
            (0, None, vec![0, n - 1])
        };
        let positions = if polyline.is_closed() { n + 1 } else { n };
        let ordered: Vec<DVec2> = (0..positions).map(|k| points[(start + k) % n]).collect();
        let bounds = points.iter().fold(Box2::EMPTY, |b, &p| b.grow(p));
        let mut tree = Self {
            polyline: polyline.clone(),
            start,
            root_disc,
            chains: Vec::new(),
            nodes: Vec::with_capacity(n.saturating_sub(2)),
            walk: Vec::with_capacity(n.saturating_sub(2)),
            ordered,
            bounds,
            grid: None,
        };
        for pair in ends.windows(2) {
            let (first, last) = (pair[0] as u32, pair[1] as u32);
            let node = tree.grow(first, last, 1);
            tree.chains.push(Chain {
                first,
                last,
                node: (node != EDGE).then_some(node as usize),
            });
        }
        if polyline.is_closed() {
            tree.grid = CellGrid::build(&tree.ordered, |x| tree.walk_containment(x));
        }
        Ok(tree)
    }

    /// Builds the subtree over positions `first..=last` at `level`, returning its node
    /// (or [`EDGE`]). Iterative: a worst-case outline makes the tree as deep as it is long.
    fn grow(&mut self, first: u32, last: u32, level: u32) -> u32 {
        if last - first < 2 {
            return EDGE;
        }
        let root = self.nodes.len() as u32;
        // (first, last, level, parent node and which child, or none for the root).
        let mut work = vec![(first, last, level, None::<(u32, usize)>)];
        while let Some((p, s, level, parent)) = work.pop() {
            let id = self.nodes.len() as u32;
            let (split, lens, bounds) = self.split(p, s);
            let width = lens.width(self.at(p), self.at(s));
            self.walk.push(Walk2 {
                bounds,
                lens,
                split,
                children: [EDGE, EDGE],
            });
            self.nodes.push(Node2 {
                first: p,
                last: s,
                split,
                level,
                lens,
                width,
                children: [EDGE, EDGE],
            });
            if let Some((parent, side)) = parent {
                self.nodes[parent as usize].children[side] = id;
                self.walk[parent as usize].children[side] = id;
            }
            // Right part pushed first, so the left is built first (depth first, in order).
            if s - split >= 2 {
                work.push((split, s, level + 1, Some((id, 1))));
            }
            if split - p >= 2 {
                work.push((p, split, level + 1, Some((id, 0))));
            }
        }
        root
    }

    /// The split vertex and bounding area of the polyline at positions `p..=s`
    /// (Definition 3 and Algorithm 1), and its vertices' bounding box.
    fn split(&self, p: u32, s: u32) -> (u32, Lens, Box2) {
        let (a, b) = (self.at(p), self.at(s));
        let mut left: Option<(f64, u32)> = None;
        let mut right: Option<(f64, u32)> = None;
        let mut bounds = Box2::EMPTY.grow(a).grow(b);
        for position in p + 1..s {
            let x = self.at(position);
            bounds = bounds.grow(x);
            match vertex_bulge(a, b, x) {
                Some((k, true)) if left.is_none_or(|(best, _)| k > best) => {
                    left = Some((k, position));
                }
                Some((k, false)) if right.is_none_or(|(best, _)| k < best) => {
                    right = Some((k, position));
                }
                _ => {}
            }
        }
        let lens = Lens {
            left: left.map_or(f64::NEG_INFINITY, |(k, _)| k),
            right: right.map_or(f64::INFINITY, |(k, _)| k),
        };
        let split = match (left, right) {
            (Some((_, q)), None) => q,
            (None, Some((_, r))) => r,
            // The larger signed radius (Definition 1's sign): the signed radius grows with
            // the bulge toward the vertex's side, so compare the left bulge with the
            // right one mirrored. Ties go to v_r, as the paper's "otherwise".
            (Some((kq, q)), Some((kr, r))) => {
                if kq > -kr {
                    q
                } else {
                    r
                }
            }
            (None, None) => p + (s - p) / 2,
        };
        (split, lens, bounds)
    }

    /// The vertex at position `position` along the outline.
    fn at(&self, position: u32) -> DVec2 {
        self.ordered[position as usize]
    }

    /// The vertex index at `position` (positions run from the start vertex; for a
    /// polygon, position `n` is the start vertex again).
    #[must_use]
    pub fn vertex_at(&self, position: u32) -> usize {
        (self.start + position as usize) % self.polyline.points().len()
    }

    /// The input.
    #[must_use]
    pub fn polyline(&self) -> &Polyline2 {
        &self.polyline
    }

    /// The nodes, depth first (each chain's subtree in turn).
    #[must_use]
    pub fn nodes(&self) -> &[Node2] {
        &self.nodes
    }

    /// The polylines of the level-0 approximation: two for a polygon (the chord's two
    /// sides), one for an open polyline.
    #[must_use]
    pub fn chains(&self) -> &[Chain] {
        &self.chains
    }

    /// The smallest disc containing every vertex (polygons only): centre and radius.
    #[must_use]
    pub fn root_disc(&self) -> Option<(DVec2, f64)> {
        self.root_disc
    }

    /// The deepest level (0 when every chain is one edge).
    #[must_use]
    pub fn depth(&self) -> usize {
        self.nodes
            .iter()
            .map(|n| n.level as usize)
            .max()
            .unwrap_or(0)
    }

    /// The level-`level` approximation: vertex indices in outline order (a polygon's
    /// closing edge implied). Level 0 is the chord's two ends; at [`HalTree2::depth`] and
    /// beyond, every vertex.
    #[must_use]
    pub fn level(&self, level: usize) -> Vec<usize> {
        self.collect(|node| node.level as usize <= level)
    }

    /// The adaptive approximation (section 3.3): a node is refined only when its own width
    /// exceeds `tolerance`. Every vertex of the outline lies within the returned
    /// [`Approximation::width`] of the line through the approximation's edge that stands
    /// for it (a width measures from the chord's line, Definition 4).
    #[must_use]
    pub fn approximate(&self, tolerance: f64) -> Approximation {
        self.approximation_by(|node| node.width > tolerance)
    }

    /// The approximation that refines exactly the nodes `refine` accepts (reached through
    /// refined parents): [`HalTree2::approximate`] refines by width, a level by
    /// `node.level <= level`, the whole outline by `|_| true`.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_hal::{HalTree2, Polyline2, parse_points};
    ///
    /// let square = Polyline2::polygon(parse_points("0 0\n2 0\n2 1\n2 2\n0 2\n")?)?;
    /// let tree = HalTree2::build(&square)?;
    /// let whole = tree.approximation_by(|_| true);
    /// assert_eq!(whole.vertices.len(), 5);
    /// assert!(whole.frontier.is_empty() && whole.width == 0.0);
    /// let coarsest = tree.approximation_by(|_| false);
    /// assert_eq!(coarsest.vertices.len(), 2);
    /// assert!(!coarsest.frontier.is_empty() && coarsest.width > 0.0);
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn approximation_by(&self, refine: impl Fn(&Node2) -> bool) -> Approximation {
        let vertices = self.collect(&refine);
        let mut frontier = Vec::new();
        let width = self.unrefined_width(&refine, &mut frontier);
        frontier.sort_unstable();
        Approximation {
            vertices,
            frontier,
            width,
        }
    }

    /// Per level from 0 to [`HalTree2::depth`], its approximation's vertex count and
    /// covering error (eq. 1), in one pass over the nodes (the level-`k` approximation
    /// holds the nodes of level at most `k`; its edges that are not original are bounded
    /// by the nodes of level `k + 1`).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_hal::{HalTree2, Polyline2, parse_points};
    ///
    /// let square = Polyline2::polygon(parse_points("0 0\n2 0\n2 1\n2 2\n0 2\n")?)?;
    /// let tree = HalTree2::build(&square)?;
    /// let levels = tree.level_summaries();
    /// assert_eq!(levels.len(), tree.depth() + 1);
    /// for summary in &levels {
    ///     assert_eq!(summary.vertices, tree.level(summary.level).len());
    ///     assert_eq!(summary.width, tree.level_width(summary.level));
    /// }
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn level_summaries(&self) -> Vec<LevelSummary> {
        let depth = self.depth();
        let mut count = vec![0_usize; depth + 2];
        let mut width = vec![0.0_f64; depth + 2];
        for node in &self.nodes {
            let level = node.level as usize;
            count[level] += 1;
            width[level] = width[level].max(node.width);
        }
        // The level-0 chords' ends (the first vertex of every chain, and a polyline's
        // last vertex).
        let mut vertices = self.chains.len() + usize::from(!self.polyline.is_closed());
        (0..=depth)
            .map(|level| {
                vertices += count[level];
                LevelSummary {
                    level,
                    vertices,
                    width: width[level + 1],
                }
            })
            .collect()
    }

    /// The covering error (eq. 1) of the level-`level` approximation: the largest width of
    /// the bounding areas of its edges that are not original edges.
    #[must_use]
    pub fn level_width(&self, level: usize) -> f64 {
        self.unrefined_width(|node| node.level as usize <= level, &mut Vec::new())
    }

    /// Vertices in outline order, descending into a node when `refine` says so.
    fn collect(&self, refine: impl Fn(&Node2) -> bool) -> Vec<usize> {
        let mut out = Vec::new();
        for chain in &self.chains {
            out.push(self.vertex_at(chain.first));
            if let Some(node) = chain.node {
                self.collect_node(node, &refine, &mut out);
            }
        }
        if !self.polyline.is_closed()
            && let Some(last) = self.chains.last()
        {
            out.push(self.vertex_at(last.last));
        }
        out
    }

    /// The inner vertices of node `root`'s polyline that `refine` keeps, in order.
    fn collect_node(&self, root: usize, refine: &impl Fn(&Node2) -> bool, out: &mut Vec<usize>) {
        // In-order, iteratively: (node, whether its left part is done).
        let mut stack = vec![(root, false)];
        while let Some((id, left_done)) = stack.pop() {
            let node = &self.nodes[id];
            if !refine(node) {
                continue;
            }
            let [left, right] = node.children();
            if !left_done {
                stack.push((id, true));
                if let Some(l) = left {
                    stack.push((l, false));
                }
                continue;
            }
            out.push(self.vertex_at(node.split));
            if let Some(r) = right {
                stack.push((r, false));
            }
        }
    }

    /// The largest width among nodes reached (through refined parents) but not refined;
    /// those nodes are pushed on `frontier`.
    fn unrefined_width(&self, refine: impl Fn(&Node2) -> bool, frontier: &mut Vec<usize>) -> f64 {
        let mut largest: f64 = 0.0;
        let mut stack: Vec<usize> = self.chains.iter().filter_map(|c| c.node).collect();
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id];
            if refine(node) {
                stack.extend(node.children().into_iter().flatten());
            } else {
                largest = largest.max(node.width);
                frontier.push(id);
            }
        }
        largest
    }

    /// The point at `position` along the outline (see [`HalTree2::vertex_at`]).
    #[must_use]
    pub fn point_at(&self, position: u32) -> DVec2 {
        self.at(position)
    }

    /// The bounding box of node `id`'s part.
    pub(crate) fn node_box(&self, id: usize) -> &Box2 {
        &self.walk[id].bounds
    }

    /// What point inclusion reads of node `id`.
    pub(crate) fn walk(&self, id: u32) -> &Walk2 {
        &self.walk[id as usize]
    }

    /// The bounding box of every vertex: `(min, max)`.
    #[must_use]
    pub fn bounding_box(&self) -> (DVec2, DVec2) {
        (self.bounds.min, self.bounds.max)
    }

    /// The bounding box of every vertex.
    pub(crate) fn bounds(&self) -> &Box2 {
        &self.bounds
    }

    /// The cell grid of a closed ring, when it has one.
    pub(crate) fn grid(&self) -> Option<&CellGrid> {
        self.grid.as_ref()
    }

    /// The vertices by position (a polygon's start repeated last).
    pub(crate) fn ordered(&self) -> &[DVec2] {
        &self.ordered
    }
}

/// An approximation of the outline ([`HalTree2::approximate`],
/// [`HalTree2::approximation_by`]).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Approximation {
    /// Vertex indices in outline order (a polygon's closing edge implied).
    pub vertices: Vec<usize>,
    /// The nodes whose bounding areas bound the approximation's edges that are not
    /// original edges, in increasing node order.
    pub frontier: Vec<usize>,
    /// Its covering error: the largest width of an edge's bounding area (0 when every
    /// edge is original).
    pub width: f64,
}

/// One level of a [`HalTree2`] ([`HalTree2::level_summaries`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct LevelSummary {
    /// The level.
    pub level: usize,
    /// The vertices of its approximation.
    pub vertices: usize,
    /// Its covering error (eq. 1): the largest width of a bounding area of its edges that
    /// are not original.
    pub width: f64,
}

/// The level-0 chord of a polygon: the two vertices farthest apart on its smallest
/// bounding disc (lowest indices on ties), as `(i, j, disc)` with `i < j`.
fn level_zero(points: &[DVec2]) -> Result<(usize, usize, (DVec2, f64)), HalError> {
    let lifted: Vec<DVec3> = points.iter().map(|p| p.extend(0.0)).collect();
    let ball = minimum_enclosing_ball_with_support(&lifted)?;
    let center = ball.sphere.center.truncate();
    let radius = ball.sphere.radius;
    let on: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].distance(center) >= radius * (1.0 - ON_DISC))
        .collect();
    // Every vertex at the centre (a polygon of one repeated point): any two.
    let pair = farthest_pair(points, &on, center).unwrap_or((0, 1));
    Ok((pair.0, pair.1, (center, radius)))
}

/// The two of `on` (vertices on a circle around `center`) farthest apart, lowest indices
/// on ties, `(i, j)` with `i < j`: the most nearly antipodal pair, found by sorting by
/// angle and looking across (`O(k log k)` for `k` vertices on the circle, which is every
/// vertex of a regular polygon).
fn farthest_pair(points: &[DVec2], on: &[usize], center: DVec2) -> Option<(usize, usize)> {
    if on.len() < 2 {
        return None;
    }
    let angle = |i: usize| {
        let d = points[i] - center;
        d.y.atan2(d.x)
    };
    let mut by_angle: Vec<(f64, usize)> = on.iter().map(|&i| (angle(i), i)).collect();
    by_angle.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let k = by_angle.len();
    let mut best: Option<(f64, usize, usize)> = None;
    let mut consider = |i: usize, j: usize| {
        if i == j {
            return;
        }
        let (i, j) = (i.min(j), i.max(j));
        let d = points[i].distance_squared(points[j]);
        let better = match best {
            None => true,
            Some((bd, bi, bj)) => d.total_cmp(&bd).then((bi, bj).cmp(&(i, j))).is_gt(),
        };
        if better {
            best = Some((d, i, j));
        }
    };
    for &(theta, i) in &by_angle {
        // The angle across, wrapped into [−π, π).
        let mut across = theta + std::f64::consts::PI;
        if across >= std::f64::consts::PI {
            across -= std::f64::consts::TAU;
        }
        let at = by_angle.partition_point(|&(t, _)| t < across);
        // The neighbours around the opposite angle (and a couple more for ties).
        for offset in [k - 2, k - 1, 0, 1] {
            consider(i, by_angle[(at + offset) % k].1);
        }
    }
    best.map(|(_, i, j)| (i, j))
}
