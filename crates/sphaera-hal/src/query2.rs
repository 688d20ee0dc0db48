//! Hierarchical operations on 2D HAL trees (section 5 of the paper): point inclusion and
//! intersection detection, with their brute-force references.

use std::ops::ControlFlow;

use glam::{DAffine2, DVec2};

use crate::lens::{CONTAINMENT_SLACK, coord};
use crate::tree2::{Box2, EDGE};
use crate::{HalError, HalTree2, Polyline2};

/// Where a point lies with respect to a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Containment {
    /// Inside (an odd number of crossings).
    Inside,
    /// Outside.
    Outside,
    /// Exactly on an edge or a vertex (decided with exact predicates).
    Boundary,
}

/// What one edge says about a point `x`: `None` when `x` lies on the edge (exactly),
/// else whether the horizontal ray from `x` to `+x` crosses it.
///
/// The half-open rule (an edge counts when exactly one end lies strictly above `x`) makes
/// every closed loop cross an even number of times when `x` is not on it, so replacing a
/// part of the outline by its chord keeps the parity whenever `x` is outside the part's
/// bounding area. Orientations are exact (`robust`).
#[must_use]
pub fn ray_crossing(a: DVec2, b: DVec2, x: DVec2) -> Option<bool> {
    let orientation = robust::orient2d(coord(a), coord(b), coord(x));
    if orientation == 0.0
        && x.x >= a.x.min(b.x)
        && x.x <= a.x.max(b.x)
        && x.y >= a.y.min(b.y)
        && x.y <= a.y.max(b.y)
    {
        return None;
    }
    if (a.y > x.y) == (b.y > x.y) {
        return Some(false);
    }
    // Upward edges cross when the point is on their left, downward ones on their right.
    Some(if b.y > a.y {
        orientation > 0.0
    } else {
        orientation < 0.0
    })
}

/// The crossing-number answer over every edge: the reference for [`HalTree2::contains`].
///
/// # Errors
///
/// [`HalError::OpenPolyline`] for an open polyline.
pub fn contains_brute(polygon: &Polyline2, x: DVec2) -> Result<Containment, HalError> {
    if !polygon.is_closed() {
        return Err(HalError::OpenPolyline);
    }
    let mut inside = false;
    for i in 0..polygon.edge_count() {
        let (a, b) = polygon.edge(i);
        match ray_crossing(a, b, x) {
            None => return Ok(Containment::Boundary),
            Some(crossed) => inside ^= crossed,
        }
    }
    Ok(if inside {
        Containment::Inside
    } else {
        Containment::Outside
    })
}

impl HalTree2 {
    /// Point inclusion: whether `x` is inside the polygon, outside, or exactly on its
    /// outline. The fastest exact method: the tree's cell grid first, the hierarchy's
    /// walk ([`HalTree2::contains_by_hierarchy`]) where the grid cannot decide.
    ///
    /// The grid (built with the tree, about 4 cells per edge) answers a point in a cell
    /// no edge touches at once, and in a cell a few edges cross by counting the edges
    /// that cross the segment from the cell's centre (whose answer the walk gave at
    /// build) to `x`, with exact orientations; a crowded cell has a grid of its own. A
    /// point on an edge's line, a segment through a vertex, a centre on the outline or a
    /// cell still crowded go to the walk. So the
    /// answer is always the walk's, and equals [`contains_brute`]'s on every input.
    /// Points exactly on an edge or at a vertex are [`Containment::Boundary`].
    ///
    /// # Errors
    ///
    /// [`HalError::OpenPolyline`] for an open polyline.
    ///
    /// # Performance
    ///
    /// A point in a cell no edge touches costs one cell lookup (most points spread over
    /// the bounding box); one next to the outline a few exact orientations more. Against
    /// GEOS prepared geometry and HAL's hierarchy alone, on points spread and near the
    /// outline, in the same run: *HAL trees* in `docs/benchmarks.md` in the repository.
    pub fn contains(&self, x: DVec2) -> Result<Containment, HalError> {
        if !self.polyline().is_closed() {
            return Err(HalError::OpenPolyline);
        }
        Ok(self.ring_containment(x))
    }

