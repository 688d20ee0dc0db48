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

/// What one edge says about a point: on it, or whether the horizontal ray from the point
/// to `+x` crosses it. The half-open rule (an edge counts when exactly one end lies
/// strictly above the point) makes every closed loop cross an even number of times when
/// the point is not on it, so replacing a part of the outline by its chord keeps the
/// parity whenever the point is outside the part's bounding area.
fn edge_test(a: DVec2, b: DVec2, x: DVec2) -> Result<bool, ()> {
    let orientation = robust::orient2d(coord(a), coord(b), coord(x));
    if orientation == 0.0
        && x.x >= a.x.min(b.x)
        && x.x <= a.x.max(b.x)
        && x.y >= a.y.min(b.y)
        && x.y <= a.y.max(b.y)
    {
        return Err(());
    }
    if (a.y > x.y) == (b.y > x.y) {
        return Ok(false);
    }
    // Upward edges cross when the point is on their left, downward ones on their right.
    Ok(if b.y > a.y {
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
        match edge_test(a, b, x) {
            Err(()) => return Ok(Location::Boundary),
            Ok(crossed) => inside ^= crossed,
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
                    match edge_test(a, b, x) {
                        Err(()) => return Ok(Location::Boundary),
                        Ok(crossed) => inside ^= crossed,
                    }
                    continue;
                };
                let n: &Node2 = &self.nodes()[id];
                if n.lens.may_contain(a, b, x) {
                    let [left, right] = n.children();
                    stack.push((n.split, s, right));
                    stack.push((p, n.split, left));
                } else if let Ok(crossed) = edge_test(a, b, x) {
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
