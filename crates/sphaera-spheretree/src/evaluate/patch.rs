//! Spherical-triangle patches of a sphere's surface and the bounds of the error on them.
//!
//! A patch is a geodesic triangle of the unit sphere given by its three corner directions.
//! The 20 faces of the icosahedron tile the sphere; splitting a patch at the geodesic
//! midpoints of its edges gives four patches whose union is exactly the parent (the
//! midpoints lie on the parent's geodesic edges), so the patches alive at any time always
//! tile the whole sphere.

use glam::DVec3;

/// Relative slack added to every upper bound, far above the rounding of the few
/// operations that compute it (so the bound stays an upper bound in floating point).
const BOUND_SLACK: f64 = 1e-12;

/// A geodesic triangle of the unit sphere.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Patch {
    /// The corner directions (unit vectors).
    pub corners: [DVec3; 3],
    /// The representative direction: the normalised sum of the corners.
    pub direction: DVec3,
    /// The smallest cosine between `direction` and a corner: the patch lies in the
    /// spherical cap of angle `acos(cos_extent)` about `direction` (see [`Patch::new`]).
    pub cos_extent: f64,
}

impl Patch {
    /// The patch of the three corner directions (unit vectors).
    ///
    /// Containment in the cap: a spherical cap of angle at most 90° is spherically
    /// convex, and a geodesic triangle smaller than a hemisphere is the spherical convex
    /// hull of its corners; so when the three corners lie in the cap of angle `θ ≤ 90°`
    /// about `direction`, the whole patch does. The icosahedron's faces have `θ ≈ 37°`
    /// and children only shrink, so this always holds here (checked in debug builds).
    pub fn new(corners: [DVec3; 3]) -> Self {
        let sum = corners[0] + corners[1] + corners[2];
        let direction = sum.normalize_or(corners[0]);
        let cos_extent = corners
            .iter()
            .map(|c| direction.dot(*c))
            .fold(1.0_f64, f64::min);
        debug_assert!(cos_extent > 0.0, "patch wider than 90 degrees (invariant)");
        Self {
            corners,
            direction,
            cos_extent: cos_extent.clamp(0.0, 1.0),
        }
    }

    /// The four children: one at each corner and the middle one.
    pub fn split(&self) -> [Self; 4] {
        let [a, b, c] = self.corners;
        let ab = (a + b).normalize_or(a);
        let bc = (b + c).normalize_or(b);
        let ca = (c + a).normalize_or(c);
        [
            Self::new([a, ab, ca]),
            Self::new([ab, b, bc]),
            Self::new([ca, bc, c]),
            Self::new([ab, bc, ca]),
        ]
    }

    /// The largest distance between the representative point and a point of the patch,
    /// on a sphere of radius `radius`: the chord of the cap's angle.
    pub fn chord(&self, radius: f64) -> f64 {
        radius * (2.0 - 2.0 * self.cos_extent).max(0.0).sqrt()
    }

    /// An upper bound of `max |x − q|` over the points `x = center + radius · u` of the
    /// patch, for any point `q`.
    ///
    /// With `w = q − center`, `|x − q|² = radius² + |w|² − 2 radius (u · w)`, so the
    /// bound maximises `u · (−ŵ)` over the cap containing the patch: 1 when `−ŵ` lies in
    /// the cap, else `cos(α − θ)` with `α` the angle between `direction` and `−ŵ` and `θ`
    /// the cap's angle. Unlike `|p − q| + chord`, this is tight to second order in the
    /// patch size where the error is largest (there `q − x` is along the sphere's normal).
    pub fn max_distance_to(&self, center: DVec3, radius: f64, q: DVec3) -> f64 {
        let w = q - center;
        let w_len = w.length();
        let best_cos = if w_len == 0.0 {
            0.0
        } else {
            let toward = -w / w_len;
            let cos_alpha = self.direction.dot(toward).clamp(-1.0, 1.0);
            let cos_theta = self.cos_extent;
            if cos_alpha >= cos_theta {
                1.0
            } else {
                let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
                let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
                (cos_alpha * cos_theta + sin_alpha * sin_theta).min(1.0)
            }
        };
        let squared = radius * radius + w_len * w_len + 2.0 * radius * w_len * best_cos;
        let bound = squared.max(0.0).sqrt();
        bound + BOUND_SLACK * (radius + w_len + bound)
    }
}

/// What is known at a patch's representative point `p`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Probe {
    /// The distance of `p` to the mesh surface.
    pub distance: f64,
    /// Its closest point on the surface.
    pub closest: DVec3,
    /// Whether the point is classified inside and farther than the guard band from the
    /// surface, where the classification is trusted.
    pub trusted_inside: bool,
}

