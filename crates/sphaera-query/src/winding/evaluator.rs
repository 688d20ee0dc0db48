//! [`WindingNumber`]: the hierarchically accelerated generalized winding number.

use std::f64::consts::PI;

use glam::DVec3;
use smallvec::SmallVec;

use super::expansion::{Expansion, far_field, truncation_bound};
use super::solid_angle::solid_angle_of_corners;
use super::tree::Tree;
use crate::QueryError;
use sphaera_mesh::TriMesh;

/// Parameters of [`WindingNumber`], set builder-style (like
/// [`PoissonDiskOptions`](crate::sampling::PoissonDiskOptions)) so that options can be added
/// without breaking callers.
///
/// # Examples
///
/// ```
/// use sphaera_query::winding::{Expansion, WindingOptions};
///
/// let options = WindingOptions::default().with_beta(3.0);
/// assert_eq!(options.beta(), 3.0);
/// assert_eq!(options.expansion(), Expansion::ThirdOrder);
/// assert_eq!(WindingOptions::default().beta(), 2.0);
/// let coarse = options.with_expansion(Expansion::FirstOrder);
/// assert_eq!(coarse.expansion(), Expansion::FirstOrder);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct WindingOptions {
    pub(super) beta: f64,
    pub(super) expansion: Expansion,
}

impl Default for WindingOptions {
    /// `beta` 2, [`Expansion::ThirdOrder`] (as in Barill et al.).
    fn default() -> Self {
        Self {
            beta: 2.0,
            expansion: Expansion::ThirdOrder,
        }
    }
}

impl WindingOptions {
    /// Sets the far-field parameter: a node whose triangles lie within distance `r` of its
    /// centre is replaced by its expansion when the query is farther than `beta · r` from
    /// that centre. Larger is more accurate and slower. Must be greater than 1 (checked by
    /// [`WindingNumber::with_options`]); `f64::INFINITY` disables the approximation (exact
    /// evaluation, equal to [`winding_number_brute`](super::winding_number_brute) up to
    /// rounding). Default 2.
    #[must_use]
    pub fn with_beta(mut self, beta: f64) -> Self {
        self.beta = beta;
        self
    }

    /// Sets the far-field expansion. Default [`Expansion::ThirdOrder`].
    #[must_use]
    pub fn with_expansion(mut self, expansion: Expansion) -> Self {
        self.expansion = expansion;
        self
    }

    /// The far-field parameter (see [`WindingOptions::with_beta`]).
    pub fn beta(&self) -> f64 {
        self.beta
    }

    /// The far-field expansion.
    pub fn expansion(&self) -> Expansion {
        self.expansion
    }
}

/// A winding number together with a rigorous bound on the error of its far-field
/// approximation, as returned by [`WindingNumber::winding_number_with_bound`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindingEstimate {
    /// The approximate winding number.
    pub value: f64,
    /// `|value − exact| ≤ error_bound`, the exact value being the true winding number
    /// ([`winding_number_brute`](super::winding_number_brute) up to its rounding). The bound
    /// covers the truncation of the expansions and a worst-case allowance for the rounding
    /// of the sum.
    pub error_bound: f64,
}

/// The generalized winding number of a triangle mesh, accelerated by a bounding-volume
/// hierarchy with far-field expansions (Barill et al. 2018; see the
/// [module documentation](super)).
///
/// Owns a copy of the triangles (reordered for locality), so it does not borrow the mesh.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::TriMesh;
/// use sphaera_query::winding::WindingNumber;
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )?;
/// let winding = WindingNumber::new(&mesh)?;
/// assert!(winding.is_inside(DVec3::splat(0.2)));
/// assert!(!winding.is_inside(DVec3::splat(0.5)));
/// assert_eq!(
///     winding.classify(&[DVec3::splat(0.1), DVec3::new(2.0, 0.0, 0.0)]),
///     vec![true, false]
/// );
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Debug)]
pub struct WindingNumber {
    pub(super) tree: Tree,
    pub(super) options: WindingOptions,
}

