//! The states of the tree's nearest-first descents: the closest point (exact or within a
//! gap), the distance alone, and the upper bound over a triangle's corners.

use std::ops::{ControlFlow, Range};

use glam::DVec3;
use sphaera_mesh::Aabb;
use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};

use crate::bvh::NearestFirst;

/// The state of one closest-point descent. Candidates are compared by
/// [`point_triangle_distance_squared`] (a third of the cost of the closest point with its
/// feature, which only the winner gets).
pub(super) struct Search<'a> {
    pub(super) corners: &'a [[DVec3; 3]],
    pub(super) p: DVec3,
    pub(super) best_squared: f64,
    /// What may still be worth a look: the square of the best distance less the gap an
    /// approximate query allows (the best distance itself for an exact one).
    pub(super) limit_squared: f64,
    /// The gap allowed for a best distance (`None`: exact).
    pub(super) gap: Option<&'a dyn Fn(f64) -> f64>,
    /// The best triangle so far (its position in tree order) and its squared distance.
    pub(super) best: Option<(usize, f64)>,
    /// The smallest squared distance (or lower bound of one) of every other triangle.
    pub(super) runner_up_squared: f64,
}

impl Search<'_> {
    /// A new best triangle at squared distance `d`.
    pub(super) fn set_best(&mut self, i: usize, d: f64) {
        self.best_squared = d;
        self.best = Some((i, d));
        self.limit_squared = match self.gap {
            None => d,
            Some(gap) => {
                let best = d.sqrt();
                let limit = (best - gap(best)).max(0.0);
                limit * limit
            }
        };
    }
}

impl NearestFirst for Search<'_> {
    fn may_improve(&self, distance_squared: f64) -> bool {
        // An approximate search needs boxes that can bring the distance *below* the best
        // less the gap (one exactly there leaves the interval exactly as wide as allowed).
        match self.gap {
            None => distance_squared <= self.limit_squared,
            Some(_) => distance_squared < self.limit_squared,
        }
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        let current = self.best.map(|(i, _)| i);
        for i in positions {
            if Some(i) == current {
                // A seed is not compared with itself.
                continue;
            }
            let [a, b, c] = self.corners[i];
            // The triangle's box first: the distance costs several times more.
            let bounds = Aabb::new(a.min(b).min(c), a.max(b).max(c));
            let to_box = bounds.distance_squared_to_point(self.p);
            if to_box > self.limit_squared {
                self.runner_up_squared = self.runner_up_squared.min(to_box);
                continue;
            }
            let d = point_triangle_distance_squared(self.p, &Triangle::new(a, b, c));
            let better = d < self.best_squared || (self.best.is_none() && d <= self.best_squared);
            if better {
                if let Some((_, previous)) = self.best {
                    self.runner_up_squared = self.runner_up_squared.min(previous);
                }
                self.set_best(i, d);
                if self.gap.is_some() && self.limit_squared <= 0.0 {
                    // The best is within the gap of 0: `[0, best]` is narrow enough, and
                    // nothing else needs a look (nor bounds the interval from below).
                    self.runner_up_squared = 0.0;
                    return ControlFlow::Break(());
                }
            } else {
                self.runner_up_squared = self.runner_up_squared.min(d);
            }
        }
        ControlFlow::Continue(())
    }

    fn pruned(&mut self, distance_squared: f64) {
        self.runner_up_squared = self.runner_up_squared.min(distance_squared);
    }
}
/// The state of one [`TriangleTree::triangle_upper_bound`](super::TriangleTree::triangle_upper_bound)
/// descent.
pub(super) struct CornersBound<'a> {
    pub(super) corners: &'a [[DVec3; 3]],
    pub(super) x: [DVec3; 3],
    pub(super) best_squared: f64,
    pub(super) enough_squared: f64,
}

impl NearestFirst for CornersBound<'_> {
    fn may_improve(&self, key: f64) -> bool {
        key < self.best_squared
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        for &[a, b, c] in &self.corners[positions] {
            let bounds = Aabb::new(a.min(b).min(c), a.max(b).max(c));
            if self
                .x
                .iter()
                .any(|&p| bounds.distance_squared_to_point(p) >= self.best_squared)
            {
                continue;
            }
            let triangle = Triangle::new(a, b, c);
            let mut worst = 0.0_f64;
            for &p in &self.x {
                worst = worst.max(point_triangle_distance_squared(p, &triangle));
                if worst >= self.best_squared {
                    break;
                }
            }
            self.best_squared = self.best_squared.min(worst);
            if self.best_squared <= self.enough_squared {
                return ControlFlow::Break(());
            }
        }
        ControlFlow::Continue(())
    }
}

/// The state of one distance-only descent.
pub(super) struct Distance<'a> {
    pub(super) corners: &'a [[DVec3; 3]],
    pub(super) p: DVec3,
    pub(super) best_squared: f64,
}

impl NearestFirst for Distance<'_> {
    fn may_improve(&self, distance_squared: f64) -> bool {
        distance_squared < self.best_squared
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        for &[a, b, c] in &self.corners[positions] {
            let d = point_triangle_distance_squared(self.p, &Triangle::new(a, b, c));
            self.best_squared = self.best_squared.min(d);
        }
        ControlFlow::Continue(())
    }
}
