//! Triangulation of polygonal faces (the readers feed them through
//! [`MeshBuilder`](super::builder::MeshBuilder)).
//!
//! A face with `n > 3` vertices becomes `n - 2` triangles:
//!
//! 1. the polygon's normal is its Newell normal (robust for non-planar and non-convex
//!    polygons), and the vertices are projected onto the plane through their centroid
//!    perpendicular to it;
//! 2. a convex projection is fanned from its first vertex;
//! 3. a non-convex one is ear-clipped in the plane (outputs keep the polygon's
//!    orientation);
//! 4. when ear clipping fails (self-intersecting outline, zero Newell normal, more than
//!    [`MAX_EAR_CLIP_VERTICES`] vertices), the polygon is fanned from its first vertex.
//!
//! Each case is counted in the [`LoadReport`](super::LoadReport).

use glam::{DVec2, DVec3};

/// Non-convex polygons larger than this are fanned rather than ear-clipped (ear clipping
/// is quadratic or worse in the vertex count).
pub(crate) const MAX_EAR_CLIP_VERTICES: usize = 1024;

/// Relative distance from the best-fit plane above which a polygon counts as non-planar.
const PLANARITY_TOLERANCE: f64 = 1e-6;

/// How a polygon was triangulated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct PolygonShape {
    pub(crate) non_planar: bool,
    pub(crate) non_convex: bool,
    pub(crate) fan_fallback: bool,
}

/// Triangulates the polygon `points` (in order), appending `points.len() - 2` triangles of
/// local indices to `out`.
pub(crate) fn triangulate(points: &[DVec3], out: &mut Vec<[usize; 3]>) -> PolygonShape {
    let n = points.len();
    let mut shape = PolygonShape::default();
    if n < 3 {
        return shape;
    }
    if n == 3 {
        out.push([0, 1, 2]);
        return shape;
    }
    let centroid = points.iter().sum::<DVec3>() / n as f64;
    // Newell's normal (twice the vector area), about the centroid for accuracy.
    let mut normal = DVec3::ZERO;
    for (i, &p) in points.iter().enumerate() {
        let q = points[(i + 1) % n];
        normal += (p - centroid).cross(q - centroid);
    }
    let scale = points
        .iter()
        .map(|p| (*p - centroid).length())
        .fold(0.0, f64::max);
    let Some(unit_normal) = normal.try_normalize() else {
        shape.fan_fallback = true;
        fan(n, out);
        return shape;
    };
    shape.non_planar = points
        .iter()
        .any(|p| (*p - centroid).dot(unit_normal).abs() > PLANARITY_TOLERANCE * scale);
    let u = unit_normal.any_orthonormal_vector();
    let v = unit_normal.cross(u);
    let flat: Vec<DVec2> = points
        .iter()
        .map(|p| {
            let d = *p - centroid;
            DVec2::new(d.dot(u), d.dot(v))
        })
        .collect();
    let area_tolerance = 1e-12 * scale * scale;
    shape.non_convex = (0..n).any(|i| {
        let a = flat[(i + n - 1) % n];
        let b = flat[i];
        let c = flat[(i + 1) % n];
        (b - a).perp_dot(c - b) < -area_tolerance
    });
    if !shape.non_convex {
        fan(n, out);
        return shape;
    }
    if n > MAX_EAR_CLIP_VERTICES || !ear_clip(&flat, area_tolerance, out) {
        shape.fan_fallback = true;
        fan(n, out);
    }
    shape
}

/// Fan from vertex 0.
fn fan(n: usize, out: &mut Vec<[usize; 3]>) {
    out.extend((1..n - 1).map(|i| [0, i, i + 1]));
}

/// Ear clipping of a counter-clockwise polygon (`area_tolerance` decides which vertices
/// count as collinear with their neighbours). On failure `out` is left as it was and
/// `false` is returned.
fn ear_clip(flat: &[DVec2], area_tolerance: f64, out: &mut Vec<[usize; 3]>) -> bool {
    let start = out.len();
    let mut ring: Vec<usize> = (0..flat.len()).collect();
    let mut i = 0;
    let mut since_last_ear = 0;
    while ring.len() > 3 {
        let m = ring.len();
        if since_last_ear > m {
            // No strictly convex empty ear: clip a vertex collinear with its neighbours
            // (a zero-area triangle that changes nothing), or give up.
            let collinear = (0..m).find(|&k| {
                let (a, b, c) = (
                    flat[ring[(k + m - 1) % m]],
                    flat[ring[k]],
                    flat[ring[(k + 1) % m]],
                );
                (b - a).perp_dot(c - b).abs() <= area_tolerance
            });
            let Some(k) = collinear else {
                out.truncate(start);
                return false;
            };
            out.push([ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]]);
            ring.remove(k);
            since_last_ear = 0;
            i = k % ring.len();
            continue;
        }
        let (ia, ib, ic) = (ring[(i + m - 1) % m], ring[i % m], ring[(i + 1) % m]);
        let (a, b, c) = (flat[ia], flat[ib], flat[ic]);
        let convex = (b - a).perp_dot(c - b) > 0.0;
        let empty = convex
            && ring.iter().all(|&j| {
                j == ia || j == ib || j == ic || {
                    let p = flat[j];
                    p == a || p == b || p == c || !inside_or_on(p, a, b, c)
                }
            });
        if empty {
            out.push([ia, ib, ic]);
            ring.remove(i % m);
            since_last_ear = 0;
            i %= ring.len();
        } else {
            i = (i + 1) % m;
            since_last_ear += 1;
        }
    }
    if let [a, b, c] = ring[..] {
        out.push([a, b, c]);
    }
    true
}