impl WindingNumber {
    /// Builds the evaluator with the default options (`beta = 2`, third-order expansion).
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`] if the mesh has no triangles.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_query::QueryError;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::WindingNumber;
    ///
    /// let empty = TriMesh::default();
    /// assert!(matches!(WindingNumber::new(&empty), Err(QueryError::EmptyMesh)));
    /// ```
    ///
    /// # Performance
    ///
    /// `O(n log n)`, single-threaded; memory linear in the triangles (see the
    /// [module documentation](super)). No bench times the build yet (see the section
    /// *Inside/outside (generalized winding number)* of `docs/benchmarks.md` in the
    /// repository).
    pub fn new(mesh: &TriMesh) -> Result<Self, QueryError> {
        Self::with_options(mesh, &WindingOptions::default())
    }

    /// Builds the exact evaluator: no far-field approximation (`beta = ∞`). Its values
    /// equal [`winding_number_brute`](super::winding_number_brute) up to rounding, and it is
    /// about as slow (`O(n)` per query).
    ///
    /// # Errors
    ///
    /// [`QueryError::EmptyMesh`] if the mesh has no triangles.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::{WindingNumber, winding_number_brute};
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let exact = WindingNumber::exact(&mesh)?;
    /// let p = DVec3::new(0.3, -0.2, 0.9);
    /// assert!((exact.winding_number(p) - winding_number_brute(&mesh, p)).abs() < 1e-14);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    pub fn exact(mesh: &TriMesh) -> Result<Self, QueryError> {
        Self::with_options(mesh, &WindingOptions::default().with_beta(f64::INFINITY))
    }

    /// Builds the evaluator with the given options.
    ///
    /// # Errors
    ///
    /// - [`QueryError::EmptyMesh`] if the mesh has no triangles;
    /// - [`QueryError::InvalidParameter`] (`beta`) if `options.beta()` is NaN or not greater
    ///   than 1 (the expansion diverges when the query can be inside the node's ball);
    /// - [`QueryError::TooManyTriangles`] if the mesh has `u32::MAX` triangles or more.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_query::QueryError;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::{WindingNumber, WindingOptions};
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let careful = WindingNumber::with_options(
    ///     &mesh,
    ///     &WindingOptions::default().with_beta(4.0),
    /// )?;
    /// assert!(careful.is_inside(DVec3::splat(0.1)));
    ///
    /// let err = WindingNumber::with_options(
    ///     &mesh,
    ///     &WindingOptions::default().with_beta(0.5),
    /// )
    /// .unwrap_err();
    /// assert!(matches!(err, QueryError::InvalidParameter { name: "beta", .. }));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    pub fn with_options(mesh: &TriMesh, options: &WindingOptions) -> Result<Self, QueryError> {
        if options.beta.is_nan() || options.beta <= 1.0 {
            return Err(QueryError::InvalidParameter {
                name: "beta",
                value: options.beta,
                requirement: "greater than 1 (or infinity for exact evaluation)",
            });
        }
        if mesh.triangle_count() == 0 {
            return Err(QueryError::EmptyMesh);
        }
        if u32::try_from(mesh.triangle_count()).is_err() {
            return Err(QueryError::TooManyTriangles {
                count: mesh.triangle_count(),
            });
        }
        Ok(Self {
            tree: Tree::build(mesh)?,
            options: *options,
        })
    }

    /// The evaluator of `mesh` with the default options on `boxes`, the box tree over
    /// [`triangle_boxes`](crate::closest::triangle_boxes) with the winding tree's leaf
    /// size (built, or refined from a coarser build); `mesh` has at least one triangle.
    pub(crate) fn with_boxes(
        mesh: &TriMesh,
        boxes: &crate::bvh::BoxTree,
    ) -> Result<Self, QueryError> {
        if u32::try_from(mesh.triangle_count()).is_err() {
            return Err(QueryError::TooManyTriangles {
                count: mesh.triangle_count(),
            });
        }
        Ok(Self {
            tree: Tree::with_boxes(mesh, boxes),
            options: WindingOptions::default(),
        })
    }

    /// The options this evaluator was built with.
    pub fn options(&self) -> WindingOptions {
        self.options
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.tree.corners.len()
    }

    /// The generalized winding number at `p`: about 1 inside a closed outward-oriented
    /// mesh, 0 outside, smoothly in between near holes of an open mesh.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::WindingNumber;
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let winding = WindingNumber::new(&mesh)?;
    /// assert!((winding.winding_number(DVec3::splat(0.2)) - 1.0).abs() < 1e-9);
    /// assert!(winding.winding_number(DVec3::new(5.0, 1.0, 0.0)).abs() < 1e-3);
    /// assert!(winding.winding_number(DVec3::new(f64::NAN, 0.0, 0.0)).is_nan());
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never. A non-finite `p` gives NaN; a point on the surface gives a finite value
    /// between the values on either side.
    ///
    /// # Performance
    ///
    /// `O(log n)` for points away from the surface. No bench times it on its own yet (see
    /// the section *Inside/outside (generalized winding number)* of `docs/benchmarks.md`
    /// in the repository).
    pub fn winding_number(&self, p: DVec3) -> f64 {
        self.evaluate::<false>(p, self.options.beta, f64::INFINITY)
            .0
            / (4.0 * PI)
    }

    /// The winding number at `p` together with a rigorous bound on its approximation
    /// error (a Taylor remainder bound per expanded node). The bound is pessimistic
    /// (typically orders of magnitude above the actual error at `beta = 2`) but certain.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::{WindingNumber, winding_number_brute};
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let p = DVec3::new(3.0, 2.0, 1.0);
    /// let estimate = WindingNumber::new(&mesh)?.winding_number_with_bound(p);
    /// let exact = winding_number_brute(&mesh, p);
    /// assert!((estimate.value - exact).abs() <= estimate.error_bound + 1e-12);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never; a non-finite `p` gives a NaN value and bound.
    pub fn winding_number_with_bound(&self, p: DVec3) -> WindingEstimate {
        let (omega, bound) = self.evaluate::<true>(p, self.options.beta, f64::INFINITY);
        WindingEstimate {
            value: omega / (4.0 * PI),
            error_bound: bound / (4.0 * PI),
        }
    }

    /// Whether `p` is inside: winding number greater than 1/2.
    ///
    /// For a closed outward-oriented mesh this is the usual inside test (robust to
    /// cracks, duplicated and self-intersecting triangles); for an open mesh it is the
    /// natural extension. An inward-oriented mesh has winding number −1 inside, so every
    /// point is "outside": use [`WindingNumber::check_solid`] to detect that.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::WindingNumber;
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let winding = WindingNumber::new(&mesh)?;
    /// assert!(winding.is_inside(DVec3::new(0.1, 0.2, 0.3)));
    /// assert!(!winding.is_inside(DVec3::new(-0.1, 0.2, 0.3)));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never; a non-finite `p` is outside.
    pub fn is_inside(&self, p: DVec3) -> bool {
        self.winding_number(p) > 0.5
    }

    /// [`WindingNumber::winding_number`] for many points, in parallel with the `parallel`
    /// feature (the results are identical either way).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::WindingNumber;
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let w = WindingNumber::new(&mesh)?.winding_numbers(&[DVec3::splat(0.1), DVec3::splat(3.0)]);
    /// assert!((w[0] - 1.0).abs() < 1e-9 && w[1].abs() < 1e-3);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    pub fn winding_numbers(&self, points: &[DVec3]) -> Vec<f64> {
        map_points(points, |p| self.winding_number(p))
    }

    /// [`WindingNumber::is_inside`] for many points, in parallel with the `parallel`
    /// feature (the results are identical either way).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::WindingNumber;
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let inside = WindingNumber::new(&mesh)?.classify(&[DVec3::splat(0.1), DVec3::splat(3.0)]);
    /// assert_eq!(inside, vec![true, false]);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    pub fn classify(&self, points: &[DVec3]) -> Vec<bool> {
        map_points(points, |p| self.is_inside(p))
    }

    /// [`WindingNumber::is_inside_certified`] for many points, in parallel with the
    /// `parallel` feature (the results are identical either way).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::TriMesh;
    /// use sphaera_query::winding::WindingNumber;
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let winding = WindingNumber::new(&mesh)?;
    /// let inside = winding.classify_certified(&[DVec3::splat(0.1), DVec3::splat(3.0)]);
    /// assert_eq!(inside, vec![true, false]);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    pub fn classify_certified(&self, points: &[DVec3]) -> Vec<bool> {
        map_points(points, |p| self.is_inside_certified(p))
    }

    /// The sum of solid angles at `q` (4π times the winding number) and, when `BOUND`, a
    /// bound on the truncation error of the expansions (otherwise 0).
    ///
    /// When `BOUND`, a node is expanded only if, in addition, its own truncation bound is at
    /// most `node_tolerance` (so the traversal refines where the bound is large).
    fn evaluate<const BOUND: bool>(&self, q: DVec3, beta: f64, node_tolerance: f64) -> (f64, f64) {
        if !q.is_finite() {
            return (f64::NAN, f64::NAN);
        }
        let beta_squared = beta * beta;
        let order = self.options.expansion;
        let nodes = &self.tree.nodes;
        let mut omega = 0.0;
        let mut bound = 0.0;
        let mut magnitude = 0.0;
        let mut terms = 0.0;
        let mut stack: SmallVec<[u32; 64]> = SmallVec::new();
        stack.push(0);
        while let Some(index) = stack.pop() {
            let Some(node) = nodes.get(index as usize) else {
                continue; // invariant: child indices are in range; never taken
            };
            let x = node.center - q;
            let d2 = x.length_squared();
            // With beta = ∞ the right side is ∞ (or NaN for a zero radius): never far.
            let far = d2 > beta_squared * node.radius * node.radius;
            let node_bound = if BOUND && far {
                truncation_bound(node, d2.sqrt(), order)
            } else {
                0.0
            };
            if far && node_bound <= node_tolerance {
                let term = far_field(node, x, d2, order);
                omega += term;
                if BOUND {
                    magnitude += term.abs();
                    terms += 1.0;
                    bound += node_bound;
                }
            } else if node.count > 0 {
                let start = node.first as usize;
                let end = start + node.count as usize;
                for [a, b, c] in self.tree.corners.get(start..end).unwrap_or(&[]) {
                    let term = solid_angle_of_corners(*a - q, *b - q, *c - q);
                    omega += term;
                    if BOUND {
                        magnitude += term.abs();
                        terms += 1.0;
                    }
                }
            } else {
                stack.push(node.first);
                stack.push(index + 1);
            }
        }
        // Rounding: each term is accurate to a few ulps of its magnitude, and a sum of `n`
        // terms to `n` ulps of the sum of magnitudes (the classical worst case).
        let rounding = (terms + 16.0) * 4.0 * f64::EPSILON * magnitude;
        (omega, bound + rounding)
    }
}

/// `points.map(f)`, in parallel with the `parallel` feature; the same results either way
/// (each point's value is computed independently).
fn map_points<T, F>(points: &[DVec3], f: F) -> Vec<T>
where
    T: Send,
    F: Fn(DVec3) -> T + Sync + Send,
{
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        points.par_iter().map(|&p| f(p)).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        points.iter().map(|&p| f(p)).collect()
    }
}
