//! The entry points [`simplify`] and [`Hierarchy::build`], their [`SimplifyOptions`], and
//! the result, [`Simplified`].

use sphaera_mesh::topology::HalfEdgeMesh;
use sphaera_mesh::{Length, TriMesh};

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

impl Placement {
    /// The name users type and reports show (`"subset"`, …), as
    /// [`Display`](std::fmt::Display) writes it and [`FromStr`](std::str::FromStr) reads it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Subset => "subset",
            Self::Optimal => "optimal",
        }
    }
}

impl std::fmt::Display for Placement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Placement {
    type Err = sphaera_mesh::ParseNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "subset" => Ok(Self::Subset),
            "optimal" => Ok(Self::Optimal),
            _ => Err(sphaera_mesh::ParseNameError::new(
                "placement",
                s,
                "subset or optimal",
            )),
        }
    }
}

/// In which order collapses are applied.
///
/// Both orders apply only collapses whose radius is certified on the mesh as it is when
/// they are applied; they differ in how eagerly the candidates a collapse changed are
/// re-evaluated, which trades time for how closely the order follows the smallest radius.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{Order, SimplifyOptions, simplify};
///
/// let sphere = shapes::sphere(1.0, 24)?;
/// let options = SimplifyOptions::default().with_target_ratio(0.2);
/// let strict = simplify(&sphere, &options.clone().with_order(Order::Strict))?;
/// let batched = simplify(&sphere, &options.with_order(Order::Batched))?;
/// assert_eq!(strict.mesh.triangle_count(), batched.mesh.triangle_count());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Order {
    /// [`Order::Strict`] for meshes under [`Order::STRICT_BELOW`] vertices, where it costs
    /// little, [`Order::Batched`] above.
    #[default]
    Auto,
    /// The greedy order: after every collapse, every vertex it changed is re-evaluated, so
    /// the next collapse is always the one with the smallest radius. More
    /// re-evaluations per collapse than [`Order::Batched`], one after the other.
    Strict,
    /// Batched re-evaluation: collapses are applied while the cheapest candidate is up to
    /// date; a stale one at the front is re-evaluated alone, and the changed vertices near
    /// the front are re-evaluated in batches of a few hundred, on every core with the
    /// `parallel` feature (those whose queued radius is far behind the front wait until
    /// they reach it). Fewer re-evaluations per collapse than [`Order::Strict`]; the order
    /// drifts a little from the greedy one (a changed vertex can become cheaper). The times
    /// and bounds of both orders are in the section *Issue 20: batched re-evaluation on
    /// every core (2026-11-27)* of `docs/benchmarks.md` in the repository.
    Batched,
}

impl Order {
    /// The name users type and reports show (`"auto"`, …), as
    /// [`Display`](std::fmt::Display) writes it and [`FromStr`](std::str::FromStr) reads it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Strict => "strict",
            Self::Batched => "batched",
        }
    }
}

impl std::fmt::Display for Order {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Order {
    type Err = sphaera_mesh::ParseNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "auto" => Ok(Self::Auto),
            "strict" => Ok(Self::Strict),
            "batched" => Ok(Self::Batched),
            _ => Err(sphaera_mesh::ParseNameError::new(
                "collapse order",
                s,
                "auto, strict or batched",
            )),
        }
    }
}

