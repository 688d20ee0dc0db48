//! The default engine of [`hausdorff`](super::hausdorff): exact closest points from a
//! [`TriangleTree`] of each mesh, bounds from the corners' answers, and refinement in
//! rounds that run on every core.
//!
//! Each direction `S → T` samples `S` at its vertices, then at edge midpoints of the
//! triangles it refines. Every sample gets an **exact** closest point on `T` (so every
//! sample distance is a certified lower bound, and the corners' triangles are the right
//! candidates for the upper bounds). A triangle of samples is bounded as the paper-engine
//! bounds it (bisector, single target triangle, split across a shared edge: see
//! [`bound`](super::bound)), from the target triangles its corners' answers lie on and
//! their neighbours; when that is not enough, by the best single target triangle found
//! by the tree ([`TriangleTree::triangle_upper_bound`]).
//!
//! Work proceeds in rounds with a fixed lower bound `L` (the largest sample distance so
//! far, both directions together when symmetric): every triangle whose bound is within
//! the tolerance of `L` is settled, the others are split in four, their new midpoints are
//! queried (in parallel, numbered in a fixed order), and the children are bounded (in
//! parallel). The result therefore does not depend on the number of threads.

use std::collections::HashMap;

use crate::QueryError;
use crate::closest::{ClosestPoint, Feature, TriangleTree};
use glam::DVec3;
use smallvec::SmallVec;
use sphaera_mesh::TriMesh;
use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};

use super::Rows;
use super::bound::{CornerAnswer, ROUNDING, TrianglePair, triangle_upper_bound};
use super::{DirectedHausdorff, HausdorffProgress};

/// The tree's search for the best single target triangle is made only for triangles
/// whose local bound is within this factor of what would settle them. Measured on the
/// bunny pair (`sphaera-eval/benches/hausdorff.rs`): beyond 1.5 the search settles 14 % of
/// the triangles it is tried on, beyond 3 almost none, while below 1.5 it settles 44 %;
/// 2 was the fastest of 1.2, 1.5, 2, 3 and always.
const FALLBACK_RATIO: f64 = 2.0;

/// The mesh measured against: its tree and the triangles around each vertex.
pub(super) struct TreeTarget<'m> {
    mesh: &'m TriMesh,
    tree: TriangleTree,
    around: Rows,
}

impl<'m> TreeTarget<'m> {
    /// Builds the tree of `mesh`.
    pub(super) fn new(mesh: &'m TriMesh) -> Result<Self, QueryError> {
        let tree = TriangleTree::new(mesh)?;
        let pairs = mesh
            .triangles()
            .iter()
            .enumerate()
            .flat_map(|(t, corners)| corners.map(|v| (v, t as u32)))
            .collect();
        let around = Rows::from_pairs(mesh.vertex_count(), pairs);
        Ok(Self { mesh, tree, around })
    }

    fn triangle(&self, t: u32) -> Option<Triangle> {
        self.mesh.triangle(t as usize)
    }

    /// The two triangles `a` and `b` as a pair if they share an edge.
    fn pair(&self, a: u32, b: u32) -> Option<TrianglePair> {
        let triangles = self.mesh.triangles();
        let (ia, ib) = (triangles.get(a as usize)?, triangles.get(b as usize)?);
        let mut shared = ia.iter().filter(|v| ib.contains(v));
        let (&p, &q) = (shared.next()?, shared.next()?);
        let positions = self.mesh.positions();
        Some(TrianglePair {
            first: self.triangle(a)?,
            second: self.triangle(b)?,
            p: *positions.get(p as usize)?,
            q: *positions.get(q as usize)?,
        })
    }
}

/// A point of the source mesh with its exact closest point on the target.
#[derive(Clone, Copy, Debug)]
struct Sample {
    position: DVec3,
    answer: ClosestPoint,
}

/// A triangle of samples of one side waiting to be bounded or split.
#[derive(Clone, Copy, Debug)]
struct Node {
    side: u8,
    corners: [u32; 3],
    upper: f64,
}

