//! One direction `S → T` of a Hausdorff computation: the samples of the source mesh `S`,
//! the points found for them on the target `T`, and the certified lower bound.

use std::collections::HashMap;

use glam::DVec3;
use sphaera_mesh::geometry::Triangle;
use sphaera_simplify::Hierarchy;

use super::target::{Found, Rows, Target};
use super::{DirectedHausdorff, Tracker, peel};
use crate::{ClosestPoint, Feature, Session, SweepError, Sweeper};
use sphaera_query::hausdorff::bound::{CornerAnswer, level_upper_bound, triangle_upper_bound};

/// A point of the source mesh with a point found on the target.
#[derive(Clone, Copy, Debug)]
struct Sample {
    position: DVec3,
    /// The nearest point found (exact once certified, usually exact before).
    found: Found,
    /// The nearest triangle found on the level of detail (`u32::MAX`: none yet).
    level: u32,
}

/// One direction: the source mesh's samples, the target's geometry, and a session on the
/// target for certified lower bounds.
pub(super) struct Side<'s> {
    source: &'s Hierarchy,
    target_hierarchy: &'s Hierarchy,
    target: Target,
    /// A level of detail of the target, for the level bound (after the vertices).
    level: Option<Target>,
    /// The peel order of the vertices and their neighbours.
    peel: Option<(Vec<u32>, Rows)>,
    session: Session<'s>,
    samples: Vec<Sample>,
    midpoints: HashMap<(u32, u32), u32>,
    /// The largest certified lower bound at a sample, and that sample.
    pub(super) lower: f64,
    farthest: Option<usize>,
    /// A lower bound already certified elsewhere (the other direction's, in a symmetric
    /// computation): samples that cannot beat it are not certified.
    pub(super) floor: f64,
    pub(super) refined: usize,
    certified: usize,
}

impl<'s> Side<'s> {
    pub(super) fn new(source: &'s Sweeper<'s>, target: &'s Sweeper<'s>) -> Self {
        Self {
            source: source.hierarchy(),
            target_hierarchy: target.hierarchy(),
            target: Target::new(target.hierarchy()),
            level: None,
            peel: None,
            session: target.session(),
            samples: Vec::new(),
            midpoints: HashMap::new(),
            lower: 0.0,
            farthest: None,
            floor: 0.0,
            refined: 0,
            certified: 0,
        }
    }

