//! The mesh measured against: its triangles, the triangles around each vertex, and a
//! local search for a near point from a nearby answer.
//!
//! The local search (a greedy walk over triangles sharing a vertex) finds *a* point of
//! the mesh, usually the closest; its distance is an upper bound of the true distance
//! whatever it finds, which is all an upper bound of the Hausdorff distance needs. Lower
//! bounds come from certified queries of a [`Session`](crate::Session) only.

use glam::DVec3;
use sphaera_mesh::geometry::{self, Triangle, closest_point_on_triangle};
use sphaera_simplify::{Hierarchy, Simplified};

pub(crate) use sphaera_query::hausdorff::Rows;
use sphaera_query::hausdorff::bound::TrianglePair;

/// The most triangles a walk moves through before it settles for what it found.
const MAX_STEPS: usize = 64;

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

/// A target mesh's geometry and adjacency: the input mesh (from a hierarchy), or a level
/// of detail whose vertices carry error radii.
pub(crate) struct Target {
    /// Positions by vertex key (input vertex for the input mesh).
    positions: Vec<DVec3>,
    /// The error radius of each vertex (empty: all zero).
    radii: Vec<f64>,
    /// Triangles, as vertex keys.
    triangles: Vec<[u32; 3]>,
    /// The triangles around each vertex key.
    around: Rows,
    /// The triangle of each input triangle (input mesh only).
    of_input: Vec<u32>,
}

impl Target {
    /// The input mesh of `hierarchy`; triangles keep the hierarchy's ids.
    pub(crate) fn new(hierarchy: &Hierarchy) -> Self {
        let count = hierarchy.triangle_count() as u32;
        let key = |v: u32| hierarchy.original_vertex(v).unwrap_or(v);
        let hierarchy_positions = hierarchy.positions();
        let keys = (0..hierarchy_positions.len() as u32)
            .map(key)
            .max()
            .map_or(0, |k| k as usize + 1);
        let mut positions = vec![DVec3::ZERO; keys];
        for (v, &p) in hierarchy_positions.iter().enumerate() {
            if let Some(slot) = positions.get_mut(key(v as u32) as usize) {
                *slot = p;
            }
        }
        let mut triangles = Vec::with_capacity(count as usize);
        let mut of_input = Vec::new();
        for t in 0..count {
            let corners = hierarchy.triangle(t).map_or([u32::MAX; 3], |c| c.map(key));
            triangles.push(corners);
            if let Some(i) = hierarchy.original_triangle(t) {
                let i = i as usize;
                if of_input.len() <= i {
                    of_input.resize(i + 1, u32::MAX);
                }
                of_input[i] = t;
            }
        }
        Self::assemble(positions, Vec::new(), triangles, of_input)
    }

    /// A level of detail of the target: every point of its triangles lies within the
    /// radius interpolated there of the input surface (the simplifier's invariant (B)).
    pub(crate) fn level(level: &Simplified) -> Self {
        Self::assemble(
            level.mesh.positions().to_vec(),
            level.vertex_radii.clone(),
            level.mesh.triangles().to_vec(),
            Vec::new(),
        )
    }

    fn assemble(
        positions: Vec<DVec3>,
        radii: Vec<f64>,
        triangles: Vec<[u32; 3]>,
        of_input: Vec<u32>,
    ) -> Self {
        let mut pairs = Vec::with_capacity(3 * triangles.len());
        for (t, corners) in triangles.iter().enumerate() {
            for &v in corners {
                pairs.push((v, t as u32));
            }
        }
        let around = Rows::from_pairs(positions.len(), pairs);
        Self {
            positions,
            radii,
            triangles,
            around,
            of_input,
        }
    }

    /// Triangles.
    pub(crate) fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The triangle of input triangle `i`.
    pub(crate) fn of_input(&self, i: u32) -> Option<u32> {
        self.of_input
            .get(i as usize)
            .copied()
            .filter(|&t| t != u32::MAX)
    }

    /// The triangles around vertex key `v` (none for `u32::MAX`).
    pub(crate) fn around(&self, v: u32) -> &[u32] {
        self.around.row(v)
    }

    /// The geometry of triangle `t`.
    pub(crate) fn triangle(&self, t: u32) -> Option<Triangle> {
        let corners = self.triangles.get(t as usize)?;
        let at = |i: usize| self.positions.get(corners[i] as usize).copied();
        Some(Triangle::new(at(0)?, at(1)?, at(2)?))
    }

    /// The largest error radius at a corner of triangle `t` (0 for the input mesh).
    pub(crate) fn radius(&self, t: u32) -> f64 {
        self.triangles.get(t as usize).map_or(f64::INFINITY, |c| {
            c.iter()
                .map(|&v| {
                    if self.radii.is_empty() {
                        0.0
                    } else {
                        self.radii.get(v as usize).copied().unwrap_or(f64::INFINITY)
                    }
                })
                .fold(0.0, f64::max)
        })
    }

    /// Triangles `a` and `b` with their shared edge, if they share one.
    pub(crate) fn pair(&self, a: u32, b: u32) -> Option<TrianglePair> {
        let (ia, ib) = (
            self.triangles.get(a as usize)?,
            self.triangles.get(b as usize)?,
        );
        let (ta, tb) = (self.triangle(a)?, self.triangle(b)?);
        let shared: Vec<usize> = (0..3).filter(|&k| ib.contains(&ia[k])).collect();
        let [k, l] = shared.as_slice() else {
            return None;
        };
        let corners = ta.corners();
        Some(TrianglePair {
            first: ta,
            second: tb,
            p: corners[*k],
            q: corners[*l],
        })
    }

    /// The closest point of triangle `t` to `x`, as a [`Found`].
    pub(crate) fn on_triangle(&self, x: DVec3, t: u32) -> Option<Found> {
        let corners = self.triangles.get(t as usize)?;
        let hit = closest_point_on_triangle(x, &self.triangle(t)?);
        let feature_vertex = match hit.feature {
            geometry::TriangleFeature::Vertex(i) | geometry::TriangleFeature::Edge(i) => {
                corners[usize::from(i)]
            }
            geometry::TriangleFeature::Face => u32::MAX,
        };
        Some(Found {
            point: hit.point,
            distance: hit.distance_squared.sqrt(),
            triangle: t,
            feature_vertex,
        })
    }

    /// The nearest triangle to `x` by trying every one (for a walk's first start).
    pub(crate) fn nearest(&self, x: DVec3) -> Option<Found> {
        (0..self.triangles.len() as u32)
            .filter_map(|t| self.on_triangle(x, t))
            .min_by(|a, b| a.distance.total_cmp(&b.distance))
    }

    /// A point of the mesh near `x`, by a greedy walk from triangle `start`: while the
    /// nearest point found lies on a vertex or an edge, the triangles around that feature
    /// (the surface near the point) are tried, and the walk moves to a nearer one (at most
    /// [`MAX_STEPS`] moves). It stops at a local minimum of the distance over the surface:
    /// a point inside a face, or on a feature none of whose triangles is nearer. `None`
    /// only if `start` is not a triangle.
    pub(crate) fn walk(&self, x: DVec3, start: u32) -> Option<Found> {
        let mut best = self.on_triangle(x, start)?;
        for _ in 0..MAX_STEPS {
            if best.feature_vertex == u32::MAX {
                break;
            }
            let current = best.triangle;
            for &t in self.around(best.feature_vertex) {
                if t != current
                    && let Some(found) = self.on_triangle(x, t)
                    && found.distance < best.distance
                {
                    best = found;
                }
            }
            if best.triangle == current {
                break;
            }
        }
        Some(best)
    }
}
