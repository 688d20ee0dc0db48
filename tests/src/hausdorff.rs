//! A measured (sampled) Hausdorff distance between two triangle meshes, computed with an
//! independent peer: parry3d-f64's point projection.
//!
//! # What it is for
//!
//! Sphaera's simplifier (error spheres) and its Meshsweeper-style distance queries report
//! *certified upper bounds* on the Hausdorff distance between two surfaces. This module
//! gives the other side of the check: a *measured* distance that is, by construction, a
//! **lower bound** of the true one-sided distances. A certified bound that ever comes out
//! below the measured value is wrong. The measurement shares no distance code with the
//! code it checks: the distance from a point to a mesh is parry's BVH-accelerated
//! projection, not our own closest-point routine (which appears here only for degenerate
//! triangles, see [`DistanceToMesh`]).
//!
//! The sample set and the maxima are `sphaera-mesh`'s ([`sphaera_query::measure`], the
//! same code behind `sphaera simplify --measure`), measured here with the parry oracle;
//! the local refinement (below) is this module's own.
//!
//! # Why the result is a lower bound
//!
//! The directed Hausdorff distance `h(A → B) = sup_{p ∈ A} d(p, B)` is a supremum over
//! every point of the surface `A`. Every sample used here is a point of `A` (a referenced
//! vertex, an edge midpoint, a uniformly random point, or a refinement point inside a
//! triangle), and `d(p, B)` is measured against the whole of `B`, so each measured value
//! is one of the terms of the supremum: `max_i d(p_i, B) ≤ h(A → B)`, up to floating-point
//! rounding (a few ulps of the coordinates; tests allow `1e-9`). More samples or refinement
//! can only raise the value towards the true distance, never past it.
//!
//! # The sample set
//!
//! For each mesh: every **referenced vertex** (maxima of the distance to a surface are
//! often at vertices: corners that were cut or pushed by a simplification; unreferenced
//! vertex records are not on the surface and are ignored), every **edge midpoint** (one
//! per distinct undirected edge), and `samples_per_mesh` **uniform random points**
//! ([`sphaera_query::sampling::random`], reproducible from the seed; the second mesh's
//! seed is offset by a fixed constant, 2⁶⁴ over the golden ratio): a [`SurfaceSamples`]
//! with the default [`SampleOptions`] but for the random points and the seed. Then a
//! **local refinement** around the best few samples: each triangle that holds one of them
//! is sampled on a barycentric grid, and a pattern search walks uphill from the best grid
//! point with shrinking steps (see [`ReferenceOptions::refine_top`]).
//!
//! # Determinism
//!
//! Distances are computed in parallel (by [`sphaera_query::measure::distances`] with
//! `sphaera-mesh`'s `parallel` feature, and by rayon for the refinement) but collected in
//! order, and every maximum breaks ties by the lowest sample index, so the result (value
//! and location) is the same on every run and for any number of threads.
//!
//! # Examples
//!
//! ```
//! use sphaera_mesh::{DVec3, TriMesh, shapes};
//! use sphaera_tests::hausdorff::reference_hausdorff;
//!
//! let small = shapes::cube(1.0, 2)?;
//! let (positions, triangles) = small.clone().into_parts();
//! let big = TriMesh::new(positions.iter().map(|&p| 1.1 * p).collect(), triangles)?;
//! let h = reference_hausdorff(&small, &big, 2_000, 1);
//! // Every point of the small cube is 0.05 from the big one; the big cube's corners are
//! // 0.05·√3 from the small one.
//! assert!((h.a_to_b - 0.05).abs() < 1e-12);
//! assert!((h.b_to_a - 0.05 * 3f64.sqrt()).abs() < 1e-12);
//! assert_eq!(h.symmetric(), h.b_to_a);
//! # Ok::<(), sphaera_query::QueryError>(())
//! ```

use parry3d_f64::{
    query::PointQuery,
    shape::{TriMesh as ParryTriMesh, TriMeshFlags},
};
use rayon::prelude::*;
use sphaera_mesh::{
    DVec3, TriMesh,
    geometry::{Triangle, closest_point_on_triangle},
};
use sphaera_query::QueryError;
use sphaera_query::measure::{self, DirectedDistance, SampleOptions, SampleOrigin, SurfaceSamples};

