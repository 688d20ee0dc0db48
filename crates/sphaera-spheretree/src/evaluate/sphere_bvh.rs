//! A bounding-volume hierarchy over spheres, for the distance from a point to their union.

use glam::DVec3;
use sphaera_mesh::Aabb;

use crate::Sphere;

/// Spheres per leaf.
const LEAF_SIZE: usize = 4;

/// A node: its box and either two children or a range of `order`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Children `(left, right)` for an inner node, `None` for a leaf.
    children: Option<(usize, usize)>,
    start: usize,
    end: usize,
}

/// A binary hierarchy over sphere boxes (median split of the centres along the longest
/// axis, ties broken by index, so the same spheres always give the same tree).
#[derive(Clone, Debug)]
pub(crate) struct SphereBvh {
    spheres: Vec<Sphere>,
    order: Vec<usize>,
    nodes: Vec<Node>,
}

impl SphereBvh {
    /// The hierarchy over `spheres` (valid spheres).
    pub fn new(spheres: &[Sphere]) -> Self {
        let mut bvh = Self {
            spheres: spheres.to_vec(),
            order: (0..spheres.len()).collect(),
            nodes: Vec::with_capacity(2 * spheres.len() / LEAF_SIZE + 1),
        };
        if !spheres.is_empty() {
            bvh.build(0, spheres.len());
        }
        bvh
    }

    /// Builds the node over `order[start..end]` and returns its index.
    fn build(&mut self, start: usize, end: usize) -> usize {
        let bounds = self.order[start..end]
            .iter()
            .map(|&i| self.spheres[i].bounding_box())
            .fold(Aabb::EMPTY, Aabb::union);
        let index = self.nodes.len();
        self.nodes.push(Node {
            bounds,
            children: None,
            start,
            end,
        });
        if end - start > LEAF_SIZE {
            let centers = Aabb::from_points(
                self.order[start..end]
                    .iter()
                    .map(|&i| self.spheres[i].center),
            );
            let axis = centers.longest_axis();
            let mid = start + (end - start) / 2;
            let spheres = &self.spheres;
            self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
                spheres[a].center[axis]
                    .total_cmp(&spheres[b].center[axis])
                    .then(a.cmp(&b))
            });
            let left = self.build(start, mid);
            let right = self.build(mid, end);
            self.nodes[index].children = Some((left, right));
        }
        index
    }

    /// The distance from `p` to the union of the balls: 0 when a ball contains `p`, else
    /// `min (|p − c| − r)` over the spheres (`f64::INFINITY` with no sphere).
    pub fn distance_to_union(&self, p: DVec3) -> f64 {
        let mut best = f64::INFINITY;
        let mut stack = Vec::with_capacity(64);
        if !self.nodes.is_empty() {
            stack.push(0_usize);
        }
        while let Some(n) = stack.pop() {
            let node = self.nodes[n];
            if node.bounds.distance_squared_to_point(p).sqrt() >= best {
                continue;
            }
            match node.children {
                Some((left, right)) => {
                    let dl = self.nodes[left].bounds.distance_squared_to_point(p);
                    let dr = self.nodes[right].bounds.distance_squared_to_point(p);
                    // The nearer child is popped first.
                    if dl <= dr {
                        stack.extend([right, left]);
                    } else {
                        stack.extend([left, right]);
                    }
                }
                None => {
                    for &i in &self.order[node.start..node.end] {
                        let s = self.spheres[i];
                        let gap = p.distance(s.center) - s.radius;
                        if gap <= 0.0 {
                            return 0.0;
                        }
                        best = best.min(gap);
                    }
                }
            }
        }
        best
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
        let bvh = SphereBvh::new(&spheres);
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
                .distance_to_union(DVec3::ZERO)
                .is_infinite()
        );
    }
}
