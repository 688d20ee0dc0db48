//! Closest point on a triangle and on a segment to a query point.
//!
//! Both queries are robust for every finite input: degenerate (zero-area, collinear or
//! point) triangles and zero-length segments return the true closest point, never NaN.

use glam::DVec3;

use super::Triangle;

/// The feature of a mesh a closest point lies on, in the mesh's vertex indices.
///
/// A single triangle's closest point names its feature by corner number instead
/// ([`TriangleFeature`]); its [`in_mesh`](TriangleFeature::in_mesh) gives this one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Feature {
    /// A vertex of the mesh.
    Vertex(u32),
    /// The interior of the edge between two vertices (in the triangle's corner order).
    Edge(u32, u32),
    /// The interior of the triangle.
    Face,
}

/// The part of a triangle a closest point lies on, in the triangle's own corner numbers.
///
/// Corner `i` is `a`, `b`, `c` for `i = 0, 1, 2`; edge `i` runs from corner `i` to corner
/// `(i + 1) % 3` (edge 0 is `ab`, edge 1 is `bc`, edge 2 is `ca`). For a triangle of a
/// mesh, [`TriangleFeature::in_mesh`] names the same feature by the mesh's vertex
/// indices (the [`Feature`](Feature) a mesh query reports).
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::{Feature, Triangle, TriangleFeature, closest_point_on_triangle};
///
/// let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
/// let hit = closest_point_on_triangle(DVec3::new(2.0, -1.0, 0.0), &t);
/// assert_eq!(hit.feature, TriangleFeature::Vertex(1));
/// // The same corner of mesh triangle [7, 8, 9] is mesh vertex 8.
/// assert_eq!(hit.feature.in_mesh([7, 8, 9]), Feature::Vertex(8));
/// assert_eq!(TriangleFeature::Edge(2).in_mesh([7, 8, 9]), Feature::Edge(9, 7));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TriangleFeature {
    /// Corner `0`, `1` or `2`.
    Vertex(u8),
    /// The interior of edge `0` (`ab`), `1` (`bc`) or `2` (`ca`).
    Edge(u8),
    /// The interior of the face.
    Face,
}

impl TriangleFeature {
    /// The same feature named by mesh vertex indices, for a triangle whose corners are
    /// the mesh vertices `corners` (an edge keeps the triangle's corner order).
    #[must_use]
    pub fn in_mesh(self, corners: [u32; 3]) -> Feature {
        use Feature;
        match self {
            Self::Vertex(k) => Feature::Vertex(corners[usize::from(k) % 3]),
            Self::Edge(k) => {
                let k = usize::from(k) % 3;
                Feature::Edge(corners[k], corners[(k + 1) % 3])
            }
            Self::Face => Feature::Face,
        }
    }
}

/// The closest point on a triangle to a query point, from [`closest_point_on_triangle`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleClosestPoint {
    /// The closest point on the triangle.
    pub point: DVec3,
    /// Squared distance from the query point to [`point`](Self::point).
    pub distance_squared: f64,
    /// Barycentric coordinates of [`point`](Self::point) with respect to `a`, `b`, `c`:
    /// non-negative, summing to 1 (up to rounding).
    pub barycentric: [f64; 3],
    /// The feature the point lies on.
    pub feature: TriangleFeature,
}

/// The part of a segment a closest point lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SegmentFeature {
    /// The first endpoint (`t = 0`).
    Start,
    /// The second endpoint (`t = 1`).
    End,
    /// Strictly between the endpoints.
    Interior,
}

/// The closest point on a segment to a query point, from [`closest_point_on_segment`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentClosestPoint {
    /// The closest point on the segment.
    pub point: DVec3,
    /// Squared distance from the query point to [`point`](Self::point).
    pub distance_squared: f64,
    /// Parameter in `[0, 1]`: `point = start + t (end − start)`.
    pub t: f64,
    /// The feature the point lies on.
    pub feature: SegmentFeature,
}

