//! Exact contact predicates between two triangles of a mesh, on Shewchuk's adaptive
//! orientation predicates (the `robust` crate): every answer is the exact answer for the
//! `f64` coordinates given, degenerate configurations included (touching at a point,
//! collinear edges, coplanar overlap).
//!
//! Exactness needs intermediate products that neither overflow nor underflow; the
//! embedding certificate only calls these predicates on meshes whose coordinates pass
//! [`in_exact_range`].

use glam::DVec3;
use robust::{Coord, Coord3D, orient2d, orient3d};

/// The smallest non-zero coordinate magnitude for which the predicates are exact: the
/// products of three coordinate differences and of their rounding errors stay normal
/// numbers (`2^-250`).
const SMALLEST_EXACT: f64 = f64::from_bits(773 << 52);

/// The largest coordinate magnitude for which the predicates are exact (`2^250`): the
/// products of three differences stay finite.
const LARGEST_EXACT: f64 = f64::from_bits(1273 << 52);

/// Whether every coordinate of `p` is zero or has a magnitude in `[2^-250, 2^250]`, where
/// [`orient`] and the 2D predicates are exact.
pub(crate) fn in_exact_range(p: DVec3) -> bool {
    p.to_array()
        .iter()
        .all(|&c| c == 0.0 || (SMALLEST_EXACT..=LARGEST_EXACT).contains(&c.abs()))
}

fn coord3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// The exact sign of the volume `(a − d) · ((b − d) × (c − d))`: positive when `d` lies
/// behind the triangle `a, b, c` (on the side opposite to its normal `(b − a) × (c − a)`),
/// negative in front of it, zero when the four points are coplanar.
#[inline]
pub(crate) fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    orient3d(coord3(a), coord3(b), coord3(c), coord3(d))
}

/// A projection onto a coordinate plane that keeps a given triangle non-degenerate:
/// points of the triangle's plane keep their incidences and orientations (up to one sign
/// for all), so coplanar questions become 2D ones.
#[derive(Clone, Copy, Debug)]
struct Projection {
    /// The axes kept.
    u: usize,
    v: usize,
}

impl Projection {
    /// The projection in which `a, b, c` has the largest exact signed area, or `None` when
    /// the three points are collinear (zero area in every projection).
    fn for_triangle(a: DVec3, b: DVec3, c: DVec3) -> Option<Self> {
        let mut best: Option<(Self, f64)> = None;
        for (u, v) in [(0, 1), (1, 2), (2, 0)] {
            let projection = Self { u, v };
            let area = projection.orient(a, b, c).abs();
            if area > 0.0 && best.is_none_or(|(_, largest)| area > largest) {
                best = Some((projection, area));
            }
        }
        best.map(|(projection, _)| projection)
    }

    fn coord(self, p: DVec3) -> Coord<f64> {
        Coord {
            x: p[self.u],
            y: p[self.v],
        }
    }

    /// The exact sign of the projected triangle's area (positive counter-clockwise).
    fn orient(self, a: DVec3, b: DVec3, c: DVec3) -> f64 {
        orient2d(self.coord(a), self.coord(b), self.coord(c))
    }

    /// Whether `p`, in the plane of the triangle `t`, lies in the closed triangle.
    fn point_in_triangle(self, p: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
        let sense = self.orient(a, b, c).signum();
        sense * self.orient(a, b, p) >= 0.0
            && sense * self.orient(b, c, p) >= 0.0
            && sense * self.orient(c, a, p) >= 0.0
    }

    /// Whether the closed segments `[a, b]` and `[c, d]` of one plane meet.
    fn segments_meet(self, a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> bool {
        let (o1, o2) = (self.orient(a, b, c), self.orient(a, b, d));
        let (o3, o4) = (self.orient(c, d, a), self.orient(c, d, b));
        if o1 * o2 > 0.0 || o3 * o4 > 0.0 {
            return false;
        }
        if o1 == 0.0 && o2 == 0.0 && o3 == 0.0 && o4 == 0.0 {
            // Collinear: the projections onto the line overlap. Order the points
            // lexicographically in the projection (exact comparisons).
            let key = |p: DVec3| (p[self.u], p[self.v]);
            let (ab_min, ab_max) = ordered(key(a), key(b));
            let (cd_min, cd_max) = ordered(key(c), key(d));
            return lexicographic_le(ab_min, cd_max) && lexicographic_le(cd_min, ab_max);
        }
        true
    }

    /// Whether the closed segment `[a, b]`, in the plane of triangle `t`, meets the closed
    /// triangle.
    fn segment_meets_triangle(self, a: DVec3, b: DVec3, t: [DVec3; 3]) -> bool {
        self.point_in_triangle(a, t)
            || self.point_in_triangle(b, t)
            || (0..3).any(|i| self.segments_meet(a, b, t[i], t[(i + 1) % 3]))
    }
}

fn ordered(p: (f64, f64), q: (f64, f64)) -> ((f64, f64), (f64, f64)) {
    if lexicographic_le(p, q) {
        (p, q)
    } else {
        (q, p)
    }
}

fn lexicographic_le(p: (f64, f64), q: (f64, f64)) -> bool {
    p.0 < q.0 || (p.0 <= q.0 && p.1 <= q.1)
}

/// Whether the three points are collinear (exactly: zero area in every coordinate plane).
pub(crate) fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    Projection::for_triangle(a, b, c).is_none()
}

