//! The shared, read-only part of the distance engine.

use sphaera_mesh::{DVec3, TriMesh};
use sphaera_simplify::{Hierarchy, Simplifier, SimplifyError};

use crate::{Session, SessionOptions, SweepError};

/// Closest-point queries on the mesh a [`Hierarchy`] was built from (Meshsweeper).
///
/// The sweeper holds only what is fixed: a reference to the hierarchy's tables and the
/// base mesh's triangles. It is `Sync`; every thread opens its own [`Session`], which owns
/// the changing state (the refined mesh and the priority queue).
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
    /// One scan of the hierarchy's triangles to list the base mesh (`O(T × depth)`).
    pub fn new(hierarchy: &'h Hierarchy) -> Result<Self, SweepError> {
        let base: Vec<u32> = hierarchy.refinement().live_triangles().collect();
        if base.is_empty() {
            return Err(SweepError::EmptyMesh);
        }
        let (min, max) = hierarchy.positions().iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let diagonal = (max - min).length();
        Ok(Self {
            hierarchy,
            base,
            diagonal: if diagonal.is_finite() { diagonal } else { 0.0 },
        })
    }

    /// The hierarchy queried.
    pub fn hierarchy(&self) -> &'h Hierarchy {
        self.hierarchy
    }

    /// The bounding-box diagonal of the mesh's vertices.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The triangles of the base mesh (where every session starts and resets to).
    pub fn base_triangles(&self) -> &[u32] {
        &self.base
    }

    /// A new query session with the default [`SessionOptions`].
    pub fn session(&self) -> Session<'_> {
        Session::new(self, SessionOptions::default())
    }

    /// A new query session with `options`.
    pub fn session_with(&self, options: SessionOptions) -> Session<'_> {
        Session::new(self, options)
    }
}

/// The hierarchy a distance engine wants for `mesh`: simplified as far as possible, with
/// boundary vertices allowed to collapse, so the base mesh is small.
///
/// # Errors
///
/// As [`Simplifier::build_hierarchy`] (an empty mesh, non-finite coordinates).
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
    Simplifier::new(mesh).lock_boundary(false).build_hierarchy()
}