use crate::pattern_search::{Boundary, PatternSearch, SIX_DIRECTIONS, SearchBudget};

/// Triangles whose area is at most this times their squared longest edge are kept out of
/// parry's mesh and measured with our own closest-point routine instead.
pub const DEGENERATE_RELATIVE_TOLERANCE: f64 = 1e-12;

/// A measured Hausdorff distance between meshes `A` and `B`: both one-sided maxima, where
/// they were reached, and how many points were measured.
///
/// Each one-sided value is a **lower bound** of the true directed Hausdorff distance (see
/// the [module documentation](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceHausdorff {
    /// The largest measured distance from a point of `A` to the surface `B`.
    pub a_to_b: f64,
    /// The largest measured distance from a point of `B` to the surface `A`.
    pub b_to_a: f64,
    /// The point of `A` where `a_to_b` was reached.
    pub a_to_b_at: DVec3,
    /// The point of `B` where `b_to_a` was reached.
    pub b_to_a_at: DVec3,
    /// How many points of `A` were measured (vertices, edge midpoints, random points and
    /// refinement points).
    pub samples_a: usize,
    /// How many points of `B` were measured.
    pub samples_b: usize,
}

impl ReferenceHausdorff {
    /// The symmetric distance `max(a_to_b, b_to_a)`, a lower bound of the true symmetric
    /// Hausdorff distance.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::DVec3;
    /// use sphaera_tests::hausdorff::ReferenceHausdorff;
    ///
    /// let h = ReferenceHausdorff {
    ///     a_to_b: 0.5,
    ///     b_to_a: 0.25,
    ///     a_to_b_at: DVec3::ZERO,
    ///     b_to_a_at: DVec3::X,
    ///     samples_a: 10,
    ///     samples_b: 10,
    /// };
    /// assert_eq!(h.symmetric(), 0.5);
    /// ```
    pub fn symmetric(&self) -> f64 {
        self.a_to_b.max(self.b_to_a)
    }
}

/// Options of [`reference_hausdorff_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceOptions {
    /// Uniform random points per mesh, on top of the vertices and edge midpoints.
    pub samples_per_mesh: usize,
    /// Seed of the random points (the second mesh uses a fixed offset of it).
    pub seed: u64,
    /// How many of the best samples (per direction) get a local refinement; 0 disables it.
    /// Each triangle holding one of them (all triangles around a vertex, both sides of an
    /// edge) is sampled on a barycentric grid of [`Self::refine_grid`] steps per side,
    /// then a pattern search climbs from the best grid point, halving its step down to
    /// `1e-7` of the triangle.
    pub refine_top: usize,
    /// Grid steps per triangle side for the refinement (at least 1).
    pub refine_grid: usize,
}

impl Default for ReferenceOptions {
    /// 10,000 random points per mesh, seed 0, refinement of the best 8 samples on a grid
    /// of 8 steps.
    fn default() -> Self {
        Self {
            samples_per_mesh: 10_000,
            seed: 0,
            refine_top: 8,
            refine_grid: 8,
        }
    }
}

/// The unsigned distance from points to the surface of one mesh, through parry3d-f64.
///
/// parry's [`ParryTriMesh`] is built with [`TriMeshFlags::empty()`]: no topology is needed
/// for point projection, so open, non-manifold and multi-component meshes are accepted
/// as they are (merging duplicate vertices would not change any distance).
/// Triangles that are degenerate (area at most [`DEGENERATE_RELATIVE_TOLERANCE`] times
/// the squared longest edge, i.e. needles, collinear or point triangles) are kept out of
/// parry's mesh, whose face projection is ill-conditioned for them; they are still part of
/// the surface, so their distance is taken with
/// [`sphaera_mesh::geometry::closest_point_on_triangle`] (exact for such triangles) and
/// the minimum of both is returned. Dropping them would make the target smaller and the
/// measured distance possibly *larger* than the true one, breaking the lower-bound
/// guarantee.
pub struct DistanceToMesh {
    parry: Option<ParryTriMesh>,
    degenerate: Vec<Triangle>,
}

impl std::fmt::Debug for DistanceToMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DistanceToMesh")
            .field(
                "parry_triangles",
                &self.parry.as_ref().map_or(0, |m| m.indices().len()),
            )
            .field("degenerate_triangles", &self.degenerate.len())
            .finish()
    }
}

