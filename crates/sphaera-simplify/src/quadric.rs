//! Garland–Heckbert error quadrics and the optimal position of a merged vertex.
//!
//! A quadric `Q(x) = xᵀAx + 2bᵀx + c` (symmetric `A`, stored as its 6 upper entries, with
//! the 3 entries of `b` and `c`: 10 numbers) measures the weighted sum of squared
//! distances from `x` to a set of planes. Each face contributes the plane it lies in,
//! weighted by its area; a vertex carries the sum over its incident faces; an edge
//! collapse `u → v` is priced with `Q_u + Q_v`, and [`optimal_position`] minimises it.
//!
//! Boundary edges may add a penalty plane (through the edge, perpendicular to its face),
//! weighted by the squared edge length times a factor, so that collapses keep open
//! borders in place.
//!
//! The quadric only ranks and places collapses: the certified error is the error-sphere
//! radius of [`crate::edge_radius`].

use std::ops::{Add, AddAssign};

use glam::DVec3;
use sphaera_mesh::topology::{FaceId, HalfEdgeId, HalfEdgeMesh};

/// The smallest accepted ratio of the smallest to the largest eigenvalue of `A` for an
/// exact solve; below it the system counts as ill-conditioned (a flat region or a crease
/// leaves one or two directions undetermined) and [`optimal_position`] falls back to the
/// segment `u–v`.
const MIN_EIGENVALUE_RATIO: f64 = 1e-7;

/// How far (in edge lengths, from the midpoint of `u–v`) an exact solution may lie before
/// it is distrusted and the segment fallback is used instead. A barely well-conditioned
/// system can put its minimum far from the edge; such a position would fold the mesh or
/// need a huge error sphere anyway.
const MAX_SOLVE_DISTANCE: f64 = 4.0;

/// The smallest accepted curvature of the quadric along the segment (relative to the
/// largest eigenvalue of `A` times the squared edge length) for the 1D minimisation;
/// below it the restriction is (nearly) affine and the best of `u`, `v` and the midpoint
/// is taken instead.
const MIN_SEGMENT_CURVATURE: f64 = 1e-12;

/// A symmetric 4×4 error quadric, as `Q(x) = xᵀAx + 2bᵀx + c`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Quadric {
    /// `[a00, a01, a02, a11, a12, a22, b0, b1, b2, c]`.
    m: [f64; 10],
}

impl Quadric {
    /// The quadric of the plane `n·x + d = 0` (`n` of unit length) with weight `w`: `w`
    /// times the squared distance to the plane.
    pub(crate) fn plane(n: DVec3, d: f64, w: f64) -> Self {
        Self {
            m: [
                w * n.x * n.x,
                w * n.x * n.y,
                w * n.x * n.z,
                w * n.y * n.y,
                w * n.y * n.z,
                w * n.z * n.z,
                w * d * n.x,
                w * d * n.y,
                w * d * n.z,
                w * d * d,
            ],
        }
    }

    /// The area-weighted quadric of the triangle's plane (zero for a degenerate triangle).
    pub(crate) fn triangle(a: DVec3, b: DVec3, c: DVec3) -> Self {
        let cross = (b - a).cross(c - a);
        let twice_area = cross.length();
        if !twice_area.is_finite() || twice_area <= 0.0 {
            return Self::default();
        }
        let n = cross / twice_area;
        Self::plane(n, -n.dot(a), 0.5 * twice_area)
    }

    /// The penalty quadric of a boundary edge `a–b` of the triangle `(a, b, c)`: the plane
    /// through the edge perpendicular to the triangle, weighted by `weight · |b − a|²`
    /// (zero when degenerate).
    pub(crate) fn boundary_edge(a: DVec3, b: DVec3, c: DVec3, weight: f64) -> Self {
        let edge = b - a;
        let face_normal = edge.cross(c - a);
        let Some(n) = edge.cross(face_normal).try_normalize() else {
            return Self::default();
        };
        Self::plane(n, -n.dot(a), weight * edge.length_squared())
    }

