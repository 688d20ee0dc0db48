//! The [`Simplifier`] builder and its result, [`Simplified`].

use sphaera_mesh::TriMesh;
use sphaera_mesh::topology::HalfEdgeMesh;

use crate::engine::{self, Stop};
use crate::record::Recorder;
use crate::weights::Weights;
use crate::{Hierarchy, SimplifyError};

use crate::spheres::BoundaryPolicy;

/// Where the kept vertex of a collapse goes.
///
/// # Examples
///
/// ```
/// use sphaera_simplify::Placement;
///
/// assert_eq!(Placement::default(), Placement::Subset);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Placement {
    /// Half-edge collapse: the kept vertex stays where it is, so every simplified vertex is
    /// an original vertex and per-vertex data stays valid at every level.
    #[default]
    Subset,
    /// Full-edge collapse: the kept vertex moves to the position minimising the sum of the
    /// two vertices' error quadrics (Garland–Heckbert; on the segment, or the better
    /// endpoint or midpoint, when the system is ill-conditioned), unless the half-edge
    /// collapse onto the kept vertex needs a smaller radius. Radii are as rigorous as with
    /// [`Placement::Subset`] (the full-edge collapse has its own tight and simple maps);
    /// output vertices are no longer input vertices, so
    /// [`Simplified::original_vertex`] names the input vertex that *stands for* each one.
    /// Deformation ([`Hierarchy::replay`](crate::Hierarchy::replay),
    /// [`Hierarchy::inflate`](crate::Hierarchy::inflate)) needs Subset placement.
    Optimal,
}

/// A maximum error bound: the simplification stops before any vertex's error radius would
/// exceed it.
///
/// # Examples
///
/// ```
/// use sphaera_simplify::MaxError;
///
/// assert_eq!(MaxError::Absolute(0.5).resolve(10.0), 0.5);
/// assert_eq!(MaxError::RelativeToDiagonal(0.01).resolve(10.0), 0.1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MaxError {
    /// In the mesh's length unit.
    Absolute(f64),
    /// As a fraction of the input's bounding-box diagonal.
    RelativeToDiagonal(f64),
}

impl MaxError {
    /// The bound in length units, for a mesh whose bounding-box diagonal is `diagonal`.
    pub fn resolve(self, diagonal: f64) -> f64 {
        match self {
            Self::Absolute(e) => e,
            Self::RelativeToDiagonal(f) => f * diagonal,
        }
    }

    /// The value as given (for validation messages).
    fn value(self) -> f64 {
        match self {
            Self::Absolute(x) | Self::RelativeToDiagonal(x) => x,
        }
    }
}

/// What the simplifier could not touch.
///
/// # Examples
///
/// ```
/// use sphaera_simplify::LockReport;
///
/// assert_eq!(LockReport::default().total(), 0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct LockReport {
    /// Boundary vertices, when [`Simplifier::lock_boundary`] is on (the default); 0
    /// otherwise.
    pub boundary: usize,
    /// Non-manifold vertices and their copies (never removed; neither are edges into them).
    pub non_manifold: usize,
}

impl LockReport {
    /// All locked vertices.
    pub fn total(&self) -> usize {
        self.boundary + self.non_manifold
    }
}

/// The result of [`Simplifier::build`].
///
/// The two-sided guarantee: every point of the input surface lies within the tolerance
/// volume of some output triangle (the triangle swept by the balls centred on its points
/// with the linearly interpolated radius of [`Simplified::vertex_radii`]), and every point
/// of an output triangle is within its interpolated radius of the input surface. So the
/// symmetric Hausdorff distance between input and output is at most
/// [`Simplified::error_bound`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Simplified {
    /// The simplified mesh (no unreferenced vertices).
    pub mesh: TriMesh,
    /// The error radius of each output vertex (0 for a vertex nothing was collapsed into).
    pub vertex_radii: Vec<f64>,
    /// The largest radius: a bound on the symmetric Hausdorff distance to the input.
    pub error_bound: f64,
    /// For each output vertex, the input vertex it is (Subset placement keeps positions).
    pub original_vertex: Vec<u32>,
    /// How many edge collapses were applied.
    pub collapses: usize,
    /// What could not be simplified.
    pub locked: LockReport,
}

