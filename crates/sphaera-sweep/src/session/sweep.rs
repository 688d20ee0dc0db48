//! The sweep of a [`Session`]: moving the query point, and popping the queue's front
//! until it is exact, narrow enough or out of budget, splitting as it goes.

use glam::DVec3;

use super::{Session, Stop};
use crate::Tolerance;
use crate::queue::Entry;

impl Session<'_> {
    /// Moves the query point to `p`: widens every interval by the motion (lazily, through
    /// the key shift), or resets per [`SessionOptions`].
    pub(super) fn move_to(&mut self, p: DVec3) {
        self.warm_up();
        self.safe = None;
        let jump = self.query.map_or(0.0, |q| (p - q).length());
        let grown = self
            .refinement
            .live_triangle_count()
            .saturating_sub(self.warm.triangle_count())
            > self.options.max_triangles;
        let far = jump > self.options.jump_factor * self.last_distance;
        let imprecise = self.keys.exhausted(jump, self.diagonal);
        if self.query.is_some() && (grown || far || imprecise) {
            self.reset();
        }
        if self.query.is_none() || self.queue.len() == 0 {
            self.query = Some(p);
            self.keys.restart();
            self.best_upper = f64::INFINITY;
            self.refill(p);
            return;
        }
        if jump > 0.0 {
            self.query = Some(p);
            self.keys.widen(jump);
            self.best_upper += jump;
        }
    }

    /// Queues every live triangle of the current mesh for `p` (after a reset: the base
    /// mesh).
    fn refill(&mut self, p: DVec3) {
        if self.shape.is_none()
            && self.refinement.undone_count() == self.warm_undone
            && self.warm.node_count() > 0
        {
            self.warm_mark = self.mark;
            self.evaluate(self.triangles, p);
        } else if self.refinement.undone_count() == 0 {
            for i in 0..self.base.len() {
                let t = self.base[i];
                self.evaluate(t, p);
            }
        } else {
            let live: Vec<u32> = self.refinement.live_triangles().collect();
            for t in live {
                self.evaluate(t, p);
            }
        }
    }

    /// The sweep for a single answer: until the front is a leaf, the interval is within
    /// `tolerance`, or `max_splits` splits were made.
    pub(super) fn sweep(
        &mut self,
        p: DVec3,
        tolerance: Option<Tolerance>,
        max_splits: usize,
    ) -> Stop {
        let mut splits = 0;
        loop {
            let Some(front) = self.queue.first() else {
                return Stop::Empty;
            };
            if front.stamp != self.keys.stamp() {
                self.evaluate(front.triangle, p);
                continue;
            }
            if front.triangle >= self.triangles {
                self.expand(front.triangle, p);
                continue;
            }
            if self.is_leaf(front.triangle) {
                if self.is_current(front, p) {
                    return Stop::Exact(front.triangle);
                }
                continue;
            }
            let lower = self.lower(front.key);
            let done = tolerance.is_some_and(|t| {
                self.best_upper - lower.max(0.0) <= t.allowed_gap(self.best_upper)
            });
            if done || splits >= max_splits {
                return Stop::Approximate { lower };
            }
            self.split_front(front.triangle, p);
            splits += 1;
        }
    }

    /// The sweep for collecting leaves: the next leaf at the front, or `None` once the
    /// front's lower bound exceeds `limit` or the queue is empty.
    pub(super) fn sweep_until(&mut self, p: DVec3, limit: f64) -> Option<u32> {
        loop {
            let front = self.queue.first()?;
            if front.stamp != self.keys.stamp() {
                self.evaluate(front.triangle, p);
                continue;
            }
            if self.lower(front.key) > limit {
                return None;
            }
            if front.triangle >= self.triangles {
                self.expand(front.triangle, p);
                continue;
            }
            if self.is_leaf(front.triangle) {
                if self.is_current(front, p) {
                    return Some(front.triangle);
                }
                continue;
            }
            self.split_front(front.triangle, p);
        }
    }

    /// Whether live triangle `t` is a triangle of the input mesh: none of its corners can
    /// be split (then its corners are its input corners, at their input positions).
    fn is_leaf(&self, t: u32) -> bool {
        self.refinement
            .corners(t)
            .is_some_and(|corners| corners.iter().all(|&c| !self.refinement.can_split(c)))
    }

    /// Splits a corner of `t` (the one with the largest radius) and re-queues the
    /// triangles the split changed; `false` if `t` is a leaf (an input triangle).
    fn split_front(&mut self, t: u32, p: DVec3) -> bool {
        let Some(corners) = self.refinement.corners(t) else {
            // Not live (cannot happen for a queued triangle); drop it.
            self.queue.remove(t);
            return true;
        };
        let Some(v) = corners
            .into_iter()
            .filter(|&c| self.refinement.can_split(c))
            .max_by(|&a, &b| {
                let (ra, rb) = (self.radius(a), self.radius(b));
                ra.total_cmp(&rb).then(b.cmp(&a))
            })
        else {
            return false;
        };
        self.undone.clear();
        if self
            .refinement
            .split_vertex_into(v, &mut self.undone)
            .is_err()
        {
            return false;
        }
        self.stats.splits += 1;
        self.touched.clear();
        self.mark += 1;
        if self.mark == u32::MAX {
            // The marks start over: expand every pending group first, so no member
            // needs to know whether it was touched before.
            for n in 0..self.warm.node_count() as u32 {
                if self.queue.contains(self.triangles + n) {
                    self.expand_all(self.triangles + n, p);
                }
            }
            self.touched_at.fill(u32::MAX);
            self.mark = 0;
            self.warm_mark = 0;
        }
        let mark = self.mark;
        for &c in &self.undone {
            for &t in self
                .hierarchy
                .triangles_added_by_split(c)
                .iter()
                .chain(self.hierarchy.triangles_affected_by_split(c))
            {
                if let Some(at) = self.touched_at.get_mut(t as usize)
                    && *at != mark
                {
                    *at = mark;
                    self.touched.push(t);
                }
            }
        }
        for i in 0..self.touched.len() {
            let t = self.touched[i];
            match self.refinement.corners(t) {
                Some(corners) => self.evaluate_corners(t, corners, p),
                None => {
                    self.queue.remove(t);
                }
            }
        }
        true
    }

    /// The lower end of the interval of an entry with `key`: the key minus the motion
    /// since the reset, minus a rounding slack proportional to the motion (so the bound
    /// stays conservative however the shift rounded).
    pub(super) fn lower(&self, key: f64) -> f64 {
        self.keys.lower(key)
    }

    /// Whether `entry` (a clean leaf at the front) was computed with the radii its corners
    /// have now. A split's tables name the triangles around the parent *as built*; a
    /// triangle revived out of build order may keep a key computed with a corner's larger
    /// earlier radius — a lower bound still, but not its exact distance. If so it is
    /// re-queued with its exact key and `false` is returned.
    fn is_current(&mut self, entry: Entry, p: DVec3) -> bool {
        self.evaluate(entry.triangle, p);
        self.queue
            .first()
            .is_some_and(|now| now.triangle == entry.triangle && now.key <= entry.key)
    }
}