/// One direction: the source's samples against the target.
pub(super) struct TreeSide<'m> {
    source: &'m TriMesh,
    target: &'m TreeTarget<'m>,
    samples: Vec<Sample>,
    /// The sample of each source vertex (`u32::MAX` for a vertex no triangle uses).
    vertex_sample: Vec<u32>,
    midpoints: HashMap<(u32, u32), u32>,
    lower: f64,
    farthest: Option<usize>,
    /// The largest bound of a settled triangle.
    settled: f64,
    refined: usize,
}

impl<'m> TreeSide<'m> {
    pub(super) fn new(source: &'m TriMesh, target: &'m TreeTarget<'m>) -> Self {
        Self {
            source,
            target,
            samples: Vec::new(),
            vertex_sample: Vec::new(),
            midpoints: HashMap::new(),
            lower: 0.0,
            farthest: None,
            settled: 0.0,
            refined: 0,
        }
    }

    /// Queries every vertex some triangle uses.
    fn query_vertices(&mut self) -> Result<(), QueryError> {
        let mut used = vec![false; self.source.vertex_count()];
        for &v in self.source.triangles().iter().flatten() {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
        let positions: Vec<DVec3> = self
            .source
            .positions()
            .iter()
            .zip(&used)
            .filter(|(_, u)| **u)
            .map(|(&p, _)| p)
            .collect();
        let answers = self.target.tree.closest_many(&positions)?;
        let mut next = 0u32;
        self.vertex_sample = used
            .iter()
            .map(|&u| {
                if u {
                    next += 1;
                    next - 1
                } else {
                    u32::MAX
                }
            })
            .collect();
        self.samples = positions
            .into_iter()
            .zip(answers)
            .map(|(position, answer)| Sample { position, answer })
            .collect();
        for i in 0..self.samples.len() {
            self.raise(i);
        }
        Ok(())
    }

    /// Takes sample `i`'s distance into the lower bound.
    fn raise(&mut self, i: usize) {
        if let Some(s) = self.samples.get(i)
            && (self.farthest.is_none() || s.answer.distance > self.lower)
        {
            self.lower = s.answer.distance;
            self.farthest = Some(i);
        }
    }

    /// The source's triangles as nodes (bound not yet computed).
    fn initial_nodes(&self, side: u8) -> Vec<Node> {
        self.source
            .triangles()
            .iter()
            .filter_map(|t| {
                let corners = t.map(|v| self.vertex_sample.get(v as usize).copied());
                Some(Node {
                    side,
                    corners: [corners[0]?, corners[1]?, corners[2]?],
                    upper: f64::INFINITY,
                })
            })
            .collect()
    }

    /// The certified upper bound of the distance from every point of the triangle of
    /// samples `corners` to the target; the tree's search for a better single target
    /// triangle is made only when the corners' candidates leave the bound above
    /// `enough`.
    fn upper_bound(&self, corners: [u32; 3], enough: f64) -> f64 {
        let mut samples = [None; 3];
        for (slot, &s) in samples.iter_mut().zip(&corners) {
            *slot = self.samples.get(s as usize).copied();
        }
        let [Some(s0), Some(s1), Some(s2)] = samples else {
            return f64::INFINITY;
        };
        let samples = [s0, s1, s2];
        let answers = samples.map(|s| CornerAnswer {
            position: s.position,
            closest: s.answer.point,
        });
        let mut own = samples.map(|s| s.answer.triangle);
        own.sort_unstable();
        let mut ids: SmallVec<[u32; 32]> = SmallVec::from_slice(&own);
        for s in &samples {
            match s.answer.feature {
                Feature::Vertex(v) | Feature::Edge(v, _) => {
                    ids.extend_from_slice(self.target.around.row(v));
                }
                Feature::Face => {}
            }
        }
        ids.sort_unstable();
        ids.dedup();
        let targets: SmallVec<[Triangle; 32]> = ids
            .iter()
            .filter_map(|&t| self.target.triangle(t))
            .collect();
        let mut pairs: SmallVec<[TrianglePair; 3]> = SmallVec::new();
        for (i, &a) in own.iter().enumerate() {
            for &b in own.iter().skip(i + 1) {
                if a != b
                    && let Some(pair) = self.target.pair(a, b)
                {
                    pairs.push(pair);
                }
            }
        }
        let local = triangle_upper_bound(&answers, &targets, &pairs);
        if local <= enough || local > FALLBACK_RATIO * enough {
            return local;
        }
        let x = answers.map(|a| a.position);
        match self.target.tree.triangle_upper_bound(x, enough) {
            Ok(found) if found < local => {
                let scale = x.iter().fold(0.0_f64, |m, p| m.max(p.abs().max_element())) + found;
                found + ROUNDING * scale
            }
            _ => local,
        }
    }

    /// The sample at the midpoint of samples `a` and `b`, if it exists.
    fn midpoint(&self, a: u32, b: u32) -> Option<u32> {
        self.midpoints.get(&(a.min(b), a.max(b))).copied()
    }

    /// Adds the midpoints of `edges` (sorted, without those that exist), queried in
    /// parallel.
    fn add_midpoints(&mut self, edges: &[(u32, u32)]) -> Result<(), QueryError> {
        let sample = |s: u32| self.samples.get(s as usize);
        let query = |&(a, b): &(u32, u32)| -> Result<(DVec3, ClosestPoint), QueryError> {
            let (Some(sa), Some(sb)) = (sample(a), sample(b)) else {
                return Err(QueryError::EmptyMesh);
            };
            // Halves first: no overflow for coordinates near the largest float.
            let p = 0.5 * sa.position + 0.5 * sb.position;
            // The ends' triangles bound the distance, which prunes the descent.
            let near = [sa.answer.triangle, sb.answer.triangle]
                .into_iter()
                .filter_map(|t| self.target.triangle(t))
                .map(|t| point_triangle_distance_squared(p, &t))
                .fold(f64::INFINITY, f64::min)
                .sqrt();
            let tree = &self.target.tree;
            let seeded = tree.closest_within(p, near * (1.0 + 1e-9))?;
            let answer = match seeded {
                Some(answer) => answer,
                None => tree.closest(p)?,
            };
            Ok((p, answer))
        };
        #[cfg(feature = "parallel")]
        let found: Vec<(DVec3, ClosestPoint)> = {
            use rayon::prelude::*;
            edges.par_iter().map(query).collect::<Result<_, _>>()?
        };
        #[cfg(not(feature = "parallel"))]
        let found: Vec<(DVec3, ClosestPoint)> =
            edges.iter().map(query).collect::<Result<_, _>>()?;
        for (&edge, (position, answer)) in edges.iter().zip(found) {
            let index = self.samples.len();
            self.samples.push(Sample { position, answer });
            self.midpoints.insert(edge, index as u32);
            self.raise(index);
        }
        Ok(())
    }

    /// The direction's result; `upper` is the largest bound of a triangle left
    /// unsettled (0 if none).
    pub(super) fn finish(self, unsettled: f64) -> DirectedHausdorff {
        let mut vertex_distances = vec![0.0; self.source.vertex_count()];
        for (slot, &s) in vertex_distances.iter_mut().zip(&self.vertex_sample) {
            if let Some(sample) = self.samples.get(s as usize) {
                *slot = sample.answer.distance;
            }
        }
        let far = self.farthest.and_then(|i| self.samples.get(i));
        DirectedHausdorff {
            lower: self.lower,
            upper: self.settled.max(unsettled).max(self.lower),
            farthest: far.map_or(DVec3::ZERO, |s| s.position),
            closest: far.map_or(DVec3::ZERO, |s| s.answer.point),
            vertex_distances,
            samples: self.samples.len(),
            certified_samples: self.samples.len(),
            refined_triangles: self.refined,
        }
    }
}

/// The sides' results after refining until every bound is within `allowed` of the lower
/// bound (`true`) or the sample budget runs out (`false`).
pub(super) fn refine(
    sides: &mut [TreeSide<'_>],
    allowed: f64,
    max_samples: usize,
    progress: &(dyn Fn(&HausdorffProgress) + Sync),
) -> Result<(Vec<f64>, bool), QueryError> {
    let vertices: usize = sides.iter().map(|s| s.source.vertex_count()).sum();
    for side in sides.iter_mut() {
        side.query_vertices()?;
    }
    let samples = |sides: &[TreeSide<'_>]| sides.iter().map(|s| s.samples.len()).sum::<usize>();
    let lower_of = |sides: &[TreeSide<'_>]| sides.iter().map(|s| s.lower).fold(0.0_f64, f64::max);
    let report = |sides: &[TreeSide<'_>], upper: f64| {
        progress(&HausdorffProgress {
            vertices_done: vertices,
            vertices,
            samples: samples(sides),
            lower: lower_of(sides),
            upper,
        });
    };
    report(sides, f64::INFINITY);
    let mut nodes: Vec<Node> = sides
        .iter()
        .enumerate()
        .flat_map(|(i, side)| side.initial_nodes(i as u8))
        .collect();
    loop {
        let threshold = lower_of(sides) + allowed;
        bound_nodes(sides, &mut nodes, threshold);
        let mut pending = Vec::with_capacity(nodes.len() / 4);
        for node in nodes.drain(..) {
            if node.upper <= threshold {
                if let Some(side) = sides.get_mut(usize::from(node.side)) {
                    side.settled = side.settled.max(node.upper);
                }
            } else {
                pending.push(node);
            }
        }
        let upper = pending
            .iter()
            .map(|n| n.upper)
            .chain(sides.iter().map(|s| s.settled))
            .fold(lower_of(sides), f64::max);
        report(sides, upper);
        if pending.is_empty() {
            return Ok((vec![0.0; sides.len()], true));
        }
        // Stop, every pending bound unsettled, if splitting them all (at most three new
        // samples each) would pass the sample budget.
        if pending.len() > max_samples.saturating_sub(samples(sides)) / 3 {
            let mut unsettled = vec![0.0_f64; sides.len()];
            for node in &pending {
                if let Some(u) = unsettled.get_mut(usize::from(node.side)) {
                    *u = u.max(node.upper);
                }
            }
            return Ok((unsettled, false));
        }
        nodes = split(sides, &pending)?;
    }
}

/// Splits every node of `pending` in four at its edge midpoints (queried first).
fn split(sides: &mut [TreeSide<'_>], pending: &[Node]) -> Result<Vec<Node>, QueryError> {
    for (index, side) in sides.iter_mut().enumerate() {
        let mut edges: Vec<(u32, u32)> = pending
            .iter()
            .filter(|n| usize::from(n.side) == index)
            .flat_map(|n| {
                let [a, b, c] = n.corners;
                [(a, b), (b, c), (c, a)]
            })
            .map(|(a, b)| (a.min(b), a.max(b)))
            .filter(|&(a, b)| side.midpoint(a, b).is_none())
            .collect();
        edges.sort_unstable();
        edges.dedup();
        side.add_midpoints(&edges)?;
    }
    let mut children = Vec::with_capacity(4 * pending.len());
    for node in pending {
        let Some(side) = sides.get_mut(usize::from(node.side)) else {
            continue;
        };
        let [a, b, c] = node.corners;
        let (Some(ab), Some(bc), Some(ca)) = (
            side.midpoint(a, b),
            side.midpoint(b, c),
            side.midpoint(c, a),
        ) else {
            continue;
        };
        side.refined += 1;
        for corners in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
            children.push(Node {
                side: node.side,
                corners,
                upper: f64::INFINITY,
            });
        }
    }
    Ok(children)
}

/// Computes every node's upper bound (in parallel).
fn bound_nodes(sides: &[TreeSide<'_>], nodes: &mut [Node], threshold: f64) {
    let bound = |node: &mut Node| {
        node.upper = sides
            .get(usize::from(node.side))
            .map_or(f64::INFINITY, |side| {
                side.upper_bound(node.corners, threshold)
            });
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        nodes.par_iter_mut().with_min_len(256).for_each(bound);
    }
    #[cfg(not(feature = "parallel"))]
    nodes.iter_mut().for_each(bound);
}