/// Builder for a simplification.
///
/// Stops at whichever comes first: the triangle target ([`Simplifier::target_triangles`],
/// [`Simplifier::target_ratio`]), the error bound ([`Simplifier::max_error`]), or no legal
/// collapse left. With no target and no bound it simplifies as far as it can.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{MaxError, Simplifier};
///
/// let sphere = shapes::sphere(1.0, 16)?;
/// let out = Simplifier::new(&sphere)
///     .target_ratio(0.25)
///     .max_error(MaxError::RelativeToDiagonal(0.5))
///     .build()?;
/// assert!(out.mesh.triangle_count() <= sphere.triangle_count() / 4 + 1);
/// assert!(out.error_bound > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone)]
pub struct Simplifier<'a> {
    mesh: &'a TriMesh,
    target_triangles: Option<usize>,
    target_ratio: Option<f64>,
    max_error: Option<MaxError>,
    lock_boundary: bool,
    placement: Placement,
    progress: Option<&'a (dyn Fn(Progress) + Sync)>,
    weights: Option<&'a [f64]>,
}

/// How far a running simplification is, passed to the [`Simplifier::progress`] callback.
///
/// # Examples
///
/// ```
/// use sphaera_simplify::Progress;
///
/// let p = Progress { removed: 50, to_remove: 200 };
/// assert_eq!(p.fraction(), 0.25);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Progress {
    /// Triangles removed so far.
    pub removed: usize,
    /// Triangles to remove to reach the triangle target (the whole mesh minus the target;
    /// the run may stop earlier at the error bound or when no collapse is legal).
    pub to_remove: usize,
}

impl Progress {
    /// `removed / to_remove`, in `[0, 1]` (1 when there is nothing to remove).
    pub fn fraction(&self) -> f64 {
        if self.to_remove == 0 {
            1.0
        } else {
            (self.removed as f64 / self.to_remove as f64).min(1.0)
        }
    }
}

impl std::fmt::Debug for Simplifier<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simplifier")
            .field("triangles", &self.mesh.triangle_count())
            .field("target_triangles", &self.target_triangles)
            .field("target_ratio", &self.target_ratio)
            .field("max_error", &self.max_error)
            .field("lock_boundary", &self.lock_boundary)
            .field("placement", &self.placement)
            .field("progress", &self.progress.is_some())
            .field("weights", &self.weights.map(<[f64]>::len))
            .finish()
    }
}

impl<'a> Simplifier<'a> {
    /// A simplifier of `mesh` with no target (as far as possible), boundary locked and
    /// [`Placement::Subset`].
    pub fn new(mesh: &'a TriMesh) -> Self {
        Self {
            mesh,
            target_triangles: None,
            target_ratio: None,
            max_error: None,
            lock_boundary: true,
            placement: Placement::Subset,
            progress: None,
            weights: None,
        }
    }

    /// Stop at `n` triangles (or one more: an interior collapse removes two).
    #[must_use]
    pub fn target_triangles(mut self, n: usize) -> Self {
        self.target_triangles = Some(n);
        self
    }

    /// Stop at `ceil(ratio × input triangles)` triangles; `ratio` must be in `(0, 1]`
    /// (checked by [`Simplifier::build`]).
    #[must_use]
    pub fn target_ratio(mut self, ratio: f64) -> Self {
        self.target_ratio = Some(ratio);
        self
    }

    /// Never let the error bound exceed `bound` (must be finite and non-negative, checked
    /// by [`Simplifier::build`]).
    #[must_use]
    pub fn max_error(mut self, bound: MaxError) -> Self {
        self.max_error = Some(bound);
        self
    }

