//! Localisation in 2D: the edge of an outline nearest a point, by branch and bound over
//! the tree's bounds, and its brute-force reference.

use glam::DVec2;

use crate::lens::CONTAINMENT_SLACK;
use crate::{HalTree2, LensKind, Polyline2, SignedDisc};

/// The edge of an outline nearest a point ([`HalTree2::nearest_edge`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearestEdge {
    /// The edge's index (edge `i` runs from vertex `i` to the next, as [`Polyline2::edge`]).
    pub edge: usize,
    /// The distance from the point to the edge (0 on it).
    pub distance: f64,
    /// The edge's point nearest the point.
    pub point: DVec2,
}

/// The point of the segment `a–b` nearest `x`.
#[must_use]
pub fn closest_on_segment(a: DVec2, b: DVec2, x: DVec2) -> DVec2 {
    let ab = b - a;
    let length_squared = ab.length_squared();
    if length_squared == 0.0 {
        return a;
    }
    let t = ((x - a).dot(ab) / length_squared).clamp(0.0, 1.0);
    // The ends exactly at the ends of the range (a + 1·ab need not round to b).
    if t <= 0.0 {
        a
    } else if t >= 1.0 {
        b
    } else {
        a + ab * t
    }
}

/// The nearest edge by brute force: the reference for [`HalTree2::nearest_edge`] (the
/// first of equally near edges).
#[must_use]
pub fn nearest_edge_brute(outline: &Polyline2, x: DVec2) -> NearestEdge {
    let mut best = NearestEdge {
        edge: 0,
        distance: f64::INFINITY,
        point: outline.points()[0],
    };
    for i in 0..outline.edge_count() {
        let (a, b) = outline.edge(i);
        let point = closest_on_segment(a, b, x);
        let distance = point.distance(x);
        if distance < best.distance {
            best = NearestEdge {
                edge: i,
                distance,
                point,
            };
        }
    }
    best
}

impl HalTree2 {
    /// Localisation: the edge nearest `x`, its distance and nearest point, by branch and
    /// bound. A part is skipped when a lower bound of its distance to `x` exceeds the
    /// nearest edge found so far; the bound is the larger of the distances to its bounding
    /// box and to each disc (or half-plane) of its bounding area, the part lying in all
    /// of them. Nearer parts are visited first.
    ///
    /// The distance is that of [`nearest_edge_brute`] (the same segment computation); on
    /// a tie between edges (a point equally near two), either may be returned, the same
    /// one on every run.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec2;
    /// use sphaera_hal::{HalTree2, Polyline2};
    ///
    /// let p = |x, y| DVec2::new(x, y);
    /// let square = HalTree2::build(&Polyline2::polygon(vec![
    ///     p(0.0, 0.0), p(4.0, 0.0), p(4.0, 4.0), p(0.0, 4.0),
    /// ])?)?;
    /// let nearest = square.nearest_edge(p(3.0, 1.5));
    /// assert_eq!(nearest.edge, 1); // from (4, 0) to (4, 4)
    /// assert_eq!(nearest.distance, 1.0);
    /// assert_eq!(nearest.point, p(4.0, 1.5));
    /// # Ok::<(), sphaera_hal::HalError>(())
    /// ```
    #[must_use]
    pub fn nearest_edge(&self, x: DVec2) -> NearestEdge {
        let mut best = NearestEdge {
            edge: 0,
            distance: f64::INFINITY,
            point: self.polyline().points()[0],
        };
        self.nearest_edge_within(x, &mut best);
        best
    }

    /// Improves `best` with this outline's nearest edge to `x` when nearer (`best` starts
    /// as the nearest known elsewhere, which prunes from the start).
    pub(crate) fn nearest_edge_within(&self, x: DVec2, best: &mut NearestEdge) -> bool {
        let mut improved = false;
        // (lower bound, first, last, node): nodes are pushed in pairs, the nearer last.
        let mut stack: Vec<(f64, u32, u32, Option<usize>)> = Vec::new();
        for chain in self.chains().iter().rev() {
            stack.push((0.0, chain.first, chain.last, chain.node));
        }
        while let Some((bound, p, s, node)) = stack.pop() {
            if bound > best.distance {
                continue;
            }
            let Some(id) = node else {
                let (a, b) = (self.point_at(p), self.point_at(s));
                let point = closest_on_segment(a, b, x);
                let distance = point.distance(x);
                if distance < best.distance {
                    *best = NearestEdge {
                        edge: self.vertex_at(p),
                        distance,
                        point,
                    };
                    improved = true;
                }
                continue;
            };
            let n = &self.nodes()[id];
            let [left, right] = n.children();
            let halves = [(p, n.split, left), (n.split, s, right)].map(|(first, last, child)| {
                (self.part_bound(x, first, last, child), first, last, child)
            });
            let [near, far] = if halves[0].0 <= halves[1].0 {
                halves
            } else {
                [halves[1], halves[0]]
            };
            for part in [far, near] {
                if part.0 <= best.distance {
                    stack.push(part);
                }
            }
        }
        improved
    }

    /// A lower bound of the distance from `x` to the part over positions `first..=last`.
    fn part_bound(&self, x: DVec2, first: u32, last: u32, node: Option<usize>) -> f64 {
        let (a, b) = (self.point_at(first), self.point_at(last));
        let Some(id) = node else {
            // An edge: its box.
            let lo = a.min(b);
            let hi = a.max(b);
            return (lo - x).max(x - hi).max(DVec2::ZERO).length();
        };
        let mut bound = self.node_box(id).distance(x);
        let lens = self.nodes()[id].lens;
        if lens.kind() == LensKind::Intersection {
            for disc in lens.discs(a, b) {
                let gap = match disc {
                    SignedDisc::Disc { center, radius } => {
                        let d = x.distance(center);
                        // Rounding of the disc's own size must not overstate the gap.
                        d - radius.abs() - CONTAINMENT_SLACK * (d + radius.abs())
                    }
                    SignedDisc::HalfPlane { point, inward } => {
                        let offset = -(x - point).dot(inward);
                        offset - CONTAINMENT_SLACK * (x - point).abs().element_sum()
                    }
                };
                bound = bound.max(gap);
            }
        }
        bound.max(0.0)
    }
}