/// The certified upper bound of `f` (distance to the surface of the points outside the
/// object, 0 inside) on `patch`, from the probe at its representative point.
///
/// - `f(x) ≤ d(x) ≤ |x − q|` for the surface point `q` closest to `p`
///   ([`Patch::max_distance_to`]), whatever the classification;
/// - `f(x) ≤ d(p) + |x − p|` (the distance is 1-Lipschitz), whatever the classification;
/// - when `p` is inside (beyond the guard band): a point `x` of the patch outside the
///   object is separated from `p` by the surface, which the segment `[p, x]` crosses at
///   least `d(p)` from `p`, so `f(x) ≤ |x − p| − d(p)`.
pub(crate) fn upper_bound(patch: &Patch, center: DVec3, radius: f64, probe: &Probe) -> f64 {
    let chord = patch.chord(radius);
    let slack = BOUND_SLACK * (radius + probe.distance);
    let lipschitz = if probe.trusted_inside {
        (chord - probe.distance + slack).max(0.0)
    } else {
        probe.distance + chord + slack
    };
    let closest = patch.max_distance_to(center, radius, probe.closest);
    lipschitz.min(closest)
}

/// The 20 faces of the regular icosahedron, as patches of the unit sphere, in a fixed
/// order.
pub(crate) fn icosahedron() -> Vec<Patch> {
    let phi = f64::midpoint(1.0, 5.0_f64.sqrt());
    let mut vertices = Vec::with_capacity(12);
    for s in [-1.0, 1.0] {
        for t in [-phi, phi] {
            vertices.push(DVec3::new(s, t, 0.0));
            vertices.push(DVec3::new(0.0, s, t));
            vertices.push(DVec3::new(t, 0.0, s));
        }
    }
    // The edges are the pairs at distance 2 (squared 4); the faces, the triples of
    // mutually adjacent vertices.
    let adjacent = |a: DVec3, b: DVec3| (a.distance_squared(b) - 4.0).abs() < 1e-9;
    let mut faces = Vec::with_capacity(20);
    for i in 0..vertices.len() {
        for j in i + 1..vertices.len() {
            for k in j + 1..vertices.len() {
                let (a, b, c) = (vertices[i], vertices[j], vertices[k]);
                if adjacent(a, b) && adjacent(b, c) && adjacent(c, a) {
                    faces.push(Patch::new([a.normalize(), b.normalize(), c.normalize()]));
                }
            }
        }
    }
    faces
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_tests::point_sets::fibonacci_sphere;

    /// Whether `u` lies in the geodesic triangle (on the positive side of the three great
    /// circles through its edges).
    fn in_patch(p: &Patch, u: DVec3) -> bool {
        let [a, b, c] = p.corners;
        let n = (b - a).cross(c - a);
        let s = n.dot(a).signum();
        [(a, b), (b, c), (c, a)]
            .iter()
            .all(|(x, y)| s * x.cross(*y).dot(u) >= -1e-12)
    }

    #[test]
    fn icosahedron_has_twenty_faces_covering_the_sphere() {
        let faces = icosahedron();
        assert_eq!(faces.len(), 20);
        for u in fibonacci_sphere(2000) {
            assert!(faces.iter().any(|f| in_patch(f, u)), "{u} uncovered");
        }
        for f in &faces {
            assert!(
                f.cos_extent > 0.78 && f.cos_extent < 0.8,
                "{}",
                f.cos_extent
            );
        }
    }

    #[test]
    fn children_tile_the_parent() {
        let parent = icosahedron()[3];
        let children = parent.split();
        for u in fibonacci_sphere(20_000) {
            if in_patch(&parent, u) {
                assert!(children.iter().any(|c| in_patch(c, u)));
            }
            for c in &children {
                if in_patch(c, u) {
                    assert!(in_patch(&parent, u));
                }
            }
        }
    }

    #[test]
    fn bounds_hold_on_every_point_of_a_patch() {
        let center = DVec3::new(0.3, -0.2, 0.1);
        let radius = 1.7;
        let mut patches = icosahedron();
        for _ in 0..2 {
            patches = patches.iter().flat_map(Patch::split).collect();
        }
        let dirs = fibonacci_sphere(30_000);
        for q in [
            DVec3::ZERO,
            DVec3::new(3.0, 1.0, -2.0),
            DVec3::new(0.3, -0.2, 1.9),
        ] {
            for patch in patches.iter().step_by(7) {
                let bound = patch.max_distance_to(center, radius, q);
                let chord = patch.chord(radius);
                let p = center + radius * patch.direction;
                for u in dirs.iter().filter(|u| in_patch(patch, **u)) {
                    let x = center + radius * *u;
                    assert!(x.distance(q) <= bound, "{} > {bound}", x.distance(q));
                    assert!(x.distance(p) <= chord + 1e-12);
                }
            }
        }
    }

    #[test]
    fn closest_point_bound_is_second_order_at_the_top() {
        // q straight below the patch's representative point: the bound exceeds the
        // distance at p by O(chord²), not O(chord).
        let patch = icosahedron()[0].split()[0].split()[0].split()[0];
        let radius = 1.0;
        let p = radius * patch.direction;
        let q = 0.5 * patch.direction;
        let bound = patch.max_distance_to(DVec3::ZERO, radius, q);
        let chord = patch.chord(radius);
        assert!(bound - p.distance(q) < 0.5 * chord * chord + 1e-9);
        assert!(bound - p.distance(q) < 0.2 * chord);
    }
}
