//! The 3D HAL tree (section 4 of the paper): a closed genus-0 mesh kept as a tree of
//! triangles on its own vertices, each standing for a patch of the surface bounded by
//! three shortest edge paths, refined level by level (Algorithm 2).

use std::collections::HashMap;

use glam::DVec3;
use sphaera_mesh::{Sphere, TriMesh};

use crate::HalError;
use crate::intersect3::{Region, bound_regions};
use crate::lens::bulge_width;
use crate::surface3::{GenusZeroSurface, RootBall};

/// Angles below this are not split: such a triangle is split at its sides instead (the
/// paper's "arbitrarily set to π/4").
pub const SMALLEST_SPLIT_ANGLE: f64 = std::f64::consts::FRAC_PI_4;

/// The bounding volume of a patch approximated by the triangle `p, s, t`: the balls through
/// the three corners (centres on the axis of their circumcircle, at `c + k·R·n`, `R` the
/// circumradius, `n` the unit normal of `p → s → t`), by their bulges `k`, one holding the
/// patch's vertices above the plane, one those below (Definition 5); `±∞` are the
/// half-spaces, exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound3 {
    /// Bulge of the ball holding the vertices above the plane (`−∞`: none above; `+∞`: a
    /// vertex in the plane outside the circumcircle).
    pub above: f64,
    /// Bulge of the ball holding the vertices below (`+∞`: none below).
    pub below: f64,
}

impl Bound3 {
    /// Intersection (`above ≤ below`) or union of the two balls (Definition 2 for balls;
    /// in 3D a union can occur, the paper's "no 3D analogue to Theorem 1").
    #[must_use]
    pub fn is_intersection(&self) -> bool {
        self.above <= self.below
    }

    /// The widths `w₁` (above) and `w₂` (below) of Definition 6 for the triangle
    /// `corners`: the largest distance from the plane to each ball's boundary on its side.
    #[must_use]
    pub fn widths(&self, corners: [DVec3; 3]) -> (f64, f64) {
        let radius = circle(corners).map_or(0.0, |(_, r, _)| r);
        (
            bulge_width(self.above, radius),
            bulge_width(-self.below, radius),
        )
    }
}

/// Circumcentre, circumradius and unit normal of a triangle (`None` when degenerate).
pub(crate) fn circle([a, b, c]: [DVec3; 3]) -> Option<(DVec3, f64, DVec3)> {
    let (ab, ac) = (b - a, c - a);
    let normal = ab.cross(ac);
    let area2 = normal.length_squared();
    if area2 <= f64::MIN_POSITIVE {
        return None;
    }
    let offset = (normal.cross(ab) * ac.length_squared() + ac.cross(normal) * ab.length_squared())
        / (2.0 * area2);
    Some((a + offset, offset.length(), normal / area2.sqrt()))
}

/// One node of a [`HalTree3`]: an approximating triangle and the patch it stands for.
#[derive(Clone, Debug, PartialEq)]
pub struct Node3 {
    /// The corners (mesh vertex indices), counter-clockwise seen from outside.
    pub corners: [u32; 3],
    /// The level: the two root triangles are at level 0.
    pub level: u32,
    /// The patch's faces (mesh triangle indices, ascending).
    pub faces: Vec<u32>,
    /// The bounding volume; `None` for a leaf (an original face).
    pub bound: Option<Bound3>,
    /// `max(w₁, w₂)` (0 for a leaf).
    pub width: f64,
    /// The children (empty for a leaf).
    pub children: Vec<u32>,
    /// The node's three sides (ids shared with the neighbours across them).
    sides: [u32; 3],
}

/// A side of an approximating triangle: its ends and the shortest edge path between them
/// (from `from` to `to`), shared by the two triangles on either side.
#[derive(Clone, Debug)]
struct Side {
    path: Vec<u32>,
    /// Once split: the vertex and the two halves (from `path[0]`, then to its end).
    halves: Option<(u32, [u32; 2])>,
}

/// A hierarchical approximation and localization tree of a closed genus-0 mesh.
#[derive(Clone, Debug)]
pub struct HalTree3 {
    surface: GenusZeroSurface,
    root: RootBall,
    nodes: Vec<Node3>,
    /// The root triangles (one or two).
    roots: Vec<u32>,
    sides: Vec<Side>,
    /// Per node, the two convex regions holding its patch (everything for a leaf), for
    /// point inclusion.
    regions: Vec<[Region; 2]>,
}

