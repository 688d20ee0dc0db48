//! Polygons with holes and multipolygons (a country with its islands and lakes): one HAL
//! tree per ring, one answer for the whole, as GEOS and shapely give it.

use std::ops::ControlFlow;

use glam::{DAffine2, DVec2};

use crate::nearest2::NearestEdge;
use crate::ring_index::RingIndex;
use crate::tree2::Box2;
use crate::{Containment, HalError, HalTree2, Polyline2, contains_brute};

/// A polygon with holes: an exterior ring and any number of hole rings, each a closed
/// [`Polyline2`].
///
/// Its region is the exterior's inside less the holes' insides; a point on its exterior,
/// or on a hole where the exterior's closure holds it, is on its boundary. Rings are taken
/// as given: their orientation does not matter, and holes are not checked to lie inside
/// the exterior (GEOS's validity); answers on an invalid polygon follow the rule above.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon2 {
    exterior: Polyline2,
    holes: Vec<Polyline2>,
}

impl Polygon2 {
    /// The polygon bounded by `exterior`, less `holes`.
    ///
    /// # Errors
    ///
    /// [`HalError::OpenRing`] when a ring is an open polyline.
    pub fn new(exterior: Polyline2, holes: Vec<Polyline2>) -> Result<Self, HalError> {
        for (ring, outline) in std::iter::once(&exterior).chain(&holes).enumerate() {
            if !outline.is_closed() {
                return Err(HalError::OpenRing { ring });
            }
        }
        Ok(Self { exterior, holes })
    }

    /// The exterior ring.
    #[must_use]
    pub fn exterior(&self) -> &Polyline2 {
        &self.exterior
    }

    /// The hole rings.
    #[must_use]
    pub fn holes(&self) -> &[Polyline2] {
        &self.holes
    }

    /// Every ring, the exterior first ([`RingId::ring`] numbers them so).
    pub fn rings(&self) -> impl Iterator<Item = &Polyline2> {
        std::iter::once(&self.exterior).chain(&self.holes)
    }
}

/// Several polygons with holes: a country with its islands, a part with its holes.
///
/// Its region is the union of its polygons' regions (GEOS's and shapely's meaning of a
/// valid multipolygon, whose polygons do not overlap; on overlapping polygons the union is
/// still what [`HalMultiPolygon2`] answers).
///
/// # Examples
///
/// ```
/// use glam::DVec2;
/// use sphaera_hal::{Containment, HalMultiPolygon2, MultiPolygon2};
///
/// let square = |lo: f64, hi: f64| {
///     vec![DVec2::new(lo, lo), DVec2::new(hi, lo), DVec2::new(hi, hi), DVec2::new(lo, hi)]
/// };
/// // A square with a square lake, and an island off its coast.
/// let land = MultiPolygon2::from_rings(vec![
///     vec![square(0.0, 10.0), square(4.0, 6.0)],
///     vec![square(12.0, 13.0)],
/// ])?;
/// let tree = HalMultiPolygon2::build(&land)?;
/// assert_eq!(tree.contains(DVec2::new(1.0, 1.0)), Containment::Inside);
/// assert_eq!(tree.contains(DVec2::new(5.0, 5.0)), Containment::Outside); // the lake
/// assert_eq!(tree.contains(DVec2::new(12.5, 12.5)), Containment::Inside); // the island
/// assert_eq!(tree.contains(DVec2::new(4.0, 5.0)), Containment::Boundary); // the shore
/// # Ok::<(), sphaera_hal::HalError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct MultiPolygon2 {
    polygons: Vec<Polygon2>,
}

impl MultiPolygon2 {
    /// The multipolygon of `polygons` (at least one).
    ///
    /// # Errors
    ///
    /// [`HalError::EmptyMultiPolygon`] for no polygon.
    pub fn new(polygons: Vec<Polygon2>) -> Result<Self, HalError> {
        if polygons.is_empty() {
            return Err(HalError::EmptyMultiPolygon);
        }
        Ok(Self { polygons })
    }

