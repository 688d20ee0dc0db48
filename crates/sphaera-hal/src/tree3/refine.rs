//! Refining the tree one level at a time (Algorithm 2): which sides split where, and the
//! child triangles of a split patch.

use super::{HalTree3, Node3, SMALLEST_SPLIT_ANGLE, circle};

impl HalTree3 {
    /// The vertex Algorithm 2 splits a patch at: `v_q` or `v_r`, whichever ball has the
    /// larger signed radius (the first of the patch's inner vertices if none is off the
    /// plane, or if the corners are collinear).
    fn split_vertex(&self, node: &Node3) -> Option<u32> {
        let positions = self.surface.mesh().positions();
        let points = node.corners.map(|v| positions[v as usize]);
        let inner = self.inner_vertices(node.corners, &node.faces);
        let bound = node.bound?;
        let Some(circle) = circle(points) else {
            return inner.first().copied();
        };
        let mut best: Option<(f64, u32)> = None;
        let want_above = bound.above > -bound.below;
        for &v in &inner {
            let ph = circle.power_and_height(positions[v as usize]);
            let h = ph.height;
            if h == 0.0 || (h > 0.0) != want_above {
                continue;
            }
            let k = ph.power / (2.0 * circle.radius * h);
            let key = if want_above { k } else { -k };
            if best.is_none_or(|(b, _)| key > b) {
                best = Some((key, v));
            }
        }
        best.map(|(_, v)| v).or_else(|| inner.first().copied())
    }

    /// The corner angles of `corners`, at each corner.
    fn angles(&self, corners: [u32; 3]) -> [f64; 3] {
        let p = corners.map(|v| self.surface.mesh().positions()[v as usize]);
        [0, 1, 2].map(|i| {
            let (a, b, c) = (p[i], p[(i + 1) % 3], p[(i + 2) % 3]);
            (b - a).angle_between(c - a)
        })
    }

    /// The sides a triangle wants split (by their index 0..3, side `i` from corner `i` to
    /// corner `i + 1`): the two beside its only small angle, or the one between its two.
    fn wanted_sides(&self, corners: [u32; 3]) -> Vec<usize> {
        let small: Vec<usize> = (0..3)
            .filter(|&i| self.angles(corners)[i] < SMALLEST_SPLIT_ANGLE)
            .collect();
        match small.as_slice() {
            // The sides beside corner c: c−1 → c (index c − 1) and c → c+1 (index c).
            [c] => vec![(c + 2) % 3, *c],
            // Corners c and d: the side joining them.
            [c, d] => {
                if (c + 1) % 3 == *d {
                    vec![*c]
                } else {
                    vec![*d]
                }
            }
            _ => Vec::new(),
        }
    }

    /// The vertex on a side's path (not an end) that makes the two new sides most nearly
    /// equal in length; `None` for a one-edge path.
    fn side_split(&self, side: u32) -> Option<u32> {
        let path = &self.sides[side as usize].path;
        let positions = self.surface.mesh().positions();
        let (a, b) = (
            positions[path[0] as usize],
            positions[*path.last()? as usize],
        );
        path.get(1..path.len().saturating_sub(1))?
            .iter()
            .copied()
            .min_by(|&u, &v| {
                let d = |m: u32| {
                    (a.distance(positions[m as usize]) - positions[m as usize].distance(b)).abs()
                };
                d(u).total_cmp(&d(v)).then(u.cmp(&v))
            })
    }