/// The closest point to `p` on the segment from `start` to `end`.
///
/// A zero-length segment returns `start` with `t = 0` and [`SegmentFeature::Start`].
/// The endpoints are returned exactly (bit for bit) when they are the closest point.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::{SegmentFeature, closest_point_on_segment};
///
/// let hit = closest_point_on_segment(DVec3::new(0.5, 2.0, 0.0), DVec3::ZERO, DVec3::X);
/// assert_eq!(hit.point, DVec3::new(0.5, 0.0, 0.0));
/// assert_eq!(hit.t, 0.5);
/// assert_eq!(hit.distance_squared, 4.0);
/// assert_eq!(hit.feature, SegmentFeature::Interior);
/// ```
///
/// # Panics
///
/// Never. Non-finite input gives non-finite output.
///
/// # Performance
///
/// Constant time, no allocation.
pub fn closest_point_on_segment(p: DVec3, start: DVec3, end: DVec3) -> SegmentClosestPoint {
    let direction = end - start;
    let length_squared = direction.length_squared();
    let projection = (p - start).dot(direction);
    // `projection <= 0` also covers zero-length segments (projection is then exactly 0).
    if projection <= 0.0 || length_squared <= 0.0 {
        return SegmentClosestPoint {
            point: start,
            distance_squared: p.distance_squared(start),
            t: 0.0,
            feature: SegmentFeature::Start,
        };
    }
    if projection >= length_squared {
        return SegmentClosestPoint {
            point: end,
            distance_squared: p.distance_squared(end),
            t: 1.0,
            feature: SegmentFeature::End,
        };
    }
    let t = projection / length_squared;
    let point = start + t * direction;
    SegmentClosestPoint {
        point,
        distance_squared: p.distance_squared(point),
        t,
        feature: SegmentFeature::Interior,
    }
}

/// The closest point to `p` on the (filled) triangle, with its barycentric coordinates and
/// the [`TriangleFeature`] it lies on.
///
/// The result is the better of the three edge projections and, when `p` projects strictly
/// inside the face, the face projection. The face candidate is a convex combination of the
/// corners, so the returned point always lies on the triangle, and the returned distance is
/// never above the true distance by more than rounding, also for needle, collinear and
/// point triangles (which simply never report [`TriangleFeature::Face`]). When two features are
/// equally close, vertices win over edges and edges over the face.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::{Triangle, TriangleFeature, closest_point_on_triangle};
///
/// let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
/// let hit = closest_point_on_triangle(DVec3::new(0.25, 0.25, 3.0), &t);
/// assert_eq!(hit.feature, TriangleFeature::Face);
/// assert!((hit.point - DVec3::new(0.25, 0.25, 0.0)).length() < 1e-15);
/// assert!((hit.distance_squared - 9.0).abs() < 1e-12);
/// assert!((hit.barycentric[0] - 0.5).abs() < 1e-15);
///
/// // A point triangle still answers.
/// let dot = Triangle::new(DVec3::X, DVec3::X, DVec3::X);
/// let hit = closest_point_on_triangle(DVec3::ZERO, &dot);
/// assert_eq!(hit.point, DVec3::X);
/// assert_eq!(hit.distance_squared, 1.0);
/// ```
///
/// # Panics
///
/// Never. Non-finite input gives non-finite output. Coordinates beyond about `1e75` overflow
/// the face test, which is then skipped (the edge answer is still returned).
///
/// # Performance
///
/// Constant time, no allocation; costlier than [`point_triangle_distance_squared`],
/// which skips the edges for points over the face.
pub fn closest_point_on_triangle(p: DVec3, triangle: &Triangle) -> TriangleClosestPoint {
    let corners = triangle.corners();
    let mut best = edge_candidate(p, &corners, 0);
    for edge in 1..3 {
        let candidate = edge_candidate(p, &corners, edge);
        if candidate.distance_squared < best.distance_squared {
            best = candidate;
        }
    }
    if let Some(face) = face_candidate(p, triangle)
        && face.distance_squared < best.distance_squared
    {
        best = face;
    }
    best
}

