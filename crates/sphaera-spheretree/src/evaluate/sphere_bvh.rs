//! The distance from a point to a union of spheres, over the workspace's box tree.

use std::ops::{ControlFlow, Range};

use glam::DVec3;
use sphaera_mesh::Aabb;
use sphaera_query::bvh::{BoxTree, NearestFirst};

use crate::Sphere;

/// Spheres per leaf.
const LEAF_SIZE: usize = 4;

/// Spheres in a [`BoxTree`] over their boxes (median splits of the centres, so the same
/// spheres always give the same tree).
#[derive(Clone, Debug)]
pub(crate) struct SphereBvh {
    /// The spheres in tree order.
    spheres: Vec<Sphere>,
    boxes: BoxTree,
}

impl SphereBvh {
    /// The hierarchy over `spheres` (valid spheres).
    ///
    /// # Errors
    ///
    /// [`MeshError::TooManyItems`](sphaera_mesh::MeshError::TooManyItems) for more
    /// spheres than 32-bit indices address.
    pub fn new(spheres: &[Sphere]) -> Result<Self, sphaera_query::QueryError> {
        let items: Vec<(Aabb, DVec3)> = spheres
            .iter()
            .map(|s| (s.bounding_box(), s.center))
            .collect();
        let boxes = BoxTree::build(&items, LEAF_SIZE)?;
        Ok(Self {
            spheres: boxes.order().iter().map(|&i| spheres[i as usize]).collect(),
            boxes,
        })
    }

    /// The distance from `p` to the union of the balls: 0 when a ball contains `p`, else
    /// `min (|p − c| − r)` over the spheres (`f64::INFINITY` with no sphere).
    pub fn distance_to_union(&self, p: DVec3) -> f64 {
        let mut search = Gap {
            spheres: &self.spheres,
            p,
            best: f64::INFINITY,
        };
        self.boxes.search_nearest_first(p, &mut search);
        search.best
    }
}

/// The smallest gap so far of one search.
struct Gap<'a> {
    spheres: &'a [Sphere],
    p: DVec3,
    best: f64,
}

impl NearestFirst for Gap<'_> {
    fn may_improve(&self, distance_squared: f64) -> bool {
        distance_squared.sqrt() < self.best
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        for s in &self.spheres[positions] {
            let gap = self.p.distance(s.center) - s.radius;
            if gap <= 0.0 {
                self.best = 0.0;
                return ControlFlow::Break(());
            }
            self.best = self.best.min(gap);
        }
        ControlFlow::Continue(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(spheres: &[Sphere], p: DVec3) -> f64 {
        spheres
            .iter()
            .map(|s| p.distance(s.center) - s.radius)
            .fold(f64::INFINITY, f64::min)
            .max(0.0)
    }

    #[test]
    fn matches_brute_force() {
        let mut spheres = Vec::new();
        for i in 0..200_u32 {
            let t = f64::from(i);
            let c = DVec3::new((t * 0.37).sin(), (t * 0.71).cos(), (t * 0.13).sin()) * 3.0;
            spheres.push(Sphere::new(c, 0.05 + 0.2 * (t * 0.9).sin().abs()));
        }
        let bvh = SphereBvh::new(&spheres).unwrap();
        for j in 0..500_u32 {
            let t = f64::from(j);
            let p = DVec3::new((t * 1.3).sin(), (t * 0.5).cos(), (t * 0.77).cos()) * 4.0;
            let (a, b) = (bvh.distance_to_union(p), brute(&spheres, p));
            assert!((a - b).abs() <= 1e-12, "{a} != {b}");
        }
    }

    #[test]
    fn empty_is_infinitely_far() {
        assert!(
            SphereBvh::new(&[])
                .unwrap()
                .distance_to_union(DVec3::ZERO)
                .is_infinite()
        );
    }
}