    /// Point inclusion by the paper's method alone (section 5.1): the crossing number
    /// of a ray from `x`, with every part of the outline whose bounding area does not
    /// contain `x` replaced by its chord, without the cell grid of
    /// [`HalTree2::contains`] (the same answers, slower; for comparison).
    ///
    /// The answer equals [`contains_brute`]'s on every input: the same half-open crossing
    /// rule and exact orientation tests are used, a chord is used only for a part whose
    /// bounding area `x` is clearly outside of (so `x` lies on neither), and a union
    /// bounding area (never made by a polygon whose vertices avoid their chords' lines,
    /// Theorem 1) is always descended. Points exactly on an edge or at a vertex are
    /// [`Containment::Boundary`].
    ///
    /// # Errors
    ///
    /// [`HalError::OpenPolyline`] for an open polyline.
    pub fn contains_by_hierarchy(&self, x: DVec2) -> Result<Containment, HalError> {
        if !self.polyline().is_closed() {
            return Err(HalError::OpenPolyline);
        }
        if !self.bounds().holds(x) {
            return Ok(Containment::Outside);
        }
        Ok(self.walk_containment(x))
    }

    /// [`HalTree2::contains`] of a closed ring, without the check: the grid, then the
    /// walk.
    pub(crate) fn ring_containment(&self, x: DVec2) -> Containment {
        if !self.bounds().holds(x) {
            return Containment::Outside;
        }
        if let Some(answer) = self
            .grid()
            .and_then(|grid| grid.containment(self.ordered(), x))
        {
            return answer;
        }
        self.walk_containment(x)
    }

    /// The walk of [`HalTree2::contains_by_hierarchy`] for `x` in the bounding box.
    ///
    /// A part is replaced by its chord when `x` lies outside its bounding box or its
    /// bounding area. With the horizontal ray, the box often decides more: a part wholly
    /// above, below or left of `x` crosses nothing, and one wholly right of it crosses as
    /// often (mod 2) as its ends lie on different sides of `x`'s height; these are
    /// coordinate comparisons, exact, and agree with the exact orientation tests.
    pub(crate) fn walk_containment(&self, x: DVec2) -> Containment {
        PART_STACK.with_borrow_mut(|stack| {
            stack.clear();
            let mut inside = false;
            for chain in self.chains() {
                stack.push((
                    chain.first,
                    chain.last,
                    chain.node.map_or(EDGE, |n| n as u32),
                ));
                while let Some((p, s, id)) = stack.pop() {
                    let (a, b) = (self.point_at(p), self.point_at(s));
                    if id == EDGE {
                        // One original edge.
                        match ray_crossing(a, b, x) {
                            None => return Containment::Boundary,
                            Some(crossed) => inside ^= crossed,
                        }
                        continue;
                    }
                    let n = self.walk(id);
                    let bounds = &n.bounds;
                    if x.y < bounds.min.y || x.y > bounds.max.y || x.x > bounds.max.x {
                        continue;
                    }
                    if x.x < bounds.min.x {
                        inside ^= (a.y > x.y) != (b.y > x.y);
                        continue;
                    }
                    if n.lens.may_contain(a, b, x) {
                        stack.push((n.split, s, n.children[1]));
                        stack.push((p, n.split, n.children[0]));
                    } else if let Some(crossed) = ray_crossing(a, b, x) {
                        inside ^= crossed;
                    }
                }
            }
            if inside {
                Containment::Inside
            } else {
                Containment::Outside
            }
        })
    }
}