    /// The multipolygon of rings given as points, GeoJSON's layout: per polygon, its
    /// exterior ring then its holes, each closed implicitly (a repeated first point at
    /// the end, as GeoJSON and WKT write rings, is dropped).
    ///
    /// # Errors
    ///
    /// [`HalError::EmptyMultiPolygon`]; [`HalError::Ring`] naming the polygon and ring of
    /// a ring that is not a polygon (too few vertices, a non-finite coordinate) or of a
    /// polygon given with no ring.
    pub fn from_rings(polygons: Vec<Vec<Vec<DVec2>>>) -> Result<Self, HalError> {
        let mut out = Vec::with_capacity(polygons.len());
        for (index, rings) in polygons.into_iter().enumerate() {
            let at = |ring: usize, source: HalError| HalError::Ring {
                polygon: index,
                ring,
                source: Box::new(source),
            };
            let mut outlines = Vec::with_capacity(rings.len());
            for (ring, mut points) in rings.into_iter().enumerate() {
                if points.len() > 1 && points.first() == points.last() {
                    points.pop();
                }
                outlines.push(Polyline2::polygon(points).map_err(|e| at(ring, e))?);
            }
            if outlines.is_empty() {
                return Err(at(
                    0,
                    HalError::TooFewVertices {
                        shape: "polygon",
                        count: 0,
                        needed: 3,
                    },
                ));
            }
            let exterior = outlines.remove(0);
            out.push(Polygon2 {
                exterior,
                holes: outlines,
            });
        }
        Self::new(out)
    }

    /// [`MultiPolygon2::from_rings`] after dropping the rings that bound no area: fewer
    /// than three distinct points (published data has them: Natural Earth's 1:10m Italy
    /// has a hole of two points where the Vatican is, which GEOS and shapely refuse to
    /// build). A dropped exterior drops its polygon's holes too. Returns the rings dropped
    /// (their ids in the input's numbering), so that a caller can say so.
    ///
    /// # Errors
    ///
    /// As [`MultiPolygon2::from_rings`] (every ring dropped is
    /// [`HalError::EmptyMultiPolygon`]).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_hal::{MultiPolygon2, RingId};
    ///
    /// let p = |x, y| DVec2::new(x, y);
    /// let square = vec![p(0.0, 0.0), p(4.0, 0.0), p(4.0, 4.0), p(0.0, 4.0)];
    /// let sliver = vec![p(1.0, 1.0), p(2.0, 2.0), p(1.0, 1.0)];
    /// let (shape, dropped) = MultiPolygon2::from_rings_dropping_degenerate(vec![vec![square, sliver]])?;
    /// assert_eq!(dropped, vec![RingId { polygon: 0, ring: 1 }]);
    /// assert_eq!(shape.ring_count(), 1);
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    pub fn from_rings_dropping_degenerate(
        polygons: Vec<Vec<Vec<DVec2>>>,
    ) -> Result<(Self, Vec<RingId>), HalError> {
        let mut dropped = Vec::new();
        let mut kept = Vec::with_capacity(polygons.len());
        for (polygon, rings) in polygons.into_iter().enumerate() {
            let mut out = Vec::with_capacity(rings.len());
            for (ring, points) in rings.into_iter().enumerate() {
                if distinct_at_least_three(&points) {
                    out.push(points);
                } else if ring == 0 {
                    dropped.push(RingId { polygon, ring });
                    break;
                } else {
                    dropped.push(RingId { polygon, ring });
                }
            }
            if !out.is_empty() {
                kept.push(out);
            }
        }
        Ok((Self::from_rings(kept)?, dropped))
    }

    /// The polygons.
    #[must_use]
    pub fn polygons(&self) -> &[Polygon2] {
        &self.polygons
    }

    /// The rings of every polygon.
    #[must_use]
    pub fn ring_count(&self) -> usize {
        self.polygons.iter().map(|p| 1 + p.holes.len()).sum()
    }

