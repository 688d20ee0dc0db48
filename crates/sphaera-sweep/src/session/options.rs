//! [`SessionOptions`]: when a [`Session`](crate::Session) resets, and which engine answers
//! exact queries.

/// When a [`Session`](crate::Session) goes back to the base mesh before a query.
///
/// A session only refines (paper section 4.2); it coarsens all at once, by a reset to the
/// sweeper's warm start (see
/// [`Sweeper::with_warm_start`](crate::Sweeper::with_warm_start); the base mesh without
/// one). A reset costs `O(changed)`; not resetting costs re-evaluating stale intervals. The
/// defaults reset when the refined mesh has grown by more than `max_triangles` live
/// triangles beyond the warm start, or when the query point jumped farther than
/// `jump_factor` times the previous distance (then almost every interval is stale, and the
/// warm start is cheaper to start from).
///
/// # Examples
///
/// ```
/// use sphaera_sweep::SessionOptions;
///
/// let options = SessionOptions::default().with_jump_factor(4.0);
/// assert_eq!(options.max_triangles, SessionOptions::default().max_triangles);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SessionOptions {
    /// Reset before a query when the refined mesh has grown by more than this many live
    /// triangles beyond the warm start.
    pub max_triangles: usize,
    /// Reset before a query when the query point moved more than this many times the
    /// previous answer's distance (`f64::INFINITY`: never for motion).
    pub jump_factor: f64,
    /// Answer [`Session::closest`](crate::Session::closest) from the sweeper's tree of
    /// input triangles through a [`TreeCursor`](sphaera_query::closest::TreeCursor)
    /// (`true`, the default: the fastest exact engine, coherent from one query to the
    /// next) while the mesh has its own shape (rigid poses included), or
    /// by refining the hierarchy, the paper's way (`false`). A deformed mesh is always
    /// answered the paper's way. The answers are exact either way.
    pub exact_by_tree: bool,
}

impl Default for SessionOptions {
    fn default() -> Self {
        Self {
            max_triangles: 20_000,
            jump_factor: 1.0,
            exact_by_tree: true,
        }
    }
}

impl SessionOptions {
    /// With a reset past `n` live triangles beyond the warm start.
    #[must_use]
    pub fn with_max_triangles(mut self, n: usize) -> Self {
        self.max_triangles = n;
        self
    }

    /// With a reset when the query point jumps more than `factor` times the previous
    /// distance.
    #[must_use]
    pub fn with_jump_factor(mut self, factor: f64) -> Self {
        self.jump_factor = factor;
        self
    }

    /// With exact queries from the tree of input triangles (`true`) or the paper's
    /// refinement (`false`); see [`SessionOptions::exact_by_tree`].
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_mesh::{DVec3, shapes};
    /// use sphaera_sweep::{SessionOptions, Sweeper, build_hierarchy};
    ///
    /// let torus = shapes::torus(1.0, 0.25, 24)?;
    /// let hierarchy = build_hierarchy(&torus)?;
    /// let sweeper = Sweeper::new(&hierarchy)?;
    /// let mut tree = sweeper.session();
    /// let mut paper = sweeper.session_with(&SessionOptions::default().with_exact_by_tree(false));
    /// let p = DVec3::new(2.0, 0.1, 0.3);
    /// assert_eq!(tree.closest(p)?.distance, paper.closest(p)?.distance);
    /// assert_eq!((tree.stats().splits, tree.stats().tree_queries), (0, 1));
    /// assert!(paper.stats().splits > 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn with_exact_by_tree(mut self, by_tree: bool) -> Self {
        self.exact_by_tree = by_tree;
        self
    }
}