impl DistanceToMesh {
    /// Prepares distance queries to the surface of `mesh` (builds parry's BVH).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_tests::hausdorff::DistanceToMesh;
    ///
    /// let cube = DistanceToMesh::new(&shapes::cube(2.0, 1)?);
    /// assert!((cube.distance(DVec3::new(3.0, 0.0, 0.0)) - 2.0).abs() < 1e-12);
    /// assert!((cube.distance(DVec3::ZERO) - 1.0).abs() < 1e-12); // unsigned, to the surface
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// If `mesh` has no triangles (there is no surface to measure against).
    pub fn new(mesh: &TriMesh) -> Self {
        assert!(
            mesh.triangle_count() > 0,
            "DistanceToMesh::new: the mesh has no triangles"
        );
        let mut kept = Vec::with_capacity(mesh.triangle_count());
        let mut degenerate = Vec::new();
        for (indices, triangle) in mesh.triangles().iter().zip(mesh.triangle_iter()) {
            if triangle.is_degenerate(DEGENERATE_RELATIVE_TOLERANCE) {
                degenerate.push(triangle);
            } else {
                kept.push(*indices);
            }
        }
        let parry = (!kept.is_empty()).then(|| {
            ParryTriMesh::with_flags(mesh.positions().to_vec(), kept, TriMeshFlags::empty())
                // parry only rejects an empty index buffer, excluded just above (invariant).
                .expect("invariant: parry accepts a non-empty triangle list without flags")
        });
        Self { parry, degenerate }
    }

    /// How many triangles were degenerate and are measured by our own routine instead of
    /// parry.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, TriMesh};
    /// use sphaera_tests::hausdorff::DistanceToMesh;
    ///
    /// let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, 2.0 * DVec3::X];
    /// let mesh = TriMesh::new(positions, vec![[0, 1, 2], [0, 1, 3]])?; // the second is flat
    /// let target = DistanceToMesh::new(&mesh);
    /// assert_eq!(target.degenerate_triangle_count(), 1);
    /// // The degenerate triangle is still part of the surface.
    /// assert!((target.distance(DVec3::new(2.0, 0.5, 0.0)) - 0.5).abs() < 1e-12);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    pub fn degenerate_triangle_count(&self) -> usize {
        self.degenerate.len()
    }

    /// The unsigned distance from `p` to the surface: parry's
    /// `distance_to_local_point(p, false)` (its absolute value: without `solid`, it is the
    /// distance to the triangles themselves), and the degenerate triangles.
    ///
    /// # Examples
    ///
    /// See [`DistanceToMesh::new`].
    ///
    /// # Panics
    ///
    /// Never.
    pub fn distance(&self, p: DVec3) -> f64 {
        let mut best = self.parry.as_ref().map_or(f64::INFINITY, |mesh| {
            mesh.distance_to_local_point(p, false).abs()
        });
        for triangle in &self.degenerate {
            best = best.min(
                closest_point_on_triangle(p, triangle)
                    .distance_squared
                    .sqrt(),
            );
        }
        best
    }
}

/// The sample set of `mesh`: every referenced vertex, the midpoint of every distinct edge,
/// then `n` random points drawn with `seed` ([`SurfaceSamples::new`]).
///
/// # Panics
///
/// If `n > 0` and random sampling fails: the mesh has no triangle of positive area, or `n`
/// exceeds [`sphaera_query::sampling::MAX_SAMPLES`].
fn sample_set(mesh: &TriMesh, n: usize, seed: u64) -> SurfaceSamples {
    let options = SampleOptions::default()
        .with_random_points(n)
        .with_seed(seed);
    let samples = SurfaceSamples::new(mesh, &options)
        .unwrap_or_else(|e| panic!("cannot sample {n} random points on the mesh: {e}"));
    if n > 0 && samples.random_point_count() == 0 {
        // The library skips the random points of a surface without area; this helper has
        // always refused it.
        let e = if mesh.is_empty() {
            QueryError::EmptyMesh
        } else {
            QueryError::ZeroSurfaceArea {
                triangle_count: mesh.triangle_count(),
            }
        };
        panic!("cannot sample {n} random points on the mesh: {e}");
    }
    samples
}