    /// The vertices of every ring.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.polygons
            .iter()
            .flat_map(Polygon2::rings)
            .map(|r| r.points().len())
            .sum()
    }

    /// The bounding box of every vertex: `(min, max)`.
    #[must_use]
    pub fn bounds(&self) -> (DVec2, DVec2) {
        self.polygons.iter().map(|p| p.exterior.bounds()).fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), (l, h)| (lo.min(l), hi.max(h)),
        )
    }

    /// Point inclusion by brute force over every edge: the reference for
    /// [`HalMultiPolygon2::contains`].
    #[must_use]
    pub fn contains_brute(&self, x: DVec2) -> Containment {
        let mut boundary = false;
        for polygon in &self.polygons {
            let mut states = polygon
                .rings()
                .map(|ring| contains_brute(ring, x).unwrap_or(Containment::Outside));
            match states.next() {
                Some(Containment::Inside) => {}
                Some(Containment::Boundary) => {
                    boundary = true;
                    continue;
                }
                _ => continue,
            }
            let mut in_hole = false;
            for state in states {
                match state {
                    Containment::Inside => in_hole = true,
                    Containment::Boundary => {
                        boundary = true;
                        in_hole = true;
                    }
                    Containment::Outside => {}
                }
            }
            if !in_hole {
                return Containment::Inside;
            }
        }
        if boundary {
            Containment::Boundary
        } else {
            Containment::Outside
        }
    }
}

/// A ring of a multipolygon: its polygon, and which ring (0 the exterior, `k` the hole
/// `k − 1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RingId {
    /// The polygon's index.
    pub polygon: usize,
    /// 0 for the exterior, `k` for the hole `k − 1`.
    pub ring: usize,
}

impl RingId {
    /// Whether the ring is a hole.
    #[must_use]
    pub fn is_hole(&self) -> bool {
        self.ring > 0
    }
}

/// Where a point lies in a multipolygon ([`HalMultiPolygon2::locate`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Location2 {
    /// Inside, outside or on the boundary.
    pub containment: Containment,
    /// The innermost ring whose closed region holds the point: the exterior of the
    /// polygon holding it (inside), the ring it lies on (boundary), the hole it lies in
    /// (outside, in a lake), or `None` (outside every polygon).
    pub ring: Option<RingId>,
}

/// An edge of a ring of a multipolygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RingEdge {
    /// The ring.
    pub ring: RingId,
    /// The edge (edge `i` runs from the ring's vertex `i` to the next).
    pub edge: usize,
}

/// The edge of a multipolygon nearest a point ([`HalMultiPolygon2::nearest_edge`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearestRingEdge {
    /// The ring and edge.
    pub at: RingEdge,
    /// The distance from the point to the edge (0 on it).
    pub distance: f64,
    /// The edge's point nearest the point.
    pub point: DVec2,
}

/// HAL trees over every ring of a [`MultiPolygon2`], with a box hierarchy over the
/// rings: point inclusion, localisation and intersection for the whole.
///
/// A query visits only the rings whose bounding boxes hold the point, so a country's
/// hundreds of islands cost a few box tests. Every answer equals the brute-force one
/// ([`MultiPolygon2::contains_brute`], edges tested pairwise).
#[derive(Clone, Debug)]
pub struct HalMultiPolygon2 {
    trees: Vec<HalTree2>,
    rings: Vec<RingId>,
    /// Per polygon, the index in `trees` of its exterior (holes follow it).
    first_ring: Vec<usize>,
    index: RingIndex,
    bounds: Box2,
}