/// Whether the closed segment `[a, b]` meets the closed, non-degenerate triangle `t`.
pub(crate) fn segment_meets_triangle(a: DVec3, b: DVec3, t: [DVec3; 3]) -> bool {
    let [p, q, r] = t;
    let (sa, sb) = (orient(p, q, r, a), orient(p, q, r, b));
    if sa * sb > 0.0 {
        return false;
    }
    let Some(projection) = Projection::for_triangle(p, q, r) else {
        // A degenerate triangle; never asked by the certificate (it refuses them first).
        return true;
    };
    match (sa == 0.0, sb == 0.0) {
        (true, true) => projection.segment_meets_triangle(a, b, t),
        (true, false) => projection.point_in_triangle(a, t),
        (false, true) => projection.point_in_triangle(b, t),
        (false, false) => {
            // The segment crosses the plane at one interior point: it lies in the closed
            // triangle when the line sees the three edges turning the same way.
            let o = [orient(a, b, p, q), orient(a, b, q, r), orient(a, b, r, p)];
            !(o.iter().any(|&s| s > 0.0) && o.iter().any(|&s| s < 0.0))
        }
    }
}

/// Whether two closed triangles meet anywhere (touching counts).
fn triangles_meet(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
    // Strictly on one side of the other's plane: apart.
    let apart = |t: [DVec3; 3], s: [DVec3; 3]| {
        let o = s.map(|x| orient(t[0], t[1], t[2], x));
        o.iter().all(|&v| v > 0.0) || o.iter().all(|&v| v < 0.0)
    };
    if apart(t1, t2) || apart(t2, t1) {
        return false;
    }
    // Two closed triangles meet exactly when an edge of one meets the other (their
    // intersection with the common line, or their overlap in a common plane, has an end
    // on an edge).
    (0..3).any(|i| segment_meets_triangle(t1[i], t1[(i + 1) % 3], t2))
        || (0..3).any(|i| segment_meets_triangle(t2[i], t2[(i + 1) % 3], t1))
}

/// Whether two non-degenerate triangles of a mesh (corners `p1`, `p2`, vertex indices
/// `v1`, `v2`, distinct positions for distinct indices) meet in more than what they share
/// by index: a common vertex, a common edge, or nothing.
///
/// - no shared vertex: any contact;
/// - one shared vertex `v`: the intersection is more than `v` exactly when the edge of one
///   opposite `v` meets the other triangle (the intersection is convex and contains `v`;
///   followed from `v`, it leaves the nearer triangle through that triangle's opposite
///   edge), in either direction, coplanar or not;
/// - a shared edge: the triangles fold onto each other (coplanar, on the same side of the
///   edge);
/// - three shared vertices: a duplicate triangle.
pub(crate) fn improper_contact(p1: [DVec3; 3], v1: [u32; 3], p2: [DVec3; 3], v2: [u32; 3]) -> bool {
    // `in_2[i]`: the corner of triangle 2 with triangle 1's vertex `i`.
    let in_2 = v1.map(|v| v2.iter().position(|&w| w == v));
    match in_2.iter().filter(|c| c.is_some()).count() {
        0 => triangles_meet(p1, p2),
        1 => {
            let Some(i) = in_2.iter().position(Option::is_some) else {
                return true;
            };
            let Some(j) = in_2[i] else {
                return true;
            };
            let (a1, b1) = (p1[(i + 1) % 3], p1[(i + 2) % 3]);
            let (a2, b2) = (p2[(j + 1) % 3], p2[(j + 2) % 3]);
            segment_meets_triangle(a1, b1, p2) || segment_meets_triangle(a2, b2, p1)
        }
        2 => {
            let Some(i) = in_2.iter().position(Option::is_none) else {
                return true;
            };
            // Triangle 1's corner off the shared edge, and triangle 2's.
            let w1 = p1[i];
            let Some(w2) = (0..3).find(|j| !v1.contains(&v2[*j])).map(|j| p2[j]) else {
                return true;
            };
            let (u, v) = (p1[(i + 1) % 3], p1[(i + 2) % 3]);
            if orient(u, v, w1, w2) != 0.0 {
                return false;
            }
            let Some(projection) = Projection::for_triangle(u, v, w1) else {
                return true;
            };
            projection.orient(u, v, w1) * projection.orient(u, v, w2) > 0.0
        }
        _ => true,
    }
}

#[cfg(test)]
mod tests;