/// The points of `mesh` that [`reference_hausdorff`] measures before refinement: every
/// referenced vertex, the midpoint of every distinct edge, and `n` uniform random points
/// from [`sphaera_query::sampling::random`] with `seed`, in that order
/// ([`SurfaceSamples`]).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_tests::hausdorff::surface_points;
///
/// let cube = shapes::cube(1.0, 1)?; // 8 vertices, 18 edges (12 sides, 6 diagonals)
/// assert_eq!(surface_points(&cube, 100, 3).len(), 8 + 18 + 100);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Panics
///
/// If `n > 0` and random sampling fails: the mesh has no triangle of positive area, or `n`
/// exceeds [`sphaera_query::sampling::MAX_SAMPLES`].
pub fn surface_points(mesh: &TriMesh, n: usize, seed: u64) -> Vec<DVec3> {
    sample_set(mesh, n, seed).into_points()
}

/// The largest distance from `points` to `target`, and the first point (lowest index)
/// reaching it; `None` for no points ([`DirectedDistance::measure`] with the parry
/// oracle).
///
/// Parallel over the points (with `sphaera-mesh`'s `parallel` feature); deterministic.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_tests::hausdorff::{DistanceToMesh, directed_max};
///
/// let target = DistanceToMesh::new(&shapes::cube(2.0, 1)?);
/// let points = [DVec3::ZERO, DVec3::new(0.0, 0.0, 4.0), DVec3::new(0.0, -4.0, 0.0)];
/// let (d, at) = directed_max(&points, &target).unwrap();
/// assert!((d - 3.0).abs() < 1e-12);
/// assert_eq!(at, points[1]); // ties go to the lowest index
/// assert!(directed_max(&[], &target).is_none());
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Panics
///
/// Never.
pub fn directed_max(points: &[DVec3], target: &DistanceToMesh) -> Option<(f64, DVec3)> {
    let directed = DirectedDistance::measure(points, |p| target.distance(p));
    directed.farthest.map(|f| (directed.distance, f.point))
}

/// The sampled Hausdorff distance between the surfaces of `a` and `b`, with
/// `samples_per_mesh` random points per mesh on top of the vertices and edge midpoints,
/// and the default refinement ([`ReferenceOptions::default`]).
///
/// Every returned one-sided value is a lower bound of the true directed Hausdorff distance
/// (see the [module documentation](self)).
///
/// # Examples
///
/// See the [module documentation](self).
///
/// # Panics
///
/// If a mesh has no triangles, or (with `samples_per_mesh > 0`) no triangle of positive
/// area.
///
/// # Performance
///
/// One parry projection (`O(log T)` expected) per sample, parallel over the samples. On
/// the bunny pair (`stanford-bunny.obj`, 69,451 triangles, vs `stanford-bunny-qem15.obj`,
/// 10,418) with 50,000 random points per mesh: 192,120 + 73,248 measured points in about
/// 0.24 s wall at `opt-level = 1` (parry at 2) on the shared 2-core machine.
pub fn reference_hausdorff(
    a: &TriMesh,
    b: &TriMesh,
    samples_per_mesh: usize,
    seed: u64,
) -> ReferenceHausdorff {
    reference_hausdorff_with(
        a,
        b,
        &ReferenceOptions {
            samples_per_mesh,
            seed,
            ..ReferenceOptions::default()
        },
    )
}

/// [`reference_hausdorff`] with every option.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_tests::hausdorff::{ReferenceOptions, reference_hausdorff_with};
///
/// let inner = shapes::sphere(1.0, 24)?;
/// let outer = shapes::sphere(1.25, 24)?;
/// let plain = ReferenceOptions { samples_per_mesh: 500, refine_top: 0, ..Default::default() };
/// let refined = ReferenceOptions { refine_top: 4, ..plain };
/// let coarse = reference_hausdorff_with(&inner, &outer, &plain);
/// let fine = reference_hausdorff_with(&inner, &outer, &refined);
/// assert!(fine.a_to_b >= coarse.a_to_b && fine.b_to_a >= coarse.b_to_a);
/// assert!((fine.symmetric() - 0.25).abs() < 0.02);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
///
/// # Panics
///
/// As [`reference_hausdorff`].
pub fn reference_hausdorff_with(
    a: &TriMesh,
    b: &TriMesh,
    options: &ReferenceOptions,
) -> ReferenceHausdorff {
    let target_a = DistanceToMesh::new(a);
    let target_b = DistanceToMesh::new(b);
    let seed_b = options
        .seed
        .wrapping_add(measure::DEFAULT_SECOND_SEED_OFFSET);
    let (a_to_b, a_to_b_at, samples_a) = directed(a, &target_b, options, options.seed);
    let (b_to_a, b_to_a_at, samples_b) = directed(b, &target_a, options, seed_b);
    ReferenceHausdorff {
        a_to_b,
        b_to_a,
        a_to_b_at,
        b_to_a_at,
        samples_a,
        samples_b,
    }
}

