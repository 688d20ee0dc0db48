//! The far-field expansions of a node's solid angle ([`Expansion`]) and rigorous bounds on
//! their truncation error.

use glam::DVec3;

use super::tree::{Node, trace};

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
pub(super) fn truncation_bound(node: &Node, d: f64, order: Expansion) -> f64 {
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
