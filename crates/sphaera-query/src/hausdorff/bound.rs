//! Upper bounds of the distance from every point of a triangle to a mesh, from the exact
//! answers at its corners (paper section 6, Fig. 9).
//!
//! Let the triangle `t = (x0, x1, x2)` have corner answers: closest points `c_i` on the
//! target mesh `M`, lying on the target triangles `T_i`. Two bounds of
//! `max over x ∈ t of d(x, M)` follow, and the smaller is kept:
//!
//! - **Bisector bound** (the paper's): `d(x, M) ≤ min_i |x − c_i|`, a lower envelope of
//!   distances to up to three points. Inside the part of `t` closest to `c_i` (a convex
//!   polygon cut by the bisector planes of the `c_i`) that envelope is the convex
//!   `|x − c_i|`, so its maximum over `t` is reached at a vertex of one of those parts: a
//!   corner of `t`, a crossing of a bisector plane with an edge of `t`, or the point of
//!   `t`'s plane equidistant from all three `c_i`. Evaluating the envelope at every such
//!   candidate and taking the largest value gives the maximum exactly (up to rounding).
//! - **Triangle bound**: `d(x, M) ≤ d(x, T)` for any triangle `T` of `M`, and
//!   `x ↦ d(x, T)` is convex (the distance to a convex set), so over `t` it is largest
//!   at a corner: `max over x ∈ t of d(x, M) ≤ min over T of max_j d(x_j, T)`. The `T`
//!   tried are the target triangles holding the `c_i` and, when `c_i` is on a vertex or an
//!   edge, every triangle around that feature. Tight where one target triangle lies under
//!   the whole of `t`, which the bisector bound never is (it grows with the size of `t`
//!   even on two coincident planes).
//! - **Level bound**: a level of detail of the target (from its hierarchy) has larger
//!   triangles, each within its error radius of the target surface, so one of them often
//!   lies under the whole of `t` where no input triangle does (see `level_upper_bound`).
//! - **Split bound**: where `t` straddles the edge shared by two target triangles (their
//!   corner answers lie on both), neither triangle alone lies under all of `t`; a plane
//!   through the shared edge cuts `t` into two convex pieces, each bounded by the
//!   triangle on its side (see `split_bound_squared`). Without it, every triangle that
//!   straddles an edge of the target would be refined down to tolerance.
//!
//! Both are computed in floating point; [`ROUNDING`] times the coordinate scale is added
//! (the envelope is 1-Lipschitz, so a candidate located a little off moves it by no more
//! than that).

use glam::DVec3;
use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};

/// Relative slack added to a bound, against rounding (times the largest coordinate).
pub const ROUNDING: f64 = 1e-12;

/// What is known at a corner: its position and its exact closest point on the target
/// mesh.
#[derive(Clone, Copy, Debug)]
pub struct CornerAnswer {
    /// The corner.
    pub position: DVec3,
    /// Its exact closest point on the target mesh.
    pub closest: DVec3,
}

/// An upper bound of the distance from every point of the triangle with corners
/// `corners` to the target mesh (module docs), trying each of `targets` (triangles of the
/// target mesh; those holding the corners' closest points and their neighbours) for the
/// triangle bound.
///
/// A bound computed as exactly zero (every corner found exactly on one target triangle,
/// as for identical meshes) stays zero; any other gets the rounding slack.
#[must_use]
pub fn triangle_upper_bound(
    corners: &[CornerAnswer; 3],
    targets: &[Triangle],
    pairs: &[TrianglePair],
) -> f64 {
    let bisector = bisector_bound(corners);
    // The smallest over targets of the largest squared corner distance, each target
    // abandoned as soon as a corner exceeds the best so far.
    let mut best = bisector * bisector;
    for target in targets {
        let mut worst = 0.0_f64;
        for x in corners {
            worst = worst.max(point_triangle_distance_squared(x.position, target));
            if worst >= best {
                break;
            }
        }
        best = best.min(worst);
    }
    let x = corners.map(|c| c.position);
    for pair in pairs {
        best = best.min(split_bound_squared(x, pair));
    }
    let triangle = best.sqrt();
    let bound = bisector.min(triangle);
    if bound == 0.0 {
        return 0.0;
    }
    let scale = corners
        .iter()
        .flat_map(|c| [c.position, c.closest])
        .fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
    bound + ROUNDING * scale
}

