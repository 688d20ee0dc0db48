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
        let radius = circle(corners).map_or(0.0, |c| c.radius);
        (
            bulge_width(self.above, radius),
            bulge_width(-self.below, radius),
        )
    }
}

/// The circumcircle of a triangle, computed with care: relative to the corner opposite
/// the longest side (so from the two shortest sides, Shewchuk's advice for the
/// circumcentre), on edge vectors scaled by a power of two (exact) so that neither
/// underflow nor overflow depends on the coordinates' magnitude. The result is
/// scale-equivariant: a mesh scaled by a power of two and moved gives the same circle,
/// scaled and moved, up to the rounding of `origin + offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Circle {
    /// The corner the circle is measured from (opposite the longest side).
    pub(crate) origin: DVec3,
    /// The circumcentre relative to `origin`.
    pub(crate) offset: DVec3,
    /// The circumradius, `|offset|`.
    pub(crate) radius: f64,
    /// The unit normal of the triangle as given (`p → s → t` counter-clockwise seen from
    /// the side it points to).
    pub(crate) normal: DVec3,
}

impl Circle {
    /// For a point `x`: its power with respect to the circle's sphere,
    /// `|x − c|² − R²`, and its height `(x − c)·n` over the plane, both computed relative
    /// to `origin` (`|r|² − 2 r·offset` and `r·n` for `r = x − origin`, so a corner has
    /// power 0 up to its own rounding, whatever the coordinates' magnitude), with bounds
    /// on their rounding errors.
    pub(crate) fn power_and_height(&self, x: DVec3) -> PowerHeight {
        let r = x - self.origin;
        let (length, reach) = (r.length(), self.offset.length());
        PowerHeight {
            power: r.length_squared() - 2.0 * r.dot(self.offset),
            power_error: ROUNDING * length * (length + 2.0 * reach),
            height: r.dot(self.normal),
            height_error: ROUNDING * length,
        }
    }
}

/// A point's power and height with respect to a [`Circle`], and bounds on their rounding
/// errors (see [`Circle::power_and_height`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PowerHeight {
    pub(crate) power: f64,
    pub(crate) power_error: f64,
    pub(crate) height: f64,
    pub(crate) height_error: f64,
}

/// A bound on the relative rounding of the few operations of a power or a height (each a
/// handful of roundings of `2⁻⁵³`, taken 64 times over).
const ROUNDING: f64 = 64.0 * f64::EPSILON;

