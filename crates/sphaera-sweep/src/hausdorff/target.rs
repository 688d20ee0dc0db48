//! The mesh measured against: its triangles, the triangles around each vertex, and a
//! local search for a near point from a nearby answer.
//!
//! The local search (a greedy walk over triangles sharing a vertex) finds *a* point of
//! the mesh, usually the closest; its distance is an upper bound of the true distance
//! whatever it finds, which is all an upper bound of the Hausdorff distance needs. Lower
//! bounds come from certified queries of a [`Session`](crate::Session) only.

use glam::DVec3;
use sphaera_mesh::geometry::{self, Triangle, closest_point_on_triangle};
use sphaera_simplify::Hierarchy;

/// The most triangles a walk moves through before it settles for what it found.
const MAX_STEPS: usize = 64;

/// Rows of `u32` items in compressed form (row `i` is `items[offsets[i]..offsets[i + 1]]`).
pub(crate) struct Rows {
    offsets: Vec<usize>,
    items: Vec<u32>,
}

impl Rows {
    /// The rows of the `(row, item)` pairs (sorted and deduplicated here).
    pub(crate) fn from_pairs(rows: usize, mut pairs: Vec<(u32, u32)>) -> Self {
        pairs.retain(|&(r, _)| (r as usize) < rows);
        pairs.sort_unstable();
        pairs.dedup();
        let mut offsets = vec![0; rows + 1];
        for &(r, _) in &pairs {
            offsets[r as usize + 1] += 1;
        }
        for i in 0..rows {
            offsets[i + 1] += offsets[i];
        }
        Self {
            offsets,
            items: pairs.into_iter().map(|(_, item)| item).collect(),
        }
    }

    /// Row `r` (empty for an unknown row).
    pub(crate) fn row(&self, r: u32) -> &[u32] {
        let r = r as usize;
        match (self.offsets.get(r), self.offsets.get(r + 1)) {
            (Some(&a), Some(&b)) => self.items.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }
}

/// A point found on the target mesh.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Found {
    pub point: DVec3,
    pub distance: f64,
    /// The hierarchy triangle holding `point`.
    pub triangle: u32,
    /// The input vertex `point` lies on, or one end of the input edge it lies on, or
    /// `u32::MAX` inside a face.
    pub feature_vertex: u32,
}

impl Found {
    /// The placeholder for a vertex no triangle uses (not a point of the surface): at
    /// distance 0, on no triangle.
    pub(crate) fn unused(point: DVec3) -> Self {
        Self {
            point,
            distance: 0.0,
            triangle: u32::MAX,
            feature_vertex: u32::MAX,
        }
    }
}

/// The target mesh's geometry and adjacency.
pub(crate) struct Target<'h> {
    hierarchy: &'h Hierarchy,
    /// The hierarchy triangles around each input vertex.
    around: Rows,
    /// The hierarchy triangle of each input triangle.
    of_input: Vec<u32>,
}

impl<'h> Target<'h> {
    pub(crate) fn new(hierarchy: &'h Hierarchy) -> Self {
        let count = hierarchy.triangle_count() as u32;
        let mut pairs = Vec::with_capacity(3 * count as usize);
        let mut of_input = Vec::new();
        for t in 0..count {
            for v in hierarchy.triangle(t).into_iter().flatten() {
                pairs.push((hierarchy.original_vertex(v).unwrap_or(v), t));
            }
            if let Some(i) = hierarchy.original_triangle(t) {
                let i = i as usize;
                if of_input.len() <= i {
                    of_input.resize(i + 1, u32::MAX);
                }
                of_input[i] = t;
            }
        }
        let rows = pairs
            .iter()
            .map(|&(v, _)| v as usize + 1)
            .max()
            .unwrap_or(0);
        Self {
            hierarchy,
            around: Rows::from_pairs(rows, pairs),
            of_input,
        }
    }

    /// The hierarchy triangle of input triangle `i`.
    pub(crate) fn of_input(&self, i: u32) -> Option<u32> {
        self.of_input
            .get(i as usize)
            .copied()
            .filter(|&t| t != u32::MAX)
    }

    /// The hierarchy triangles around input vertex `v` (none for `u32::MAX`).
    pub(crate) fn around(&self, v: u32) -> &[u32] {
        self.around.row(v)
    }

    /// The geometry of hierarchy triangle `t`.
    pub(crate) fn triangle(&self, t: u32) -> Option<Triangle> {
        let corners = self.hierarchy.triangle(t)?;
        let positions = self.hierarchy.positions();
        let at = |i: usize| positions.get(corners[i] as usize).copied();
        Some(Triangle::new(at(0)?, at(1)?, at(2)?))
    }

    /// The closest point of triangle `t` to `x`, as a [`Found`].
    pub(crate) fn on_triangle(&self, x: DVec3, t: u32) -> Option<Found> {
        let corners = self.hierarchy.triangle(t)?;
        let hit = closest_point_on_triangle(x, &self.triangle(t)?);
        let input = |i: u8| {
            let v = corners[usize::from(i)];
            self.hierarchy.original_vertex(v).unwrap_or(v)
        };
        let feature_vertex = match hit.feature {
            geometry::Feature::Vertex(i) | geometry::Feature::Edge(i) => input(i),
            geometry::Feature::Face => u32::MAX,
        };
        Some(Found {
            point: hit.point,
            distance: hit.distance_squared.sqrt(),
            triangle: t,
            feature_vertex,
        })
    }

    /// A point of the mesh near `x`, by a greedy walk from triangle `start`: moves to the
    /// nearest triangle around the current one's corners while that gets closer (at most
    /// [`MAX_STEPS`] moves). `None` only if `start` is not a triangle.
    pub(crate) fn walk(&self, x: DVec3, start: u32) -> Option<Found> {
        let mut best = self.on_triangle(x, start)?;
        for _ in 0..MAX_STEPS {
            let current = best.triangle;
            let corners = self.hierarchy.triangle(current)?;
            for v in corners {
                let v = self.hierarchy.original_vertex(v).unwrap_or(v);
                for &t in self.around(v) {
                    if t != current
                        && let Some(found) = self.on_triangle(x, t)
                        && found.distance < best.distance
                    {
                        best = found;
                    }
                }
            }
            if best.triangle == current {
                break;
            }
        }
        Some(best)
    }
}