/// Squared distance from `p` to the (filled) triangle: the fast path of
/// [`closest_point_on_triangle`] when only the distance is needed.
///
/// Uses the Voronoi-region classification of the corners and edges (dot products only) for
/// well-shaped triangles, and falls back to [`closest_point_on_triangle`] for triangles
/// whose smallest angle is below about 0.01° or whose face classification is doubtful.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::geometry::{Triangle, point_triangle_distance_squared};
///
/// let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
/// assert_eq!(point_triangle_distance_squared(DVec3::new(-1.0, -1.0, 0.0), &t), 2.0);
/// assert!((point_triangle_distance_squared(DVec3::new(0.2, 0.2, -2.0), &t) - 4.0).abs() < 1e-12);
/// ```
///
/// # Panics
///
/// Never.
///
/// # Performance
///
/// Constant time, no allocation.
pub fn point_triangle_distance_squared(p: DVec3, triangle: &Triangle) -> f64 {
    let Triangle { a, b, c } = *triangle;
    let ab = b - a;
    let ac = c - a;
    let bc = c - b;
    let normal = ab.cross(ac);
    let longest_squared = ab
        .length_squared()
        .max(ac.length_squared())
        .max(bc.length_squared());
    // sin(smallest angle) ≳ |n| / longest²; below 1e-4 use the robust path.
    let normal_squared = normal.length_squared();
    if normal_squared.is_nan() || normal_squared <= 1e-8 * longest_squared * longest_squared {
        return closest_point_on_triangle(p, triangle).distance_squared;
    }
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length_squared();
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length_squared();
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length_squared();
    }
    // Signed (scaled) barycentric areas, computed directly against the normal so that
    // their signs are reliable for well-shaped triangles.
    let va = normal.dot((b - p).cross(c - p));
    let vb = normal.dot((c - p).cross(a - p));
    let vc = normal.dot((a - p).cross(b - p));
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return closest_point_on_segment(p, a, b).distance_squared;
    }
    if va <= 0.0 && d4 >= d3 && d5 >= d6 {
        return closest_point_on_segment(p, b, c).distance_squared;
    }
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return closest_point_on_segment(p, c, a).distance_squared;
    }
    let sum = va + vb + vc;
    if va > 0.0 && vb > 0.0 && vc > 0.0 && sum.is_finite() {
        // Distance to the plane; exact up to rounding for a point over the face.
        let height = normal.dot(ap);
        return height * height / normal.length_squared();
    }
    closest_point_on_triangle(p, triangle).distance_squared
}

/// The closest point of edge `edge` (from corner `edge` to corner `(edge + 1) % 3`).
fn edge_candidate(p: DVec3, corners: &[DVec3; 3], edge: usize) -> TriangleClosestPoint {
    let next = (edge + 1) % 3;
    let hit = closest_point_on_segment(p, corners[edge], corners[next]);
    let mut barycentric = [0.0; 3];
    barycentric[edge] = 1.0 - hit.t;
    barycentric[next] = hit.t;
    // `edge` and `next` are below 3, so the casts cannot truncate.
    let feature = match hit.feature {
        SegmentFeature::Start => TriangleFeature::Vertex(edge as u8),
        SegmentFeature::End => TriangleFeature::Vertex(next as u8),
        SegmentFeature::Interior => TriangleFeature::Edge(edge as u8),
    };
    TriangleClosestPoint {
        point: hit.point,
        distance_squared: hit.distance_squared,
        barycentric,
        feature,
    }
}

