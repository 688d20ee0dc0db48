//! The sample set of a surface: referenced vertices, distinct edge midpoints and seeded
//! random points, each part optional.

use glam::DVec3;

use crate::QueryError;
use crate::sampling::{self, MAX_SAMPLES};
use sphaera_mesh::TriMesh;

/// Which points of a surface [`SurfaceSamples::new`] takes.
///
/// The default takes every referenced vertex, every distinct edge midpoint and 10,000
/// random points drawn with seed 0. Each part can be switched off; the vertices can be
/// thinned to every `n`-th one.
///
/// # Examples
///
/// ```
/// use sphaera_query::measure::SampleOptions;
///
/// let options = SampleOptions::default()
///     .with_edge_midpoints(false)
///     .with_random_points(100_000)
///     .with_seed(0x5EED);
/// assert!(options.vertices && !options.edge_midpoints);
/// assert_eq!(options.random_points, 100_000);
/// assert_eq!(options.vertex_stride, 1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct SampleOptions {
    /// Take the referenced vertices (default `true`). Maxima of the distance between a
    /// surface and its simplification are often at vertices: corners cut or pushed.
    pub vertices: bool,
    /// Take only every `vertex_stride`-th referenced vertex, starting with the first
    /// (default 1: all of them; must be at least 1). A timed baseline measures a subset
    /// and extrapolates.
    pub vertex_stride: usize,
    /// Take the midpoint of every distinct edge (default `true`).
    pub edge_midpoints: bool,
    /// Draw this many uniform random points ([`sampling::random`]; default 10,000; at
    /// most [`MAX_SAMPLES`]; 0 for none).
    pub random_points: usize,
    /// The seed of the random points (default 0).
    pub seed: u64,
}

impl Default for SampleOptions {
    /// Every referenced vertex, every distinct edge midpoint, 10,000 random points, seed 0.
    fn default() -> Self {
        Self {
            vertices: true,
            vertex_stride: 1,
            edge_midpoints: true,
            random_points: 10_000,
            seed: 0,
        }
    }
}

impl SampleOptions {
    /// With the referenced vertices taken or not.
    #[must_use]
    pub fn with_vertices(mut self, vertices: bool) -> Self {
        self.vertices = vertices;
        self
    }

    /// With one referenced vertex in `vertex_stride` taken.
    #[must_use]
    pub fn with_vertex_stride(mut self, vertex_stride: usize) -> Self {
        self.vertex_stride = vertex_stride;
        self
    }

    /// With the edge midpoints taken or not.
    #[must_use]
    pub fn with_edge_midpoints(mut self, edge_midpoints: bool) -> Self {
        self.edge_midpoints = edge_midpoints;
        self
    }

    /// With `random_points` random points.
    #[must_use]
    pub fn with_random_points(mut self, random_points: usize) -> Self {
        self.random_points = random_points;
        self
    }

    /// With the given seed of the random points.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
}

/// Where a sample of a [`SurfaceSamples`] comes from on its mesh.
///
/// A caller that refines around the best samples reads here which triangles hold one:
/// those around a vertex, the one or more on both sides of an edge, the one a random point
/// was drawn in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SampleOrigin {
    /// The referenced vertex with this index.
    Vertex(u32),
    /// The midpoint of the edge between these two vertices (the smaller index first).
    EdgeMidpoint(u32, u32),
    /// A random point.
    Random {
        /// The triangle it was drawn in.
        triangle: usize,
    },
}

/// The points of a surface that a sampled Hausdorff distance measures, in a fixed order:
/// the referenced vertices (by index), the distinct edge midpoints (by vertex pair), then
/// the random points (as drawn).
///
/// Every sample is a point of the surface, so a distance measured from it is one term of
/// the supremum that defines the directed Hausdorff distance (see the
/// [module documentation](super)). An unreferenced vertex is not on the surface and is
/// never taken; an edge whose two ends are the same vertex (a triangle such as `[4, 4, 7]`)
/// is not an edge.
///
/// # Examples
///
/// ```
/// use sphaera_query::measure::{SampleOptions, SampleOrigin, SurfaceSamples};
/// use sphaera_mesh::shapes;
///
/// let cube = shapes::cube(1.0, 1)?; // 8 vertices, 18 edges (12 sides, 6 diagonals)
/// let samples = SurfaceSamples::new(&cube, &SampleOptions::default().with_random_points(100))?;
/// assert_eq!(samples.len(), 8 + 18 + 100);
/// assert_eq!(samples.origins()[0], SampleOrigin::Vertex(0));
/// assert!(matches!(samples.origins()[8], SampleOrigin::EdgeMidpoint(_, _)));
/// assert!(matches!(samples.origins()[26], SampleOrigin::Random { .. }));
///
/// // Only every third vertex.
/// let options = SampleOptions::default()
///     .with_vertex_stride(3)
///     .with_edge_midpoints(false)
///     .with_random_points(0);
/// assert_eq!(SurfaceSamples::new(&cube, &options)?.len(), 3); // vertices 0, 3 and 6
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceSamples {
    points: Vec<DVec3>,
    origins: Vec<SampleOrigin>,
    vertex_count: usize,
    edge_midpoint_count: usize,
}