impl HalMultiPolygon2 {
    /// One HAL tree per ring ([`HalTree2::build`]) and the hierarchy over the rings.
    ///
    /// # Errors
    ///
    /// [`HalError::Ring`] naming the polygon and ring whose tree cannot be built.
    pub fn build(shape: &MultiPolygon2) -> Result<Self, HalError> {
        let mut trees = Vec::with_capacity(shape.ring_count());
        let mut rings = Vec::with_capacity(shape.ring_count());
        let mut first_ring = Vec::with_capacity(shape.polygons.len());
        for (polygon, p) in shape.polygons.iter().enumerate() {
            first_ring.push(trees.len());
            for (ring, outline) in p.rings().enumerate() {
                let tree = HalTree2::build(outline).map_err(|source| HalError::Ring {
                    polygon,
                    ring,
                    source: Box::new(source),
                })?;
                trees.push(tree);
                rings.push(RingId { polygon, ring });
            }
        }
        let boxes: Vec<Box2> = trees.iter().map(|t| *t.bounds()).collect();
        let bounds = boxes.iter().fold(Box2::EMPTY, |b, r| b.union(r));
        Ok(Self {
            trees,
            rings,
            first_ring,
            index: RingIndex::new(boxes),
            bounds,
        })
    }

    /// The tree of a ring.
    ///
    /// # Panics
    ///
    /// If the ring does not exist.
    #[must_use]
    pub fn ring(&self, id: RingId) -> &HalTree2 {
        &self.trees[self.first_ring[id.polygon] + id.ring]
    }

    /// Every ring's tree with its id, polygon by polygon, exteriors first.
    pub fn rings(&self) -> impl Iterator<Item = (RingId, &HalTree2)> {
        self.rings.iter().copied().zip(&self.trees)
    }

    /// The number of polygons.
    #[must_use]
    pub fn polygon_count(&self) -> usize {
        self.first_ring.len()
    }

    /// The bounding box of every vertex: `(min, max)`.
    #[must_use]
    pub fn bounding_box(&self) -> (DVec2, DVec2) {
        (self.bounds.min, self.bounds.max)
    }

    /// Point inclusion: inside the region, outside, or on a ring (exact, as
    /// [`HalTree2::contains`] for each ring).
    #[must_use]
    pub fn contains(&self, x: DVec2) -> Containment {
        self.locate(x).containment
    }

    /// Point inclusion that says where: the containment and the innermost ring holding
    /// the point ([`Location2`]).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_hal::{Containment, HalMultiPolygon2, MultiPolygon2, RingId};
    ///
    /// let square = |lo: f64, hi: f64| {
    ///     vec![DVec2::new(lo, lo), DVec2::new(hi, lo), DVec2::new(hi, hi), DVec2::new(lo, hi)]
    /// };
    /// let tree = HalMultiPolygon2::build(&MultiPolygon2::from_rings(vec![vec![
    ///     square(0.0, 10.0),
    ///     square(4.0, 6.0),
    /// ]])?)?;
    /// let in_lake = tree.locate(DVec2::new(5.0, 5.0));
    /// assert_eq!(in_lake.containment, Containment::Outside);
    /// assert_eq!(in_lake.ring, Some(RingId { polygon: 0, ring: 1 }));
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn locate(&self, x: DVec2) -> Location2 {
        if !self.bounds.holds(x) {
            return Location2 {
                containment: Containment::Outside,
                ring: None,
            };
        }
        CANDIDATES.with_borrow_mut(|candidates| {
            candidates.clear();
            self.index.for_each_holding(x, |r| {
                let state = self.trees[r].ring_containment(x);
                if state != Containment::Outside {
                    candidates.push((r as u32, state));
                }
            });
            candidates.sort_unstable_by_key(|c| c.0);
            let mut boundary = None;
            let mut lake = None;
            for &(r, state) in candidates.iter() {
                let id = self.rings[r as usize];
                if state == Containment::Boundary {
                    // A hole's ring bounds the polygon where the exterior's closure holds
                    // it (a hole sticking out of an invalid polygon bounds nothing there).
                    let bounds_polygon = !id.is_hole()
                        || candidates
                            .iter()
                            .any(|&(e, _)| self.rings[e as usize] == RingId { ring: 0, ..id });
                    if bounds_polygon {
                        boundary.get_or_insert(id);
                    }
                    continue;
                }
                if id.is_hole() {
                    continue;
                }
                // Inside an exterior: inside the polygon unless in (or on) one of its holes.
                let hole = candidates.iter().find(|&&(h, _)| {
                    let hid = self.rings[h as usize];
                    hid.polygon == id.polygon && hid.is_hole()
                });
                match hole {
                    None => {
                        return Location2 {
                            containment: Containment::Inside,
                            ring: Some(id),
                        };
                    }
                    Some(&(h, Containment::Inside)) => {
                        lake.get_or_insert(self.rings[h as usize]);
                    }
                    Some(_) => {}
                }
            }
            match boundary {
                Some(ring) => Location2 {
                    containment: Containment::Boundary,
                    ring: Some(ring),
                },
                None => Location2 {
                    containment: Containment::Outside,
                    ring: lake,
                },
            }
        })
    }