/// The projection of `p` onto the face when it falls strictly inside, else `None`.
fn face_candidate(p: DVec3, triangle: &Triangle) -> Option<TriangleClosestPoint> {
    let Triangle { a, b, c } = *triangle;
    let normal = triangle.scaled_normal();
    let (pa, pb, pc) = (a - p, b - p, c - p);
    // Each weight is |n|² times a barycentric coordinate of the projection of p.
    let wa = normal.dot(pb.cross(pc));
    let wb = normal.dot(pc.cross(pa));
    let wc = normal.dot(pa.cross(pb));
    let sum = wa + wb + wc;
    if !(wa > 0.0 && wb > 0.0 && wc > 0.0 && sum.is_finite()) {
        return None;
    }
    let barycentric = [wa / sum, wb / sum, wc / sum];
    let point = barycentric[0] * a + barycentric[1] * b + barycentric[2] * c;
    Some(TriangleClosestPoint {
        point,
        distance_squared: p.distance_squared(point),
        barycentric,
        feature: TriangleFeature::Face,
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact endpoints and zero weights are part of the contract
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Brute force: dense sampling of the triangle plus the exact edge minima.
    fn brute_force_triangle(p: DVec3, t: &Triangle) -> f64 {
        let mut best = f64::INFINITY;
        let steps = 40;
        for i in 0..=steps {
            for j in 0..=(steps - i) {
                let u = f64::from(i) / f64::from(steps);
                let v = f64::from(j) / f64::from(steps);
                let q = (1.0 - u - v) * t.a + u * t.b + v * t.c;
                best = best.min(p.distance_squared(q));
            }
        }
        for (s, e) in [(t.a, t.b), (t.b, t.c), (t.c, t.a)] {
            // Exact edge minimum by dense sampling plus the analytic projection.
            for k in 0..=200 {
                let q = s.lerp(e, f64::from(k) / 200.0);
                best = best.min(p.distance_squared(q));
            }
            best = best.min(closest_point_on_segment(p, s, e).distance_squared);
        }
        // The exact plane distance when the projection is inside (well-shaped triangles).
        if let Some(n) = t.unit_normal() {
            let h = n.dot(p - t.a);
            let q = p - h * n;
            let w = [
                n.dot((t.b - q).cross(t.c - q)),
                n.dot((t.c - q).cross(t.a - q)),
                n.dot((t.a - q).cross(t.b - q)),
            ];
            if w.iter().all(|&x| x >= 0.0) && !t.is_degenerate(1e-6) {
                best = best.min(h * h);
            }
        }
        best
    }

    fn scale_of(p: DVec3, t: &Triangle) -> f64 {
        1.0 + p.abs().max_element()
            + t.a.abs().max_element()
            + t.b.abs().max_element()
            + t.c.abs().max_element()
    }

    fn check_triangle(p: DVec3, t: &Triangle) {
        let hit = closest_point_on_triangle(p, t);
        let scale = scale_of(p, t);
        let brute = brute_force_triangle(p, t);
        assert!(hit.distance_squared.is_finite());
        let d = hit.distance_squared.sqrt();
        assert!(
            d <= brute.sqrt() + 1e-12 * scale,
            "distance {d} above brute force {} for {p:?} {t:?}",
            brute.sqrt()
        );
        // The reported distance matches the reported point.
        assert!((p.distance(hit.point) - d).abs() <= 1e-12 * scale);
        // The point lies on the triangle: barycentrics valid and reproduce the point.
        let [u, v, w] = hit.barycentric;
        assert!(u >= 0.0 && v >= 0.0 && w >= 0.0);
        assert!((u + v + w - 1.0).abs() < 1e-12);
        let q = u * t.a + v * t.b + w * t.c;
        assert!(q.distance(hit.point) <= 1e-12 * scale);
        match hit.feature {
            TriangleFeature::Vertex(i) => assert_eq!(hit.point, t.corners()[usize::from(i)]),
            TriangleFeature::Edge(i) => {
                let opposite = (usize::from(i) + 2) % 3;
                assert!(hit.barycentric[opposite] == 0.0);
            }
            TriangleFeature::Face => assert!(u > 0.0 && v > 0.0 && w > 0.0),
        }
        // The fast path agrees.
        let fast = point_triangle_distance_squared(p, t).sqrt();
        assert!(fast.is_finite());
        assert!(
            (fast - d).abs() <= 1e-9 * scale,
            "fast path {fast} vs {d} for {p:?} {t:?}"
        );
    }

    fn coord() -> impl Strategy<Value = f64> {
        -10.0..10.0f64
    }

    fn point() -> impl Strategy<Value = DVec3> {
        (coord(), coord(), coord()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    proptest! {
        #[test]
        fn triangle_matches_brute_force(p in point(), a in point(), b in point(), c in point()) {
            check_triangle(p, &Triangle::new(a, b, c));
        }

        #[test]
        fn degenerate_triangles_match_brute_force(
            p in point(), a in point(), b in point(), s in -2.0..3.0f64, eps in 0.0..1e-9f64, kind in 0..4u8,
        ) {
            let t = match kind {
                // Collinear, third corner on the line (inside or outside the segment).
                0 => Triangle::new(a, b, a.lerp(b, s)),
                // Needle: third corner barely off the line.
                1 => Triangle::new(a, b, a.lerp(b, s) + DVec3::splat(eps)),
                // Two coincident corners.
                2 => Triangle::new(a, a, b),
                // Point triangle.
                _ => Triangle::new(a, a, a),
            };
            check_triangle(p, &t);
        }

        #[test]
        fn segment_matches_brute_force(p in point(), a in point(), b in point(), same in any::<bool>()) {
            let b = if same { a } else { b };
            let hit = closest_point_on_segment(p, a, b);
            let scale = 1.0 + p.abs().max_element() + a.abs().max_element() + b.abs().max_element();
            let mut brute = f64::INFINITY;
            for k in 0..=1000 {
                brute = brute.min(p.distance_squared(a.lerp(b, f64::from(k) / 1000.0)));
            }
            prop_assert!(hit.distance_squared.sqrt() <= brute.sqrt() + 1e-12 * scale);
            prop_assert!((0.0..=1.0).contains(&hit.t));
            prop_assert!(hit.point.distance(a.lerp(b, hit.t)) <= 1e-12 * scale);
            match hit.feature {
                SegmentFeature::Start => prop_assert!(hit.point == a && hit.t == 0.0),
                SegmentFeature::End => prop_assert!(hit.point == b && hit.t == 1.0),
                SegmentFeature::Interior => prop_assert!(hit.t > 0.0 && hit.t < 1.0),
            }
        }
    }

    #[test]
    fn features_of_the_unit_triangle() {
        let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
        let cases = [
            (DVec3::new(-1.0, -1.0, 1.0), TriangleFeature::Vertex(0)),
            (DVec3::new(2.0, -0.5, 0.0), TriangleFeature::Vertex(1)),
            (DVec3::new(-0.5, 2.0, 0.0), TriangleFeature::Vertex(2)),
            (DVec3::new(0.5, -1.0, 0.0), TriangleFeature::Edge(0)),
            (DVec3::new(1.0, 1.0, 0.0), TriangleFeature::Edge(1)),
            (DVec3::new(-1.0, 0.5, 0.0), TriangleFeature::Edge(2)),
            (DVec3::new(0.2, 0.2, 0.0), TriangleFeature::Face),
        ];
        for (p, feature) in cases {
            assert_eq!(closest_point_on_triangle(p, &t).feature, feature, "{p:?}");
        }
    }

    #[test]
    fn collinear_triangle_returns_true_closest_point() {
        // c lies beyond b on the x axis: the triangle is the segment [0, 2].
        let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0));
        let hit = closest_point_on_triangle(DVec3::new(1.5, 1.0, 0.0), &t);
        assert!(hit.point.distance(DVec3::new(1.5, 0.0, 0.0)) < 1e-15);
        assert!((hit.distance_squared - 1.0).abs() < 1e-15);
        assert_ne!(hit.feature, TriangleFeature::Face);
        assert!(
            (point_triangle_distance_squared(DVec3::new(1.5, 1.0, 0.0), &t) - 1.0).abs() < 1e-15
        );
    }

    #[test]
    fn huge_coordinates_do_not_give_nan() {
        let t = Triangle::new(DVec3::ZERO, DVec3::X * 1e200, DVec3::Y * 1e200);
        let hit = closest_point_on_triangle(DVec3::new(1e199, 1e199, 1.0), &t);
        assert!(hit.point.is_finite());
        assert!(!hit.distance_squared.is_nan());
    }
}