/// Two target triangles sharing the edge `(p, q)`.
#[derive(Clone, Copy, Debug)]
pub struct TrianglePair {
    /// One triangle.
    pub first: Triangle,
    /// The other.
    pub second: Triangle,
    /// One end of the shared edge.
    pub p: DVec3,
    /// The other end.
    pub q: DVec3,
}

/// The split bound (squared): a plane through the pair's shared edge (containing the
/// average of their normals) cuts the triangle `x` into two convex pieces; on the first
/// triangle's side `d(·, first)` bounds the distance to the mesh, on the other side
/// `d(·, second)`; each is convex, so its largest value on a piece is at one of the
/// piece's vertices (corners of `x` on that side, and crossings of `x`'s edges with the
/// plane). Any plane would do; this one makes the bound tight where the mesh is smooth
/// across the edge and `x` straddles it, where neither triangle alone is. Infinite when
/// the pair is degenerate.
fn split_bound_squared(x: [DVec3; 3], pair: &TrianglePair) -> f64 {
    let (Some(n1), Some(n2)) = (pair.first.unit_normal(), pair.second.unit_normal()) else {
        return f64::INFINITY;
    };
    let edge = pair.q - pair.p;
    let across = (n1 + n2).cross(edge);
    let side_of = |v: DVec3| across.dot(v - pair.p);
    let first_side = side_of(pair.first.centroid());
    let second_side = side_of(pair.second.centroid());
    let product = first_side * second_side;
    if product.is_nan() || product >= 0.0 {
        return f64::INFINITY;
    }
    let f = x.map(side_of);
    let mut worst = 0.0_f64;
    for i in 0..3 {
        let target = if f[i] * first_side >= 0.0 {
            &pair.first
        } else {
            &pair.second
        };
        worst = worst.max(point_triangle_distance_squared(x[i], target));
        let j = (i + 1) % 3;
        if f[i] * f[j] < 0.0 {
            // The crossing belongs to both pieces.
            let crossing = x[i] + (f[i] / (f[i] - f[j])) * (x[j] - x[i]);
            worst = worst
                .max(point_triangle_distance_squared(crossing, &pair.first))
                .max(point_triangle_distance_squared(crossing, &pair.second));
        }
    }
    worst
}

/// The bound through a level of detail of the target: every point of a level triangle `Q`
/// lies within `r` (its largest corner radius) of the target surface (the simplifier's
/// invariant (B)), so `d(x, M) ≤ d(x, Q) + r`, convex in `x`: its largest value over the
/// triangle `x` is at a corner. Pairs of level triangles sharing an edge are split as in
/// the split bound, with the larger radius. The smallest of all candidates is returned
/// (infinite without candidates), with the rounding slack.
#[must_use]
pub fn level_upper_bound(
    x: [DVec3; 3],
    candidates: &[(Triangle, f64)],
    pairs: &[(TrianglePair, f64)],
) -> f64 {
    let mut best = f64::INFINITY;
    for (q, r) in candidates {
        let worst = x
            .iter()
            .map(|&p| point_triangle_distance_squared(p, q))
            .fold(0.0_f64, f64::max);
        best = best.min(worst.sqrt() + r);
    }
    for (pair, r) in pairs {
        best = best.min(split_bound_squared(x, pair).sqrt() + r);
    }
    let scale = x.iter().fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
    best + ROUNDING * scale
}