    /// The matrix `A`.
    fn a(&self) -> [[f64; 3]; 3] {
        let m = &self.m;
        [[m[0], m[1], m[2]], [m[1], m[3], m[4]], [m[2], m[4], m[5]]]
    }

    /// The vector `b`.
    fn b(&self) -> DVec3 {
        DVec3::new(self.m[6], self.m[7], self.m[8])
    }

    /// `A x`.
    fn a_times(&self, x: DVec3) -> DVec3 {
        let a = self.a();
        DVec3::new(
            a[0][0] * x.x + a[0][1] * x.y + a[0][2] * x.z,
            a[1][0] * x.x + a[1][1] * x.y + a[1][2] * x.z,
            a[2][0] * x.x + a[2][1] * x.y + a[2][2] * x.z,
        )
    }

    /// `Q(x)`, the weighted sum of squared plane distances (may be slightly negative
    /// through rounding).
    pub(crate) fn evaluate(&self, x: DVec3) -> f64 {
        x.dot(self.a_times(x)) + 2.0 * self.b().dot(x) + self.m[9]
    }
}

impl Add for Quadric {
    type Output = Self;

    fn add(mut self, other: Self) -> Self {
        self += other;
        self
    }
}

impl AddAssign for Quadric {
    fn add_assign(&mut self, other: Self) {
        for (a, b) in self.m.iter_mut().zip(other.m) {
            *a += b;
        }
    }
}

/// The quadric of every vertex of `mesh` (indexed by vertex; zero for deleted and
/// isolated vertices): the sum of the area-weighted plane quadrics of its live faces, plus,
/// when `boundary_weight > 0`, the penalty planes of its boundary edges (see
/// [`Quadric::boundary_edge`]).
pub(crate) fn vertex_quadrics(mesh: &HalfEdgeMesh, boundary_weight: f64) -> Vec<Quadric> {
    let mut quadrics = vec![Quadric::default(); mesh.vertex_count()];
    for f in 0..mesh.face_count() {
        let f = FaceId(f as u32);
        if mesh.is_deleted_face(f) {
            continue;
        }
        let corners = mesh.face_vertices(f);
        let p = corners.map(|x| mesh.position(x));
        let q = Quadric::triangle(p[0], p[1], p[2]);
        for x in corners {
            if let Some(slot) = quadrics.get_mut(x.0 as usize) {
                *slot += q;
            }
        }
        if boundary_weight > 0.0 {
            for i in 0..3 {
                // Half-edge `i` of the face runs from corner `i` to corner `i + 1`.
                let h = HalfEdgeId(3 * f.0 + i as u32);
                if !mesh.is_boundary_halfedge(h) {
                    continue;
                }
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                let q = Quadric::boundary_edge(p[i], p[j], p[k], boundary_weight);
                for x in [corners[i], corners[j]] {
                    if let Some(slot) = quadrics.get_mut(x.0 as usize) {
                        *slot += q;
                    }
                }
            }
        }
    }
    quadrics
}

