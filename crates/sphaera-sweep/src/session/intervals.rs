//! The distance intervals of a [`Session`]'s queue: evaluating live triangles and
//! expanding the warm start's groups into their members.

use glam::DVec3;
use sphaera_mesh::geometry::{Triangle, closest_point_on_triangle};

use super::Session;
use crate::queue::Entry;
use crate::sweeper::Contents;

impl Session<'_> {
    /// Replaces node `id` in the queue by every triangle under it (as [`Session::expand`]).
    pub(super) fn expand_all(&mut self, id: u32, p: DVec3) {
        let mut stack = vec![id];
        while let Some(id) = stack.pop() {
            if let Contents::Children(a, b) = self.warm.node((id - self.triangles) as usize) {
                self.queue.remove(id);
                stack.extend([self.triangles + a, self.triangles + b]);
            } else {
                self.expand(id, p);
            }
        }
    }

    /// Computes the interval of live triangle `t` for `p` and queues it.
    pub(super) fn evaluate(&mut self, t: u32, p: DVec3) {
        if t >= self.triangles {
            // A group of the warm start: one bound for all its members (with a deformed
            // shape none is known: the group is expanded as soon as it is seen).
            let lower = match self.shape {
                Some(_) => f64::NEG_INFINITY,
                None => self.warm.lower_bound((t - self.triangles) as usize, p),
            };
            self.queue.set(Entry {
                key: self.keys.key(lower),
                triangle: t,
                stamp: self.keys.stamp(),
            });
        } else if let Some(corners) = self.refinement.corners(t) {
            self.evaluate_corners(t, corners, p);
        }
    }

    /// Replaces group `id` in the queue by the exact intervals of its members, except
    /// those a split touched since the group was queued (they have their own entries).
    pub(super) fn expand(&mut self, id: u32, p: DVec3) {
        self.queue.remove(id);
        let (members, corners) = match self.warm.node((id - self.triangles) as usize) {
            Contents::Children(a, b) => {
                self.evaluate(self.triangles + a, p);
                self.evaluate(self.triangles + b, p);
                return;
            }
            Contents::Triangles(members, corners) => (members, corners),
        };
        for (&t, &c) in members.iter().zip(corners) {
            let touched = self
                .touched_at
                .get(t as usize)
                .is_some_and(|&m| m != u32::MAX && m > self.warm_mark);
            if !touched {
                debug_assert_eq!(
                    self.refinement.corners(t),
                    Some(c),
                    "untouched warm corners"
                );
                self.evaluate_corners(t, c, p);
            }
        }
    }

    /// [`Session::evaluate`] for live triangle `t` with its current `corners`.
    pub(super) fn evaluate_corners(&mut self, t: u32, corners: [u32; 3], p: DVec3) {
        self.stats.distance_evaluations += 1;
        let positions = corners.map(|c| self.position(c));
        // A leaf is an input triangle at its true position: it bounds itself, radius 0
        // (inflated offsets on unsplittable vertices only matter for the other triangles).
        let radii = if corners.iter().all(|&c| !self.refinement.can_split(c)) {
            [0.0; 3]
        } else {
            corners.map(|c| self.radius(c))
        };
        let triangle = Triangle::new(positions[0], positions[1], positions[2]);
        let hit = closest_point_on_triangle(p, &triangle);
        let d = hit.distance_squared.sqrt();
        let eps = radii[0].max(radii[1]).max(radii[2]);
        let at_point = hit.barycentric[0] * radii[0]
            + hit.barycentric[1] * radii[1]
            + hit.barycentric[2] * radii[2];
        self.best_upper = self.best_upper.min(d + at_point);
        self.queue.set(Entry {
            key: self.keys.key(d - eps),
            triangle: t,
            stamp: self.keys.stamp(),
        });
    }
}
