//! The signed closest point: the exact closest point and the side of the query, decided
//! by the pseudo-normal test where the surface is certified embedded, by the winding
//! number elsewhere.
//!
//! # Why the plane test is exact
//!
//! Let `q` be the exact closest point of the surface to `p` (at distance `d > 0`) and `F`
//! the vertex, edge or face whose relative interior holds it. On a closed, embedded,
//! outward-oriented 2-manifold, nothing of the surface lies in the open ball of radius `d`
//! about `p`, so `p` is on the same side as the points of the segment `(q, p]` next to
//! `q`, where the solid coincides with the tangent cone `K` of the triangles through `F`
//! (a half-space for a face, a wedge for an edge, the cone of the fan for a vertex).
//! Bærentzen and Aanæs (2005) decide `p − q ∈ K` by the sign of `(p − q) · n` with the
//! angle-weighted pseudo-normal `n` of `F`, a positive combination of the normals of the
//! triangles through `F`. When `p` lies strictly behind the plane of **every** triangle
//! through `F` (exact orientation predicates, since `q` lies on all those planes), every
//! term of that combination has the same sign, and `p − q ∈ K` (for a face or an edge
//! directly; for a vertex by the divergence theorem on `K` within the unit ball, whose
//! sectors would otherwise have to balance the cap); strictly in front of every plane,
//! `p − q ∉ K` likewise.
//!
//! The triangles through `F` are not known exactly, since `q` is computed in floating
//! point; they are among the triangles whose computed distance is within a slack of the
//! computed closest distance (the **near ties**, found in the same descent as the closest
//! point). The query asks the plane of each near tie: when all agree, that is the answer
//! (exactly the winding number's answer, 1 behind and 0 in front of every triangle, which
//! the certificate checked per component). When they do not (a sharp edge or a saddle
//! vertex with `p` between its planes), the pseudo-normal itself is evaluated in floating
//! point with rigorous error bounds ([`super::pseudo_normal`]); what neither decides (a
//! point on the medial axis, on a plane, within rounding of the surface) is left to the
//! certified winding number.

use std::ops::{ControlFlow, Range};

use glam::DVec3;
use smallvec::SmallVec;

use super::intersect::{in_exact_range, orient};
use crate::QueryError;
use crate::bvh::NearestFirst;
use crate::closest::{ClosestPoint, TriangleTree};
use sphaera_mesh::Aabb;
use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};

/// The relative slack of the near ties, `2^-36` (about `1.5e-11`): far above the rounding
/// of a point–triangle distance (a few hundred units in the last place of the coordinates
/// involved), so the near ties hold every triangle at the exact closest distance.
pub(crate) const TIE_SLACK: f64 = 1.0 / 68_719_476_736.0;

/// A closest point of a [`Surface`](crate::Surface) and the side of the query point, from
/// [`Surface::signed_closest`](crate::Surface::signed_closest).
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_query::Surface;
///
/// let surface = Surface::new(&shapes::cube(2.0, 2)?)?; // the cube [-1, 1]³
/// let answer = surface.signed_closest(DVec3::new(0.5, 0.0, 0.0))?;
/// assert!(answer.inside);
/// assert_eq!(answer.signed_distance(), -0.5);
/// assert_eq!(answer.closest, surface.closest(DVec3::new(0.5, 0.0, 0.0))?);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignedClosest {
    /// The exact closest point, as [`Surface::closest`](crate::Surface::closest) gives it.
    pub closest: ClosestPoint,
    /// Whether the query point is inside (generalized winding number above ½).
    pub inside: bool,
    /// How `inside` was decided.
    pub method: SideMethod,
}

impl SignedClosest {
    /// The distance, negative inside.
    #[must_use]
    pub fn signed_distance(&self) -> f64 {
        if self.inside {
            -self.closest.distance
        } else {
            self.closest.distance
        }
    }
}

/// How a [`SignedClosest`] decided its side.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::{DVec3, shapes};
/// use sphaera_query::{Surface, surface::SideMethod};
///
/// let surface = Surface::new(&shapes::sphere(1.0, 16)?)?;
/// let answer = surface.signed_closest(DVec3::new(0.2, 0.1, 0.3))?;
/// assert_eq!(answer.method, SideMethod::PseudoNormal);
/// # Ok::<(), sphaera_query::QueryError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SideMethod {
    /// The pseudo-normal test on a certified embedded solid: decided exactly when the
    /// query point lies strictly on the same side of every triangle through its closest
    /// point (orientation predicates), otherwise in floating point where a rigorous error
    /// bound leaves no doubt. Equal to the certified winding number's answer.
    PseudoNormal,
    /// [`Surface::is_inside_certified`](crate::Surface::is_inside_certified): the surface is
    /// not certified, or the pseudo-normal test could not decide (a query on the medial
    /// axis, on the plane of a triangle through its closest point, or within rounding of
    /// the surface).
    CertifiedWinding,
    /// [`Surface::is_inside`](crate::Surface::is_inside), the fast winding number, from
    /// [`Surface::signed_closest_approx`](crate::Surface::signed_closest_approx) only: not
    /// certified near the surface.
    FastWinding,
    /// The surface is a shell ([`Surface::shell`](crate::Surface::shell)): it has no
    /// inside, and every point is outside.
    Shell,
}

