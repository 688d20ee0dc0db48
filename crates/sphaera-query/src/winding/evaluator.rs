//! [`WindingNumber`]: the hierarchically accelerated generalized winding number.

use std::f64::consts::PI;

use glam::DVec3;
use smallvec::SmallVec;
use std::cmp::Reverse;

use sphaera_mesh::heap::{MaxHeap, Priority, TotalF64};

use super::WindingBoundary;
use super::boundary::side_from;
use super::solid_angle::solid_angle_of_corners;
use super::tree::{Node, Tree, trace};
use crate::QueryError;
use sphaera_mesh::TriMesh;

/// The truncation bound (in steradians) under which [`WindingNumber::is_inside_certified`]
/// accepts a node's expansion on its first traversal; where the sum of the bounds leaves
/// the side undecided, the expansions with the largest bounds are refined first.
const CERTIFICATION_NODE_TOLERANCE: f64 = 5e-2;

/// An expanded node of a certified evaluation, queued for refinement by its truncation
/// bound (the largest first; ties by node index, for determinism).
struct Expanded {
    bound: f64,
    index: u32,
    term: f64,
}

impl Priority for Expanded {
    type Key = (TotalF64, Reverse<u32>);

    fn priority(&self) -> Self::Key {
        (TotalF64(self.bound), Reverse(self.index))
    }
}

/// A solid angle summed from exact terms and expansions, some of them later taken out
/// again, with what rigorously bounds its error: the truncation bounds of the expansions
/// still in, and the rounding of both running sums.
#[derive(Default)]
struct CertifiedSum {
    /// The sum of the terms in.
    omega: f64,
    /// The sum of the truncation bounds of the expansions in.
    bounds: f64,
    /// The largest value `bounds` took.
    bounds_peak: f64,
    /// Additions and removals, of terms and of bounds.
    operations: f64,
    /// The sum of the magnitudes of every term added or removed.
    magnitude: f64,
}

impl CertifiedSum {
    fn add(&mut self, term: f64, bound: f64) {
        self.omega += term;
        self.bounds += bound;
        self.bounds_peak = self.bounds_peak.max(self.bounds);
        self.magnitude += term.abs();
        self.operations += 1.0;
    }

    fn remove(&mut self, term: f64, bound: f64) {
        self.omega -= term;
        self.bounds -= bound;
        self.magnitude += term.abs();
        self.operations += 1.0;
    }

    /// A bound on `|omega − exact|`: the truncation bounds in, the rounding of their sum
    /// (each operation is off by at most an ulp of a partial sum, itself at most
    /// `bounds_peak`), and the rounding of the terms and of their sum (each term is
    /// accurate to a few ulps of its magnitude, and a sum of `n` terms to `n` ulps of
    /// the sum of magnitudes, the classical worst case, as in `evaluate`).
    fn bound(&self) -> f64 {
        let rounding = (self.operations + 16.0) * 4.0 * f64::EPSILON;
        self.bounds.max(0.0) + rounding * (self.bounds_peak + self.magnitude)
    }
}

/// Which far-field expansion replaces the exact sum over a distant node.
///
/// See the [module documentation](super) for the measured accuracy of each.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Expansion {
    /// The dipole term only: the node's total area-weighted normal placed at its centre
    /// (the area-weighted mean of the centroids). Truncation error per node
    /// `O(area · r / d³)`, and `O(area · r² / d⁴)` for flat nodes.
    FirstOrder,
    /// The dipole term and its gradient (the first moments of the triangles). Error per
    /// node `O(area · r² / d⁴)`. It improves on [`Expansion::FirstOrder`] only for curved
    /// nodes, since the gradient term of a flat node vanishes about its area-weighted centre.
    SecondOrder,
    /// The first three terms of the Taylor series (the second moments of the triangles,
    /// integrated exactly), as in Barill et al. Error per node `O(area · r³ / d⁵)`; about
    /// a third more work per expanded node than [`Expansion::FirstOrder`].
    #[default]
    ThirdOrder,
}

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
    beta: f64,
    expansion: Expansion,
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

