//! Nearest distance from a point to a triangle mesh: a minimal bounding-volume hierarchy
//! (median split on the longest axis, a few triangles per leaf), for `--measure`.

use sphaera::mesh::{
    Aabb, DVec3, TriMesh,
    geometry::{Triangle, point_triangle_distance_squared},
};

/// Triangles per leaf, at most.
const LEAF_SIZE: usize = 4;

/// A node: its box, and either two children or a run of triangles.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: the first triangle. Inner: the second child (the first is the next node).
    index: usize,
    /// Leaf: the number of triangles. Inner: 0.
    count: usize,
}

/// The triangles of a mesh, ordered for nearest-point queries.
#[derive(Debug)]
pub struct NearestTriangle {
    nodes: Vec<Node>,
    triangles: Vec<Triangle>,
}

impl NearestTriangle {
    /// Builds the hierarchy over every triangle of `mesh` (degenerate ones included: they
    /// are part of the surface). `O(T log T)` time, `O(T)` memory.
    pub fn new(mesh: &TriMesh) -> Self {
        let mut items: Vec<(Triangle, DVec3)> = mesh
            .triangle_iter()
            .map(|t| (t, (t.a + t.b + t.c) / 3.0))
            .collect();
        let mut nodes = Vec::with_capacity(2 * items.len() / LEAF_SIZE + 1);
        if !items.is_empty() {
            build(&mut items, 0, &mut nodes);
        }
        Self {
            nodes,
            triangles: items.into_iter().map(|(t, _)| t).collect(),
        }
    }

    /// The distance from `p` to the nearest triangle; infinite for a mesh without
    /// triangles.
    pub fn distance(&self, p: DVec3) -> f64 {
        let mut best = f64::INFINITY;
        let mut stack = Vec::with_capacity(64);
        if !self.nodes.is_empty() {
            stack.push(0_usize);
        }
        while let Some(n) = stack.pop() {
            let node = self.nodes[n];
            if node.bounds.distance_squared_to_point(p) >= best {
                continue;
            }
            if node.count > 0 {
                for t in &self.triangles[node.index..node.index + node.count] {
                    best = best.min(point_triangle_distance_squared(p, t));
                }
            } else {
                // Visit the nearer child first (pushed last), so the other is often pruned.
                let (first, second) = (n + 1, node.index);
                let d_first = self.nodes[first].bounds.distance_squared_to_point(p);
                let d_second = self.nodes[second].bounds.distance_squared_to_point(p);
                if d_first <= d_second {
                    stack.push(second);
                    stack.push(first);
                } else {
                    stack.push(first);
                    stack.push(second);
                }
            }
        }
        best.sqrt()
    }
}

/// Appends the subtree of `items` (whose first triangle has index `offset` in the final
/// order) to `nodes`, reordering `items`; returns the subtree's root index.
fn build(items: &mut [(Triangle, DVec3)], offset: usize, nodes: &mut Vec<Node>) -> usize {
    let bounds = items.iter().fold(Aabb::EMPTY, |b, (t, _)| {
        b.union(Aabb::from_points(t.corners()))
    });
    let at = nodes.len();
    if items.len() <= LEAF_SIZE {
        nodes.push(Node {
            bounds,
            index: offset,
            count: items.len(),
        });
        return at;
    }
    nodes.push(Node {
        bounds,
        index: 0,
        count: 0,
    });
    let axis = Aabb::from_points(items.iter().map(|(_, c)| *c)).longest_axis();
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |(_, a), (_, b)| a[axis].total_cmp(&b[axis]));
    let (left, right) = items.split_at_mut(mid);
    build(left, offset, nodes);
    let second = build(right, offset + mid, nodes);
    nodes[at].index = second;
    at
}

#[cfg(test)]
mod tests {
    use sphaera::mesh::shapes;

    use super::*;

    fn brute_force(mesh: &TriMesh, p: DVec3) -> f64 {
        mesh.triangle_iter()
            .map(|t| point_triangle_distance_squared(p, &t))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    #[test]
    fn matches_brute_force_on_a_sphere() {
        let sphere = shapes::sphere(1.0, 12).expect("a sphere");
        let nearest = NearestTriangle::new(&sphere);
        for i in 0..200 {
            let f = f64::from(i);
            let p = DVec3::new(
                (0.37 * f).sin() * 1.7,
                (0.91 * f).cos() * 1.3,
                (0.13 * f).sin() * 2.1,
            );
            let (fast, slow) = (nearest.distance(p), brute_force(&sphere, p));
            assert!(
                (fast - slow).abs() <= 1e-12 * (1.0 + slow),
                "{fast} vs {slow}"
            );
        }
    }

    #[test]
    fn a_point_on_the_surface_is_at_distance_zero() {
        let cube = shapes::cube(2.0, 3).expect("a cube");
        let nearest = NearestTriangle::new(&cube);
        for &p in cube.positions() {
            assert!(nearest.distance(p) < 1e-12);
        }
    }
}