impl Order {
    /// [`Order::Auto`] is [`Order::Strict`] below this many vertices.
    ///
    /// On meshes with many locked (boundary or non-manifold) vertices, the last forced
    /// collapses set the bound, and there the greedy order is worth its cost: the meshes of
    /// `shared/data` whose bound is more than twice the measured distance all have fewer
    /// vertices than this, and the batched order is looser on most of them (the ratios are
    /// in the section *Issue 20: batched re-evaluation on every core (2026-11-27)*, the
    /// paragraph on `KNOWN_LOOSE`, of `docs/benchmarks.md` in the repository).
    pub const STRICT_BELOW: usize = 32_768;
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
    /// Boundary vertices, when [`SimplifyOptions::lock_boundary`] is on (the default); 0
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

/// The result of [`simplify`].
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

/// Options of [`simplify`] and [`Hierarchy::build`].
///
/// The simplification stops at whichever comes first: the triangle target
/// ([`SimplifyOptions::target_triangles`], [`SimplifyOptions::target_ratio`]), the error
/// bound ([`SimplifyOptions::max_error`]), or no legal collapse left. With no target and
/// no bound it simplifies as far as it can.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{Length, shapes};
/// use sphaera_simplify::{SimplifyOptions, simplify};
///
/// let sphere = shapes::sphere(1.0, 16)?;
/// let options = SimplifyOptions::default()
///     .with_target_ratio(0.25)
///     .with_max_error(Length::RelativeToDiagonal(0.5));
/// let out = simplify(&sphere, &options)?;
/// assert!(out.mesh.triangle_count() <= sphere.triangle_count() / 4 + 1);
/// assert!(out.error_bound > 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SimplifyOptions {
    /// Stop at this many triangles (or one more: an interior collapse removes two).
    pub target_triangles: Option<usize>,
    /// Stop at `ceil(ratio × input triangles)` triangles; in `(0, 1]` (checked when run).
    pub target_ratio: Option<f64>,
    /// Never let the error bound exceed this (finite and non-negative, checked when run).
    pub max_error: Option<Length>,
    /// Keep every boundary vertex (`true`, the default), or let boundary vertices
    /// collapse along boundary edges (`false`). See [`SimplifyOptions::with_lock_boundary`].
    pub lock_boundary: bool,
    /// Where kept vertices go ([`Placement::Subset`] by default).
    pub placement: Placement,
    /// Per-vertex tolerance weights, one per input vertex (see
    /// [`SimplifyOptions::with_weights`]); `None` weighs every vertex 1.
    pub weights: Option<Vec<f64>>,
    /// In which order collapses are applied ([`Order::Auto`] by default).
    pub order: Order,
}

impl Default for SimplifyOptions {
    /// No target (as far as possible), no error bound, boundary locked,
    /// [`Placement::Subset`], no weights, [`Order::Auto`].
    fn default() -> Self {
        Self {
            target_triangles: None,
            target_ratio: None,
            max_error: None,
            lock_boundary: true,
            placement: Placement::Subset,
            weights: None,
            order: Order::Auto,
        }
    }
}

impl SimplifyOptions {
    /// With a target of `n` triangles.
    #[must_use]
    pub fn with_target_triangles(mut self, n: usize) -> Self {
        self.target_triangles = Some(n);
        self
    }

    /// With a target of `ceil(ratio × input triangles)` triangles.
    #[must_use]
    pub fn with_target_ratio(mut self, ratio: f64) -> Self {
        self.target_ratio = Some(ratio);
        self
    }

    /// With an error bound the simplification never exceeds.
    #[must_use]
    pub fn with_max_error(mut self, bound: Length) -> Self {
        self.max_error = Some(bound);
        self
    }

    /// With every boundary vertex kept (`true`, the default), or boundary vertices
    /// collapsing along boundary edges (`false`).
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
    /// use sphaera_simplify::{SimplifyOptions, simplify};
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
    /// let locked = simplify(&grid, &SimplifyOptions::default())?;
    /// let free = simplify(&grid, &SimplifyOptions::default().with_lock_boundary(false))?;
    /// assert_eq!(locked.locked.boundary, 16);
    /// assert!(free.mesh.triangle_count() < locked.mesh.triangle_count());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn with_lock_boundary(mut self, lock: bool) -> Self {
        self.lock_boundary = lock;
        self
    }

    /// With the given vertex placement.
    #[must_use]
    pub fn with_placement(mut self, placement: Placement) -> Self {
        self.placement = placement;
        self
    }

    /// With the given collapse order (see [`Order`]).
    #[must_use]
    pub fn with_order(mut self, order: Order) -> Self {
        self.order = order;
        self
    }

    /// With per-vertex tolerance weights, one per input vertex: a collapse is ranked by
    /// its radius divided by the smallest weight over the vertices it changes (the
    /// removed vertex, its parent and the removed vertex's neighbours), and with
    /// [`SimplifyOptions::max_error`] it is only allowed while its radius stays below that
    /// weight times the bound. So `f < 1` keeps the error near a vertex `f` times smaller
    /// (regions with small weights are simplified last), `f > 1` allows more, and `f = 0`
    /// forbids every collapse that would change the surface near the vertex: that region
    /// stays exactly as it is.
    ///
    /// Checked when run: one finite, non-negative weight per input vertex, not all zero.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{SimplifyOptions, simplify};
    ///
    /// let sphere = shapes::sphere(1.0, 16)?;
    /// // Freeze the northern hemisphere.
    /// let weights: Vec<f64> = sphere.positions().iter().map(|p| if p.z > 0.0 { 0.0 } else { 1.0 }).collect();
    /// let options = SimplifyOptions::default().with_weights(weights).with_target_ratio(0.1);
    /// let out = simplify(&sphere, &options)?;
    /// for (i, &o) in out.original_vertex.iter().enumerate() {
    ///     if sphere.positions()[o as usize].z > 0.0 {
    ///         assert_eq!(out.vertex_radii[i], 0.0);
    ///     }
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn with_weights(mut self, weights: Vec<f64>) -> Self {
        self.weights = Some(weights);
        self
    }
}

