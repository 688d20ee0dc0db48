//! Intersection detection of two 3D HAL trees (section 5.2 of the paper), one placed
//! against the other by a similarity, with exact triangle tests at the leaves; and its
//! brute-force reference.

use std::ops::ControlFlow;

use glam::DVec3;
use sphaera_mesh::TriMesh;
use sphaera_mesh::geometry::Similarity;

use crate::tree3::{Bound3, circle};
use crate::{Containment, HalTree3, Node3};

fn coord(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn o3(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    robust::orient3d(coord(a), coord(b), coord(c), coord(d))
}

/// The 2D coordinates of `p` with the axis `drop` removed.
fn flat(p: DVec3, drop: usize) -> robust::Coord<f64> {
    let (x, y) = match drop {
        0 => (p.y, p.z),
        1 => (p.z, p.x),
        _ => (p.x, p.y),
    };
    robust::Coord { x, y }
}

/// The axis along which the normal of `t` is largest (dropped to project it).
fn dominant_axis(t: [DVec3; 3]) -> usize {
    let n = (t[1] - t[0]).cross(t[2] - t[0]).abs();
    if n.x >= n.y && n.x >= n.z {
        0
    } else if n.y >= n.z {
        1
    } else {
        2
    }
}

/// Whether two coplanar triangles share a point (exact, in their common projection).
fn coplanar_meet(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    let drop = dominant_axis(t);
    let a = t.map(|p| flat(p, drop));
    let b = u.map(|p| flat(p, drop));
    let o = robust::orient2d;
    let segments = |p: robust::Coord<f64>,
                    q: robust::Coord<f64>,
                    r: robust::Coord<f64>,
                    s: robust::Coord<f64>| {
        let within = |p: robust::Coord<f64>, q: robust::Coord<f64>, r: robust::Coord<f64>| {
            r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
        };
        let (d1, d2, d3, d4) = (o(p, q, r), o(p, q, s), o(r, s, p), o(r, s, q));
        (((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)))
            || (d1 == 0.0 && within(p, q, r))
            || (d2 == 0.0 && within(p, q, s))
            || (d3 == 0.0 && within(r, s, p))
            || (d4 == 0.0 && within(r, s, q))
    };
    // A point in a triangle of positive area. A flat one (a segment or a point: the edge
    // `[p, q, q]` of `segment_meets_triangle`) holds nothing its edges do not: every point
    // on its line would pass the three orientation tests.
    let inside = |t: [robust::Coord<f64>; 3], q: robust::Coord<f64>| {
        if o(t[0], t[1], t[2]) == 0.0 {
            return false;
        }
        let d = [o(t[0], t[1], q), o(t[1], t[2], q), o(t[2], t[0], q)];
        d.iter().all(|&v| v >= 0.0) || d.iter().all(|&v| v <= 0.0)
    };
    for i in 0..3 {
        for j in 0..3 {
            if segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]) {
                return true;
            }
        }
    }
    inside(a, b[0]) || inside(b, a[0])
}

/// Whether the closed segment `p q` meets the closed triangle `t` (exact).
fn segment_meets_triangle(p: DVec3, q: DVec3, t: [DVec3; 3]) -> bool {
    let [a, b, c] = t;
    let (sp, sq) = (o3(a, b, c, p), o3(a, b, c, q));
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        // In the plane: a degenerate triangle on the segment.
        return coplanar_meet(t, [p, q, q]);
    }
    let e = [o3(p, q, a, b), o3(p, q, b, c), o3(p, q, c, a)];
    e.iter().all(|&v| v >= 0.0) || e.iter().all(|&v| v <= 0.0)
}

/// Whether two closed triangles share a point (exact orientation tests): coplanar ones in
/// their plane, others when an edge of one meets the other.
#[must_use]
pub fn triangles_meet(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    let side = |t: [DVec3; 3], p: DVec3| o3(t[0], t[1], t[2], p);
    let su = u.map(|p| side(t, p));
    if su.iter().all(|&v| v > 0.0) || su.iter().all(|&v| v < 0.0) {
        return false;
    }
    let st = t.map(|p| side(u, p));
    if st.iter().all(|&v| v > 0.0) || st.iter().all(|&v| v < 0.0) {
        return false;
    }
    if su.iter().all(|&v| v == 0.0) {
        return coplanar_meet(t, u);
    }
    (0..3).any(|i| segment_meets_triangle(t[i], t[(i + 1) % 3], u))
        || (0..3).any(|i| segment_meets_triangle(u[i], u[(i + 1) % 3], t))
}

