//! A box tree over a polyline's segments: exact closest points, and intervals to a
//! tolerance, for independent queries (the polyline analogue of the mesh's
//! [`TriangleTree`](crate::TriangleTree)).

use std::ops::{ControlFlow, Range};

use glam::DVec3;
use sphaera_mesh::Aabb;
use sphaera_query::bvh::{BoxTree, NearestFirst};

use super::point::{PolylinePoint, closest_on_segment};
use crate::SweepError;

/// Segments per leaf. Measured on the noisy 100k helix of the `polyline_vs_parry` bench
/// against 4 and 16: a point–segment distance is cheap, so leaves hold more than the
/// triangle tree's per box test saved.
const LEAF_SIZE: usize = 8;

/// The tree: a [`BoxTree`] over the segments and their ends in tree order.
#[derive(Clone, Debug)]
pub(crate) struct SegmentTree<P> {
    boxes: BoxTree,
    ends: Vec<(P, P)>,
}

/// What a descent found: the nearest segment (input index) and its squared distance, and
/// a lower bound of the squared distance of every other segment.
pub(crate) struct Found {
    pub segment: usize,
    /// Its position in the tree (a seed for the next search).
    pub position: usize,
    pub distance_squared: f64,
    pub runner_up_squared: f64,
}

impl<P: PolylinePoint> SegmentTree<P> {
    /// The tree of the segments `points[i]..points[i + 1]`.
    pub(crate) fn new(points: &[P]) -> Result<Self, SweepError> {
        let items: Vec<(Aabb, DVec3)> = points
            .windows(2)
            .map(|w| {
                let (a, b) = (to3(w[0]), to3(w[1]));
                (Aabb::new(a.min(b), a.max(b)), 0.5 * a + 0.5 * b)
            })
            .collect();
        let boxes = BoxTree::build(&items, LEAF_SIZE).map_err(SweepError::Tree)?;
        let ends = boxes
            .order()
            .iter()
            .map(|&s| (points[s as usize], points[s as usize + 1]))
            .collect();
        Ok(Self { boxes, ends })
    }

    /// The nearest segment to `p`, skipping every box that cannot bring the distance
    /// down by more than `gap(best)` (`None`: exact). A `seed` (the tree position of a
    /// segment likely near, such as the previous answer's) starts the search with its
    /// distance as the bound.
    pub(crate) fn search(
        &self,
        p: P,
        gap: Option<&dyn Fn(f64) -> f64>,
        seed: Option<usize>,
    ) -> Option<Found> {
        let mut search = Search {
            ends: &self.ends,
            p,
            best: None,
            limit_squared: f64::INFINITY,
            gap,
            runner_up_squared: f64::INFINITY,
        };
        if let Some(&(a, b)) = seed.and_then(|i| self.ends.get(i)) {
            search.set_best(seed, closest_on_segment(p, a, b).distance_squared);
        }
        self.boxes.search_nearest_first(to3(p), &mut search);
        let (position, distance_squared) = search.best?;
        Some(Found {
            segment: self.boxes.order()[position] as usize,
            position,
            distance_squared,
            runner_up_squared: search.runner_up_squared,
        })
    }

    /// Bytes of the tree's arrays.
    pub(crate) fn memory_bytes(&self) -> usize {
        size_of_val(self.ends.as_slice())
            + size_of_val(self.boxes.nodes())
            + size_of_val(self.boxes.order())
    }
}

/// A point in 3D (a 2D point at `z = 0`, exactly).
fn to3<P: PolylinePoint>(p: P) -> DVec3 {
    DVec3::from_array(p.coordinates())
}

/// The state of one descent.
struct Search<'a, P> {
    ends: &'a [(P, P)],
    p: P,
    /// The best tree position and its squared distance.
    best: Option<(usize, f64)>,
    /// What may still be worth a look: the square of the best distance less the gap
    /// allowed.
    limit_squared: f64,
    gap: Option<&'a dyn Fn(f64) -> f64>,
    runner_up_squared: f64,
}

impl<P> Search<'_, P> {
    /// A new best at tree position `i` (when `Some`), squared distance `d`.
    fn set_best(&mut self, i: Option<usize>, d: f64) {
        if let Some(i) = i {
            self.best = Some((i, d));
        }
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

impl<P: PolylinePoint> NearestFirst for Search<'_, P> {
    fn may_improve(&self, distance_squared: f64) -> bool {
        distance_squared <= self.limit_squared
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        let current = self.best.map(|(i, _)| i);
        for i in positions {
            if Some(i) == current {
                // A seed is not compared with itself.
                continue;
            }
            let (a, b) = self.ends[i];
            let d = closest_on_segment(self.p, a, b).distance_squared;
            match self.best {
                Some((_, best)) if d >= best => {
                    self.runner_up_squared = self.runner_up_squared.min(d);
                }
                _ => {
                    if let Some((_, previous)) = self.best {
                        self.runner_up_squared = self.runner_up_squared.min(previous);
                    }
                    self.set_best(Some(i), d);
                }
            }
        }
        ControlFlow::Continue(())
    }

    fn pruned(&mut self, distance_squared: f64) {
        self.runner_up_squared = self.runner_up_squared.min(distance_squared);
    }
}
