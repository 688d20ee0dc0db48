//! The shared, read-only part of the distance engine.

use sphaera_mesh::{DVec3, TriMesh};
use sphaera_query::closest::TriangleTree;
use sphaera_simplify::{Hierarchy, SimplifyError, SimplifyOptions};

mod warm_start;

use warm_start::WARM_START_DIVISOR;
pub(crate) use warm_start::{Contents, WarmStart};

use crate::{Session, SessionOptions, SweepError};

/// Closest-point queries on the mesh a [`Hierarchy`] was built from (Meshsweeper).
///
/// The sweeper holds only what is fixed: a reference to the hierarchy's tables, the base
/// mesh's triangles, the warm start, and a [`TriangleTree`] over the input triangles,
/// which answers a session's exact queries (see [`SessionOptions::exact_by_tree`]). It is
/// `Sync`; every thread opens its own [`Session`], which owns the changing state (the
/// refined mesh and the priority queue).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_sweep::{Sweeper, build_hierarchy};
///
/// let torus = shapes::torus(1.0, 0.25, 24)?;
/// let hierarchy = build_hierarchy(&torus)?;
/// let sweeper = Sweeper::new(&hierarchy)?;
/// let mut session = sweeper.session();
/// let answer = session.closest(DVec3::new(2.0, 0.0, 0.0))?;
/// assert!((answer.distance - 0.75).abs() < 0.01);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Sweeper<'h> {
    hierarchy: &'h Hierarchy,
    base: Vec<u32>,
    diagonal: f64,
    warm: WarmStart,
    /// The input triangles, for exact queries, and the hierarchy id of each of its
    /// triangles.
    finest: TriangleTree,
    finest_ids: Vec<u32>,
}

impl<'h> Sweeper<'h> {
    /// The sweeper of `hierarchy`.
    ///
    /// # Errors
    ///
    /// [`SweepError::EmptyMesh`] if the hierarchy has no triangle.
    ///
    /// # Performance
    ///
    /// As [`Sweeper::with_warm_start`] with half the finest mesh's triangles.
    pub fn new(hierarchy: &'h Hierarchy) -> Result<Self, SweepError> {
        let target = hierarchy.finest_triangle_count() / WARM_START_DIVISOR;
        Self::with_warm_start(hierarchy, target)
    }

    /// The sweeper of `hierarchy` whose sessions start (and reset to) a state refined to
    /// at least `triangles` live triangles (the vertex with the largest radius split
    /// first), instead of [`Sweeper::new`]'s half of the finest mesh. `0` starts from the
    /// base mesh, as the paper does; the finest mesh's count or more never splits and
    /// answers every cold query from a bounding-sphere tree over the input triangles.
    ///
    /// # Errors
    ///
    /// [`SweepError::EmptyMesh`] if the hierarchy has no triangle.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_sweep::{Sweeper, build_hierarchy};
    ///
    /// let torus = shapes::torus(1.0, 0.25, 24)?;
    /// let hierarchy = build_hierarchy(&torus)?;
    /// let p = DVec3::new(2.0, 0.0, 0.0);
    /// let cold = Sweeper::with_warm_start(&hierarchy, 0)?;
    /// let warm = Sweeper::with_warm_start(&hierarchy, usize::MAX)?;
    /// let (mut a, mut b) = (cold.session(), warm.session());
    /// assert_eq!(a.closest(p)?.distance, b.closest(p)?.distance);
    /// assert_eq!(b.stats().splits, 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Performance
    ///
    /// A split per warm-start vertex and a scan of the triangles (`O(T × depth)`), then
    /// an `O(n log n)` tree build over the `n` warm triangles; the sweeper keeps about
    /// 24 bytes per warm triangle, shared by its sessions. A cold query from a larger warm
    /// start makes fewer splits (each undoing its dependants), at the cost of a reset that
    /// re-applies everything the query undid (see `docs/benchmarks.md`).
    pub fn with_warm_start(hierarchy: &'h Hierarchy, triangles: usize) -> Result<Self, SweepError> {
        let base: Vec<u32> = hierarchy.refinement().live_triangles().collect();
        if base.is_empty() {
            return Err(SweepError::EmptyMesh);
        }
        let (min, max) = hierarchy.positions().iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let diagonal = (max - min).length();
        let diagonal = if diagonal.is_finite() { diagonal } else { 0.0 };
        let (finest, finest_ids) = finest_tree(hierarchy)?;
        Ok(Self {
            hierarchy,
            base,
            diagonal,
            warm: WarmStart::new(hierarchy, triangles, diagonal),
            finest,
            finest_ids,
        })
    }