impl HalTree3 {
    /// Builds the complete tree (Algorithm 2).
    ///
    /// # Errors
    ///
    /// As [`GenusZeroSurface::new`] and [`GenusZeroSurface::root`].
    pub fn build(mesh: &TriMesh) -> Result<Self, HalError> {
        let surface = GenusZeroSurface::new(mesh)?;
        let root = surface.root()?;
        let [i, j, k] = root.vertices;
        let mut tree = Self {
            surface,
            root,
            nodes: Vec::new(),
            roots: Vec::new(),
            sides: Vec::new(),
            regions: Vec::new(),
        };
        let ij = tree.new_side(tree.surface.shortest_path(i, j));
        let jk = tree.new_side(tree.surface.shortest_path(j, k));
        let ki = tree.new_side(tree.surface.shortest_path(k, i));
        let all: Vec<u32> = (0..tree.surface.mesh().triangle_count() as u32).collect();
        let candidates = vec![([i, j, k], [ij, jk, ki]), ([i, k, j], [ki, jk, ij])];
        let level: Vec<u32> = tree.place(&all, &candidates, 0);
        tree.roots = level.clone();
        let mut frontier = level;
        while !frontier.is_empty() {
            frontier = tree.refine(&frontier);
        }
        let positions = tree.surface.mesh().positions();
        tree.regions = tree
            .nodes
            .iter()
            .map(|node| {
                node.bound.map_or([Region::Everything; 2], |bound| {
                    bound_regions(&bound, node.corners.map(|v| positions[v as usize]))
                })
            })
            .collect();
        Ok(tree)
    }

    fn new_side(&mut self, path: Vec<u32>) -> u32 {
        self.sides.push(Side { path, halves: None });
        (self.sides.len() - 1) as u32
    }

    /// The path of side `side` walked from corner `from`.
    fn side_path(&self, side: u32, from: u32) -> Vec<u32> {
        let path = &self.sides[side as usize].path;
        if path.first() == Some(&from) {
            path.clone()
        } else {
            path.iter().rev().copied().collect()
        }
    }