thread_local! {
    /// The parts still to visit of a point-inclusion walk: `(first, last, node or EDGE)`,
    /// kept per thread so that a query allocates nothing once warm.
    static PART_STACK: std::cell::RefCell<Vec<(u32, u32, u32)>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// Whether the closed segments `a–b` and `c–d` share a point (touching and collinear
/// overlap included), with exact orientation tests.
#[must_use]
pub fn segments_intersect(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let o = |p: DVec2, q: DVec2, r: DVec2| robust::orient2d(coord(p), coord(q), coord(r));
    let (d1, d2) = (o(a, b, c), o(a, b, d));
    let (d3, d4) = (o(c, d, a), o(c, d, b));
    let within = |p: DVec2, q: DVec2, r: DVec2| {
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && within(a, b, c))
        || (d2 == 0.0 && within(a, b, d))
        || (d3 == 0.0 && within(c, d, a))
        || (d4 == 0.0 && within(c, d, b))
}

/// Whether two outlines intersect, by brute force: the reference for
/// [`HalTree2::intersects`]. A closed polygon is a region (its outline and its inside),
/// an open polyline a curve, as in GEOS and shapely: two outlines intersect when they
/// share a point, or when one lies inside a closed polygon (a polygon nested in another,
/// a polyline wholly inside a polygon; the paper's section 5.2 means regions).
#[must_use]
pub fn intersects_brute(first: &Polyline2, second: &Polyline2) -> bool {
    !intersecting_edges_brute(first, second).is_empty()
        || one_inside_the_other(first, second, contains_brute)
}

/// Every pair of intersecting edges `(edge of first, edge of second)`, by brute force, in
/// increasing order: the reference for [`HalTree2::intersecting_edges`]. Edge `i` runs from
/// vertex `i` to the next.
#[must_use]
pub fn intersecting_edges_brute(first: &Polyline2, second: &Polyline2) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for i in 0..first.edge_count() {
        let (a, b) = first.edge(i);
        for j in 0..second.edge_count() {
            let (c, d) = second.edge(j);
            if segments_intersect(a, b, c, d) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

/// With boundaries known to be disjoint: whether one outline lies inside the other, a
/// closed polygon (one vertex decides, the outline being connected).
fn one_inside_the_other(
    first: &Polyline2,
    second: &Polyline2,
    locate: impl Fn(&Polyline2, DVec2) -> Result<Containment, HalError>,
) -> bool {
    let within = |polygon: &Polyline2, x: DVec2| {
        polygon.is_closed()
            && matches!(
                locate(polygon, x),
                Ok(Containment::Inside | Containment::Boundary)
            )
    };
    within(second, first.points()[0]) || within(first, second.points()[0])
}

/// A region bounding part of an outline: a disc, or a closed half-plane
/// `(z − point)·inward ≥ 0`.
#[derive(Clone, Copy, Debug)]
enum Region {
    Disc(DVec2, f64),
    HalfPlane(DVec2, DVec2),
    /// No bound (a union bounding area, which is not used to prune).
    Everything,
}

impl Region {
    /// Whether the two regions are certainly disjoint (false when in doubt). `slack` is
    /// the rounding allowance at the outlines' coordinates; a disc's own size adds its
    /// share, so that the huge discs of nearly straight parts (a vertex a few ulps off its
    /// chord's line) never prune on rounding.
    fn apart(self, other: Self, slack: f64) -> bool {
        const RELATIVE: f64 = 4.0 * f64::EPSILON;
        match (self, other) {
            (Self::Everything, _) | (_, Self::Everything) => false,
            (Self::Disc(c, r), Self::Disc(d, s)) => {
                let gap = c.distance(d);
                gap > r + s + slack + RELATIVE * (gap + r + s)
            }
            (Self::Disc(c, r), Self::HalfPlane(p, n))
            | (Self::HalfPlane(p, n), Self::Disc(c, r)) => {
                let offset = (c - p).dot(n);
                offset < -r - slack - RELATIVE * (r + (c - p).abs().element_sum())
            }
            (Self::HalfPlane(p, n), Self::HalfPlane(q, m)) => {
                (n + m).length() <= 1e-12 && (q - p).dot(n) < -slack
            }
        }
    }
}

/// A part of an outline in the pair traversal: its chord, its node (`None`: one original
/// edge), the two regions whose intersection bounds it, and its bounding box.
#[derive(Clone, Copy, Debug)]
struct Part {
    first: u32,
    last: u32,
    node: Option<usize>,
    regions: [Region; 2],
    bounds: Box2,
}

/// A tree seen through a placement (a proper similarity) into another tree's coordinates.
#[derive(Clone, Copy)]
struct Placed<'a> {
    tree: &'a HalTree2,
    map: DAffine2,
    /// The map's scale.
    scale: f64,
    /// Whether the map is the identity (boxes are then the tree's own, exactly).
    identity: bool,
    /// What rounding may move a mapped vertex by.
    slack: f64,
}

impl Placed<'_> {
    fn point(&self, position: u32) -> DVec2 {
        if self.identity {
            return self.tree.point_at(position);
        }
        self.map.transform_point2(self.tree.point_at(position))
    }

    /// The box holding the mapped vertices of a node's part: its own box mapped, corner
    /// by corner, widened by what rounding may move a mapped vertex.
    fn node_box(&self, id: usize) -> Box2 {
        let own = *self.tree.node_box(id);
        if self.identity {
            return own;
        }
        let corners = [
            own.min,
            own.max,
            DVec2::new(own.min.x, own.max.y),
            DVec2::new(own.max.x, own.min.y),
        ];
        let mapped = corners
            .iter()
            .fold(Box2::EMPTY, |b, &c| b.grow(self.map.transform_point2(c)));
        Box2 {
            min: mapped.min - self.slack,
            max: mapped.max + self.slack,
        }
    }

    /// The part over positions `first..=last` with node `node`. A proper similarity maps
    /// a disc through the chord's ends to the disc of the same bulge through the mapped
    /// ends, so the lens is rebuilt from the mapped chord.
    fn part(&self, first: u32, last: u32, node: Option<usize>) -> Part {
        let (a, b) = (self.point(first), self.point(last));
        let (regions, bounds) = match node {
            // An edge lies in its diametral disc.
            None => {
                let disc = Region::Disc(a.midpoint(b), 0.5 * a.distance(b));
                ([disc, disc], Box2::EMPTY.grow(a).grow(b))
            }
            Some(id) => {
                let lens = self.tree.nodes()[id].lens;
                let regions = if lens.kind() == crate::LensKind::Union {
                    [Region::Everything, Region::Everything]
                } else {
                    lens.discs(a, b).map(|d| match d {
                        crate::SignedDisc::Disc { center, radius } => {
                            Region::Disc(center, radius.abs())
                        }
                        crate::SignedDisc::HalfPlane { point, inward } => {
                            Region::HalfPlane(point, inward)
                        }
                    })
                };
                (regions, self.node_box(id))
            }
        };
        Part {
            first,
            last,
            node,
            regions,
            bounds,
        }
    }

    /// The two parts a node's part splits into.
    fn halves(&self, part: &Part) -> [Part; 2] {
        let node = &self.tree.nodes()[part.node.unwrap_or_default()];
        let [left, right] = node.children();
        [
            self.part(part.first, node.split, left),
            self.part(node.split, part.last, right),
        ]
    }

    /// The size used to pick which part of a pair to refine.
    fn size(&self, part: &Part, id: usize) -> f64 {
        self.point(part.first).distance(self.point(part.last))
            + self.tree.nodes()[id].width.min(f64::MAX)
    }

    /// At least the largest coordinate of the placed outline, in constant time: the
    /// placed root disc's (the outline lies in it), or the placed box's.
    fn reach(&self) -> f64 {
        match self.tree.root_disc() {
            Some((c, r)) => {
                let c = self.map.transform_point2(c);
                (c.abs().max_element() + r * self.scale) * (1.0 + 1e-12)
            }
            None => {
                let (lo, hi) = self.tree.bounding_box();
                let (c, r) = (lo.midpoint(hi), 0.5 * lo.distance(hi));
                let c = self.map.transform_point2(c);
                (c.abs().max_element() + r * self.scale) * (1.0 + 1e-12)
            }
        }
    }
}

/// Why an affine map cannot place one outline against another.
fn check_placement(placement: &DAffine2) -> Result<f64, HalError> {
    let m = placement.matrix2;
    let finite = m.is_finite() && placement.translation.is_finite();
    let (x, y) = (m.x_axis, m.y_axis);
    let scale = m.determinant();
    let tolerance = 1e-9 * x.length_squared().max(y.length_squared());
    if !finite
        || scale <= 0.0
        || (x.length_squared() - y.length_squared()).abs() > tolerance
        || x.dot(y).abs() > tolerance
    {
        return Err(HalError::InvalidPlacement {
            matrix: m.to_cols_array(),
        });
    }
    Ok(scale.sqrt())
}

impl HalTree2 {
    /// Intersection detection (section 5.2): pairs of parts whose bounding areas and boxes
    /// may meet are refined, the larger part first, down to pairs of original edges, which
    /// are tested exactly; when no edges meet, a closed polygon intersects an outline that
    /// lies inside it (a nested polygon, or an open polyline: GEOS's and shapely's
    /// semantics). Equal to [`intersects_brute`] on every input.
    ///
    /// Both outlines are in the same coordinates ([`HalTree2::intersects_placed`] places
    /// one against the other).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_hal::{HalTree2, Polyline2};
    ///
    /// let square = |lo: f64, hi: f64| {
    ///     let p = |x, y| DVec2::new(x, y);
    ///     Polyline2::polygon(vec![p(lo, lo), p(hi, lo), p(hi, hi), p(lo, hi)])
    /// };
    /// let big = HalTree2::build(&square(0.0, 10.0)?)?;
    /// let small = HalTree2::build(&square(2.0, 3.0)?)?;
    /// assert!(big.intersects(&small)); // nested: the regions meet
    /// let road = Polyline2::open(vec![DVec2::new(4.0, 4.0), DVec2::new(5.0, 6.0)])?;
    /// assert!(big.intersects(&HalTree2::build(&road)?)); // a polyline inside
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn intersects(&self, other: &Self) -> bool {
        // The identity is a proper similarity: the check cannot fail.
        self.intersects_placed(other, DAffine2::IDENTITY)
            .unwrap_or(false)
    }

    /// [`HalTree2::intersects`] with `other` placed by `placement` (a rotation, a uniform
    /// scale and a translation, mapping `other`'s coordinates into this tree's): the same
    /// answer as [`intersects_brute`] on `other`'s vertices mapped by `placement`, without
    /// building anything.
    ///
    /// # Errors
    ///
    /// [`HalError::InvalidPlacement`] for a map that is not a proper similarity (a shear,
    /// an uneven scale, a mirror, a singular or non-finite matrix).
    pub fn intersects_placed(&self, other: &Self, placement: DAffine2) -> Result<bool, HalError> {
        let mut met = false;
        self.edge_pairs(other, placement, |_, _| {
            met = true;
            ControlFlow::Break(())
        })?;
        if met {
            return Ok(true);
        }
        // Boundaries apart: one inside the other, decided by one vertex each way.
        let inside = |l: Result<Containment, HalError>| {
            matches!(l, Ok(Containment::Inside | Containment::Boundary))
        };
        let theirs_first = placement.transform_point2(other.polyline().points()[0]);
        let mine_first = placement
            .inverse()
            .transform_point2(self.polyline().points()[0]);
        Ok(inside(self.contains(theirs_first)) || inside(other.contains(mine_first)))
    }

    /// The paper's section 5.2 carried to the end: every pair of intersecting edges
    /// `(edge of self, edge of other)`, in increasing order (edge `i` runs from vertex `i`
    /// to the next, as [`Polyline2::edge`]); equal to [`intersecting_edges_brute`]. Empty
    /// when the outlines do not cross or touch, even if one lies inside the other (ask
    /// [`HalTree2::intersects`] for regions).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_hal::{HalTree2, Polyline2};
    ///
    /// let p = |x, y| DVec2::new(x, y);
    /// let square = HalTree2::build(&Polyline2::polygon(vec![
    ///     p(0.0, 0.0), p(2.0, 0.0), p(2.0, 2.0), p(0.0, 2.0),
    /// ])?)?;
    /// // A road entering through the bottom edge (0) and leaving through the right (1).
    /// let road = HalTree2::build(&Polyline2::open(vec![p(1.0, -1.0), p(1.0, 1.0), p(3.0, 1.0)])?)?;
    /// assert_eq!(square.intersecting_edges(&road), vec![(0, 0), (1, 1)]);
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn intersecting_edges(&self, other: &Self) -> Vec<(usize, usize)> {
        // The identity is a proper similarity: the check cannot fail.
        self.intersecting_edges_placed(other, DAffine2::IDENTITY)
            .unwrap_or_default()
    }

    /// [`HalTree2::intersecting_edges`] with `other` placed by `placement`, as
    /// [`HalTree2::intersects_placed`].
    ///
    /// # Errors
    ///
    /// [`HalError::InvalidPlacement`], as [`HalTree2::intersects_placed`].
    pub fn intersecting_edges_placed(
        &self,
        other: &Self,
        placement: DAffine2,
    ) -> Result<Vec<(usize, usize)>, HalError> {
        let mut pairs = Vec::new();
        self.edge_pairs(other, placement, |i, j| {
            pairs.push((i, j));
            ControlFlow::Continue(())
        })?;
        pairs.sort_unstable();
        Ok(pairs)
    }

    /// Calls `visit` with every pair of intersecting edges (indices into each outline's
    /// edges), until it breaks.
    pub(crate) fn edge_pairs(
        &self,
        other: &Self,
        placement: DAffine2,
        mut visit: impl FnMut(usize, usize) -> ControlFlow<()>,
    ) -> Result<(), HalError> {
        let scale = check_placement(&placement)?;
        let identity = placement == DAffine2::IDENTITY;
        let mine = Placed {
            tree: self,
            map: DAffine2::IDENTITY,
            scale: 1.0,
            identity: true,
            slack: 0.0,
        };
        let mut theirs = Placed {
            tree: other,
            map: placement,
            scale,
            identity,
            slack: 0.0,
        };
        let slack = CONTAINMENT_SLACK * (mine.reach() + theirs.reach()).max(f64::MIN_POSITIVE);
        theirs.slack = if identity { 0.0 } else { slack };
        {
            let (lo, hi) = self.bounding_box();
            let own = Box2 { min: lo, max: hi };
            let (lo, hi) = other.bounding_box();
            let placed = if identity {
                Box2 { min: lo, max: hi }
            } else {
                let corners = [lo, hi, DVec2::new(lo.x, hi.y), DVec2::new(hi.x, lo.y)];
                let b = corners
                    .iter()
                    .fold(Box2::EMPTY, |b, &c| b.grow(placement.transform_point2(c)));
                Box2 {
                    min: b.min - slack,
                    max: b.max + slack,
                }
            };
            if own.apart(&placed) {
                return Ok(());
            }
        }
        let mut stack: Vec<(Part, Part)> = Vec::new();
        for a in self.chains() {
            for b in other.chains() {
                stack.push((
                    mine.part(a.first, a.last, a.node),
                    theirs.part(b.first, b.last, b.node),
                ));
            }
        }
        while let Some((a, b)) = stack.pop() {
            let apart = a.bounds.apart(&b.bounds)
                || a.regions
                    .iter()
                    .any(|&r| b.regions.iter().any(|&s| r.apart(s, slack)));
            if apart {
                continue;
            }
            match (a.node, b.node) {
                (None, None) => {
                    let (p, q) = (mine.point(a.first), mine.point(a.last));
                    let (r, s) = (theirs.point(b.first), theirs.point(b.last));
                    if segments_intersect(p, q, r, s)
                        && visit(self.vertex_at(a.first), other.vertex_at(b.first)).is_break()
                    {
                        return Ok(());
                    }
                }
                (Some(_), None) => stack.extend(mine.halves(&a).map(|h| (h, b))),
                (None, Some(_)) => stack.extend(theirs.halves(&b).map(|h| (a, h))),
                (Some(i), Some(j)) => {
                    if mine.size(&a, i) >= theirs.size(&b, j) {
                        stack.extend(mine.halves(&a).map(|h| (h, b)));
                    } else {
                        stack.extend(theirs.halves(&b).map(|h| (a, h)));
                    }
                }
            }
        }
        Ok(())
    }
}