    /// Keep every boundary vertex (`true`, the default), or let boundary vertices collapse
    /// along boundary edges (`false`).
    ///
    /// Interior vertices collapse with a tight error map (see the crate documentation);
    /// boundary collapses use the simple map that sends `u` to `v`, whose radius
    /// `r_u + |u − v|` is rigorous but loose, so with `false` boundary vertices go late and
    /// the bound grows at least by the boundary edge lengths collapsed.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, TriMesh};
    /// use sphaera_simplify::Simplifier;
    ///
    /// // A flat 4 × 4 grid of squares.
    /// let mut p = Vec::new();
    /// for j in 0..5 { for i in 0..5 { p.push(DVec3::new(f64::from(i), f64::from(j), 0.0)); } }
    /// let mut t = Vec::new();
    /// for j in 0..4u32 { for i in 0..4u32 {
    ///     let a = 5 * j + i;
    ///     t.push([a, a + 1, a + 6]);
    ///     t.push([a, a + 6, a + 5]);
    /// } }
    /// let grid = TriMesh::new(p, t)?;
    /// let locked = Simplifier::new(&grid).build()?;
    /// let free = Simplifier::new(&grid).lock_boundary(false).build()?;
    /// assert_eq!(locked.locked.boundary, 16);
    /// assert!(free.mesh.triangle_count() < locked.mesh.triangle_count());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn lock_boundary(mut self, lock: bool) -> Self {
        self.lock_boundary = lock;
        self
    }

    /// Where kept vertices go ([`Placement::Subset`] by default).
    #[must_use]
    pub fn placement(mut self, placement: Placement) -> Self {
        self.placement = placement;
        self
    }

    /// Per-vertex tolerance weights, one per input vertex: a collapse is ranked by its
    /// radius divided by the smallest weight over the vertices it changes (the removed
    /// vertex, its parent and the removed vertex's neighbours), and with
    /// [`Simplifier::max_error`] it is only allowed while its radius stays below that
    /// weight times the bound. So `f < 1` keeps the error near a vertex `f` times smaller
    /// (regions with small weights are simplified last), `f > 1` allows more, and `f = 0`
    /// forbids every collapse that would change the surface near the vertex: that region
    /// stays exactly as it is.
    ///
    /// Checked by [`Simplifier::build`]: one finite, non-negative weight per input vertex,
    /// not all zero.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::Simplifier;
    ///
    /// let sphere = shapes::sphere(1.0, 16)?;
    /// // Freeze the northern hemisphere.
    /// let weights: Vec<f64> = sphere.positions().iter().map(|p| if p.z > 0.0 { 0.0 } else { 1.0 }).collect();
    /// let out = Simplifier::new(&sphere).weights(&weights).target_ratio(0.1).build()?;
    /// for (i, &o) in out.original_vertex.iter().enumerate() {
    ///     if sphere.positions()[o as usize].z > 0.0 {
    ///         assert_eq!(out.vertex_radii[i], 0.0);
    ///     }
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn weights(mut self, weights: &'a [f64]) -> Self {
        self.weights = Some(weights);
        self
    }

    /// Calls `callback` now and then (about every 1/256 of the work, and at the end) while
    /// [`Simplifier::build`] runs, e.g. to drive a progress bar. It runs on the calling
    /// thread and should be cheap.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::atomic::{AtomicUsize, Ordering};
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{Progress, Simplifier};
    ///
    /// let sphere = shapes::sphere(1.0, 16)?;
    /// let last = AtomicUsize::new(0);
    /// let report = |p: Progress| last.store(p.removed, Ordering::Relaxed);
    /// let out = Simplifier::new(&sphere).target_ratio(0.5).progress(&report).build()?;
    /// assert_eq!(last.load(Ordering::Relaxed), sphere.triangle_count() - out.mesh.triangle_count());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn progress(mut self, callback: &'a (dyn Fn(Progress) + Sync)) -> Self {
        self.progress = Some(callback);
        self
    }

    /// Runs the simplification.
    ///
    /// A target at or above the input's triangle count returns the input unchanged, with
    /// all radii and the bound 0 (and no lock report: nothing was attempted). Triangles
    /// with a repeated vertex index (segments or points) are dropped from the output; the
    /// guarantee is with respect to the other triangles.
    ///
    /// # Errors
    ///
    /// - [`SimplifyError::EmptyMesh`] if the input has no triangles;
    /// - [`SimplifyError::InvalidParameter`] if the ratio is not in `(0, 1]` or the error
    ///   bound is NaN, infinite or negative.
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// `O(T log T)` for `T` triangles (valence-bounded local work per collapse); not yet
    /// benchmarked.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{Simplifier, SimplifyError};
    ///
    /// let cube = shapes::cube(1.0, 4)?;
    /// let err = Simplifier::new(&cube).target_ratio(f64::NAN).build().unwrap_err();
    /// assert!(matches!(err, SimplifyError::InvalidParameter { name: "target_ratio", .. }));
    /// let same = Simplifier::new(&cube).target_triangles(1_000_000).build()?;
    /// assert_eq!(same.mesh, cube);
    /// assert_eq!(same.error_bound, 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn build(&self) -> Result<Simplified, SimplifyError> {
        let stop = self.stop()?;
        if stop.triangles >= self.mesh.triangle_count() {
            let n = self.mesh.vertex_count();
            return Ok(Simplified {
                mesh: self.mesh.clone(),
                vertex_radii: vec![0.0; n],
                error_bound: 0.0,
                original_vertex: (0..n as u32).collect(),
                collapses: 0,
                locked: LockReport::default(),
            });
        }
        let outcome = self.run(HalfEdgeMesh::from_trimesh(self.mesh), stop, None);
        let live = outcome.mesh.to_trimesh();
        let vertex_radii: Vec<f64> = live
            .vertex_map
            .iter()
            .map(|x| outcome.radii.get(x.0 as usize).copied().unwrap_or(0.0))
            .collect();
        let original_vertex = live
            .vertex_map
            .iter()
            .map(|&x| outcome.mesh.original_vertex(x))
            .collect();
        let error_bound = vertex_radii.iter().fold(0.0_f64, |m, &r| m.max(r));
        Ok(Simplified {
            mesh: live.mesh,
            vertex_radii,
            error_bound,
            original_vertex,
            collapses: outcome.collapses,
            locked: outcome.locked,
        })
    }

    /// Runs the simplification and records it as a progressive [`Hierarchy`], from the
    /// input (the finest mesh) to where the simplification stopped (the base mesh, equal
    /// to what [`Simplifier::build`] returns). For a distance hierarchy, leave the target
    /// unset so the base mesh is as coarse as possible.
    ///
    /// # Errors
    ///
    /// As [`Simplifier::build`].
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// The run of [`Simplifier::build`] plus the recording (a few lists per collapse); see
    /// [`Hierarchy::memory`] for the size.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::Simplifier;
    ///
    /// let cube = shapes::cube(1.0, 6)?;
    /// let simplifier = Simplifier::new(&cube).target_ratio(0.2);
    /// let hierarchy = simplifier.build_hierarchy()?;
    /// assert_eq!(hierarchy.base(), simplifier.build()?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn build_hierarchy(&self) -> Result<Hierarchy, SimplifyError> {
        let stop = self.stop()?;
        let half_edges = HalfEdgeMesh::from_trimesh(self.mesh);
        let finest = half_edges.clone();
        let mut recorder = Recorder::new(&half_edges);
        let outcome = self.run(half_edges, stop, Some(&mut recorder));
        Ok(Hierarchy::from_record(
            &finest,
            recorder,
            (self.mesh.vertex_count(), self.mesh.triangle_count()),
            outcome.locked,
            self.placement,
        ))
    }

    /// Runs the engine on `half_edges` with this builder's weights, placement and progress.
    fn run(
        &self,
        half_edges: HalfEdgeMesh,
        stop: Stop,
        recorder: Option<&mut Recorder>,
    ) -> engine::Outcome {
        let weights = self.weights.map(|w| Weights::for_mesh(&half_edges, w));
        engine::run(
            half_edges,
            stop,
            weights.as_ref(),
            self.placement == Placement::Optimal,
            self.progress,
            recorder,
        )
    }

    /// Validates the parameters into the engine's stopping rule.
    fn stop(&self) -> Result<Stop, SimplifyError> {
        let input = self.mesh.triangle_count();
        if input == 0 {
            return Err(SimplifyError::EmptyMesh);
        }
        let mut target = self.target_triangles.unwrap_or(0);
        if let Some(ratio) = self.target_ratio {
            if !(ratio > 0.0 && ratio <= 1.0) {
                return Err(SimplifyError::InvalidParameter {
                    name: "target_ratio",
                    value: ratio,
                    requirement: "in (0, 1]",
                });
            }
            // `ratio ≤ 1`, so the product is at most `input` and the cast is exact enough.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let by_ratio = (ratio * input as f64).ceil() as usize;
            target = target.max(by_ratio);
        }
        let max_radius = match self.max_error {
            None => f64::INFINITY,
            Some(bound) => {
                let value = bound.value();
                if !(value.is_finite() && value >= 0.0) {
                    return Err(SimplifyError::InvalidParameter {
                        name: "max_error",
                        value,
                        requirement: "finite and non-negative",
                    });
                }
                bound.resolve(self.mesh.bounding_box_diagonal())
            }
        };
        if let Some(weights) = self.weights {
            Weights::validate(self.mesh, weights)?;
        }
        Ok(Stop {
            triangles: target,
            max_radius,
            boundary: if self.lock_boundary {
                BoundaryPolicy::Lock
            } else {
                BoundaryPolicy::Collapse
            },
        })
    }
}