/// The paper's bound: the largest value of `min_i |x − c_i|` over the triangle.
fn bisector_bound(corners: &[CornerAnswer; 3]) -> f64 {
    let x = corners.map(|c| c.position);
    let c = corners.map(|c| c.closest);
    let envelope = |p: DVec3| {
        c.iter()
            .map(|&ci| (p - ci).length_squared())
            .fold(f64::INFINITY, f64::min)
    };
    let mut best = x.iter().map(|&p| envelope(p)).fold(0.0_f64, f64::max);
    // Bisector planes crossing the edges.
    for (i, j) in [(0, 1), (1, 2), (0, 2)] {
        let Some((normal, offset)) = bisector(c[i], c[j]) else {
            continue;
        };
        for (a, b) in [(0, 1), (1, 2), (2, 0)] {
            let (fa, fb) = (normal.dot(x[a]) - offset, normal.dot(x[b]) - offset);
            if fa * fb < 0.0 {
                let s = fa / (fa - fb);
                best = best.max(envelope(x[a] + s * (x[b] - x[a])));
            }
        }
    }
    // The point of the triangle's plane equidistant from the three closest points.
    if let (Some((n1, k1)), Some((n2, k2))) = (bisector(c[0], c[1]), bisector(c[0], c[2])) {
        let plane = (x[1] - x[0]).cross(x[2] - x[0]);
        if let Some(p) = solve_three_planes([n1, n2, plane], [k1, k2, plane.dot(x[0])])
            && inside_triangle(p, x)
        {
            best = best.max(envelope(p));
        }
    }
    best.sqrt()
}

/// The plane of points equidistant from `a` and `b`, as `(normal, offset)` with
/// `normal · x = offset`, or `None` if they coincide.
fn bisector(a: DVec3, b: DVec3) -> Option<(DVec3, f64)> {
    let normal = b - a;
    (normal.length_squared() > 0.0)
        .then(|| (normal, 0.5 * (b.length_squared() - a.length_squared())))
}

/// The common point of three planes `n_i · x = k_i`, or `None` if they are (nearly)
/// dependent.
fn solve_three_planes(n: [DVec3; 3], k: [f64; 3]) -> Option<DVec3> {
    let det = n[0].dot(n[1].cross(n[2]));
    let scale = n[0].length() * n[1].length() * n[2].length();
    if det.is_nan() || det.abs() <= 1e-12 * scale {
        return None;
    }
    let p = (k[0] * n[1].cross(n[2]) + k[1] * n[2].cross(n[0]) + k[2] * n[0].cross(n[1])) / det;
    p.is_finite().then_some(p)
}