/// How far a running simplification is, passed to the progress callback of
/// [`simplify_with_progress`] and [`Hierarchy::build_with_progress`].
///
/// # Examples
///
/// ```
/// use std::sync::Mutex;
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{SimplifyOptions, SimplifyProgress, simplify_with_progress};
///
/// let sphere = shapes::sphere(1.0, 16)?;
/// let fractions = Mutex::new(Vec::new());
/// let report = |p: &SimplifyProgress| fractions.lock().unwrap().push(p.fraction());
/// let options = SimplifyOptions::default().with_target_ratio(0.5);
/// simplify_with_progress(&sphere, &options, &report)?;
/// let fractions = fractions.into_inner().unwrap();
/// assert!(fractions.windows(2).all(|w| w[0] <= w[1]));
/// assert!(fractions.iter().all(|f| (0.0..=1.0).contains(f)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct SimplifyProgress {
    /// Triangles removed so far.
    pub removed: usize,
    /// Triangles to remove to reach the triangle target (the whole mesh minus the target;
    /// the run may stop earlier at the error bound or when no collapse is legal).
    pub to_remove: usize,
}

impl SimplifyProgress {
    /// `removed / to_remove`, in `[0, 1]` (1 when there is nothing to remove).
    pub fn fraction(&self) -> f64 {
        if self.to_remove == 0 {
            1.0
        } else {
            (self.removed as f64 / self.to_remove as f64).min(1.0)
        }
    }
}

/// Simplifies `mesh` as `options` say.
///
/// A target at or above the input's triangle count returns the input unchanged, with all
/// radii and the bound 0 (and no lock report: nothing was attempted). Triangles with a
/// repeated vertex index (segments or points) are dropped from the output; the guarantee
/// is with respect to the other triangles.
///
/// # Errors
///
/// - [`SimplifyError::EmptyMesh`] if the input has no triangles;
/// - [`SimplifyError::InvalidParameter`] if the ratio is not in `(0, 1]` or the error
///   bound is NaN, infinite or negative;
/// - [`SimplifyError::LengthMismatch`] or [`SimplifyError::InvalidVertexValue`] for
///   weights that are not one finite, non-negative value per vertex, and
///   [`SimplifyError::AllWeightsZero`].
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// `O(T log T)` for `T` triangles (valence-bounded local work per collapse); see the
/// crate documentation for measured figures.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{SimplifyError, SimplifyOptions, simplify};
///
/// let cube = shapes::cube(1.0, 4)?;
/// let err = simplify(&cube, &SimplifyOptions::default().with_target_ratio(f64::NAN)).unwrap_err();
/// assert!(matches!(err, SimplifyError::InvalidParameter { name: "target_ratio", .. }));
/// let same = simplify(&cube, &SimplifyOptions::default().with_target_triangles(1_000_000))?;
/// assert_eq!(same.mesh, cube);
/// assert_eq!(same.error_bound, 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn simplify(mesh: &TriMesh, options: &SimplifyOptions) -> Result<Simplified, SimplifyError> {
    simplify_with_progress(mesh, options, &|_| {})
}