/// The position minimising `q` for the merged vertex of the edge `u–v`.
///
/// 1. When `A` is well-conditioned (its smallest eigenvalue at least
///    [`MIN_EIGENVALUE_RATIO`] times its largest: the ratio is invariant under scaling
///    and translating the mesh) and the minimum lies within [`MAX_SOLVE_DISTANCE`] edge
///    lengths of the midpoint, that minimum (solved in `A`'s eigenbasis, relative to the
///    midpoint).
/// 2. Otherwise the minimum of `q` on the segment `u–v` (a clamped 1D minimisation): on a
///    crease the edge crossing the crease line goes to it; along a flat region or a crease
///    the quadric is constant and step 3 decides.
/// 3. When `q` is (nearly) affine along the segment, the best of the midpoint, `v` and
///    `u` (ties in that order).
///
/// Never returns NaN for finite `u` and `v` (a non-finite candidate falls back to the
/// midpoint).
pub(crate) fn optimal_position(q: &Quadric, u: DVec3, v: DVec3) -> DVec3 {
    let mid = 0.5 * (u + v);
    let edge = v - u;
    let (values, vectors) = symmetric_eigen(q.a());
    let largest = values.iter().fold(0.0_f64, |m, &x| m.max(x.abs()));
    let smallest = values.iter().fold(f64::INFINITY, |m, &x| m.min(x));
    if largest > 0.0 && smallest > MIN_EIGENVALUE_RATIO * largest {
        // Newton step from the midpoint: x = mid − A⁻¹ (A mid + b).
        let gradient = q.a_times(mid) + q.b();
        let step = vectors
            .iter()
            .zip(values)
            .fold(DVec3::ZERO, |s, (e, l)| s + (e.dot(gradient) / l) * *e);
        let x = mid - step;
        if x.is_finite() && step.length() <= MAX_SOLVE_DISTANCE * edge.length() {
            return x;
        }
    }
    // Along the segment: Q(u + s·e) = α s² + 2 β s + Q(u).
    let alpha = edge.dot(q.a_times(edge));
    let beta = edge.dot(q.a_times(u) + q.b());
    if alpha > MIN_SEGMENT_CURVATURE * largest * edge.length_squared() && alpha.is_finite() {
        let s = (-beta / alpha).clamp(0.0, 1.0);
        let x = u + s * edge;
        if x.is_finite() {
            return x;
        }
    }
    let mut best = (q.evaluate(mid), mid);
    for x in [v, u] {
        let value = q.evaluate(x);
        if value < best.0 {
            best = (value, x);
        }
    }
    if best.1.is_finite() { best.1 } else { mid }
}

/// Eigenvalues and orthonormal eigenvectors of a symmetric 3×3 matrix, by cyclic Jacobi
/// rotations (unordered).
fn symmetric_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [DVec3; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let norm = a.iter().flatten().fold(0.0_f64, |s, x| s + x * x).sqrt();
    for _sweep in 0..32 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if off.is_nan() || off <= (1e-18 * norm) * (1e-18 * norm) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = if theta.abs() > 1e150 {
                0.5 / theta
            } else {
                theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
            };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J and V ← V J, with J the rotation in the (p, q) plane.
            let mut j = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            j[p][p] = c;
            j[q][q] = c;
            j[p][q] = s;
            j[q][p] = -s;
            a = multiply(&transpose(&j), &multiply(&a, &j));
            a[p][q] = 0.0;
            a[q][p] = 0.0;
            v = multiply(&v, &j);
        }
    }
    let values = [a[0][0], a[1][1], a[2][2]];
    let vectors = [0, 1, 2].map(|k| DVec3::new(v[0][k], v[1][k], v[2][k]));
    (values, vectors)
}

fn multiply(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for (i, row) in c.iter_mut().enumerate() {
        for (k, x) in row.iter_mut().enumerate() {
            *x = a[i][0] * b[0][k] + a[i][1] * b[1][k] + a[i][2] * b[2][k];
        }
    }
    c
}