/// The side of a point by the exact winding number `w` and a certified margin, as
/// returned by [`WindingNumber::side_with_margin`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CertifiedSide {
    /// Whether `w > ½` (as [`WindingNumber::is_inside_certified`] answers).
    pub inside: bool,
    /// A certified lower bound of `|w − ½|`, positive.
    pub margin: f64,
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
    /// `O(n log n)`, single-threaded: about 0.04 s for 70k triangles and 0.7 to 1.3 s for
    /// 870k; 190 to 230 bytes per triangle (about 170 MB for 870k). See the
    /// [module documentation](super).
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
    /// `O(log n)` for points away from the surface; see the [module documentation](super)
    /// for measured query rates.
    pub fn winding_number(&self, p: DVec3) -> f64 {
        self.evaluate::<false>(p, self.options.beta, f64::INFINITY)
            .0
            / (4.0 * PI)
    }

    /// The winding number at `p` together with a rigorous bound on its approximation
    /// error (a Taylor remainder bound per expanded node). The bound is pessimistic
    /// (typically 100 to 1000 times the actual error at `beta = 2`) but certain.
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

    /// [`WindingNumber::is_inside`] with the answer the exact winding number gives. A
    /// traversal expands only the far nodes whose own truncation bound is small (below
    /// 0.05 sr); while the sum of the bounds (and of the rounding) cannot decide the side,
    /// the expansion with the largest bound is replaced by its children's (or its
    /// triangles' exact solid angles), until the side is decided or the sum is exact. The
    /// result equals `winding_number_brute(mesh, p) > 0.5` except when the exact value is
    /// within rounding (about `1e-12`) of 1/2, that is on the surface.
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
    /// let winding = WindingNumber::new(&mesh)?;
    /// let p = DVec3::new(0.33, 0.33, 0.33); // just inside the slanted face
    /// assert_eq!(winding.is_inside_certified(p), winding_number_brute(&mesh, p) > 0.5);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never; a non-finite `p` is outside.
    ///
    /// # Performance
    ///
    /// Every point pays for a traversal with bounds (finer than the plain one), and the
    /// points it cannot decide (near the surface or a hole) for the refinement of the
    /// expansions that keep it undecided, the largest bounds first (`O(n)` at worst, on
    /// the surface): on random points, 4 to 15 times slower than
    /// [`WindingNumber::is_inside`] (see the [module documentation](super)); on points
    /// near the 871k-triangle dragon about a third of the cost of the earlier two fixed
    /// finer traversals.
    pub fn is_inside_certified(&self, p: DVec3) -> bool {
        let half = 2.0 * PI;
        if !p.is_finite() {
            return false;
        }
        let mut sum = CertifiedSum::default();
        let mut first = Vec::new();
        self.expand_certified(0, p, CERTIFICATION_NODE_TOLERANCE, &mut sum, &mut first);
        if (sum.omega - half).abs() > sum.bound() {
            return sum.omega > half;
        }
        let mut expanded = MaxHeap::new();
        expanded.extend(first);
        loop {
            if (sum.omega - half).abs() > sum.bound() {
                return sum.omega > half;
            }
            // Undecided: refined where the bound is largest. With nothing left the sum
            // is exact.
            if !self.refine_largest(p, &mut sum, &mut expanded) {
                return sum.omega > half;
            }
        }
    }

    /// One step of a certified evaluation's refinement: the expansion with the largest
    /// bound is taken out of `sum` and replaced by its triangles summed exactly (a leaf)
    /// or its children's expansions. `false` when nothing is left to refine (the sum is
    /// then exact).
    fn refine_largest(
        &self,
        p: DVec3,
        sum: &mut CertifiedSum,
        expanded: &mut MaxHeap<Expanded>,
    ) -> bool {
        let Some(top) = expanded.pop() else {
            return false;
        };
        sum.remove(top.term, top.bound);
        let Some(node) = self.tree.nodes.get(top.index as usize) else {
            return true; // invariant: queued indices are in range; never taken
        };
        if node.count > 0 {
            self.leaf_exactly(node, p, sum);
        } else {
            for child in [top.index + 1, node.first] {
                self.expand_certified(child, p, CERTIFICATION_NODE_TOLERANCE, sum, expanded);
            }
        }
        true
    }

    /// The certified traversal of the subtree at `start` for
    /// [`WindingNumber::is_inside_certified`]: a node far from `q` whose truncation bound is
    /// at most `node_tolerance` is expanded (added to `sum` and to `expanded`, for
    /// refinement), a leaf that is not is summed exactly, an inner node that is not is
    /// descended.
    fn expand_certified(
        &self,
        start: u32,
        q: DVec3,
        node_tolerance: f64,
        sum: &mut CertifiedSum,
        expanded: &mut impl Extend<Expanded>,
    ) {
        let beta_squared = self.options.beta * self.options.beta;
        let order = self.options.expansion;
        let nodes = &self.tree.nodes;
        let mut stack: SmallVec<[u32; 64]> = SmallVec::new();
        stack.push(start);
        while let Some(index) = stack.pop() {
            let Some(node) = nodes.get(index as usize) else {
                continue; // invariant: child indices are in range; never taken
            };
            let x = node.center - q;
            let d2 = x.length_squared();
            // With beta = ∞ the right side is ∞ (or NaN for a zero radius): never far.
            let far = d2 > beta_squared * node.radius * node.radius;
            let bound = if far {
                truncation_bound(node, d2.sqrt(), order)
            } else {
                f64::INFINITY
            };
            if bound <= node_tolerance {
                let term = far_field(node, x, d2, order);
                sum.add(term, bound);
                expanded.extend([Expanded { bound, index, term }]);
            } else if node.count > 0 {
                self.leaf_exactly(node, q, sum);
            } else {
                stack.push(node.first);
                stack.push(index + 1);
            }
        }
    }

    /// Adds the exact solid angles of a leaf's triangles at `q` to `sum`.
    fn leaf_exactly(&self, node: &Node, q: DVec3, sum: &mut CertifiedSum) {
        let start = node.first as usize;
        let end = start + node.count as usize;
        for [a, b, c] in self.tree.corners.get(start..end).unwrap_or(&[]) {
            sum.add(solid_angle_of_corners(*a - q, *b - q, *c - q), 0.0);
        }
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

    /// [`WindingNumber::is_inside_certified`]'s answer together with a certified
    /// **margin**: `|w − ½| ≥ margin > 0` for the exact winding number `w` at `p`, so that
    /// every point whose winding number differs from `w` by less than the margin lies on
    /// the same side. The certified sum is refined as `is_inside_certified` refines it
    /// (the expansions with the largest bounds first) until it decides the side, and
    /// further while the margin is below `wanted` and refining can still reach it (the
    /// bound left is more than a twentieth of the margin and the estimate leaves room for
    /// `wanted`). `None` only when even the exact sum does not decide (`w` within rounding
    /// of ½: on the surface) or `p` is not finite.
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
    /// let side = winding.side_with_margin(DVec3::splat(0.1), 0.4).expect("decided");
    /// assert!(side.inside && side.margin >= 0.4 && side.margin <= 0.5);
    /// assert!(!winding.side_with_margin(DVec3::splat(3.0), 0.0).expect("decided").inside);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// [`WindingNumber::is_inside_certified`]'s traversal and refinement, and further
    /// refinement only while the margin is below `wanted` and within reach.
    pub fn side_with_margin(&self, p: DVec3, wanted: f64) -> Option<CertifiedSide> {
        let half = 2.0 * PI;
        let full = 4.0 * PI;
        if !p.is_finite() {
            return None;
        }
        let mut sum = CertifiedSum::default();
        let mut expanded = MaxHeap::new();
        let mut first = Vec::new();
        self.expand_certified(0, p, CERTIFICATION_NODE_TOLERANCE, &mut sum, &mut first);
        expanded.extend(first);
        loop {
            let offset = (sum.omega - half).abs();
            let bound = sum.bound();
            let decided = (offset > bound).then(|| CertifiedSide {
                inside: sum.omega > half,
                margin: (offset - bound) / full,
            });
            if let Some(side) = decided {
                // Refining can at best take the bound to nothing: stop once the margin
                // is enough, out of reach, or within a twentieth of the best it can be.
                if side.margin >= wanted
                    || (offset + bound) / full < wanted
                    || bound <= 0.05 * (offset - bound)
                {
                    return Some(side);
                }
            }
            // Refined where the bound is largest; with nothing left the sum is exact.
            if !self.refine_largest(p, &mut sum, &mut expanded) {
                return decided;
            }
        }
    }

    /// [`WindingNumber::side_with_margin`] for a mesh with holes, nearly exact and cheap
    /// near them: the certified estimate of `w` at `p`, refined only until it is within
    /// ¼ of the exact value (far coarser than deciding `w > ½` near a hole's span needs),
    /// fixes the integer `k = w + w_C` of the mesh closed by the caps of `boundary` (its
    /// [`WindingBoundary`] chain coned off, see `cap_solid_angle`), and `w = k − w_C` with
    /// `w_C` summed exactly over the caps. The margin is then `|w − ½|` less the caps'
    /// rounding. Where the caps' sum is ill-conditioned (within a tiny distance of a cap
    /// triangle's edge) or `k` is not decided, falls back to
    /// [`WindingNumber::side_with_margin`] with `wanted`. `boundary` must be that of this
    /// mesh ([`WindingBoundary::new`]); an empty one takes the fallback.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, shapes};
    /// use sphaera_query::winding::{WindingBoundary, WindingNumber, winding_number_brute};
    ///
    /// let cube = shapes::cube(2.0, 1)?;
    /// let open = TriMesh::new(cube.positions().to_vec(), cube.triangles()[1..].to_vec())?;
    /// let (winding, boundary) = (WindingNumber::new(&open)?, WindingBoundary::new(&open));
    /// let p = DVec3::new(0.3, -0.2, 0.99);
    /// let side = winding.side_with_boundary(p, &boundary, 0.0).expect("decided");
    /// let exact = winding_number_brute(&open, p);
    /// assert_eq!(side.inside, exact > 0.5);
    /// assert!(side.margin <= (exact - 0.5).abs() && side.margin > (exact - 0.5).abs() - 1e-9);
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    ///
    /// # Performance
    ///
    /// The first certified traversal of [`WindingNumber::is_inside_certified`] (rarely
    /// refined) and one solid angle per boundary edge.
    pub fn side_with_boundary(
        &self,
        p: DVec3,
        boundary: &WindingBoundary,
        wanted: f64,
    ) -> Option<CertifiedSide> {
        self.capped_side(p, boundary)
            .map(|(_, side)| side)
            .or_else(|| self.side_with_margin(p, wanted))
    }

    /// The capped evaluation of [`WindingNumber::side_with_boundary`]: the integer winding
    /// number `k` at `p` of the mesh closed by the caps of `boundary` (constant along any
    /// path meeting neither the mesh nor the caps, so that it can be handed on, see
    /// [`WindingBoundary::side_given_closed`]) and the side it gives. `None` where it does
    /// not decide (within rounding of the mesh or of a cap triangle's edge, or on the ½
    /// level set).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, shapes};
    /// use sphaera_query::winding::{WindingBoundary, WindingNumber};
    ///
    /// let cube = shapes::cube(2.0, 1)?;
    /// let open = TriMesh::new(cube.positions().to_vec(), cube.triangles()[1..].to_vec())?;
    /// let (winding, boundary) = (WindingNumber::new(&open)?, WindingBoundary::new(&open));
    /// let (k, side) = winding.capped_side(DVec3::ZERO, &boundary).expect("decided");
    /// assert!(side.inside && k == k.round());
    /// let near = DVec3::new(0.1, 0.0, 0.0);
    /// assert!(boundary.caps_avoid_segment(DVec3::ZERO, near));
    /// assert_eq!(boundary.side_given_closed(near, k), winding.capped_side(near, &boundary).map(|c| c.1));
    /// # Ok::<(), sphaera_query::QueryError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    #[must_use]
    pub fn capped_side(
        &self,
        p: DVec3,
        boundary: &WindingBoundary,
    ) -> Option<(f64, CertifiedSide)> {
        let full = 4.0 * PI;
        if boundary.is_empty() {
            return None;
        }
        let (cap, cap_error) = boundary.cap_solid_angle(p)?;
        // The caps' error and the estimate's must stay below 2π (½ in `w`) together.
        let half = 2.0 * PI;
        if cap_error.is_nan() || cap_error >= 0.5 * half {
            return None;
        }
        let mut sum = CertifiedSum::default();
        let mut first = Vec::new();
        self.expand_certified(0, p, CERTIFICATION_NODE_TOLERANCE, &mut sum, &mut first);
        let mut expanded: Option<MaxHeap<Expanded>> = None;
        loop {
            let total = sum.omega + cap;
            let rounding = 8.0 * f64::EPSILON * (sum.omega.abs() + cap.abs() + full);
            if sum.bound() + cap_error + rounding < half {
                // |total − 4πn| ≤ bound + cap_error + its rounding < 2π: `n` is the
                // nearest multiple (the caps' possible 4π offsets included).
                let k = (total / full).round();
                return side_from(k, cap, cap_error).map(|side| (k, side));
            }
            let heap = expanded.get_or_insert_with(|| {
                let mut heap = MaxHeap::new();
                heap.extend(std::mem::take(&mut first));
                heap
            });
            if !self.refine_largest(p, &mut sum, heap) {
                return None;
            }
        }
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

/// The far-field expansion of `node` at offset `x = center − q` with `d2 = |x|²`, in
/// solid-angle units (4π times the winding number).
///
/// With the kernel `K(y) = y / |y|³`, the solid angle of a triangle is `∫ n · K(p − q) dA`;
/// expanding `K` about `x` gives the dipole `N · K(x)`, the gradient term
/// `tr(M)/|x|³ − 3 xᵀMx/|x|⁵` and the Hessian term
/// `½ (−3 (2u + v) · x / |x|⁵ + 15 Σ_i x_i xᵀQ_i x / |x|⁷)`.
#[inline]
pub(super) fn far_field(node: &Node, x: DVec3, d2: f64, order: Expansion) -> f64 {
    let inv_d2 = 1.0 / d2;
    let inv_d3 = inv_d2 * inv_d2.sqrt();
    let dipole = node.normal_sum.dot(x);
    if order == Expansion::FirstOrder {
        return dipole * inv_d3;
    }
    let m = &node.moment;
    let gradient = trace(m) - 3.0 * x.dot(*m * x) * inv_d2;
    if order == Expansion::SecondOrder {
        return (dipole + gradient) * inv_d3;
    }
    let [q0, q1, q2] = &node.quadratic_moment;
    let cubic = x.x * x.dot(*q0 * x) + x.y * x.dot(*q1 * x) + x.z * x.dot(*q2 * x);
    let hessian = 0.5 * (-3.0 * node.quadratic_contraction.dot(x) + 15.0 * cubic * inv_d2) * inv_d2;
    (dipole + gradient + hessian) * inv_d3
}

/// A bound on `|exact − expansion|` of `node` at distance `d > radius` from its centre,
/// in solid-angle units: the Taylor remainder of the kernel `y / |y|³` (minus the gradient
/// of `1/|y|`), whose `k`-th derivative has norm `(k + 1)! / |y|^(k + 2)` (the `k + 1`-th
/// derivative of `1/|y|`, through the Legendre generating function), integrated over the
/// node's area with every point within `radius` of the centre and every point of the
/// segment at least `d − radius` from `q`.
fn truncation_bound(node: &Node, d: f64, order: Expansion) -> f64 {
    let r = node.radius;
    let gap = d - r;
    if gap <= 0.0 {
        return f64::INFINITY;
    }
    let ratio = r / gap;
    let scale = node.area / (gap * gap);
    match order {
        // sup |DK| = 2/|y|³, remainder ≤ 2 r / gap³.
        Expansion::FirstOrder => 2.0 * scale * ratio,
        // sup |D²K| = 6/|y|⁴, remainder ≤ ½ · 6 r² / gap⁴.
        Expansion::SecondOrder => 3.0 * scale * ratio * ratio,
        // sup |D³K| = 24/|y|⁵, remainder ≤ ⅙ · 24 r³ / gap⁵.
        Expansion::ThirdOrder => 4.0 * scale * ratio * ratio * ratio,
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