    /// One level of Algorithm 2: every non-leaf node of `frontier` is split; returns the
    /// next frontier.
    pub(super) fn refine(&mut self, frontier: &[u32]) -> Vec<u32> {
        let active: Vec<u32> = frontier
            .iter()
            .copied()
            .filter(|&n| self.nodes[n as usize].bound.is_some())
            .collect();
        // All sides to split are decided before any triangle splits.
        let mut split_sides = std::collections::BTreeSet::new();
        for &n in &active {
            let node = &self.nodes[n as usize];
            for i in self.wanted_sides(node.corners) {
                split_sides.insert(node.sides[i]);
            }
        }
        for &side in &split_sides {
            if self.sides[side as usize].halves.is_some() {
                continue;
            }
            if let Some(m) = self.side_split(side) {
                let path = self.sides[side as usize].path.clone();
                let at = path.iter().position(|&v| v == m).unwrap_or(0);
                let first = self.new_side(path[..=at].to_vec());
                let second = self.new_side(path[at..].to_vec());
                self.sides[side as usize].halves = Some((m, [first, second]));
            }
        }
        let mut next = Vec::new();
        for n in active {
            let children = self.split(n, &split_sides);
            self.nodes[n as usize].children.clone_from(&children);
            next.extend(children);
        }
        next
    }

    /// The half of side `side` that starts or ends at corner `corner`, walked from it.
    fn half_at(&self, side: u32, corner: u32) -> u32 {
        let Some((_, [first, second])) = self.sides[side as usize].halves else {
            return side;
        };
        if self.sides[first as usize].path.first() == Some(&corner)
            || self.sides[first as usize].path.last() == Some(&corner)
        {
            first
        } else {
            second
        }
    }

    /// Splits node `n` (its sides in `split_sides` at their split vertices, else at its
    /// interior vertex), returning its children.
    fn split(&mut self, n: u32, split_sides: &std::collections::BTreeSet<u32>) -> Vec<u32> {
        let node = self.nodes[n as usize].clone();
        let level = node.level + 1;
        // Split vertex of side i, if it is split.
        let mid: Vec<Option<u32>> = (0..3)
            .map(|i| {
                let side = node.sides[i];
                if split_sides.contains(&side) {
                    self.sides[side as usize].halves.map(|(m, _)| m)
                } else {
                    None
                }
            })
            .collect();
        let corner = |i: usize| node.corners[i % 3];
        // Paths inside the patch.
        let inside = |tree: &Self, a: u32, b: u32| tree.patch_path(&node.faces, a, b);
        let mut candidates: Vec<([u32; 3], [u32; 3])> = Vec::new();
        let split_count = mid.iter().flatten().count();
        match split_count {
            0 => {
                let Some(x) = self.split_vertex(&node) else {
                    return Vec::new();
                };
                candidates = self.interior_candidates(&node, x);
            }
            1 => {
                let i = (0..3).find(|&i| mid[i].is_some()).unwrap_or(0);
                let m = mid[i].unwrap_or(corner(i));
                let (a, b, c) = (corner(i), corner(i + 1), corner(i + 2));
                let mc = self.new_side(inside(self, m, c));
                let side = node.sides[i];
                candidates.push((
                    [a, m, c],
                    [self.half_at(side, a), mc, node.sides[(i + 2) % 3]],
                ));
                candidates.push((
                    [m, b, c],
                    [self.half_at(side, b), node.sides[(i + 1) % 3], mc],
                ));
            }
            2 => {
                // The two split sides meet at corner c (side c−1 and side c are split).
                let c = (0..3)
                    .find(|&i| mid[i].is_some() && mid[(i + 2) % 3].is_some())
                    .unwrap_or(0);
                let (a, d, e) = (corner(c), corner(c + 1), corner(c + 2));
                let m1 = mid[c].unwrap_or(d);
                let m2 = mid[(c + 2) % 3].unwrap_or(e);
                let (s1, s2) = (node.sides[c], node.sides[(c + 2) % 3]);
                let m1m2 = self.new_side(inside(self, m1, m2));
                let m1e = self.new_side(inside(self, m1, e));
                candidates.push((
                    [a, m1, m2],
                    [self.half_at(s1, a), m1m2, self.half_at(s2, a)],
                ));
                candidates.push((
                    [m1, d, e],
                    [self.half_at(s1, d), node.sides[(c + 1) % 3], m1e],
                ));
                candidates.push(([m1, e, m2], [m1e, self.half_at(s2, e), m1m2]));
            }
            _ => {
                let m = [0, 1, 2].map(|i| mid[i].unwrap_or(corner(i)));
                let inner = [
                    self.new_side(inside(self, m[0], m[1])),
                    self.new_side(inside(self, m[1], m[2])),
                    self.new_side(inside(self, m[2], m[0])),
                ];
                for i in 0..3 {
                    let (a, before, after) = (corner(i), m[(i + 2) % 3], m[i]);
                    candidates.push((
                        [a, after, before],
                        [
                            self.half_at(node.sides[i], a),
                            inner[(i + 2) % 3],
                            self.half_at(node.sides[(i + 2) % 3], a),
                        ],
                    ));
                }
                candidates.push((m, inner));
            }
        }
        let mut children = self.place(&node.faces, &candidates, level);
        let stuck = |tree: &Self, children: &[u32]| {
            children.is_empty()
                || (children.len() == 1
                    && tree.nodes[children[0] as usize].faces.len() == node.faces.len())
        };
        if stuck(self, &children) {
            // Nothing split off: the chosen vertex may sit on a side's path (on a sphere
            // every vertex ties), or the new sides between points of the boundary coincide
            // with it (a patch bounded by geodesics, whose shortest paths run along its
            // boundary). Split at the most central inner vertex instead (the sides the
            // neighbours split then stay whole here: a gap at this level).
            self.nodes.truncate(self.nodes.len() - children.len());
            if let Some(x) = self.central_vertex(&node) {
                let retry = self.interior_candidates(&node, x);
                children = self.place(&node.faces, &retry, level);
            }
        }
        if stuck(self, &children) {
            // No progress at all: the patch's own faces become leaves.
            self.nodes.truncate(self.nodes.len() - children.len());
            return self.faces_as_leaves(&node.faces, level);
        }
        children
    }

