//! The structures HAL trees are compared with, on the same outlines: Ballard's strip tree
//! (1981) and an axis-aligned box tree over the edges (the workspace's `BoxTree`). Both
//! answer point-in-polygon with the same exact crossing rule as the HAL tree
//! (`sphaera::hal::ray_crossing`), so every structure gives the same answers.

use sphaera::hal::{HalTree2, Polyline2, ray_crossing};
use sphaera::mesh::bvh::BoxTree;
use sphaera::mesh::glam::{DVec2, DVec3};
use sphaera::mesh::{Aabb, QueryError};

/// One strip: the chord `a → b` of a part, and the rectangle with sides parallel to it
/// holding every vertex of the part: along the chord from `along.0` to `along.1` (chord
/// coordinates from `a`), across from `-right` to `left`.
#[derive(Clone, Copy, Debug)]
pub struct Strip {
    pub first: u32,
    pub last: u32,
    /// The vertex the part is split at (farthest from the chord's line; first on ties).
    pub split: u32,
    pub along: (f64, f64),
    pub left: f64,
    pub right: f64,
    pub depth: u32,
    children: [Option<u32>; 2],
}

/// Ballard's strip tree over the same level-0 chains as a HAL tree (so the two split the
/// outline the same way at the top), each part split at the vertex farthest from its
/// chord's line (iterative end-point fit).
pub struct StripTree<'a> {
    hal: &'a HalTree2,
    strips: Vec<Strip>,
    chains: Vec<(u32, u32, Option<u32>)>,
}

impl<'a> StripTree<'a> {
    pub fn build(hal: &'a HalTree2) -> Self {
        let mut tree = Self {
            hal,
            strips: Vec::new(),
            chains: Vec::new(),
        };
        for chain in hal.chains() {
            let root = tree.grow(chain.first, chain.last);
            tree.chains.push((chain.first, chain.last, root));
        }
        tree
    }

    fn grow(&mut self, first: u32, last: u32) -> Option<u32> {
        if last - first < 2 {
            return None;
        }
        let root = self.strips.len() as u32;
        let mut work = vec![(first, last, 0_u32, None::<(u32, usize)>)];
        while let Some((p, s, depth, parent)) = work.pop() {
            let (a, b) = (self.hal.point_at(p), self.hal.point_at(s));
            let length = a.distance(b);
            let dir = if length > 0.0 {
                (b - a) / length
            } else {
                DVec2::X
            };
            let normal = dir.perp();
            let (mut along, mut left, mut right) = ((0.0_f64, length), 0.0_f64, 0.0_f64);
            let mut split = (p + (s - p) / 2, -1.0_f64);
            for position in p + 1..s {
                let x = self.hal.point_at(position) - a;
                let (t, y) = (x.dot(dir), x.dot(normal));
                along = (along.0.min(t), along.1.max(t));
                left = left.max(y);
                right = right.max(-y);
                if y.abs() > split.1 {
                    split = (position, y.abs());
                }
            }
            let id = self.strips.len() as u32;
            self.strips.push(Strip {
                first: p,
                last: s,
                split: split.0,
                along,
                left,
                right,
                depth,
                children: [None, None],
            });
            if let Some((parent, side)) = parent {
                self.strips[parent as usize].children[side] = Some(id);
            }
            let q = split.0;
            if s - q >= 2 {
                work.push((q, s, depth + 1, Some((id, 1))));
            }
            if q - p >= 2 {
                work.push((p, q, depth + 1, Some((id, 0))));
            }
        }
        Some(root)
    }

    pub fn strips(&self) -> &[Strip] {
        &self.strips
    }

    /// The strip's rectangle area.
    pub fn area(strip: &Strip) -> f64 {
        (strip.along.1 - strip.along.0) * (strip.left + strip.right)
    }

