//! The pseudo-normal test in floating point with rigorous error bounds, for the queries
//! whose closest point is on a sharp edge or a saddle vertex with the query between the
//! planes of its triangles (where the exact plane test of [`super::signed`] cannot
//! decide).
//!
//! Both tests first make sure which feature holds the exact closest point `q`, from the
//! near ties (every triangle through `q` is one):
//!
//! - **Edge** `uv` with exactly two near ties, the two triangles of the edge: `q` lies on
//!   the edge or inside one of the two faces. With `h₁`, `h₂` the signed heights of `p`
//!   over the two planes, the edge pseudo-normal test is the sign of `h₁ + h₂` (since
//!   `p − q` is orthogonal to the edge, as both unit normals are). It is taken only when
//!   one height is larger than the other by more than the ties' slack and the rounding:
//!   then `q` cannot be inside the face of the smaller height (the other face would be
//!   nearer than the slack allows), and inside the face of the larger one the face test
//!   gives the same sign.
//! - **Vertex** `v`, every near tie a triangle around `v`, and `p − v` pointing strictly
//!   away (beyond the rounding) from both edges at `v` of every near tie: then the
//!   closest point of every near tie is `v`, so `q = v`, and the angle-weighted
//!   pseudo-normal `n` of `v` decides by the sign of `(p − v) · n` (Bærentzen and Aanæs
//!   2005), taken only when it exceeds the bound of the rounding of `n` (computed once
//!   per vertex) and of the product.

use glam::DVec3;

use crate::closest::{ClosestPoint, Feature, TriangleTree};
use sphaera_mesh::TriMesh;

/// The unit roundoff's multiple used by every bound: `2^-52`, twice the unit roundoff,
/// so each "`k ε`" below over-counts by a factor of two.
const EPS: f64 = f64::EPSILON;

/// The angle-weighted pseudo-normal of every vertex and a bound on its rounding error.
#[derive(Clone, Debug, Default)]
pub(crate) struct VertexNormals {
    /// `Σ θ n̂` over the triangles at each vertex (`θ` the angle at the vertex, `n̂` the
    /// unit outward normal).
    normals: Vec<DVec3>,
    /// A bound on `|computed − exact|` of each normal.
    errors: Vec<f64>,
}

impl VertexNormals {
    /// The pseudo-normals of `mesh`'s vertices (zero for unreferenced ones), summed in
    /// triangle order.
    pub(crate) fn new(mesh: &TriMesh) -> Self {
        let positions = mesh.positions();
        let mut normals = vec![DVec3::ZERO; positions.len()];
        let mut errors = vec![0.0; positions.len()];
        // The sum of the angles and the number of terms at each vertex.
        let mut terms = vec![(0.0_f64, 0.0_f64); positions.len()];
        for triangle in mesh.triangles() {
            let corners = triangle.map(|v| positions[v as usize]);
            for k in 0..3 {
                let v = triangle[k] as usize;
                let e1 = corners[(k + 1) % 3] - corners[k];
                let e2 = corners[(k + 2) % 3] - corners[k];
                let n = e1.cross(e2);
                let length = n.length();
                let angle = length.atan2(e1.dot(e2));
                if length == 0.0 || !angle.is_finite() {
                    errors[v] = f64::INFINITY;
                    continue;
                }
                normals[v] += angle * (n / length);
                // Unit normal: 16 ε |e₁||e₂| / |n| + 3 ε; angle: 16 ε (see the module docs).
                let conditioning = e1.length() * e2.length() / length;
                errors[v] += angle * EPS * (16.0 * conditioning + 3.0) + 16.0 * EPS;
                terms[v].0 += angle;
                terms[v].1 += 1.0;
            }
        }
        for (error, &(angle_sum, count)) in errors.iter_mut().zip(&terms) {
            // The summation's rounding (`count` terms of size at most their angle), and
            // the whole doubled for safety.
            *error = 2.0 * (*error + count * EPS * angle_sum);
        }
        Self { normals, errors }
    }
}

/// The side of `p` by the pseudo-normal test in floating point, where its error bounds
/// and the near ties make it certain (`Some(true)` inside); `None` otherwise.
pub(crate) fn side(
    tree: &TriangleTree,
    normals: &VertexNormals,
    closest: &ClosestPoint,
    ties: &[u32],
    p: DVec3,
    absolute_slack: f64,
    tie_slack: f64,
) -> Option<bool> {
    match closest.feature {
        Feature::Vertex(v) => vertex_side(tree, normals, v, ties, p),
        Feature::Edge(u, v) => edge_side(tree, [u, v], ties, p, absolute_slack, tie_slack),
        Feature::Face => None,
    }
}

/// The vertex test (see the module docs).
fn vertex_side(
    tree: &TriangleTree,
    normals: &VertexNormals,
    v: u32,
    ties: &[u32],
    p: DVec3,
) -> Option<bool> {
    let (corners, vertices) = (tree.corners(), tree.vertices());
    let (normal, error) = (
        *normals.normals.get(v as usize)?,
        *normals.errors.get(v as usize)?,
    );
    let mut apex = None;
    for &i in ties {
        let (triangle, indices) = (corners.get(i as usize)?, vertices.get(i as usize)?);
        let k = indices.iter().position(|&w| w == v)?;
        let at = triangle[k];
        apex = Some(at);
        let x = p - at;
        for e in [triangle[(k + 1) % 3] - at, triangle[(k + 2) % 3] - at] {
            // Strictly away from the edge, beyond the product's rounding (8 ε |x||e|).
            if x.dot(e) >= -16.0 * EPS * x.length() * e.length() {
                return None;
            }
        }
    }
    let x = p - apex?;
    let s = x.dot(normal);
    let bound = 2.0 * x.length() * (error + 8.0 * EPS * normal.length());
    (s.abs() > bound && bound.is_finite()).then_some(s < 0.0)
}

/// The edge test (see the module docs).
fn edge_side(
    tree: &TriangleTree,
    edge: [u32; 2],
    ties: &[u32],
    p: DVec3,
    absolute_slack: f64,
    tie_slack: f64,
) -> Option<bool> {
    let &[first, second] = ties else {
        return None;
    };
    let (corners, vertices) = (tree.corners(), tree.vertices());
    let mut heights = [(0.0, 0.0); 2];
    for (slot, i) in heights.iter_mut().zip([first, second]) {
        let (triangle, indices) = (corners.get(i as usize)?, vertices.get(i as usize)?);
        if !edge.iter().all(|v| indices.contains(v)) {
            return None;
        }
        let [a, b, c] = *triangle;
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        let length = n.length();
        if length == 0.0 {
            return None;
        }
        let y = p - a;
        // Height over the plane (positive in front) and its rounding: the unit normal's
        // (16 ε |e₁||e₂| / |n| + 3 ε) and the product's (8 ε), times |y|.
        let height = y.dot(n) / length;
        let error = y.length() * EPS * (16.0 * e1.length() * e2.length() / length + 11.0);
        *slot = (height, 2.0 * error);
    }
    let [(h1, r1), (h2, r2)] = heights;
    let (large, small) = if h1.abs() >= h2.abs() {
        (h1, h2)
    } else {
        (h2, h1)
    };
    let margin = tie_slack * small.abs() + 2.0 * absolute_slack + r1 + r2;
    (large.abs() > small.abs() + margin && margin.is_finite()).then_some(large < 0.0)
}