/// Whether two closed meshes intersect, by brute force: the reference for
/// [`HalTree3::intersects`]. Their surfaces share a point, or one holds a vertex of the
/// other (by [`crate::contains3_brute`]). A mesh without triangles meets nothing.
#[must_use]
pub fn intersects3_brute(first: &TriMesh, second: &TriMesh) -> bool {
    let (Some(&[f, _, _]), Some(&[g, _, _])) =
        (first.triangles().first(), second.triangles().first())
    else {
        return false;
    };
    let corners = |m: &TriMesh, t: [u32; 3]| t.map(|v| m.positions()[v as usize]);
    for &t in first.triangles() {
        for &u in second.triangles() {
            if triangles_meet(corners(first, t), corners(second, u)) {
                return true;
            }
        }
    }
    let within = |m: &TriMesh, p: DVec3| crate::contains3_brute(m, p) != Containment::Outside;
    within(second, first.positions()[f as usize]) || within(first, second.positions()[g as usize])
}

/// A region of space bounding part of a surface: a ball, a closed half-space
/// `(z − point)·normal ≥ 0`, or everything.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Region {
    Ball(DVec3, f64),
    HalfSpace(DVec3, DVec3),
    Everything,
}

impl Region {
    /// How far `x` lies outside the region (negative or zero inside it): a lower bound on
    /// the distance from `x` to anything the region holds.
    pub(crate) fn distance_outside(self, x: DVec3) -> f64 {
        match self {
            Self::Everything => f64::NEG_INFINITY,
            Self::Ball(c, r) => x.distance(c) - r,
            Self::HalfSpace(p, n) => -(x - p).dot(n),
        }
    }

    /// Whether the ray from `x` along axis `AXIS` (toward `+∞` when `POSITIVE`) may meet
    /// the region grown by `slack` (false only when it certainly does not: conservative,
    /// so also for the ray moved infinitesimally off `x`).
    #[inline]
    pub(crate) fn meets_axis_ray<const AXIS: usize, const POSITIVE: bool>(
        self,
        x: DVec3,
        slack: f64,
    ) -> bool {
        let (u, v) = ((AXIS + 1) % 3, (AXIS + 2) % 3);
        match self {
            Self::Everything => true,
            Self::Ball(c, r) => {
                let (du, dv) = (c[u] - x[u], c[v] - x[v]);
                let reach = r + slack;
                let ahead = if POSITIVE {
                    c[AXIS] - x[AXIS]
                } else {
                    x[AXIS] - c[AXIS]
                };
                du * du + dv * dv <= reach * reach && ahead >= -reach
            }
            Self::HalfSpace(p, n) => {
                let rate = if POSITIVE { n[AXIS] } else { -n[AXIS] };
                rate > 0.0 || (x - p).dot(n) >= -slack
            }
        }
    }

    /// Whether the two regions may meet (false only when certainly apart).
    fn meets(self, other: Self, slack: f64) -> bool {
        match (self, other) {
            (Self::Everything, _) | (_, Self::Everything) => true,
            (Self::Ball(c, r), Self::Ball(d, s)) => c.distance(d) <= r + s + slack,
            (Self::Ball(c, r), Self::HalfSpace(p, n))
            | (Self::HalfSpace(p, n), Self::Ball(c, r)) => (c - p).dot(n) >= -r - slack,
            (Self::HalfSpace(p, n), Self::HalfSpace(q, m)) => {
                (n + m).length() > 1e-12 || (q - p).dot(n) >= -slack
            }
        }
    }
}

/// A node's bounding volume in placed coordinates: the intersection of two regions.
///
/// The paper's section 5.2 also pairs *unions* of two balls (its cases 2 and 3). Those
/// are not used: a union of two balls through one circle is not convex, so it holds the
/// patch's vertices but not necessarily the faces between them (the test
/// `volumes_hold_their_patch_faces` finds a cube patch whose face leaves its union). A
/// union bound is replaced by the smallest ball holding both balls, which is convex and
/// holds the faces.
#[derive(Clone, Copy, Debug)]
struct Volume {
    regions: [Region; 2],
}