    /// Whether `x` may lie in `strip` (a relative slack of 10⁻¹² on the side of yes).
    fn may_contain(&self, strip: &Strip, x: DVec2) -> bool {
        let (a, b) = (
            self.hal.point_at(strip.first),
            self.hal.point_at(strip.last),
        );
        let length = a.distance(b);
        let dir = if length > 0.0 {
            (b - a) / length
        } else {
            DVec2::X
        };
        let d = x - a;
        let (t, y) = (d.dot(dir), d.dot(dir.perp()));
        let slack = 1e-12 * (length + d.length() + strip.left + strip.right);
        t >= strip.along.0 - slack
            && t <= strip.along.1 + slack
            && y <= strip.left + slack
            && y >= -strip.right - slack
    }

    /// Point-in-polygon: `Some(true)` inside, `Some(false)` outside, `None` on the
    /// boundary; parts whose strip `x` is outside of are replaced by their chord.
    pub fn contains(&self, x: DVec2) -> Option<bool> {
        let mut inside = false;
        let mut stack = Vec::new();
        for &(first, last, root) in &self.chains {
            stack.push((first, last, root));
            while let Some((p, s, node)) = stack.pop() {
                let (a, b) = (self.hal.point_at(p), self.hal.point_at(s));
                match node {
                    None => inside ^= ray_crossing(a, b, x)?,
                    Some(id) => {
                        let strip = &self.strips[id as usize];
                        if self.may_contain(strip, x) {
                            stack.push((strip.split, s, strip.children[1]));
                            stack.push((p, strip.split, strip.children[0]));
                        } else {
                            inside ^= ray_crossing(a, b, x).unwrap_or(false);
                        }
                    }
                }
            }
        }
        Some(inside)
    }
}

/// An axis-aligned box tree over a polygon's edges: point-in-polygon visits the boxes the
/// ray from the point to `+x` passes through.
pub struct EdgeBoxTree<'a> {
    polygon: &'a Polyline2,
    tree: BoxTree,
}

/// Edges per leaf of [`EdgeBoxTree`] (the HAL and triangle trees use 4 to 8).
const LEAF_EDGES: usize = 4;

impl<'a> EdgeBoxTree<'a> {
    pub fn build(polygon: &'a Polyline2) -> Result<Self, QueryError> {
        let items: Vec<(Aabb, DVec3)> = (0..polygon.edge_count())
            .map(|i| {
                let (a, b) = polygon.edge(i);
                let (a, b) = (a.extend(0.0), b.extend(0.0));
                (Aabb::new(a.min(b), a.max(b)), (a + b) * 0.5)
            })
            .collect();
        Ok(Self {
            polygon,
            tree: BoxTree::build(&items, LEAF_EDGES)?,
        })
    }

    /// The boxes of the nodes at `depth` (the root at 0).
    pub fn boxes_at(&self, depth: usize) -> Vec<Aabb> {
        let nodes = self.tree.nodes();
        let mut out = Vec::new();
        let mut stack = vec![(0_usize, 0_usize)];
        while let Some((id, d)) = stack.pop() {
            let Some(node) = nodes.get(id) else { continue };
            if d == depth {
                out.push(node.bounds);
                continue;
            }
            if let Some(right) = node.right() {
                stack.push((id + 1, d + 1));
                stack.push((right, d + 1));
            }
        }
        out
    }

    /// Point-in-polygon as [`StripTree::contains`].
    pub fn contains(&self, x: DVec2) -> Option<bool> {
        let nodes = self.tree.nodes();
        let order = self.tree.order();
        let mut inside = false;
        let mut stack = vec![0_usize];
        while let Some(id) = stack.pop() {
            let Some(node) = nodes.get(id) else { continue };
            let (lo, hi) = (node.bounds.min, node.bounds.max);
            // The ray y = x.y, from x.x to +∞ (a point on a box's edge is kept).
            if x.y < lo.y || x.y > hi.y || x.x > hi.x {
                continue;
            }
            match node.right() {
                Some(right) => stack.extend([right, id + 1]),
                None => {
                    for &edge in &order[node.items()] {
                        let (a, b) = self.polygon.edge(edge as usize);
                        inside ^= ray_crossing(a, b, x)?;
                    }
                }
            }
        }
        Some(inside)
    }
}