/// The circumcircle of `corners` ([`Circle`]), `None` when the corners are collinear
/// (their cross product is exactly zero, or the circle is not finite).
pub(crate) fn circle(corners: [DVec3; 3]) -> Option<Circle> {
    // The corner opposite the longest side: the two sides from it are the shortest.
    let side = |i: usize| corners[(i + 1) % 3].distance_squared(corners[(i + 2) % 3]);
    let o = (0..3)
        .max_by(|&i, &j| side(i).total_cmp(&side(j)).then(j.cmp(&i)))
        .unwrap_or(0);
    let origin = corners[o];
    // Keep the orientation: walk the corners from `o` in their order.
    let (ab, ac) = (corners[(o + 1) % 3] - origin, corners[(o + 2) % 3] - origin);
    // Scale by a power of two (exact) so the largest component is near 1.
    let largest = ab.abs().max(ac.abs()).max_element();
    if largest == 0.0 || !largest.is_finite() {
        return None;
    }
    let scale = 2f64.powi(-(largest.log2().round() as i32));
    let (ab, ac) = (ab * scale, ac * scale);
    let normal = ab.cross(ac);
    let area2 = normal.length_squared();
    if area2 == 0.0 {
        return None;
    }
    let offset = (normal.cross(ab) * ac.length_squared() + ac.cross(normal) * ab.length_squared())
        / (2.0 * area2);
    let offset = offset / scale;
    let radius = offset.length();
    let normal = normal / area2.sqrt();
    (offset.is_finite() && radius.is_finite() && normal.is_finite()).then_some(Circle {
        origin,
        offset,
        radius,
        normal,
    })
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
    ///
    /// Which side of the plane a vertex lies on is decided exactly (`orient3d`). Its
    /// power and height ([`Circle::power_and_height`], relative to a corner) carry bounds
    /// on their rounding, and each vertex asks for the bulge that holds it for every value
    /// within those bounds: a vertex whose height might be zero is taken as in the plane.
    /// The balls so hold the patch's vertices exactly for the circle as computed; the
    /// rounding of each ball's centre and radius is left to [`Bound3`]'s users, who grow
    /// the balls relative to their magnitude (see `bound_regions`).
    pub(super) fn bound(&self, corners: [u32; 3], faces: &[u32]) -> Bound3 {
        let positions = self.surface.mesh().positions();
        let points = corners.map(|v| positions[v as usize]);
        let Some(circle) = circle(points) else {
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
            // robust's orient3d is positive when x lies below the plane of a
            // counter-clockwise triangle (its convention).
            let ph = circle.power_and_height(x);
            let high = ph.power + ph.power_error;
            let (h, dh) = (ph.height, ph.height_error);
            let two_r = 2.0 * circle.radius;
            if side == 0.0 {
                // In the plane: outside the circle, only the half-space above holds it (a
                // union when vertices lie below).
                if high > 0.0 {
                    above = f64::INFINITY;
                }
                continue;
            }
            // `x` is in the ball of bulge `k` iff `power ≤ 2·k·R·h`. Over every power up
            // to `high` and every height within the bounds on the exact side, the bulge
            // asked for is at its largest (above the plane) or smallest (below); a height
            // the bounds do not keep off zero asks for the half-space when `x` may lie
            // outside the circle.
            let (low_h, high_h) = (h - dh, h + dh);
            if side < 0.0 {
                let k = if high > 0.0 {
                    if low_h > 0.0 {
                        high / (two_r * low_h)
                    } else {
                        f64::INFINITY
                    }
                } else if high_h > 0.0 {
                    high / (two_r * high_h)
                } else {
                    f64::INFINITY
                };
                above = above.max(k);
            } else {
                let k = if high > 0.0 {
                    if high_h < 0.0 {
                        high / (two_r * high_h)
                    } else {
                        f64::NEG_INFINITY
                    }
                } else if low_h < 0.0 {
                    high / (two_r * low_h)
                } else {
                    f64::NEG_INFINITY
                };
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The circle of a triangle on a lattice is the same, relative to its origin,
    /// wherever the triangle is moved on the lattice (exactly representable positions,
    /// up to `2⁶⁰` times the triangle's size from the origin), and scales with it; its
    /// corners have power and height zero within the stated error bounds.
    #[test]
    fn circles_do_not_depend_on_where_or_how_large() {
        let triangles = [
            [DVec3::ZERO, DVec3::X, DVec3::Y],
            [
                DVec3::new(0.1, 0.2, 0.3),
                DVec3::new(1.7, -0.4, 0.9),
                DVec3::new(0.3, 2.1, -1.3),
            ],
            // Thin: a long side and a corner just off it.
            [
                DVec3::new(-1.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.25, 1e-5, 3e-6),
            ],
        ];
        for t in triangles {
            // On the lattice of 2⁻²⁰: every move below is exact.
            let t = t.map(|p| (p * 2f64.powi(20)).round() / 2f64.powi(20));
            let base = circle(t).expect("not collinear");
            for (scale, shift) in [
                (1.0, 0.0),
                (2f64.powi(-40), 2f64.powi(-20)),
                (2f64.powi(30), 2f64.powi(60)),
            ] {
                let moved = t.map(|p| p * scale + DVec3::new(shift, -shift, 3.0 * shift));
                let c = circle(moved).expect("not collinear");
                let error = (c.offset - base.offset * scale).length();
                assert!(
                    error <= 1e-9 * c.radius,
                    "{t:?} at {scale}, {shift}: {error}"
                );
                assert!((c.radius / (base.radius * scale) - 1.0).abs() < 1e-9);
                for p in moved {
                    let ph = c.power_and_height(p);
                    assert!(ph.power.abs() <= ph.power_error, "{p}: {ph:?}");
                    assert!(ph.height.abs() <= ph.height_error, "{p}: {ph:?}");
                }
            }
        }
        assert!(circle([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]).is_none());
        assert!(circle([DVec3::ONE; 3]).is_none());
    }
}