    /// Live triangles of the state every session starts from and resets to (see
    /// [`Sweeper::with_warm_start`]).
    pub fn warm_start_triangles(&self) -> usize {
        self.warm.triangle_count()
    }

    /// Bytes of the sweeper's own tables (the base mesh, the warm start and the tree of
    /// input triangles; the hierarchy is not counted).
    pub fn memory_bytes(&self) -> usize {
        4 * self.base.len()
            + self.warm.bytes()
            + self.finest.memory_bytes()
            + 4 * self.finest_ids.len()
    }

    /// The tree of input triangles that answers exact queries, and the hierarchy triangle
    /// id of each of its triangles.
    pub(crate) fn finest(&self) -> (&TriangleTree, &[u32]) {
        (&self.finest, &self.finest_ids)
    }

    /// The warm start sessions begin from and reset to.
    pub(crate) fn warm_start(&self) -> &WarmStart {
        &self.warm
    }

    /// The hierarchy queried.
    pub fn hierarchy(&self) -> &'h Hierarchy {
        self.hierarchy
    }

    /// The bounding-box diagonal of the mesh's vertices.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The triangles of the base mesh (the coarsest state; sessions start from the warm
    /// start, see [`Sweeper::with_warm_start`]).
    pub fn base_triangles(&self) -> &[u32] {
        &self.base
    }

    /// A new query session with the default [`SessionOptions`].
    pub fn session(&self) -> Session<'_> {
        Session::new(self, SessionOptions::default())
    }

    /// A new query session with `options`.
    pub fn session_with(&self, options: &SessionOptions) -> Session<'_> {
        Session::new(self, *options)
    }
}

/// The tree over the input triangles of `hierarchy` (its finest state), and the
/// hierarchy id of each tree triangle.
fn finest_tree(hierarchy: &Hierarchy) -> Result<(TriangleTree, Vec<u32>), SweepError> {
    let finest = hierarchy.finest_refinement();
    let (ids, triangles): (Vec<u32>, Vec<[u32; 3]>) = finest
        .live_triangles()
        .filter_map(|t| finest.corners(t).map(|corners| (t, corners)))
        .unzip();
    // The hierarchy's positions are finite and its live triangles index them (the
    // simplifier's invariants), so the mesh is valid; an empty one is reported as such.
    let mesh = TriMesh::new(hierarchy.positions().to_vec(), triangles)
        .map_err(|e| SweepError::Tree(e.into()))?;
    let tree = TriangleTree::new(&mesh).map_err(|e| match e {
        sphaera_query::QueryError::EmptyMesh => SweepError::EmptyMesh,
        other => SweepError::Tree(other),
    })?;
    Ok((tree, ids))
}

/// The hierarchy a distance engine wants for `mesh`: simplified as far as possible, with
/// boundary vertices allowed to collapse, so the base mesh is small.
///
/// # Errors
///
/// As [`Hierarchy::build`] (an empty mesh, non-finite coordinates).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::shapes;
///
/// let sphere = shapes::sphere(1.0, 16)?;
/// let hierarchy = sphaera_sweep::build_hierarchy(&sphere)?;
/// assert!(hierarchy.base().mesh.triangle_count() < sphere.triangle_count() / 10);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn build_hierarchy(mesh: &TriMesh) -> Result<Hierarchy, SimplifyError> {
    Hierarchy::build(mesh, &SimplifyOptions::default().with_lock_boundary(false))
}
