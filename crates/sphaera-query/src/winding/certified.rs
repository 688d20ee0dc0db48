//! The certified side of a point: traversals whose far-field truncation and rounding
//! are bounded rigorously, refined where the bound is largest until the side is decided
//! ([`WindingNumber::is_inside_certified`], [`WindingNumber::side_with_margin`],
//! [`WindingNumber::side_with_boundary`], [`WindingNumber::capped_side`]).

use std::cmp::Reverse;
use std::f64::consts::PI;

use glam::DVec3;
use smallvec::SmallVec;
use sphaera_mesh::heap::{MaxHeap, Priority, TotalF64};

use super::WindingBoundary;
use super::boundary::side_from;
use super::evaluator::WindingNumber;
use super::expansion::{far_field, truncation_bound};
use super::solid_angle::solid_angle_of_corners;
use super::tree::Node;
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

/// The side of a point by the exact winding number `w` and a certified margin, as
/// returned by [`WindingNumber::side_with_margin`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CertifiedSide {
    /// Whether `w > ½` (as [`WindingNumber::is_inside_certified`] answers).
    pub inside: bool,
    /// A certified lower bound of `|w − ½|`, positive.
    pub margin: f64,
}

impl WindingNumber {
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
    /// the surface): on random points, several times slower than
    /// [`WindingNumber::is_inside`] (its time per query is measured by `cargo bench -p
    /// sphaera-eval --bench hal3_vs_parry`, in the section *HAL trees* of
    /// `docs/benchmarks.md` in the repository).
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
}