/// One direction: sample `source`, measure against `target`, refine around the best.
fn directed(
    source: &TriMesh,
    target: &DistanceToMesh,
    options: &ReferenceOptions,
    seed: u64,
) -> (f64, DVec3, usize) {
    let samples = sample_set(source, options.samples_per_mesh, seed);
    let distances = measure::distances(samples.points(), |p| target.distance(p));
    let best = DirectedDistance::from_distances(samples.points(), &distances);
    let Some(farthest) = best.farthest else {
        return (0.0, DVec3::ZERO, 0);
    };
    let (mut value, mut at) = (best.distance, farthest.point);
    let mut evaluated = best.measured;
    if options.refine_top == 0 {
        return (value, at, evaluated);
    }
    // The best samples: by decreasing distance, then increasing index.
    let mut order: Vec<usize> = (0..distances.len()).collect();
    order.sort_unstable_by(|&i, &j| distances[j].total_cmp(&distances[i]).then(i.cmp(&j)));
    order.truncate(options.refine_top);
    let mut candidates: Vec<usize> = Vec::new();
    for &i in &order {
        match samples.origins()[i] {
            SampleOrigin::Random { triangle } => candidates.push(triangle),
            SampleOrigin::Vertex(v) => candidates.extend(
                source
                    .triangles()
                    .iter()
                    .enumerate()
                    .filter(|(_, tri)| tri.contains(&v))
                    .map(|(t, _)| t),
            ),
            SampleOrigin::EdgeMidpoint(u, w) => candidates.extend(
                source
                    .triangles()
                    .iter()
                    .enumerate()
                    .filter(|(_, tri)| tri.contains(&u) && tri.contains(&w))
                    .map(|(t, _)| t),
            ),
        }
    }
    candidates.sort_unstable();
    candidates.dedup();
    let grid = options.refine_grid.max(1);
    let refined: Vec<(f64, DVec3, usize)> = candidates
        .par_iter()
        .filter_map(|&t| source.triangle(t))
        .map(|triangle| refine_triangle(&triangle, target, grid))
        .collect();
    for (d, p, count) in refined {
        evaluated += count;
        if d > value {
            value = d;
            at = p;
        }
    }
    (value, at, evaluated)
}

/// The largest distance to `target` found on `triangle`: the best point of a barycentric
/// grid of `grid` steps per side, then a pattern search with halving steps
/// ([`crate::pattern_search`]: six directions, poll points outside the triangle skipped,
/// down to a step of `1e-7`, at most about 2,000 evaluations). Returns the distance, the
/// point and the number of points measured.
fn refine_triangle(
    triangle: &Triangle,
    target: &DistanceToMesh,
    grid: usize,
) -> (f64, DVec3, usize) {
    const MAX_EVALUATIONS: usize = 2_000;
    // This refinement has always measured the corner (0, 0) once before its grid, which
    // measures it again (a repeat cannot win: a poll point must be strictly farther). That
    // measurement is still counted, in the budget and in the reported sample counts, so
    // the published counts stay what they were.
    const REPEATED_CORNER: usize = 1;
    let search = PatternSearch {
        grid: u32::try_from(grid).unwrap_or(u32::MAX),
        directions: &SIX_DIRECTIONS,
        min_step: 1e-7,
        budget: SearchBudget::Evaluations(MAX_EVALUATIONS - REPEATED_CORNER),
        boundary: Boundary::Skip,
    };
    let best = search.maximise(|u, v| target.distance(triangle.point_at(u, v)));
    (
        best.value,
        triangle.point_at(best.u, best.v),
        best.evaluations + REPEATED_CORNER,
    )
}
