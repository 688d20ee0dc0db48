//! Hierarchical operations on 2D HAL trees (section 5 of the paper): point inclusion and
//! intersection detection, with their brute-force references.

use glam::{DAffine2, DVec2};

use crate::lens::{CONTAINMENT_SLACK, coord};
use crate::tree2::Node2;
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
    /// Point inclusion (section 5.1): the crossing number of a ray from `x`, with every
    /// part of the outline whose bounding area does not contain `x` replaced by its chord.
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
    pub fn contains(&self, x: DVec2) -> Result<Containment, HalError> {
        if !self.polyline().is_closed() {
            return Err(HalError::OpenPolyline);
        }
        if let Some((center, radius)) = self.root_disc() {
            let slack = CONTAINMENT_SLACK * (radius + center.abs().max_element());
            if x.distance(center) > radius + slack {
                return Ok(Containment::Outside);
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
                        None => return Ok(Containment::Boundary),
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
            Containment::Inside
        } else {
            Containment::Outside
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
    locate: impl Fn(&Polyline2, DVec2) -> Result<Containment, HalError>,
) -> bool {
    if !(first.is_closed() && second.is_closed()) {
        return false;
    }
    let within = |polygon: &Polyline2, x: DVec2| {
        matches!(
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

/// A tree seen through a placement (a proper similarity) into another tree's coordinates.
#[derive(Clone, Copy)]
struct Placed<'a> {
    tree: &'a HalTree2,
    map: DAffine2,
    /// The map's scale.
    scale: f64,
}

impl Placed<'_> {
    fn point(&self, position: u32) -> DVec2 {
        self.map.transform_point2(self.tree.point_at(position))
    }

    /// The part over positions `first..=last` with node `node`. A proper similarity maps
    /// a disc through the chord's ends to the disc of the same bulge through the mapped
    /// ends, so the lens is rebuilt from the mapped chord.
    fn part(&self, first: u32, last: u32, node: Option<usize>) -> Part {
        let (a, b) = (self.point(first), self.point(last));
        let regions = match node {
            // An edge lies in its diametral disc.
            None => {
                let disc = Region::Disc(a.midpoint(b), 0.5 * a.distance(b));
                [disc, disc]
            }
            Some(id) => {
                let lens = self.tree.nodes()[id].lens;
                if lens.kind() == crate::LensKind::Union {
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
    /// placed root disc's (the outline lies in it), or a scan when there is no disc.
    fn reach(&self) -> f64 {
        match self.tree.root_disc() {
            Some((c, r)) => {
                let c = self.map.transform_point2(c);
                (c.abs().max_element() + r * self.scale) * (1.0 + 1e-12)
            }
            None => self.tree.polyline().points().iter().fold(0.0_f64, |m, &p| {
                m.max(self.map.transform_point2(p).abs().max_element())
            }),
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
    /// Intersection detection (section 5.2): pairs of parts whose bounding areas may meet
    /// are refined, the larger part first, down to pairs of original edges, which are
    /// tested exactly; two closed polygons whose boundaries are apart then intersect when
    /// one holds a vertex of the other. Equal to [`intersects_brute`] on every input.
    ///
    /// Both outlines are in the same coordinates ([`HalTree2::intersects_placed`] places
    /// one against the other).
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
        let scale = check_placement(&placement)?;
        let (mine, theirs) = (
            Placed {
                tree: self,
                map: DAffine2::IDENTITY,
                scale: 1.0,
            },
            Placed {
                tree: other,
                map: placement,
                scale,
            },
        );
        if let (Some((c, r)), Some((d, s))) = (self.root_disc(), other.root_disc()) {
            let (d, s) = (placement.transform_point2(d), s * scale);
            let slack = CONTAINMENT_SLACK * (r + s + c.abs().max_element() + d.abs().max_element());
            if c.distance(d) > r + s + slack {
                return Ok(false);
            }
        }
        let slack = CONTAINMENT_SLACK * (mine.reach() + theirs.reach()).max(f64::MIN_POSITIVE);
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
            let apart = a
                .regions
                .iter()
                .any(|&r| b.regions.iter().any(|&s| r.apart(s, slack)));
            if apart {
                continue;
            }
            match (a.node, b.node) {
                (None, None) => {
                    let (p, q) = (mine.point(a.first), mine.point(a.last));
                    let (r, s) = (theirs.point(b.first), theirs.point(b.last));
                    if segments_intersect(p, q, r, s) {
                        return Ok(true);
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
        if !(self.polyline().is_closed() && other.polyline().is_closed()) {
            return Ok(false);
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
}