/// [`simplify`], calling `progress` now and then (about every 1/256 of the work, and at
/// the end), e.g. to drive a progress bar. It runs on the calling thread and should be
/// cheap.
///
/// # Errors
///
/// As [`simplify`].
///
/// # Examples
///
/// ```
/// use std::sync::atomic::{AtomicUsize, Ordering};
/// use sphaera_mesh::shapes;
/// use sphaera_simplify::{SimplifyOptions, SimplifyProgress, simplify_with_progress};
///
/// let sphere = shapes::sphere(1.0, 16)?;
/// let last = AtomicUsize::new(0);
/// let report = |p: &SimplifyProgress| last.store(p.removed, Ordering::Relaxed);
/// let options = SimplifyOptions::default().with_target_ratio(0.5);
/// let out = simplify_with_progress(&sphere, &options, &report)?;
/// assert_eq!(last.load(Ordering::Relaxed), sphere.triangle_count() - out.mesh.triangle_count());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn simplify_with_progress(
    mesh: &TriMesh,
    options: &SimplifyOptions,
    progress: &(dyn Fn(&SimplifyProgress) + Sync),
) -> Result<Simplified, SimplifyError> {
    let stop = stop(mesh, options)?;
    if stop.triangles >= mesh.triangle_count() {
        let n = mesh.vertex_count();
        return Ok(Simplified {
            mesh: mesh.clone(),
            vertex_radii: vec![0.0; n],
            error_bound: 0.0,
            original_vertex: (0..n as u32).collect(),
            collapses: 0,
            locked: LockReport::default(),
        });
    }
    let outcome = run(
        HalfEdgeMesh::from_trimesh(mesh),
        options,
        stop,
        progress,
        None,
    );
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

impl Hierarchy {
    /// Simplifies `mesh` as `options` say and records it as a progressive hierarchy, from
    /// the input (the finest mesh) to where the simplification stopped (the base mesh,
    /// equal to what [`simplify`] returns). For a distance hierarchy, leave the target
    /// unset so the base mesh is as coarse as possible.
    ///
    /// # Errors
    ///
    /// As [`simplify`].
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// The run of [`simplify`] plus the recording (a few lists per collapse); see
    /// [`Hierarchy::memory`] for the size.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{Hierarchy, SimplifyOptions, simplify};
    ///
    /// let cube = shapes::cube(1.0, 6)?;
    /// let options = SimplifyOptions::default().with_target_ratio(0.2);
    /// let hierarchy = Hierarchy::build(&cube, &options)?;
    /// assert_eq!(hierarchy.base(), simplify(&cube, &options)?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn build(mesh: &TriMesh, options: &SimplifyOptions) -> Result<Self, SimplifyError> {
        Self::build_with_progress(mesh, options, &|_| {})
    }

    /// [`Hierarchy::build`], calling `progress` as [`simplify_with_progress`] does.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::atomic::{AtomicUsize, Ordering};
    /// use sphaera_mesh::shapes;
    /// use sphaera_simplify::{Hierarchy, SimplifyOptions, SimplifyProgress};
    ///
    /// let cube = shapes::cube(1.0, 6)?;
    /// let removed = AtomicUsize::new(0);
    /// let report = |p: &SimplifyProgress| removed.store(p.removed, Ordering::Relaxed);
    /// let hierarchy = Hierarchy::build_with_progress(&cube, &SimplifyOptions::default(), &report)?;
    /// assert_eq!(
    ///     removed.into_inner(),
    ///     cube.triangle_count() - hierarchy.base().mesh.triangle_count()
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`simplify`].
    pub fn build_with_progress(
        mesh: &TriMesh,
        options: &SimplifyOptions,
        progress: &(dyn Fn(&SimplifyProgress) + Sync),
    ) -> Result<Self, SimplifyError> {
        let stop = stop(mesh, options)?;
        let half_edges = HalfEdgeMesh::from_trimesh(mesh);
        let finest = half_edges.clone();
        let mut recorder = Recorder::new(&half_edges);
        let outcome = run(half_edges, options, stop, progress, Some(&mut recorder));
        Ok(Self::from_record(
            &finest,
            recorder,
            (mesh.vertex_count(), mesh.triangle_count()),
            outcome.locked,
            options.placement,
        ))
    }
}

/// Runs the engine on `half_edges` with the options' weights and placement.
fn run(
    half_edges: HalfEdgeMesh,
    options: &SimplifyOptions,
    stop: Stop,
    progress: &(dyn Fn(&SimplifyProgress) + Sync),
    recorder: Option<&mut Recorder>,
) -> engine::Outcome {
    let weights = options
        .weights
        .as_deref()
        .map(|w| Weights::for_mesh(&half_edges, w));
    let strict = match options.order {
        Order::Strict => true,
        Order::Batched => false,
        Order::Auto => half_edges.vertex_count() < Order::STRICT_BELOW,
    };
    engine::run(
        half_edges,
        stop,
        engine::Settings {
            weights: weights.as_ref(),
            optimal: options.placement == Placement::Optimal,
            strict,
        },
        progress,
        recorder,
    )
}

/// Validates the options into the engine's stopping rule.
fn stop(mesh: &TriMesh, options: &SimplifyOptions) -> Result<Stop, SimplifyError> {
    let input = mesh.triangle_count();
    if input == 0 {
        return Err(SimplifyError::EmptyMesh);
    }
    let mut target = options.target_triangles.unwrap_or(0);
    if let Some(ratio) = options.target_ratio {
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
    let max_radius = match options.max_error {
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
            bound.resolve(mesh.bounding_box_diagonal())
        }
    };
    if let Some(weights) = &options.weights {
        Weights::validate(mesh, weights)?;
    }
    Ok(Stop {
        triangles: target,
        max_radius,
        boundary: if options.lock_boundary {
            BoundaryPolicy::Lock
        } else {
            BoundaryPolicy::Collapse
        },
    })
}