impl Volume {
    /// Whether two volumes may meet: each region of one meets each of the other (the
    /// paper's case 1, necessary for two intersections to meet).
    fn meets(&self, other: &Self, slack: f64) -> bool {
        self.regions
            .iter()
            .all(|a| other.regions.iter().all(|&b| a.meets(b, slack)))
    }
}

/// The smallest region holding two regions (a ball around two balls; everything when a
/// half-space is involved).
fn hull(a: Region, b: Region) -> Region {
    match (a, b) {
        (Region::Ball(c, r), Region::Ball(d, s)) => {
            let gap = c.distance(d);
            if gap + s <= r {
                a
            } else if gap + r <= s {
                b
            } else {
                let radius = 0.5 * (gap + r + s);
                let center = c + (d - c) * ((radius - r) / gap);
                // A relative margin for the rounding of the centre.
                Region::Ball(center, radius * (1.0 + 1e-12))
            }
        }
        _ => Region::Everything,
    }
}

/// Bulges beyond this (balls over a million times wider than their circle) are taken as
/// the half-space holding them.
const FLAT_BULGE: f64 = 1e6;

/// The volume of `node` with its corners mapped by `map`.
fn volume(node: &Node3, mesh: &TriMesh, map: &Similarity) -> Volume {
    let corners = node
        .corners
        .map(|v| map.point(mesh.positions()[v as usize]));
    let Some(bound) = node.bound else {
        // A leaf: the ball around its face.
        let center = (corners[0] + corners[1] + corners[2]) / 3.0;
        let radius = corners
            .iter()
            .map(|c| c.distance(center))
            .fold(0.0, f64::max);
        let ball = Region::Ball(center, radius);
        return Volume {
            regions: [ball, ball],
        };
    };
    Volume {
        regions: bound_regions(&bound, corners),
    }
}

/// The relative growth of every ball of a bounding volume: its radius is grown by
/// `BALL_SLACK` times (its centre's largest coordinate plus its radius), which bounds the
/// rounding of the centre (`origin + offset + k·R·n`, see `Circle`) and of the radius
/// with a wide margin (a few `2⁻⁵³` of those magnitudes, since the origin, the offset and
/// `k·R` are each within the ball's reach of its centre). The balls' bulges hold the
/// patch's vertices for the circle as computed (`HalTree3::bound`), so a ball so grown
/// holds them for the exact one, whatever the coordinates' magnitude: the slack scales
/// with the coordinates, never absolute.
pub(crate) const BALL_SLACK: f64 = 1e-12;

/// The two convex regions whose intersection holds the patch of a node with bound `bound`
/// over the triangle `corners`: its two balls (or half-spaces) for an intersection; the
/// ball around both, twice, for a union (which is not convex); everything for a
/// degenerate triangle. Planes pass through a corner (exact input, where the
/// circumcentre would be rounded); balls are computed relative to that corner and grown
/// by [`BALL_SLACK`].
pub(crate) fn bound_regions(bound: &Bound3, corners: [DVec3; 3]) -> [Region; 2] {
    let Some(circle) = circle(corners) else {
        return [Region::Everything, Region::Everything];
    };
    let (origin, radius, normal) = (circle.origin, circle.radius, circle.normal);
    let region = |k: f64| {
        if k == f64::INFINITY {
            Region::HalfSpace(origin, normal)
        } else if k == f64::NEG_INFINITY {
            Region::HalfSpace(origin, -normal)
        } else if k.abs() > FLAT_BULGE {
            // A ball this flat has a radius too large to compare distances with; the
            // half-space just beyond its cap holds it (twice the cap's depth below the
            // plane, `R / (√(1 + k²) + |k|)`).
            let depth = 2.0 * radius / ((1.0 + k * k).sqrt() + k.abs());
            if k > 0.0 {
                Region::HalfSpace(origin - normal * depth, normal)
            } else {
                Region::HalfSpace(origin + normal * depth, -normal)
            }
        } else {
            let center = origin + (circle.offset + normal * (k * radius));
            let reach = radius * (1.0 + k * k).sqrt();
            Region::Ball(
                center,
                reach + BALL_SLACK * (center.abs().max_element() + reach),
            )
        }
    };
    let (above, below) = (region(bound.above), region(bound.below));
    if bound.is_intersection() {
        [above, below]
    } else {
        let ball = hull(above, below);
        [ball, ball]
    }
}