/// Whether `p` lies inside or on the counter-clockwise triangle `a b c`.
fn inside_or_on(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    (b - a).perp_dot(p - a) >= 0.0
        && (c - b).perp_dot(p - b) >= 0.0
        && (a - c).perp_dot(p - c) >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn area(points: &[DVec3], tris: &[[usize; 3]]) -> DVec3 {
        tris.iter()
            .map(|&[a, b, c]| (points[b] - points[a]).cross(points[c] - points[a]) * 0.5)
            .sum()
    }

    #[test]
    fn convex_quad_is_fanned() {
        let quad = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let mut out = Vec::new();
        let shape = triangulate(&quad, &mut out);
        assert_eq!(out, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(shape, PolygonShape::default());
    }

    #[test]
    fn l_shape_is_ear_clipped_without_overlap() {
        // An L-shaped hexagon, non-convex at vertex 3; a fan from vertex 0 would overlap.
        let l = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ];
        let mut out = Vec::new();
        let shape = triangulate(&l, &mut out);
        assert!(shape.non_convex && !shape.fan_fallback && !shape.non_planar);
        assert_eq!(out.len(), 4);
        // Every triangle keeps the polygon's orientation and the areas add up to 3.
        for &[a, b, c] in &out {
            assert!((l[b] - l[a]).cross(l[c] - l[a]).z > 0.0);
        }
        assert!((area(&l, &out).z - 3.0).abs() < 1e-12);
    }

    #[test]
    fn non_planar_quad_is_counted() {
        let quad = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.5), DVec3::Y];
        let mut out = Vec::new();
        assert!(triangulate(&quad, &mut out).non_planar);
        assert_eq!(out.len(), 2);
    }

    #[test]
    fn non_convex_polygon_with_collinear_vertices_is_ear_clipped() {
        // An L whose long edges carry midpoints (T-junction style CAD output).
        let l = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let mut out = Vec::new();
        let shape = triangulate(&l, &mut out);
        assert!(shape.non_convex && !shape.fan_fallback);
        assert_eq!(out.len(), 6);
        for &[a, b, c] in &out {
            assert!((l[b] - l[a]).cross(l[c] - l[a]).z >= 0.0);
        }
        assert!((area(&l, &out).z - 3.0).abs() < 1e-12);
    }

    #[test]
    fn collinear_polygon_falls_back_to_fan() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0, DVec3::X * 3.0];
        let mut out = Vec::new();
        assert!(triangulate(&line, &mut out).fan_fallback);
        assert_eq!(out, vec![[0, 1, 2], [0, 2, 3]]);
    }

    proptest! {
        /// Star-shaped planar polygons (random radii around a centre, any orientation of
        /// the plane): the triangulation has n - 2 triangles, each uses distinct corners,
        /// and the triangles' vector areas add up to the polygon's.
        #[test]
        fn star_polygons_triangulate_exactly(
            radii in prop::collection::vec(0.2f64..2.0, 4..24),
            tilt in 0.0f64..3.0,
        ) {
            let n = radii.len();
            let axis_u = DVec3::new(tilt.cos(), tilt.sin(), 0.3).normalize();
            let axis_w = axis_u.any_orthonormal_vector();
            let axis_v = axis_w.cross(axis_u);
            let points: Vec<DVec3> = radii.iter().enumerate().map(|(i, r)| {
                let angle = std::f64::consts::TAU * i as f64 / n as f64;
                axis_u * (r * angle.cos()) + axis_v * (r * angle.sin())
            }).collect();
            let mut out = Vec::new();
            let shape = triangulate(&points, &mut out);
            prop_assert_eq!(out.len(), n - 2);
            prop_assert!(!shape.fan_fallback);
            for t in &out {
                prop_assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
            }
            let mut expected = DVec3::ZERO;
            for i in 0..n {
                expected += points[i].cross(points[(i + 1) % n]) * 0.5;
            }
            let got = area(&points, &out);
            prop_assert!((got - expected).length() < 1e-9 * (1.0 + expected.length()));
            // No triangle is flipped (ear clipping keeps orientation).
            for &[a, b, c] in &out {
                let tri_normal = (points[b] - points[a]).cross(points[c] - points[a]);
                prop_assert!(tri_normal.dot(expected) >= -1e-12);
            }
        }
    }
}