/// The closest point of `tree` to `p` (the answer of [`TriangleTree::closest`], bit for
/// bit) and the tree positions of the near ties: every triangle whose computed distance
/// is within the slack of the closest distance (the closest one included).
///
/// `scale` is the largest coordinate magnitude of the mesh; the slack is [`TIE_SLACK`]
/// times the distance plus the larger of `scale` and `p`'s largest coordinate.
pub(crate) fn closest_with_ties(
    tree: &TriangleTree,
    p: DVec3,
    scale: f64,
) -> Result<(ClosestPoint, SmallVec<[u32; 8]>), QueryError> {
    QueryError::check_query(p)?;
    let mut search = Ties {
        corners: tree.corners(),
        p,
        absolute_slack: absolute_slack(scale, p),
        best_squared: f64::INFINITY,
        limit_squared: f64::INFINITY,
        best: None,
        near: SmallVec::new(),
    };
    tree.boxes().search_nearest_first(p, &mut search);
    // A finite query on a non-empty tree always finds a triangle (invariant).
    let Some(best) = search.best else {
        return Err(QueryError::EmptyMesh);
    };
    let limit = search.limit_squared;
    let ties = search
        .near
        .iter()
        .filter(|&&(_, d)| d <= limit)
        .map(|&(i, _)| i)
        .collect();
    Ok((tree.answer_at(best, p), ties))
}

/// The absolute part of the near ties' slack for `p` on a mesh whose largest coordinate
/// magnitude is `scale`.
pub(crate) fn absolute_slack(scale: f64, p: DVec3) -> f64 {
    TIE_SLACK * scale.max(p.abs().max_element())
}

/// The side of `p` if every near tie's plane puts it strictly on one side: `Some(true)`
/// behind all of them, `Some(false)` in front of all of them, `None` otherwise (or when
/// `p` is outside the range where the orientation predicate is exact).
pub(crate) fn side_of_ties(tree: &TriangleTree, ties: &[u32], p: DVec3) -> Option<bool> {
    if !in_exact_range(p) {
        return None;
    }
    let corners = tree.corners();
    let mut side = None;
    for &i in ties {
        let [a, b, c] = *corners.get(i as usize)?;
        let o = orient(a, b, c, p);
        if o == 0.0 {
            return None;
        }
        let behind = o > 0.0;
        match side {
            None => side = Some(behind),
            Some(s) if s != behind => return None,
            Some(_) => {}
        }
    }
    side
}

/// One descent of [`closest_with_ties`]: the closest-point search of
/// [`TriangleTree::closest`] (same order, same comparisons, so the same answer) with the
/// pruning bound widened by the slack, collecting every triangle within it.
struct Ties<'a> {
    corners: &'a [[DVec3; 3]],
    p: DVec3,
    absolute_slack: f64,
    best_squared: f64,
    /// The widened bound of the best so far.
    limit_squared: f64,
    best: Option<usize>,
    /// Tree positions and squared distances of the triangles within the bound when seen.
    near: SmallVec<[(u32, f64); 16]>,
}

impl Ties<'_> {
    fn widened(&self, distance_squared: f64) -> f64 {
        let reach = (1.0 + TIE_SLACK) * distance_squared.sqrt() + self.absolute_slack;
        reach * reach
    }
}

impl NearestFirst for Ties<'_> {
    fn may_improve(&self, distance_squared: f64) -> bool {
        distance_squared <= self.limit_squared
    }

    fn visit_leaf(&mut self, positions: Range<usize>) -> ControlFlow<()> {
        for i in positions {
            let Some(&[a, b, c]) = self.corners.get(i) else {
                continue;
            };
            let bounds = Aabb::new(a.min(b).min(c), a.max(b).max(c));
            if bounds.distance_squared_to_point(self.p) > self.limit_squared {
                continue;
            }
            let d = point_triangle_distance_squared(self.p, &Triangle::new(a, b, c));
            // The comparison of `TriangleTree::closest`: the first strictly nearer wins.
            if d < self.best_squared || (self.best.is_none() && d <= self.best_squared) {
                self.best_squared = d;
                self.best = Some(i);
                self.limit_squared = self.widened(d);
            }
            if d <= self.limit_squared {
                // Positions fit in u32: the tree refuses more items.
                self.near.push((i as u32, d));
            }
        }
        ControlFlow::Continue(())
    }
}