    /// The source mesh.
    pub(super) fn source(&self) -> &'s Hierarchy {
        self.source
    }

    /// Samples so far.
    pub(super) fn sample_count(&self) -> usize {
        self.samples.len()
    }

    /// Finds a near target point for every source vertex, walking along peel paths from
    /// the previous answer (sample `i` is vertex `i`); then certifies, farthest first,
    /// the vertices that could raise the lower bound. With `exact`, every vertex gets a
    /// certified exact answer (coherent along the same paths).
    pub(super) fn query_vertices(
        &mut self,
        exact: bool,
        tracker: &mut Tracker<'_>,
    ) -> Result<(), SweepError> {
        let positions = self.source.positions();
        let triangles: Vec<[u32; 3]> = (0..self.source.triangle_count() as u32)
            .filter_map(|t| self.source.triangle(t))
            .collect();
        let (order, neighbours) = peel::peel_order(positions.len(), &triangles);
        let mut found: Vec<Option<Found>> = vec![None; positions.len()];
        let mut exact_at: Vec<(usize, f64)> = Vec::new();
        for &v in &order {
            let p = positions.get(v as usize).copied().unwrap_or(DVec3::NAN);
            // Walk from the nearest answer among the neighbours already visited (peel
            // paths visit a ring after the one inside it, so there almost always is one).
            let start = neighbours
                .row(v)
                .iter()
                .filter_map(|&n| found.get(n as usize).copied().flatten())
                .min_by(|a, b| a.distance.total_cmp(&b.distance));
            let here = if neighbours.row(v).is_empty() {
                // No triangle uses it: not a point of the surface.
                Some(Found::unused(p))
            } else {
                match start {
                    Some(f) if !exact => self.target.walk(p, f.triangle),
                    _ => {
                        let found = self.exact(p)?;
                        exact_at.push((v as usize, found.distance));
                        Some(found)
                    }
                }
            };
            if let Some(slot) = found.get_mut(v as usize) {
                *slot = here;
            }
            tracker.vertex_done(self.lower);
        }
        self.samples = positions
            .iter()
            .zip(found)
            .map(|(&position, found)| {
                found.map(|found| Sample {
                    position,
                    found,
                    level: u32::MAX,
                })
            })
            .collect::<Option<Vec<_>>>()
            .ok_or(SweepError::EmptyMesh)?;
        self.peel = Some((order, neighbours));
        for (i, d) in exact_at {
            self.raise(d, i);
        }
        if exact {
            return Ok(());
        }
        let mut by_distance: Vec<usize> = (0..self.samples.len()).collect();
        by_distance.sort_by(|&i, &j| {
            let d = |k: usize| self.samples.get(k).map_or(0.0, |s| s.found.distance);
            d(j).total_cmp(&d(i)).then(i.cmp(&j))
        });
        for i in by_distance {
            if !self.certify(i)? {
                break;
            }
        }
        Ok(())
    }

    /// Extracts the level of detail of the target whose radii are at most `error` and
    /// finds each vertex sample's nearest level triangle, walking along the peel paths.
    pub(super) fn attach_level(&mut self, error: f64) {
        let level = Target::level(&self.target_hierarchy.level_by_error(error));
        if level.triangle_count() == 0 {
            return;
        }
        if let Some((order, neighbours)) = &self.peel {
            let mut at: Vec<u32> = vec![u32::MAX; self.samples.len()];
            for &v in order {
                if neighbours.row(v).is_empty() {
                    continue;
                }
                let Some(sample) = self.samples.get(v as usize) else {
                    continue;
                };
                let start = neighbours
                    .row(v)
                    .iter()
                    .filter_map(|&n| at.get(n as usize).copied())
                    .find(|&t| t != u32::MAX);
                let found = match start {
                    Some(t) => level.walk(sample.position, t),
                    None => level.nearest(sample.position),
                };
                if let (Some(found), Some(slot)) = (found, at.get_mut(v as usize)) {
                    *slot = found.triangle;
                }
            }
            for (sample, t) in self.samples.iter_mut().zip(at) {
                sample.level = t;
            }
        }
        self.level = Some(level);
    }

    /// Certifies sample `i` if the distance found for it could raise the lower bound (or
    /// beat the [`floor`](Self::floor)): an exact query replaces its point by the closest
    /// one and raises the lower bound. `false` if it could not.
    fn certify(&mut self, i: usize) -> Result<bool, SweepError> {
        let Some(sample) = self.samples.get(i).copied() else {
            return Ok(false);
        };
        if sample.found.distance <= self.lower.max(self.floor) {
            return Ok(false);
        }
        let answer = self.session.closest(sample.position)?;
        self.certified += 1;
        if let Some(found) = self.found(answer)
            && let Some(slot) = self.samples.get_mut(i)
        {
            slot.found = found;
        }
        self.raise(answer.distance, i);
        Ok(true)
    }

    /// Takes `lower`, a certified lower bound at `sample`, into the side's lower bound.
    fn raise(&mut self, lower: f64, sample: usize) {
        if self.farthest.is_none() || lower > self.lower {
            self.lower = lower;
            self.farthest = Some(sample);
        }
    }

    /// The exact answer at `p`.
    fn exact(&mut self, p: DVec3) -> Result<Found, SweepError> {
        let answer = self.session.closest(p)?;
        self.certified += 1;
        self.found(answer).ok_or(SweepError::EmptyMesh)
    }

    /// A session's answer as a [`Found`].
    fn found(&self, answer: ClosestPoint) -> Option<Found> {
        let triangle = self.target.of_input(answer.triangle)?;
        let feature_vertex = match answer.feature {
            Feature::Vertex(v) | Feature::Edge(v, _) => v,
            Feature::Face => u32::MAX,
        };
        Some(Found {
            point: answer.point,
            distance: answer.distance,
            triangle,
            feature_vertex,
        })
    }

    /// The sample at the midpoint of samples `a` and `b` (created once per edge): the
    /// better of two walks from both ends' answers, certified if it could raise the lower
    /// bound.
    pub(super) fn midpoint(&mut self, a: u32, b: u32) -> Result<u32, SweepError> {
        let key = (a.min(b), a.max(b));
        if let Some(&m) = self.midpoints.get(&key) {
            return Ok(m);
        }
        let (Some(sa), Some(sb)) = (
            self.samples.get(a as usize).copied(),
            self.samples.get(b as usize).copied(),
        ) else {
            return Err(SweepError::EmptyMesh);
        };
        let p = 0.5 * (sa.position + sb.position);
        let from_a = self.target.walk(p, sa.found.triangle);
        let from_b = self.target.walk(p, sb.found.triangle);
        let found = match (from_a, from_b) {
            (Some(x), Some(y)) => Some(if y.distance < x.distance { y } else { x }),
            (x, y) => x.or(y),
        };
        let found = match found {
            Some(found) => found,
            None => self.exact(p)?,
        };
        let level = self.level.as_ref().map_or(u32::MAX, |level| {
            [sa.level, sb.level]
                .into_iter()
                .filter(|&t| t != u32::MAX)
                .filter_map(|t| level.walk(p, t))
                .min_by(|x, y| x.distance.total_cmp(&y.distance))
                .map_or(u32::MAX, |f| f.triangle)
        });
        let index = self.samples.len();
        self.samples.push(Sample {
            position: p,
            found,
            level,
        });
        self.midpoints.insert(key, index as u32);
        self.certify(index)?;
        Ok(index as u32)
    }

    /// The upper bound of the triangle of samples `corners` (`None` if a sample is
    /// missing).
    pub(super) fn upper_bound(&self, corners: [u32; 3]) -> Option<f64> {
        let mut answers = [CornerAnswer {
            position: DVec3::ZERO,
            closest: DVec3::ZERO,
        }; 3];
        let mut ids: Vec<u32> = Vec::with_capacity(24);
        for (slot, &s) in answers.iter_mut().zip(&corners) {
            let sample = self.samples.get(s as usize)?;
            *slot = CornerAnswer {
                position: sample.position,
                closest: sample.found.point,
            };
            ids.push(sample.found.triangle);
            ids.extend_from_slice(self.target.around(sample.found.feature_vertex));
        }
        ids.sort_unstable();
        ids.dedup();
        let targets: Vec<Triangle> = ids
            .iter()
            .filter_map(|&t| self.target.triangle(t))
            .collect();
        // Pairs of the corners' own triangles that share an edge.
        let own: Vec<u32> = {
            let mut own: Vec<u32> = corners
                .iter()
                .filter_map(|&s| self.samples.get(s as usize).map(|x| x.found.triangle))
                .collect();
            own.sort_unstable();
            own.dedup();
            own
        };
        let mut pairs = Vec::new();
        for (i, &a) in own.iter().enumerate() {
            for &b in own.iter().skip(i + 1) {
                if let Some(pair) = self.target.pair(a, b) {
                    pairs.push(pair);
                }
            }
        }
        let bound = triangle_upper_bound(&answers, &targets, &pairs);
        Some(bound.min(self.level_bound(corners)))
    }

    /// The level bound of the triangle of samples `corners` (infinite without a level).
    fn level_bound(&self, corners: [u32; 3]) -> f64 {
        let Some(level) = &self.level else {
            return f64::INFINITY;
        };
        let mut ids: Vec<u32> = corners
            .iter()
            .filter_map(|&s| self.samples.get(s as usize).map(|x| x.level))
            .filter(|&t| t != u32::MAX)
            .collect();
        ids.sort_unstable();
        ids.dedup();
        let candidates: Vec<(Triangle, f64)> = ids
            .iter()
            .filter_map(|&t| Some((level.triangle(t)?, level.radius(t))))
            .collect();
        let mut pairs = Vec::new();
        for (i, &a) in ids.iter().enumerate() {
            for &b in ids.iter().skip(i + 1) {
                if let Some(pair) = level.pair(a, b) {
                    pairs.push((pair, level.radius(a).max(level.radius(b))));
                }
            }
        }
        let x = corners.map(|s| {
            self.samples
                .get(s as usize)
                .map_or(DVec3::NAN, |x| x.position)
        });
        level_upper_bound(x, &candidates, &pairs)
    }

    /// The direction's result with its upper bound.
    pub(super) fn finish(self, upper: f64) -> DirectedHausdorff {
        let input_vertices = (0..self.source.vertex_count() as u32)
            .filter_map(|v| self.source.original_vertex(v))
            .max()
            .map_or(0, |m| m as usize + 1);
        let mut vertex_distances = vec![0.0; input_vertices];
        for v in 0..self.source.vertex_count() as u32 {
            if let (Some(i), Some(s)) =
                (self.source.original_vertex(v), self.samples.get(v as usize))
                && let Some(slot) = vertex_distances.get_mut(i as usize)
            {
                *slot = s.found.distance;
            }
        }
        let far = self.farthest.and_then(|i| self.samples.get(i));
        DirectedHausdorff {
            lower: self.lower,
            upper: upper.max(self.lower),
            farthest: far.map_or(DVec3::ZERO, |s| s.position),
            closest: far.map_or(DVec3::ZERO, |s| s.found.point),
            vertex_distances,
            samples: self.samples.len(),
            certified_samples: self.certified,
            refined_triangles: self.refined,
        }
    }
}
