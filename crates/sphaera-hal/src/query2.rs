//! Hierarchical operations on 2D HAL trees (section 5 of the paper): point inclusion and
//! intersection detection, with their brute-force references.

use glam::DVec2;

use crate::lens::{CONTAINMENT_SLACK, coord};
use crate::tree2::Node2;
use crate::{HalError, HalTree2, Polyline2};

/// Where a point lies with respect to a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Location {
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
pub fn contains_brute(polygon: &Polyline2, x: DVec2) -> Result<Location, HalError> {
    if !polygon.is_closed() {
        return Err(HalError::OpenPolyline);
    }
    let mut inside = false;
    for i in 0..polygon.edge_count() {
        let (a, b) = polygon.edge(i);
        match ray_crossing(a, b, x) {
            None => return Ok(Location::Boundary),
            Some(crossed) => inside ^= crossed,
        }
    }
    Ok(if inside {
        Location::Inside
    } else {
        Location::Outside
    })
}

impl HalTree2 {
    /// Point inclusion (section 5.1): the crossing number of a ray from `x`, with every
    /// part of the outline whose bounding area does not contain `x` replaced by its chord.
    ///
    /// The answer equals [`contains_brute`]'s on every input: the same half-open crossing
    /// rule and exact orientation tests are used, a chord is used only for a part whose
    /// bounding area `x` is clearly outside of (so `x` lies on neither), and a union
    /// bounding area (never made by a polygon whose vertices avoid their chords' lines,
    /// Theorem 1) is always descended. Points exactly on an edge or at a vertex are
    /// [`Location::Boundary`].
    ///
    /// # Errors
    ///
    /// [`HalError::OpenPolyline`] for an open polyline.
    pub fn contains(&self, x: DVec2) -> Result<Location, HalError> {
        if !self.polyline().is_closed() {
            return Err(HalError::OpenPolyline);
        }
        if let Some((centre, radius)) = self.root_disc() {
            let slack = CONTAINMENT_SLACK * (radius + centre.abs().max_element());
            if x.distance(centre) > radius + slack {
                return Ok(Location::Outside);
            }
        }
        let mut inside = false;
        let mut stack: Vec<(u32, u32, Option<usize>)> = Vec::new();
        for chain in self.chains() {
            stack.push((chain.first, chain.last, chain.node));
            while let Some((p, s, node)) = stack.pop() {
                let (a, b) = (self.point_at(p), self.point_at(s));
                let Some(id) = node else {
                    // One original edge.
                    match ray_crossing(a, b, x) {
                        None => return Ok(Location::Boundary),
                        Some(crossed) => inside ^= crossed,
                    }
                    continue;
                };
                let n: &Node2 = &self.nodes()[id];
                if n.lens.may_contain(a, b, x) {
                    let [left, right] = n.children();
                    stack.push((n.split, s, right));
                    stack.push((p, n.split, left));
                } else if let Some(crossed) = ray_crossing(a, b, x) {
                    inside ^= crossed;
                }
            }
        }
        Ok(if inside {
            Location::Inside
        } else {
            Location::Outside
        })
    }
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
/// [`HalTree2::intersects`]. Two closed polygons intersect when their boundaries share a
/// point or one lies inside the other (regions, as the paper's section 5.2 means);
/// anything with an open polyline, when the outlines share a point.
#[must_use]
pub fn intersects_brute(first: &Polyline2, second: &Polyline2) -> bool {
    for i in 0..first.edge_count() {
        let (a, b) = first.edge(i);
        for j in 0..second.edge_count() {
            let (c, d) = second.edge(j);
            if segments_intersect(a, b, c, d) {
                return true;
            }
        }
    }
    one_inside_the_other(first, second, contains_brute)
}

/// With boundaries known to be disjoint: whether one closed polygon lies inside the other
/// (one vertex of each decides).
fn one_inside_the_other(
    first: &Polyline2,
    second: &Polyline2,
    locate: impl Fn(&Polyline2, DVec2) -> Result<Location, HalError>,
) -> bool {
    if !(first.is_closed() && second.is_closed()) {
        return false;
    }
    let within = |polygon: &Polyline2, x: DVec2| {
        matches!(
            locate(polygon, x),
            Ok(Location::Inside | Location::Boundary)
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
    /// Whether the two regions are certainly disjoint (false when in doubt).
    fn apart(self, other: Self, slack: f64) -> bool {
        match (self, other) {
            (Self::Everything, _) | (_, Self::Everything) => false,
            (Self::Disc(c, r), Self::Disc(d, s)) => c.distance(d) > r + s + slack,
            (Self::Disc(c, r), Self::HalfPlane(p, n))
            | (Self::HalfPlane(p, n), Self::Disc(c, r)) => (c - p).dot(n) < -r - slack,
            (Self::HalfPlane(p, n), Self::HalfPlane(q, m)) => {
                (n + m).length() <= 1e-12 && (q - p).dot(n) < -slack
            }
        }
    }
}

/// A part of an outline in the pair traversal: its chord, its node (`None`: one original
/// edge), and the two regions whose intersection bounds it.
#[derive(Clone, Copy, Debug)]
struct Part {
    first: u32,
    last: u32,
    node: Option<usize>,
    regions: [Region; 2],
}

impl HalTree2 {
    /// The part over positions `first..=last` with node `node`.
    fn part(&self, first: u32, last: u32, node: Option<usize>) -> Part {
        let (a, b) = (self.point_at(first), self.point_at(last));
        let regions = match node {
            // An edge lies in its diametral disc.
            None => {
                let disc = Region::Disc(a.midpoint(b), 0.5 * a.distance(b));
                [disc, disc]
            }
            Some(id) => {
                let lens = self.nodes()[id].lens;
                if lens.kind() == crate::LensKind::Union {
                    [Region::Everything, Region::Everything]
                } else {
                    lens.discs(a, b).map(|d| match d {
                        crate::SignedDisc::Disc { centre, radius } => {
                            Region::Disc(centre, radius.abs())
                        }
                        crate::SignedDisc::HalfPlane { point, inward } => {
                            Region::HalfPlane(point, inward)
                        }
                    })
                }
            }
        };
        Part {
            first,
            last,
            node,
            regions,
        }
    }

    /// The two parts a node's part splits into.
    fn halves(&self, part: &Part) -> [Part; 2] {
        let node = &self.nodes()[part.node.unwrap_or_default()];
        let [left, right] = node.children();
        [
            self.part(part.first, node.split, left),
            self.part(node.split, part.last, right),
        ]
    }

    /// Intersection detection (section 5.2): pairs of parts whose bounding areas may meet
    /// are refined, the larger part first, down to pairs of original edges, which are
    /// tested exactly; two closed polygons whose boundaries are apart then intersect when
    /// one holds a vertex of the other. Equal to [`intersects_brute`] on every input.
    ///
    /// Both outlines are in the same coordinates.
    #[must_use]
    pub fn intersects(&self, other: &Self) -> bool {
        if let (Some((c, r)), Some((d, s))) = (self.root_disc(), other.root_disc()) {
            let slack = CONTAINMENT_SLACK * (r + s + c.abs().max_element() + d.abs().max_element());
            if c.distance(d) > r + s + slack {
                return false;
            }
        }
        let scale = |tree: &Self| {
            tree.polyline()
                .points()
                .iter()
                .fold(0.0_f64, |m, p| m.max(p.abs().max_element()))
        };
        let slack = CONTAINMENT_SLACK * (scale(self) + scale(other)).max(f64::MIN_POSITIVE);
        let mut stack: Vec<(Part, Part)> = Vec::new();
        for a in self.chains() {
            for b in other.chains() {
                stack.push((
                    self.part(a.first, a.last, a.node),
                    other.part(b.first, b.last, b.node),
                ));
            }
        }
        while let Some((a, b)) = stack.pop() {
            let apart = a
                .regions
                .iter()
                .any(|&r| b.regions.iter().any(|&s| r.apart(s, slack)));
            if apart {
                continue;
            }
            match (a.node, b.node) {
                (None, None) => {
                    let (p, q) = (self.point_at(a.first), self.point_at(a.last));
                    let (r, s) = (other.point_at(b.first), other.point_at(b.last));
                    if segments_intersect(p, q, r, s) {
                        return true;
                    }
                }
                (Some(_), None) => {
                    stack.extend(self.halves(&a).map(|h| (h, b)));
                }
                (None, Some(_)) => {
                    stack.extend(other.halves(&b).map(|h| (a, h)));
                }
                (Some(i), Some(j)) => {
                    let size = |tree: &Self, part: &Part, id: usize| {
                        tree.point_at(part.first).distance(tree.point_at(part.last))
                            + tree.nodes()[id].width.min(f64::MAX)
                    };
                    if size(self, &a, i) >= size(other, &b, j) {
                        stack.extend(self.halves(&a).map(|h| (h, b)));
                    } else {
                        stack.extend(other.halves(&b).map(|h| (a, h)));
                    }
                }
            }
        }
        one_inside_the_other(self.polyline(), other.polyline(), |polygon, x| {
            if std::ptr::eq(polygon, self.polyline()) {
                self.contains(x)
            } else {
                other.contains(x)
            }
        })
    }
}