/// Whether `p` (in the triangle's plane) lies inside the triangle `x`.
fn inside_triangle(p: DVec3, x: [DVec3; 3]) -> bool {
    let normal = (x[1] - x[0]).cross(x[2] - x[0]);
    [(0, 1), (1, 2), (2, 0)]
        .iter()
        .all(|&(a, b)| (x[b] - x[a]).cross(p - x[a]).dot(normal) >= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_tests::random::Lcg64;

    fn answer(position: DVec3, closest: DVec3) -> CornerAnswer {
        CornerAnswer { position, closest }
    }

    fn triangle(c: [DVec3; 3]) -> Triangle {
        Triangle::new(c[0], c[1], c[2])
    }

    /// The largest `min_i |x − c_i|` over a fine grid of the triangle.
    fn sampled_envelope(corners: &[CornerAnswer; 3], n: u32) -> f64 {
        let mut best = 0.0_f64;
        for i in 0..=n {
            for j in 0..=(n - i) {
                let (a, b) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
                let p = a * corners[0].position
                    + b * corners[1].position
                    + (1.0 - a - b) * corners[2].position;
                let d = corners
                    .iter()
                    .map(|c| (p - c.closest).length())
                    .fold(f64::INFINITY, f64::min);
                best = best.max(d);
            }
        }
        best
    }

    #[test]
    fn bisector_bound_is_the_envelope_maximum() {
        let mut rng = Lcg64::with_increment(7, 1);
        let mut next = || rng.unit() * 2.0 - 1.0;
        for _ in 0..200 {
            let mut point = || DVec3::new(next(), next(), next());
            let corners = [
                answer(point(), point()),
                answer(point(), point()),
                answer(point(), point()),
            ];
            let exact = bisector_bound(&corners);
            let sampled = sampled_envelope(&corners, 200);
            assert!(exact >= sampled - 1e-12, "{exact} < {sampled}");
            assert!(exact <= sampled + 0.02, "{exact} ≫ {sampled}");
        }
    }

    #[test]
    fn coincident_planes_give_zero_with_the_triangle_bound() {
        let target = triangle([
            DVec3::new(-5.0, -5.0, 0.0),
            DVec3::new(5.0, -5.0, 0.0),
            DVec3::Y * 5.0,
        ]);
        let x = [DVec3::new(0.1, 0.2, 0.0), DVec3::X, DVec3::Y];
        let corners = x.map(|p| answer(p, p));
        assert!(bisector_bound(&corners) > 0.4);
        assert!(triangle_upper_bound(&corners, &[target], &[]) <= 0.0);
        let lifted = x.map(|p| answer(p + DVec3::Z, p));
        let bound = triangle_upper_bound(&lifted, &[target], &[]);
        assert!((1.0..1.0 + 1e-9).contains(&bound), "{bound}");
    }

    #[test]
    fn shared_closest_point_gives_the_farthest_corner() {
        let target = triangle([DVec3::ZERO, DVec3::X * -1e-3, DVec3::Y * -1e-3]);
        let x = [
            DVec3::Z,
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.0, 2.0, 1.0),
        ];
        let corners = x.map(|p| answer(p, DVec3::ZERO));
        let bound = triangle_upper_bound(&corners, &[target], &[]);
        assert!((bound - 5f64.sqrt()).abs() < 1e-9, "{bound}");
        // With no target triangle, the bisector bound alone (one point: the farthest corner).
        assert!((triangle_upper_bound(&corners, &[], &[]) - 5f64.sqrt()).abs() < 1e-9);
    }

    #[test]
    fn split_bound_is_tight_across_a_flat_edge_where_single_triangles_are_not() {
        // A unit square split along its diagonal; a triangle 0.1 above it, straddling the
        // diagonal.
        let (a, b, c, d) = (DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y);
        let (first, second) = (Triangle::new(a, b, c), Triangle::new(a, c, d));
        let x = [
            DVec3::new(0.9, 0.1, 0.1),
            DVec3::new(0.1, 0.9, 0.1),
            DVec3::new(0.8, 0.6, 0.1),
        ];
        let pair = TrianglePair {
            first,
            second,
            p: a,
            q: c,
        };
        let split = split_bound_squared(x, &pair).sqrt();
        assert!((split - 0.1).abs() < 1e-12, "{split}");
        let corners = x.map(|p| answer(p, p - 0.1 * DVec3::Z));
        let single = triangle_upper_bound(&corners, &[first, second], &[]);
        assert!(single > 0.3, "{single}");
        let with_pair = triangle_upper_bound(&corners, &[first, second], &[pair]);
        assert!((with_pair - 0.1).abs() < 1e-9, "{with_pair}");
        // A folded pair (both on one side of the plane) gives nothing.
        let folded = TrianglePair {
            first,
            second: first,
            p: a,
            q: c,
        };
        assert!(split_bound_squared(x, &folded).is_infinite());
    }

    #[test]
    fn level_bound_adds_the_radius() {
        let q = triangle([
            DVec3::new(-2.0, -2.0, 0.0),
            DVec3::new(3.0, -2.0, 0.0),
            DVec3::new(0.0, 3.0, 0.0),
        ]);
        let x = [
            DVec3::new(0.0, 0.0, 0.5),
            DVec3::new(1.0, 0.0, 0.25),
            DVec3::new(0.0, 1.0, 0.5),
        ];
        let bound = level_upper_bound(x, &[(q, 0.1)], &[]);
        assert!((bound - 0.6).abs() < 1e-9, "{bound}");
        assert!(level_upper_bound(x, &[], &[]).is_infinite());
    }
}