fn transpose(a: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [a[0][i], a[1][i], a[2][i]])
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::TriMesh;
    use sphaera_tests::random::SplitMix64;

    fn plane_through(p: DVec3, n: DVec3) -> Quadric {
        let n = n.normalize();
        Quadric::plane(n, -n.dot(p), 1.0)
    }

    #[test]
    fn plane_quadric_measures_squared_distance() {
        let q = plane_through(DVec3::new(0.0, 0.0, 2.0), DVec3::Z);
        assert!((q.evaluate(DVec3::new(5.0, -3.0, 5.0)) - 9.0).abs() < 1e-12);
        assert!(q.evaluate(DVec3::new(1.0, 1.0, 2.0)).abs() < 1e-12);
        let tri = Quadric::triangle(DVec3::ZERO, DVec3::X * 2.0, DVec3::Y * 2.0);
        // Area 2, so twice the squared distance.
        assert!((tri.evaluate(DVec3::new(0.3, 0.4, 1.5)) - 2.0 * 2.25).abs() < 1e-12);
        assert_eq!(
            Quadric::triangle(DVec3::ZERO, DVec3::X, DVec3::X),
            Quadric::default()
        );
    }

    #[test]
    fn single_plane_falls_back_to_the_segment_or_midpoint() {
        let q = plane_through(DVec3::ZERO, DVec3::Z);
        // Edge crossing the plane: the crossing point.
        let x = optimal_position(&q, DVec3::new(0.0, 0.0, -1.0), DVec3::new(1.0, 0.0, 3.0));
        assert!((x - DVec3::new(0.25, 0.0, 0.0)).length() < 1e-12, "{x}");
        // Edge in the plane: every point is optimal, the midpoint wins the tie.
        let x = optimal_position(&q, DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0));
        assert!((x - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
        // Edge on one side: the nearer end.
        let x = optimal_position(&q, DVec3::new(0.0, 0.0, 1.0), DVec3::new(1.0, 0.0, 2.0));
        assert!((x - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-12);
    }

    #[test]
    fn crease_puts_the_optimum_on_the_crease_line() {
        // Planes z = 0 and y = 0 meet on the x axis.
        let q = plane_through(DVec3::ZERO, DVec3::Z) + plane_through(DVec3::ZERO, DVec3::Y);
        let u = DVec3::new(0.0, -1.0, -1.0);
        let v = DVec3::new(2.0, 1.0, 1.0);
        let x = optimal_position(&q, u, v);
        assert!((x - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-12, "{x}");
        assert!(q.evaluate(x).abs() < 1e-12);
        // An edge along the crease: the midpoint.
        let x = optimal_position(&q, DVec3::X, DVec3::X * 3.0);
        assert!((x - DVec3::X * 2.0).length() < 1e-12);
    }

    #[test]
    fn corner_is_solved_exactly() {
        let corner = DVec3::new(1.0, 2.0, 3.0);
        let q = plane_through(corner, DVec3::new(1.0, 0.2, 0.0))
            + plane_through(corner, DVec3::new(0.0, 1.0, 0.3))
            + plane_through(corner, DVec3::new(0.1, 0.0, 1.0));
        let x = optimal_position(&q, corner + DVec3::X * 0.3, corner - DVec3::Y * 0.2);
        assert!((x - corner).length() < 1e-12, "{x}");
        // Too far from the edge: the solve is distrusted, the segment used.
        let far = optimal_position(&q, corner + DVec3::X * 100.0, corner + DVec3::X * 100.1);
        assert!((far - (corner + DVec3::X * 100.0)).length() < 1e-9, "{far}");
    }

    #[test]
    fn random_tetrahedra_corners_are_found_and_beat_the_fallbacks() {
        let mut rng = SplitMix64::new(7);
        for _ in 0..200 {
            let p = [0, 1, 2, 3].map(|_| rng.vector_by_max());
            // The quadric of the three faces around p[0] vanishes at p[0] only.
            let q = Quadric::triangle(p[0], p[1], p[2])
                + Quadric::triangle(p[0], p[2], p[3])
                + Quadric::triangle(p[0], p[3], p[1]);
            let u = p[0] + 0.1 * rng.vector_by_max();
            let v = p[0] + 0.1 * rng.vector_by_max();
            let x = optimal_position(&q, u, v);
            assert!(x.is_finite());
            let best = q.evaluate(x);
            for y in [u, v, 0.5 * (u + v)] {
                assert!(best <= q.evaluate(y) + 1e-12, "{best} vs {}", q.evaluate(y));
            }
            let (values, _) = symmetric_eigen(q.a());
            let ratio = values.iter().fold(f64::INFINITY, |m, &x| m.min(x))
                / values.iter().fold(0.0_f64, |m, &x| m.max(x));
            let mid = 0.5 * (u + v);
            if ratio > 1e-3 && (p[0] - mid).length() < 0.9 * MAX_SOLVE_DISTANCE * (v - u).length() {
                assert!((x - p[0]).length() < 1e-9, "{x} vs {}", p[0]);
            } else if (p[0] - mid).length() > 1.1 * MAX_SOLVE_DISTANCE * (v - u).length() {
                // Distrusted solve: the point lies on the segment.
                let s = (x - u).dot(v - u) / (v - u).length_squared();
                assert!((u + s * (v - u) - x).length() < 1e-12 && (0.0..=1.0).contains(&s));
            }
        }
    }

    #[test]
    fn optimum_is_scale_and_translation_invariant() {
        let mut rng = SplitMix64::new(11);
        for _ in 0..50 {
            let p = [0, 1, 2, 3].map(|_| rng.vector_by_max());
            let (u, v) = (rng.vector_by_max(), rng.vector_by_max());
            for (scale, shift) in [(1e-6, DVec3::ZERO), (1e6, DVec3::new(3e6, -1e6, 2e6))] {
                let build = |s: f64, t: DVec3| {
                    let p = p.map(|x| s * x + t);
                    let q = Quadric::triangle(p[0], p[1], p[2])
                        + Quadric::triangle(p[0], p[2], p[3])
                        + Quadric::triangle(p[1], p[3], p[2]);
                    optimal_position(&q, s * u + t, s * v + t)
                };
                let reference = build(1.0, DVec3::ZERO);
                let scaled = (build(scale, shift) - shift) / scale;
                assert!(
                    (reference - scaled).length() < 1e-6,
                    "{reference} vs {scaled} at scale {scale}"
                );
            }
        }
    }

    #[test]
    fn degenerate_and_empty_quadrics_never_give_nan() {
        let (u, v) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(2.0, 2.0, 3.0));
        assert_eq!(optimal_position(&Quadric::default(), u, v), 0.5 * (u + v));
        assert_eq!(optimal_position(&Quadric::default(), u, u), u);
        let nan = Quadric { m: [f64::NAN; 10] };
        assert_eq!(optimal_position(&nan, u, v), 0.5 * (u + v));
    }

    #[test]
    fn eigen_decomposition_reconstructs_the_matrix() {
        let mut rng = SplitMix64::new(3);
        for _ in 0..100 {
            let r = [0; 6].map(|_| rng.unit_by_max() - 0.5);
            let a = [[r[0], r[1], r[2]], [r[1], r[3], r[4]], [r[2], r[4], r[5]]];
            let (values, vectors) = symmetric_eigen(a);
            for (l, e) in values.iter().zip(vectors) {
                let ae = DVec3::new(
                    a[0][0] * e.x + a[0][1] * e.y + a[0][2] * e.z,
                    a[1][0] * e.x + a[1][1] * e.y + a[1][2] * e.z,
                    a[2][0] * e.x + a[2][1] * e.y + a[2][2] * e.z,
                );
                assert!((ae - *l * e).length() < 1e-12);
                assert!((e.length() - 1.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn vertex_quadrics_vanish_on_the_surface_and_penalise_boundaries() {
        // A flat square of two triangles in z = 0.
        let mesh = TriMesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap();
        let he = HalfEdgeMesh::from_trimesh(&mesh);
        let plain = vertex_quadrics(&he, 0.0);
        assert_eq!(plain.len(), 4);
        // Vertex 0 touches both faces (total area 1): Q = z².
        assert!((plain[0].evaluate(DVec3::new(0.3, 0.2, 2.0)) - 4.0).abs() < 1e-12);
        // Vertex 1 touches one face (area 1/2).
        assert!((plain[1].evaluate(DVec3::new(0.0, 0.0, 2.0)) - 2.0).abs() < 1e-12);
        let penalised = vertex_quadrics(&he, 1.0);
        // Moving vertex 1 within the plane but off its boundary edges now costs.
        let inside = DVec3::new(0.5, 0.5, 0.0);
        assert!(plain[1].evaluate(inside).abs() < 1e-12);
        assert!(penalised[1].evaluate(inside) > 0.1);
        // Sliding along the boundary line x = 1 (edge 1–2) costs only the other edge.
        assert!(penalised[2].evaluate(DVec3::new(1.0, 0.5, 0.0)) > 0.0);
        assert!(penalised[2].evaluate(DVec3::new(1.0, 1.0, 0.0)).abs() < 1e-12);
    }
}