    /// The three triangles of an interior split of `node` at `x`, with new sides from the
    /// corners to `x` inside the patch.
    fn interior_candidates(&mut self, node: &Node3, x: u32) -> Vec<([u32; 3], [u32; 3])> {
        let to_x = node.corners.map(|c| {
            let path = self.patch_path(&node.faces, c, x);
            self.new_side(path)
        });
        (0..3)
            .map(|i| {
                let (a, b) = (node.corners[i], node.corners[(i + 1) % 3]);
                ([a, b, x], [node.sides[i], to_x[(i + 1) % 3], to_x[i]])
            })
            .collect()
    }

    /// The inner vertex of `node`'s patch farthest from its nearest corner (lowest index on
    /// ties).
    fn central_vertex(&self, node: &Node3) -> Option<u32> {
        let positions = self.surface.mesh().positions();
        let corners = node.corners.map(|v| positions[v as usize]);
        self.inner_vertices(node.corners, &node.faces)
            .into_iter()
            .map(|v| {
                let x = positions[v as usize];
                let nearest = corners
                    .iter()
                    .map(|c| c.distance(x))
                    .fold(f64::INFINITY, f64::min);
                (nearest, v)
            })
            .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)))
            .map(|(_, v)| v)
    }

    /// Leaves for every face of a patch (the fallback when a patch cannot be split).
    fn faces_as_leaves(&mut self, faces: &[u32], level: u32) -> Vec<u32> {
        let triangles = self.surface.mesh().triangles().to_vec();
        faces
            .iter()
            .map(|&f| {
                let [a, b, c] = triangles[f as usize];
                let sides = [
                    self.new_side(vec![a, b]),
                    self.new_side(vec![b, c]),
                    self.new_side(vec![c, a]),
                ];
                self.make_node([a, b, c], sides, vec![f], level)
            })
            .collect()
    }

    /// The shortest edge path from `a` to `b` through the vertices of the patch `faces`.
    fn patch_path(&self, faces: &[u32], a: u32, b: u32) -> Vec<u32> {
        self.surface.shortest_path_within(faces, a, b)
    }
}