    /// Localisation: the edge of any ring nearest `x`, its distance and nearest point
    /// (rings visited nearest box first, each by [`HalTree2::nearest_edge`]'s branch and
    /// bound, stopping when a ring's box is farther than the nearest edge found).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_hal::{HalMultiPolygon2, MultiPolygon2, RingId};
    ///
    /// let square = |lo: f64, hi: f64| {
    ///     vec![DVec2::new(lo, lo), DVec2::new(hi, lo), DVec2::new(hi, hi), DVec2::new(lo, hi)]
    /// };
    /// let tree = HalMultiPolygon2::build(&MultiPolygon2::from_rings(vec![vec![
    ///     square(0.0, 10.0),
    ///     square(4.0, 6.0),
    /// ]])?)?;
    /// let nearest = tree.nearest_edge(DVec2::new(3.0, 5.0));
    /// assert_eq!(nearest.at.ring, RingId { polygon: 0, ring: 1 }); // the lake's shore
    /// assert_eq!(nearest.distance, 1.0);
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn nearest_edge(&self, x: DVec2) -> NearestRingEdge {
        let mut best = NearestEdge {
            edge: 0,
            distance: f64::INFINITY,
            point: DVec2::ZERO,
        };
        let mut ring = 0;
        for (bound, r) in self.index.by_distance(x) {
            if bound > best.distance {
                break;
            }
            if self.trees[r].nearest_edge_within(x, &mut best) {
                ring = r;
            }
        }
        NearestRingEdge {
            at: RingEdge {
                ring: self.rings[ring],
                edge: best.edge,
            },
            distance: best.distance,
            point: best.point,
        }
    }

    /// Whether the regions meet (GEOS's `intersects`): rings cross or touch, or a polygon
    /// of one lies inside a polygon of the other.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_hal::{HalMultiPolygon2, MultiPolygon2};
    ///
    /// let square = |lo: f64, hi: f64| {
    ///     vec![DVec2::new(lo, lo), DVec2::new(hi, lo), DVec2::new(hi, hi), DVec2::new(lo, hi)]
    /// };
    /// let build = |rings| HalMultiPolygon2::build(&MultiPolygon2::from_rings(rings)?);
    /// let land = build(vec![vec![square(0.0, 10.0), square(4.0, 6.0)]])?;
    /// let boat = build(vec![vec![square(4.5, 5.5)]])?;
    /// let shore = build(vec![vec![square(3.0, 4.5)]])?;
    /// assert!(!land.intersects(&boat)); // afloat in the lake
    /// assert!(land.intersects(&shore));
    /// assert!(land.intersecting_edges(&boat).is_empty());
    /// assert_eq!(land.intersecting_edges(&shore).len(), 2);
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn intersects(&self, other: &Self) -> bool {
        let mut met = false;
        self.ring_pairs(other, |_, _| {
            met = true;
            ControlFlow::Break(())
        });
        met || self
            .first_ring
            .iter()
            .any(|&r| other.contains(self.trees[r].polyline().points()[0]) != Containment::Outside)
            || other.first_ring.iter().any(|&r| {
                self.contains(other.trees[r].polyline().points()[0]) != Containment::Outside
            })
    }