    /// Divides `faces` among the candidate triangles (corners counter-clockwise, side
    /// ids): the faces are cut along the candidates' side paths, and each candidate gets
    /// the region to the left of its sides (the face holding the directed first edge of
    /// each of its sides' paths); a candidate whose sides disagree on that region, or
    /// whose region another took, approximates nothing and is discarded (the paper's
    /// coalescing paths). Returns the nodes made.
    fn place(
        &mut self,
        faces: &[u32],
        candidates: &[([u32; 3], [u32; 3])],
        level: u32,
    ) -> Vec<u32> {
        let triangles = self.surface.mesh().triangles();
        let mut cut = std::collections::HashSet::new();
        for (_, sides) in candidates {
            for &side in sides {
                for pair in self.sides[side as usize].path.windows(2) {
                    cut.insert((pair[0].min(pair[1]), pair[0].max(pair[1])));
                }
            }
        }
        let (regions, region_of) = self.surface.regions(faces, &cut);
        let mut by_edge: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        let mut by_directed: HashMap<(u32, u32), u32> = HashMap::new();
        for &f in faces {
            let [a, b, c] = triangles[f as usize];
            for (u, v) in [(a, b), (b, c), (c, a)] {
                by_edge.entry((u.min(v), u.max(v))).or_default().push(f);
                by_directed.insert((u, v), f);
            }
        }
        // Every edge of a candidate's side paths votes for the region to its left (the
        // face holding the directed edge); each region goes to the candidate with the most
        // votes (the lowest on ties). Paths that coincide near a corner cast a few votes
        // on a neighbour's region; a candidate whose paths coalesce gets no region at all.
        let mut votes: HashMap<(u32, usize), usize> = HashMap::new();
        for (index, &(corners, sides)) in candidates.iter().enumerate() {
            for (k, &side) in sides.iter().enumerate() {
                let path = self.side_path(side, corners[k]);
                for edge in path.windows(2) {
                    if let Some(f) = by_directed.get(&(edge[0], edge[1])) {
                        *votes.entry((region_of[f], index)).or_default() += 1;
                    }
                }
            }
        }
        // First the candidates all of whose votes go to one region (their sides enclose
        // it: the rightful owner), the most votes first; then the regions left go to the
        // candidate with the most votes among those still without a region, then among all.
        let mut owner: Vec<Option<usize>> = vec![None; regions.len()];
        let mut voted: Vec<Vec<(u32, usize)>> = vec![Vec::new(); candidates.len()];
        let mut ballots: Vec<(&(u32, usize), &usize)> = votes.iter().collect();
        ballots.sort_by_key(|&(&(r, c), _)| (r, c));
        for &(&(r, c), &count) in &ballots {
            voted[c].push((r, count));
        }
        let mut sole: Vec<(usize, u32, usize)> = voted
            .iter()
            .enumerate()
            .filter(|(_, v)| v.len() == 1)
            .map(|(c, v)| (v[0].1, v[0].0, c))
            .collect();
        sole.sort_by(|x, y| y.0.cmp(&x.0).then(x.2.cmp(&y.2)));
        let mut owns = vec![false; candidates.len()];
        for (_, r, c) in sole {
            if owner[r as usize].is_none() {
                owner[r as usize] = Some(c);
                owns[c] = true;
            }
        }
        for pass in 0..2 {
            for (r, slot) in owner.iter_mut().enumerate() {
                if slot.is_some() {
                    continue;
                }
                let pick = ballots
                    .iter()
                    .filter(|&&(&(q, c), _)| q as usize == r && (pass == 1 || !owns[c]))
                    .max_by(|x, y| x.1.cmp(y.1).then(y.0.1.cmp(&x.0.1)))
                    .map(|&(&(_, c), _)| c);
                if let Some(c) = pick {
                    *slot = Some(c);
                    owns[c] = true;
                }
            }
        }
        if owner.iter().all(Option::is_none) {
            return Vec::new();
        }
        // Regions left between coinciding paths join the claimed neighbour they share the
        // most cut edges with (the lowest candidate on ties), until none is left.
        loop {
            let mut changed = false;
            for r in 0..regions.len() {
                if owner[r].is_some() {
                    continue;
                }
                let mut shared: HashMap<usize, usize> = HashMap::new();
                for &f in &regions[r] {
                    let [a, b, c] = triangles[f as usize];
                    for (u, v) in [(a, b), (b, c), (c, a)] {
                        for &g in &by_edge[&(u.min(v), u.max(v))] {
                            if let Some(o) = owner[region_of[&g] as usize] {
                                *shared.entry(o).or_default() += 1;
                            }
                        }
                    }
                }
                if let Some((&o, _)) = shared.iter().max_by(|x, y| x.1.cmp(y.1).then(y.0.cmp(x.0)))
                {
                    owner[r] = Some(o);
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        let mut made = Vec::new();
        for (index, &(corners, sides)) in candidates.iter().enumerate() {
            let mut patch: Vec<u32> = (0..regions.len())
                .filter(|&r| owner[r] == Some(index))
                .flat_map(|r| regions[r].iter().copied())
                .collect();
            if patch.is_empty() {
                continue;
            }
            patch.sort_unstable();
            made.push(self.make_node(corners, sides, patch, level));
        }
        made
    }

    /// A node for `corners` over `faces`: a leaf when the patch is the one face on these
    /// corners, else with its bounding volume.
    fn make_node(
        &mut self,
        corners: [u32; 3],
        sides: [u32; 3],
        faces: Vec<u32>,
        level: u32,
    ) -> u32 {
        let positions = self.surface.mesh().positions();
        // A leaf is an original face on its own corners; a one-face patch on other corners
        // (paths that run out to a vertex and back) still splits at its face's third vertex.
        let leaf = faces.len() == 1 && {
            let mut face = self.surface.mesh().triangles()[faces[0] as usize];
            let mut own = corners;
            face.sort_unstable();
            own.sort_unstable();
            face == own
        };
        let (bound, width) = if leaf {
            (None, 0.0)
        } else {
            let bound = self.bound(corners, &faces);
            let points = corners.map(|v| positions[v as usize]);
            let (w1, w2) = bound.widths(points);
            (Some(bound), w1.max(w2))
        };
        self.nodes.push(Node3 {
            corners,
            level,
            faces,
            bound,
            width,
            children: Vec::new(),
            sides,
        });
        (self.nodes.len() - 1) as u32
    }

    /// The patch's vertices other than the corners, ascending.
    fn inner_vertices(&self, corners: [u32; 3], faces: &[u32]) -> Vec<u32> {
        let triangles = self.surface.mesh().triangles();
        let mut vertices: Vec<u32> = faces
            .iter()
            .flat_map(|&f| triangles[f as usize])
            .filter(|v| !corners.contains(v))
            .collect();
        vertices.sort_unstable();
        vertices.dedup();
        vertices
    }

    /// Definition 5's bounding volume of the patch `faces` over `corners`.
    fn bound(&self, corners: [u32; 3], faces: &[u32]) -> Bound3 {
        let positions = self.surface.mesh().positions();
        let points = corners.map(|v| positions[v as usize]);
        let Some((centre, radius, normal)) = circle(points) else {
            // A degenerate approximating triangle: bound nothing away.
            return Bound3 {
                above: f64::INFINITY,
                below: f64::NEG_INFINITY,
            };
        };
        let (mut above, mut below) = (f64::NEG_INFINITY, f64::INFINITY);
        for v in self.inner_vertices(corners, faces) {
            let x = positions[v as usize];
            let side = robust::orient3d(
                coord(points[0]),
                coord(points[1]),
                coord(points[2]),
                coord(x),
            );
            let power = x.distance_squared(centre) - radius * radius;
            // robust's orient3d is positive when x lies below the plane of a
            // counter-clockwise triangle (its convention); the height above is `h`.
            let h = (x - centre).dot(normal);
            if side == 0.0 || h == 0.0 || (h > 0.0) != (side < 0.0) {
                if power > 0.0 {
                    above = f64::INFINITY;
                }
                continue;
            }
            let k = power / (2.0 * radius * h);
            if side < 0.0 {
                above = above.max(k);
            } else {
                below = below.min(k);
            }
        }
        Bound3 { above, below }
    }

    /// The vertex Algorithm 2 splits a patch at: `v_q` or `v_r`, whichever ball has the
    /// larger signed radius (the first of the patch's inner vertices if none is off the
    /// plane).
    fn split_vertex(&self, node: &Node3) -> Option<u32> {
        let positions = self.surface.mesh().positions();
        let points = node.corners.map(|v| positions[v as usize]);
        let inner = self.inner_vertices(node.corners, &node.faces);
        let bound = node.bound?;
        let (centre, radius, normal) = circle(points)?;
        let mut best: Option<(f64, u32)> = None;
        let want_above = bound.above > -bound.below;
        for &v in &inner {
            let x = positions[v as usize];
            let h = (x - centre).dot(normal);
            if h == 0.0 || (h > 0.0) != want_above {
                continue;
            }
            let k = (x.distance_squared(centre) - radius * radius) / (2.0 * radius * h);
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
    fn refine(&mut self, frontier: &[u32]) -> Vec<u32> {
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

    /// The mesh the tree was built on.
    #[must_use]
    pub fn mesh(&self) -> &TriMesh {
        self.surface.mesh()
    }

    /// The nodes.
    #[must_use]
    pub fn nodes(&self) -> &[Node3] {
        &self.nodes
    }

    /// The two convex regions holding node `n`'s patch.
    pub(crate) fn node_regions(&self, n: u32) -> [Region; 2] {
        self.regions[n as usize]
    }

    /// The root triangles (one or two: the three root paths may leave one patch).
    #[must_use]
    pub fn roots(&self) -> &[u32] {
        &self.roots
    }

    /// The root ball.
    #[must_use]
    pub fn root_ball(&self) -> Sphere {
        self.root.sphere
    }

    /// The deepest level.
    #[must_use]
    pub fn depth(&self) -> u32 {
        self.nodes.iter().map(|n| n.level).max().unwrap_or(0)
    }

    /// The approximation at `level`: the triangles of that level, and the leaves above
    /// it, as a watertight mesh on the input's vertices: every edge is used as often in
    /// one direction as in the other (where a filled gap meets the level, an edge can
    /// carry four triangles). The deepest level is the input mesh.
    ///
    /// Two things open gaps in a level, both from the paper's construction: a triangle
    /// whose paths coalesce is discarded (it approximates no face), and a patch that cannot
    /// be split as the paper says is split at its most central vertex, or into its faces,
    /// without the side splits its neighbours made. Each gap's boundary is a loop of the
    /// level's edges; it is closed by a fan of triangles on the loop's vertices (for a
    /// discarded triangle, that triangle itself), so that every edge has as many
    /// triangles on one side as on the other.
    ///
    /// # Errors
    ///
    /// As [`TriMesh::new`] (cannot fail for a tree's own vertices).
    pub fn level(&self, level: u32) -> Result<TriMesh, HalError> {
        self.extract(|node| node.level < level)
    }

    /// The adaptive approximation (section 4.3): a triangle is refined only when its own
    /// width (Definition 6) exceeds `tolerance`. Where a neighbour refined past a shared
    /// side (a T-junction) and where a level has gaps, the gap is closed as in
    /// [`HalTree3::level`]: the mesh is watertight.
    ///
    /// # Errors
    ///
    /// As [`HalTree3::level`].
    pub fn approximate(&self, tolerance: f64) -> Result<TriMesh, HalError> {
        self.extract(|node| node.width > tolerance)
    }

    /// The triangles reached from the roots, descending where `refine` says so, with the
    /// gaps closed.
    fn extract(&self, refine: impl Fn(&Node3) -> bool) -> Result<TriMesh, HalError> {
        let mut triangles = Vec::new();
        let mut stack: Vec<u32> = self.roots.clone();
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if node.children.is_empty() || !refine(node) {
                triangles.push(node.corners);
            } else {
                stack.extend(node.children.iter().copied());
            }
        }
        triangles.sort_unstable();
        close_gaps(&mut triangles);
        Ok(TriMesh::new(
            self.surface.mesh().positions().to_vec(),
            triangles,
        )?)
    }
}

/// Closes the gaps of a triangle set: the directed edges without an opposite partner
/// (counted with multiplicity) are chained into loops, and each loop is filled by a fan
/// from its first vertex, oriented to balance them. Deterministic: loops start at the
/// lowest unmatched edge and turn to the lowest next vertex.
fn close_gaps(triangles: &mut Vec<[u32; 3]>) {
    // Net count per undirected edge: + for (low, high), − for (high, low).
    let mut net: HashMap<(u32, u32), i64> = HashMap::new();
    for &[a, b, c] in triangles.iter() {
        for (u, v) in [(a, b), (b, c), (c, a)] {
            if u == v {
                continue;
            }
            *net.entry((u.min(v), u.max(v))).or_default() += if u < v { 1 } else { -1 };
        }
    }
    // The edges the filling must provide, as outgoing lists per vertex.
    let mut needed: std::collections::BTreeMap<u32, Vec<u32>> = std::collections::BTreeMap::new();
    let mut pending = 0_usize;
    for (&(low, high), &count) in &net {
        // count > 0: the set has (low, high) too often, so the fill needs (high, low).
        let (from, to) = if count > 0 { (high, low) } else { (low, high) };
        for _ in 0..count.unsigned_abs() {
            needed.entry(from).or_default().push(to);
            pending += 1;
        }
    }
    for list in needed.values_mut() {
        list.sort_unstable_by(|a, b| b.cmp(a));
    }
    while pending > 0 {
        let Some((&start, _)) = needed.iter().find(|(_, list)| !list.is_empty()) else {
            break;
        };
        let mut lasso = vec![start];
        let mut at = start;
        while let Some(next) = needed.get_mut(&at).and_then(Vec::pop) {
            pending -= 1;
            if let Some(position) = lasso.iter().position(|&v| v == next) {
                // A loop closed: fill it and keep walking from where it began.
                let ring: Vec<u32> = lasso.split_off(position);
                for k in 1..ring.len().saturating_sub(1) {
                    triangles.push([ring[0], ring[k], ring[k + 1]]);
                }
                lasso.push(next);
                if lasso.len() == 1 && needed.get(&next).is_none_or(Vec::is_empty) {
                    break;
                }
            } else {
                lasso.push(next);
            }
            at = next;
        }
    }
}

/// A `robust` coordinate.
fn coord(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}