impl HalTree3 {
    /// Intersection detection (section 5.2) with `other` placed by `placement` (mapping
    /// `other`'s coordinates into this tree's): pairs of nodes whose bounding volumes may
    /// meet (a union bound taken as the ball around its two balls, see below) are
    /// refined, the wider first, down to pairs of original faces tested exactly; when the
    /// surfaces are apart, the solids still intersect if one holds a vertex of the other.
    /// Equal to [`intersects3_brute`] on `other`'s mesh mapped by `placement`.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_hal::HalTree3;
    /// use sphaera_mesh::geometry::Similarity;
    /// use sphaera_mesh::{DVec3, shapes};
    ///
    /// let ball = HalTree3::build(&shapes::sphere(1.0, 12)?)?;
    /// let near = Similarity::from_translation(DVec3::new(1.5, 0.0, 0.0))?;
    /// let far = Similarity::from_translation(DVec3::new(3.0, 0.0, 0.0))?;
    /// assert!(ball.intersects(&ball, &near));
    /// assert!(!ball.intersects(&ball, &far));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn intersects(&self, other: &Self, placement: &Similarity) -> bool {
        let Some(slack) = self.placed_slack(other, placement) else {
            // Balls apart: neither the surfaces meet nor does one solid hold the other.
            return false;
        };
        if self
            .meeting_faces(other, placement, slack, |_, _| ControlFlow::Break(()))
            .is_break()
        {
            return true;
        }
        let (mine, theirs) = (self.mesh(), other.mesh());
        // Surfaces apart: one solid inside the other? (A tree's mesh was checked closed,
        // so it has a triangle.)
        let first = mine.positions()[mine.triangles()[0][0] as usize];
        let second = placement.point(theirs.positions()[theirs.triangles()[0][0] as usize]);
        if self.contains(second) != Containment::Outside {
            return true;
        }
        let back = Similarity::new(placement.affine().inverse())
            .map_or(first, |inverse| inverse.point(first));
        other.contains(back) != Containment::Outside
    }

    /// Every pair of faces that meet, this tree's face first and `other`'s (placed by
    /// `placement`) second, ascending: the pair traversal of [`HalTree3::intersects`]
    /// carried to the end instead of stopping at the first pair (the paper's section 5.2,
    /// "the iteration must be continued until all intersecting boundary faces are
    /// found"), each pair tested exactly by [`triangles_meet`] on `other`'s corners mapped
    /// by `placement`. Only the surfaces: a solid inside the other without touching it
    /// gives no pair (where [`HalTree3::intersects`] says true).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_hal::{HalTree3, triangles_meet};
    /// use sphaera_mesh::geometry::Similarity;
    /// use sphaera_mesh::{DVec3, TriMesh};
    ///
    /// let tetrahedron = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let tree = HalTree3::build(&tetrahedron)?;
    /// // A copy moved so that its corner 0 lies inside the first one's bottom face 0.
    /// let shift = DVec3::new(0.25, 0.25, 0.0);
    /// let pairs = tree.intersecting_faces(&tree, &Similarity::from_translation(shift)?);
    /// // Every pair of faces that meet, as testing all pairs finds them.
    /// let corners = |t: [u32; 3], by: DVec3| t.map(|v| tetrahedron.positions()[v as usize] + by);
    /// let mut all = Vec::new();
    /// for (i, &t) in tetrahedron.triangles().iter().enumerate() {
    ///     for (j, &u) in tetrahedron.triangles().iter().enumerate() {
    ///         if triangles_meet(corners(t, DVec3::ZERO), corners(u, shift)) {
    ///             all.push((i, j));
    ///         }
    ///     }
    /// }
    /// assert_eq!(pairs, all);
    /// // The two bottoms overlap in their plane; the copy's faces at its corner 0 touch the
    /// // first one's bottom there.
    /// assert!(pairs.contains(&(0, 0)) && pairs.contains(&(0, 1)) && pairs.contains(&(0, 2)));
    /// let apart = Similarity::from_translation(DVec3::new(3.0, 0.0, 0.0))?;
    /// assert!(tree.intersecting_faces(&tree, &apart).is_empty());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Performance
    ///
    /// As [`HalTree3::intersects`] when the surfaces meet nowhere; otherwise every pair of
    /// nodes whose volumes may meet is refined down to its faces, so the cost grows with
    /// the length of the intersection curve.
    #[must_use]
    pub fn intersecting_faces(&self, other: &Self, placement: &Similarity) -> Vec<(usize, usize)> {
        let Some(slack) = self.placed_slack(other, placement) else {
            return Vec::new();
        };
        let mut pairs = Vec::new();
        let _ = self.meeting_faces(other, placement, slack, |a, b| {
            pairs.push((a as usize, b as usize));
            ControlFlow::Continue(())
        });
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }

    /// The slack of placed comparisons (relative to both placed meshes' largest
    /// coordinates, from their root balls in constant time), or `None` when the root balls
    /// are apart.
    fn placed_slack(&self, other: &Self, placement: &Similarity) -> Option<f64> {
        let (a, b) = (self.root_ball(), other.root_ball());
        let (ca, cb, rb) = (
            a.center,
            placement.point(b.center),
            b.radius * placement.scale(),
        );
        let reach = |c: DVec3, r: f64| (c.abs().max_element() + r) * (1.0 + 1e-12);
        let slack = 1e-9 * (reach(ca, a.radius) + reach(cb, rb)).max(f64::MIN_POSITIVE);
        (ca.distance(cb) <= a.radius + rb + slack).then_some(slack)
    }

    /// The pair traversal: pairs of nodes whose volumes may meet are refined, the wider
    /// first, down to pairs of faces; `meet` is called with each pair of faces that meet
    /// (this tree's, `other`'s), and the traversal stops when it breaks.
    fn meeting_faces(
        &self,
        other: &Self,
        placement: &Similarity,
        slack: f64,
        mut meet: impl FnMut(u32, u32) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let (mine, theirs) = (self.mesh(), other.mesh());
        let identity = Similarity::IDENTITY;
        let mut stack: Vec<(u32, u32)> = Vec::new();
        for &a in self.roots() {
            for &b in other.roots() {
                stack.push((a, b));
            }
        }
        while let Some((a, b)) = stack.pop() {
            let (na, nb) = (&self.nodes()[a as usize], &other.nodes()[b as usize]);
            let (va, vb) = (volume(na, mine, &identity), volume(nb, theirs, placement));
            if !va.meets(&vb, slack) {
                continue;
            }
            match (na.children.is_empty(), nb.children.is_empty()) {
                (true, true) => {
                    for &f in &nb.faces {
                        let u = theirs.triangles()[f as usize]
                            .map(|v| placement.point(theirs.positions()[v as usize]));
                        for &g in &na.faces {
                            let t =
                                mine.triangles()[g as usize].map(|v| mine.positions()[v as usize]);
                            if triangles_meet(t, u) {
                                meet(g, f)?;
                            }
                        }
                    }
                }
                (false, true) => stack.extend(na.children.iter().map(|&c| (c, b))),
                (true, false) => stack.extend(nb.children.iter().map(|&c| (a, c))),
                (false, false) => {
                    if na.width >= nb.width * placement.scale() {
                        stack.extend(na.children.iter().map(|&c| (c, b)));
                    } else {
                        stack.extend(nb.children.iter().map(|&c| (a, c)));
                    }
                }
            }
        }
        ControlFlow::Continue(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sphaera_mesh::shapes;

    impl Region {
        fn holds(self, x: DVec3, slack: f64) -> bool {
            match self {
                Self::Everything => true,
                Self::Ball(c, r) => c.distance(x) <= r + slack,
                Self::HalfSpace(p, n) => (x - p).dot(n) >= -slack,
            }
        }
    }

    /// The same far from the origin and at tiny and huge scales, with a slack relative
    /// to the coordinates' magnitude only (`1e-12` of it, where the balls grow by
    /// [`BALL_SLACK`]).
    #[test]
    fn volumes_hold_their_patch_faces_at_any_scale_and_offset() {
        let shapes = [
            shapes::sphere(1.0, 12).unwrap(),
            shapes::cube(1.0, 3).unwrap(),
            shapes::ellipsoid(DVec3::new(2.0, 1.0, 0.5), 10).unwrap(),
        ];
        for mesh in &shapes {
            for (scale, offset) in [
                (1e-6, 1.0),
                (1e-6, 0.0),
                (1e6, 1e12),
                (1.0, 1e6),
                (1e-3, -1e3),
            ] {
                let mesh = TriMesh::new(
                    mesh.positions()
                        .iter()
                        .map(|&p| p * scale + DVec3::new(offset, -0.7 * offset, 0.3 * offset))
                        .collect(),
                    mesh.triangles().to_vec(),
                )
                .unwrap();
                let diagonal = mesh.bounding_box().diagonal();
                let tree = HalTree3::build(&mesh).unwrap();
                for node in tree.nodes() {
                    let v = volume(node, &mesh, &Similarity::IDENTITY);
                    for &f in &node.faces {
                        let [a, b, c] =
                            mesh.triangles()[f as usize].map(|i| mesh.positions()[i as usize]);
                        for x in [a, b, c, (a + b + c) / 3.0] {
                            let slack = 1e-12 * (x.abs().max_element() + diagonal);
                            let held = v.regions.iter().all(|r| r.holds(x, slack));
                            assert!(held, "{scale}, {offset}: {x} outside {v:?}");
                        }
                    }
                }
            }
        }
    }

    /// Regression: an edge of one triangle lying in the other's plane, on the line of one
    /// of its sides but far from it, was taken as meeting it (the edge, as a flat
    /// triangle, "held" every point of its line).
    #[test]
    fn an_edge_on_the_line_of_a_far_side_does_not_meet() {
        let t = [
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(-1.0, 0.0, -1.0),
            DVec3::new(0.0, 0.0, -1.0),
        ];
        let u = [
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(2.0, -1.0, -1.0),
            DVec3::new(2.0, -1.0, 0.0),
        ];
        assert!(!triangles_meet(t, u) && !triangles_meet(u, t));
        // Moved to touch the side's end, it meets.
        let touching = u.map(|p| p - DVec3::X * 2.0);
        assert!(triangles_meet(t, touching) && triangles_meet(touching, t));
    }

    /// Every point of every face of a patch lies in the node's volume as the
    /// intersection test uses it (vertices, edge midpoints, centroids): a union of two
    /// balls through a circle is not convex, so it need not hold the faces between its
    /// vertices.
    #[test]
    fn volumes_hold_their_patch_faces() {
        let mut meshes = vec![
            shapes::sphere(1.0, 12).unwrap(),
            shapes::cube(1.0, 3).unwrap(),
            shapes::capsule(0.3, 2.0, 10).unwrap(),
            shapes::ellipsoid(DVec3::new(2.0, 1.0, 0.5), 10).unwrap(),
        ];
        if let Some(data) = sphaera_tests::data_dir("volumes_hold_their_patch_faces") {
            // Coplanar-rich: flat bulges and half-spaces.
            meshes.push(sphaera_io::load(data.join("fandisk.obj")).unwrap());
        }
        for mesh in &meshes {
            let tree = HalTree3::build(mesh).unwrap();
            for node in tree.nodes() {
                let v = volume(node, mesh, &Similarity::IDENTITY);
                for &f in &node.faces {
                    let [a, b, c] =
                        mesh.triangles()[f as usize].map(|i| mesh.positions()[i as usize]);
                    for x in [
                        a,
                        b,
                        c,
                        (a + b) / 2.0,
                        (b + c) / 2.0,
                        (c + a) / 2.0,
                        (a + b + c) / 3.0,
                    ] {
                        let inside = |r: Region| r.holds(x, 1e-9);
                        let held = inside(v.regions[0]) && inside(v.regions[1]);
                        assert!(held, "{x} outside the volume of {:?} ({v:?})", node.corners);
                    }
                }
            }
        }
    }
}