    /// Every pair of intersecting edges of the two multipolygons' rings, in increasing
    /// order; empty when no rings cross or touch (even if one region holds the other).
    #[must_use]
    pub fn intersecting_edges(&self, other: &Self) -> Vec<(RingEdge, RingEdge)> {
        let mut pairs = Vec::new();
        self.ring_pairs(other, |a, b| {
            pairs.push((a, b));
            ControlFlow::Continue(())
        });
        pairs.sort_unstable();
        pairs
    }

    /// Whether an outline (an open polyline or a closed polygon) meets the region: it
    /// crosses or touches a ring, lies inside the region, or (closed) holds a polygon.
    #[must_use]
    pub fn intersects_outline(&self, outline: &HalTree2) -> bool {
        if !self
            .outline_edges(outline, |_, _| ControlFlow::Break(()))
            .is_empty()
        {
            return true;
        }
        let inside = |c: Containment| c != Containment::Outside;
        inside(self.contains(outline.polyline().points()[0]))
            || (outline.polyline().is_closed()
                && self.first_ring.iter().any(|&r| {
                    outline
                        .contains(self.trees[r].polyline().points()[0])
                        .is_ok_and(inside)
                }))
    }

    /// Every pair `(edge of a ring, edge of the outline)` that intersects, in increasing
    /// order.
    #[must_use]
    pub fn intersecting_outline_edges(&self, outline: &HalTree2) -> Vec<(RingEdge, usize)> {
        let mut pairs = self.outline_edges(outline, |_, _| ControlFlow::Continue(()));
        pairs.sort_unstable();
        pairs
    }

    /// The pairs of edges between the rings and `outline`, stopping when `visit` breaks.
    fn outline_edges(
        &self,
        outline: &HalTree2,
        mut visit: impl FnMut(RingEdge, usize) -> ControlFlow<()>,
    ) -> Vec<(RingEdge, usize)> {
        let mut pairs = Vec::new();
        let mut stop = false;
        self.index.for_each_meeting(outline.bounds(), |r| {
            if stop {
                return;
            }
            // The identity is a proper similarity: the placement check cannot fail.
            let _ = self.trees[r].edge_pairs(outline, DAffine2::IDENTITY, |i, j| {
                let edge = RingEdge {
                    ring: self.rings[r],
                    edge: i,
                };
                pairs.push((edge, j));
                let flow = visit(edge, j);
                stop = flow.is_break();
                flow
            });
        });
        pairs
    }

    /// Calls `visit` with every pair of intersecting ring edges, until it breaks.
    fn ring_pairs(
        &self,
        other: &Self,
        mut visit: impl FnMut(RingEdge, RingEdge) -> ControlFlow<()>,
    ) {
        if self.bounds.apart(&other.bounds) {
            return;
        }
        for (r, tree) in self.trees.iter().enumerate() {
            let mut stop = false;
            other.index.for_each_meeting(tree.bounds(), |s| {
                if stop {
                    return;
                }
                // The identity is a proper similarity: the placement check cannot fail.
                let _ = tree.edge_pairs(&other.trees[s], DAffine2::IDENTITY, |i, j| {
                    let flow = visit(
                        RingEdge {
                            ring: self.rings[r],
                            edge: i,
                        },
                        RingEdge {
                            ring: other.rings[s],
                            edge: j,
                        },
                    );
                    stop = flow.is_break();
                    flow
                });
            });
            if stop {
                return;
            }
        }
    }
}

thread_local! {
    /// The rings holding a point in [`HalMultiPolygon2::locate`], with their answers.
    static CANDIDATES: std::cell::RefCell<Vec<(u32, Containment)>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// Whether `points` hold at least three distinct points (non-finite ones count, so that
/// [`Polyline2::polygon`] names them).
fn distinct_at_least_three(points: &[DVec2]) -> bool {
    let Some(&first) = points.first() else {
        return false;
    };
    let Some(&second) = points.iter().find(|&&p| p != first) else {
        return false;
    };
    points.iter().any(|&p| p != first && p != second)
}