impl SurfaceSamples {
    /// The samples of `mesh` that `options` asks for.
    ///
    /// Random points need area to be drawn from: a mesh without triangles, or whose
    /// triangles all have zero area, gets none (its vertices and edge midpoints are still
    /// points of the surface); [`SurfaceSamples::random_point_count`] says how many were
    /// drawn.
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidParameter`] if the vertex stride is 0, if more than
    /// [`MAX_SAMPLES`] random points are asked for, or if [`sampling::random`] cannot
    /// reserve their memory or the surface area overflows `f64`.
    ///
    /// # Performance
    ///
    /// `O(V + T log T + n log T)` for `V` vertices, `T` triangles and `n` random points
    /// (the edges are sorted to find the distinct ones), single-threaded.
    pub fn new(mesh: &TriMesh, options: &SampleOptions) -> Result<Self, QueryError> {
        if options.vertex_stride == 0 {
            return Err(QueryError::InvalidParameter {
                name: "vertex_stride",
                value: 0.0,
                requirement: "at least 1",
            });
        }
        if options.random_points > MAX_SAMPLES {
            return Err(QueryError::InvalidParameter {
                name: "random_points",
                value: options.random_points as f64,
                requirement: "at most `sampling::MAX_SAMPLES` (2^24)",
            });
        }
        let positions = mesh.positions();
        let mut referenced = vec![false; positions.len()];
        let mut edges = Vec::new();
        if options.edge_midpoints {
            edges.reserve(3 * mesh.triangle_count());
        }
        for triangle in mesh.triangles() {
            for k in 0..3 {
                let (u, w) = (triangle[k], triangle[(k + 1) % 3]);
                // Indices are in range in a `TriMesh` (invariant); `get_mut` avoids a
                // panic regardless.
                if let Some(used) = referenced.get_mut(u as usize) {
                    *used = true;
                }
                if options.edge_midpoints && u != w {
                    edges.push((u.min(w), u.max(w)));
                }
            }
        }
        edges.sort_unstable();
        edges.dedup();

        let mut samples = Self {
            points: Vec::new(),
            origins: Vec::new(),
            vertex_count: 0,
            edge_midpoint_count: 0,
        };
        if options.vertices {
            let vertices = positions
                .iter()
                .zip(&referenced)
                .enumerate()
                .filter(|(_, (_, used))| **used)
                .step_by(options.vertex_stride);
            for (v, (&p, _)) in vertices {
                // `TriMesh::new` checked that vertex indices fit in u32 (invariant).
                samples.push(
                    p,
                    SampleOrigin::Vertex(u32::try_from(v).unwrap_or(u32::MAX)),
                );
                samples.vertex_count += 1;
            }
        }
        for &(u, w) in &edges {
            let (Some(&pu), Some(&pw)) = (positions.get(u as usize), positions.get(w as usize))
            else {
                continue; // indices are in range (invariant)
            };
            samples.push(0.5 * (pu + pw), SampleOrigin::EdgeMidpoint(u, w));
            samples.edge_midpoint_count += 1;
        }
        if options.random_points > 0 {
            match sampling::random(mesh, options.random_points, options.seed) {
                Ok(random) => {
                    for s in random {
                        samples.push(
                            s.position,
                            SampleOrigin::Random {
                                triangle: s.triangle,
                            },
                        );
                    }
                }
                // No area to draw from: the vertices and midpoints are all there is.
                Err(QueryError::EmptyMesh | QueryError::ZeroSurfaceArea { .. }) => {}
                Err(e) => return Err(e),
            }
        }
        Ok(samples)
    }

    fn push(&mut self, point: DVec3, origin: SampleOrigin) {
        self.points.push(point);
        self.origins.push(origin);
    }

    /// The sample points, in order (vertices, edge midpoints, random points).
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// Where each sample comes from, parallel to [`SurfaceSamples::points`].
    pub fn origins(&self) -> &[SampleOrigin] {
        &self.origins
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there is no sample.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// How many samples are vertices (the first ones).
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// How many samples are edge midpoints (after the vertices).
    pub fn edge_midpoint_count(&self) -> usize {
        self.edge_midpoint_count
    }

    /// How many samples are random points (the last ones): as many as asked for, or 0 for
    /// a surface without area.
    pub fn random_point_count(&self) -> usize {
        self.points.len() - self.vertex_count - self.edge_midpoint_count
    }

    /// The sample points, without their origins.
    pub fn into_points(self) -> Vec<DVec3> {
        self.points
    }
}
