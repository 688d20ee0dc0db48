//! The bounding volume of a patch (Definition 5) and its widths (Definition 6).

use glam::DVec3;

use super::HalTree3;
use crate::lens::bulge_width;

/// The bounding volume of a patch approximated by the triangle `p, s, t`: the balls through
/// the three corners (centres on the axis of their circumcircle, at `c + k·R·n`, `R` the
/// circumradius, `n` the unit normal of `p → s → t`), by their bulges `k`, one holding the
/// patch's vertices above the plane, one those below (Definition 5); `±∞` are the
/// half-spaces, exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound3 {
    /// Bulge of the ball holding the vertices above the plane (`−∞`: none above; `+∞`: a
    /// vertex in the plane outside the circumcircle).
    pub above: f64,
    /// Bulge of the ball holding the vertices below (`+∞`: none below).
    pub below: f64,
}

impl Bound3 {
    /// Intersection (`above ≤ below`) or union of the two balls (Definition 2 for balls;
    /// in 3D a union can occur, the paper's "no 3D analogue to Theorem 1").
    #[must_use]
    pub fn is_intersection(&self) -> bool {
        self.above <= self.below
    }

    /// The widths `w₁` (above) and `w₂` (below) of Definition 6 for the triangle
    /// `corners`: the largest distance from the plane to each ball's boundary on its side.
    #[must_use]
    pub fn widths(&self, corners: [DVec3; 3]) -> (f64, f64) {
        let radius = circle(corners).map_or(0.0, |(_, r, _)| r);
        (
            bulge_width(self.above, radius),
            bulge_width(-self.below, radius),
        )
    }
}

/// Circumcentre, circumradius and unit normal of a triangle (`None` when degenerate).
pub(crate) fn circle([a, b, c]: [DVec3; 3]) -> Option<(DVec3, f64, DVec3)> {
    let (ab, ac) = (b - a, c - a);
    let normal = ab.cross(ac);
    let area2 = normal.length_squared();
    if area2 <= f64::MIN_POSITIVE {
        return None;
    }
    let offset = (normal.cross(ab) * ac.length_squared() + ac.cross(normal) * ab.length_squared())
        / (2.0 * area2);
    Some((a + offset, offset.length(), normal / area2.sqrt()))
}

impl HalTree3 {
    /// The patch's vertices other than the corners, ascending.
    pub(super) fn inner_vertices(&self, corners: [u32; 3], faces: &[u32]) -> Vec<u32> {
        let triangles = self.surface.mesh().triangles();
        let mut vertices: Vec<u32> = faces
            .iter()
            .flat_map(|&f| triangles[f as usize])
            .filter(|v| !corners.contains(v))
            .collect();
        vertices.sort_unstable();
        vertices.dedup();
        vertices
    }

    /// Definition 5's bounding volume of the patch `faces` over `corners`.
    pub(super) fn bound(&self, corners: [u32; 3], faces: &[u32]) -> Bound3 {
        let positions = self.surface.mesh().positions();
        let points = corners.map(|v| positions[v as usize]);
        let Some((center, radius, normal)) = circle(points) else {
            // A degenerate approximating triangle: bound nothing away.
            return Bound3 {
                above: f64::INFINITY,
                below: f64::NEG_INFINITY,
            };
        };
        let (mut above, mut below) = (f64::NEG_INFINITY, f64::INFINITY);
        for v in self.inner_vertices(corners, faces) {
            let x = positions[v as usize];
            let side = robust::orient3d(
                coord(points[0]),
                coord(points[1]),
                coord(points[2]),
                coord(x),
            );
            let power = x.distance_squared(center) - radius * radius;
            // robust's orient3d is positive when x lies below the plane of a
            // counter-clockwise triangle (its convention); the height above is `h`.
            let h = (x - center).dot(normal);
            if side == 0.0 || h == 0.0 || (h > 0.0) != (side < 0.0) {
                if power > 0.0 {
                    above = f64::INFINITY;
                }
                continue;
            }
            let k = power / (2.0 * radius * h);
            if side < 0.0 {
                above = above.max(k);
            } else {
                below = below.min(k);
            }
        }
        Bound3 { above, below }
    }
}

/// A `robust` coordinate.
fn coord(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}
