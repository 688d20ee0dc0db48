//! Where a point lies in a closed outline or a closed mesh, and whether two outlines or two
//! solids meet: the brute-force references of the HAL tests, written here rather than in
//! `sphaera-hal` so that the crate under test is not its own judge.
//!
//! Each answer is reached by a different route than HAL's:
//!
//! - in 2D, a point is located by its **winding number** (Sunday's edge-by-edge count with
//!   exact orientation tests), the even–odd rule taken from its parity; HAL counts ray
//!   crossings. Two segments meet by the strict-sign rule, collinear ones by the overlap
//!   of their endpoints in lexicographic order; HAL tests bounding boxes;
//! - in 3D, a point is located by its **generalised winding number**: every triangle's solid
//!   angle, with the sign of its determinant exact, so that points a rounding away from
//!   a face fall on the right side. Points exactly on a face are found by exact
//!   orientation tests. Two surfaces meet by parry3d-f64's intersection test; HAL shoots
//!   rays and tests triangle pairs with its own predicates.
//!
//! The functions take slices and `sphaera-mesh`'s `TriMesh`, not HAL's types, so they judge
//! whatever HAL builds from the same points.
//!
//! # Examples
//!
//! ```
//! use sphaera_mesh::glam::DVec2;
//! use sphaera_mesh::{DVec3, TriMesh, shapes};
//! use sphaera_tests::regions::{self, Side};
//!
//! let square = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)].map(DVec2::from);
//! assert_eq!(regions::locate_in_outline(&square, DVec2::new(1.0, 1.0)), Side::Inside);
//! assert_eq!(regions::locate_in_outline(&square, DVec2::new(2.0, 1.0)), Side::Boundary);
//!
//! let cube = shapes::cube(1.0, 2).unwrap();
//! assert_eq!(regions::locate_in_solid(&cube, DVec3::ZERO), Side::Inside);
//! assert_eq!(regions::locate_in_solid(&cube, DVec3::splat(0.5)), Side::Boundary);
//! let moved = TriMesh::new(
//!     cube.positions().iter().map(|&p| p + DVec3::X * 0.9).collect(),
//!     cube.triangles().to_vec(),
//! )
//! .unwrap();
//! assert!(regions::solids_meet(&cube, &moved));
//! ```

use std::f64::consts::TAU;

use parry3d_f64::math::Pose;
use parry3d_f64::query;
use parry3d_f64::shape::{TriMesh as ParryTriMesh, TriMeshFlags};
use sphaera_mesh::glam::DVec2;
use sphaera_mesh::{DVec3, TriMesh};

/// Where a point lies with respect to a closed outline or surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// Strictly inside (odd winding number).
    Inside,
    /// Exactly on the outline or the surface.
    Boundary,
    /// Strictly outside (even winding number).
    Outside,
}

fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    let p = |v: DVec2| robust::Coord { x: v.x, y: v.y };
    robust::orient2d(p(a), p(b), p(c))
}

fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// `a` before or equal to `b` in lexicographic order (x, then y).
fn lex_le(a: DVec2, b: DVec2) -> bool {
    (a.x, a.y) <= (b.x, b.y)
}

/// Whether the closed segments `ab` and `cd` share a point, exactly.
#[must_use]
pub fn segments_meet(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let (c_side, d_side) = (orient2d(a, b, c), orient2d(a, b, d));
    let (a_side, b_side) = (orient2d(c, d, a), orient2d(c, d, b));
    let apart = |s: f64, t: f64| (s > 0.0 && t > 0.0) || (s < 0.0 && t < 0.0);
    if apart(c_side, d_side) || apart(a_side, b_side) {
        return false;
    }
    if [c_side, d_side, a_side, b_side].iter().any(|&s| s != 0.0) {
        return true;
    }
    // All four points on one line, where lexicographic order is the order along it.
    let ordered = |p: DVec2, q: DVec2| if lex_le(p, q) { (p, q) } else { (q, p) };
    let ((a0, a1), (c0, c1)) = (ordered(a, b), ordered(c, d));
    lex_le(a0, c1) && lex_le(c0, a1)
}

/// Whether `x` lies on the closed segment `ab`, exactly.
fn on_segment(a: DVec2, b: DVec2, x: DVec2) -> bool {
    segments_meet(a, b, x, x)
}

/// Where `x` lies with respect to the closed outline through `ring` (the last point joins
/// the first): on an edge, or inside or outside by the parity of its winding number (the
/// even–odd rule, which HAL's crossing count follows for self-crossing outlines too).
///
/// A ring of fewer than two points has no edges: every point is outside.
#[must_use]
pub fn locate_in_outline(ring: &[DVec2], x: DVec2) -> Side {
    let edges = || (0..ring.len()).map(|i| (ring[i], ring[(i + 1) % ring.len()]));
    if ring.len() < 2 {
        return Side::Outside;
    }
    if edges().any(|(a, b)| on_segment(a, b, x)) {
        return Side::Boundary;
    }
    // Sunday's winding number: an upward edge with `x` strictly left of it counts +1, a
    // downward edge with `x` strictly right of it −1 (half-open in y).
    let mut winding = 0_i64;
    for (a, b) in edges() {
        if a.y <= x.y {
            if b.y > x.y && orient2d(a, b, x) > 0.0 {
                winding += 1;
            }
        } else if b.y <= x.y && orient2d(a, b, x) < 0.0 {
            winding -= 1;
        }
    }
    if winding % 2 == 0 {
        Side::Outside
    } else {
        Side::Inside
    }
}

/// Whether two outlines meet as GEOS sees them (a closed outline is a region, an open
/// one a curve): their edges share a point, or a closed one holds a vertex of the other
/// (with disjoint boundaries, a region meets a connected outline only when it holds the
/// whole of it, whatever the fill rule). An outline with a single point has no edges and
/// meets nothing.
#[must_use]
pub fn outlines_meet(
    first: &[DVec2],
    first_closed: bool,
    second: &[DVec2],
    second_closed: bool,
) -> bool {
    let edges = |points: &[DVec2], closed: bool| -> Vec<(DVec2, DVec2)> {
        let n = points.len();
        let count = if closed && n > 2 {
            n
        } else {
            n.saturating_sub(1)
        };
        (0..count)
            .map(|i| (points[i], points[(i + 1) % n]))
            .collect()
    };
    let (e, f) = (edges(first, first_closed), edges(second, second_closed));
    if e.iter()
        .any(|&(a, b)| f.iter().any(|&(c, d)| segments_meet(a, b, c, d)))
    {
        return true;
    }
    let holds = |ring: &[DVec2], x: Option<&DVec2>| {
        x.is_some_and(|&x| locate_in_outline(ring, x) != Side::Outside)
    };
    (second_closed && holds(second, first.first()))
        || (first_closed && holds(first, second.first()))
}

/// Whether `x` lies on the closed triangle `t`, exactly: on its plane, and inside it in
/// each of the three coordinate projections (at least one of which is not flat for a
/// triangle of positive area; a degenerate triangle is reduced to its bounding box on
/// its line).
fn on_triangle(t: [DVec3; 3], x: DVec3) -> bool {
    if orient3d(t[0], t[1], t[2], x) != 0.0 {
        return false;
    }
    let projections: [fn(DVec3) -> DVec2; 3] = [
        |p| DVec2::new(p.x, p.y),
        |p| DVec2::new(p.y, p.z),
        |p| DVec2::new(p.z, p.x),
    ];
    let within = |project: fn(DVec3) -> DVec2| {
        let [a, b, c] = t.map(project);
        let q = project(x);
        let s = [orient2d(a, b, q), orient2d(b, c, q), orient2d(c, a, q)];
        !(s.iter().any(|&v| v > 0.0) && s.iter().any(|&v| v < 0.0))
    };
    let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
    projections.into_iter().all(within) && x.cmpge(lo).all() && x.cmple(hi).all()
}

/// The solid angle of triangle `t` seen from `x`, signed by its orientation, with the
/// sign of the determinant exact (Van Oosterom and Strackee's formula).
fn solid_angle(t: [DVec3; 3], x: DVec3) -> f64 {
    let [a, b, c] = t.map(|p| p - x);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let determinant = orient3d(t[0], t[1], t[2], x);
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * determinant.atan2(denominator)
}

/// Where `x` lies with respect to the closed surface `mesh`: exactly on a face, or inside
/// or outside by the parity of its generalised winding number (the sum of the faces'
/// solid angles over 4π). A mesh without triangles holds nothing.
///
/// # Panics
///
/// When the winding number is not within 0.1 of an integer, which for a closed mesh
/// means the sum lost its precision (a point off every face by less than the rounding of
/// a solid angle): the test that asked then cannot be judged, and says so.
#[must_use]
pub fn locate_in_solid(mesh: &TriMesh, x: DVec3) -> Side {
    let corners = |t: &[u32; 3]| t.map(|v| mesh.positions()[v as usize]);
    if mesh.triangles().iter().any(|t| on_triangle(corners(t), x)) {
        return Side::Boundary;
    }
    let total: f64 = mesh
        .triangles()
        .iter()
        .map(|t| solid_angle(corners(t), x))
        .sum();
    let winding = total / (2.0 * TAU);
    let nearest = winding.round();
    assert!(
        (winding - nearest).abs() < 0.1,
        "winding number {winding} at {x} is not near an integer: is the mesh closed?"
    );
    // `nearest` is a small integer held exactly; its parity decides.
    if nearest.rem_euclid(2.0) == 0.0 {
        Side::Outside
    } else {
        Side::Inside
    }
}

/// parry3d-f64's mesh of `mesh`'s triangles as they are (no flags: nothing merged or
/// oriented), or `None` when it has none.
fn parry_mesh(mesh: &TriMesh) -> Option<ParryTriMesh> {
    if mesh.triangles().is_empty() {
        return None;
    }
    let built = ParryTriMesh::with_flags(
        mesh.positions().to_vec(),
        mesh.triangles().to_vec(),
        TriMeshFlags::empty(),
    );
    Some(built.unwrap_or_else(|e| panic!("parry refuses the mesh: {e}")))
}

/// Whether two closed meshes meet as solids: their surfaces share a point
/// ([`surfaces_meet`]), or one holds a vertex of the other ([`locate_in_solid`]). A mesh without triangles meets
/// nothing.
///
/// # Panics
///
/// When parry refuses a mesh or the pair (it takes every triangle mesh with
/// triangles), or as [`locate_in_solid`].
#[must_use]
pub fn solids_meet(first: &TriMesh, second: &TriMesh) -> bool {
    if first.triangles().is_empty() || second.triangles().is_empty() {
        return false;
    }
    let holds = |solid: &TriMesh, x: DVec3| locate_in_solid(solid, x) != Side::Outside;
    surfaces_meet(first, second)
        || holds(second, first.positions()[0])
        || holds(first, second.positions()[0])
}

/// Whether two triangle soups share a point: parry3d-f64's intersection test, triangle
/// against triangle under its bounding-volume trees. Open, non-manifold and degenerate
/// meshes are fine; a mesh without triangles meets nothing.
///
/// # Panics
///
/// When parry refuses a mesh or the pair (it takes every triangle mesh with triangles).
#[must_use]
pub fn surfaces_meet(first: &TriMesh, second: &TriMesh) -> bool {
    let (Some(a), Some(b)) = (parry_mesh(first), parry_mesh(second)) else {
        return false;
    };
    let identity = Pose::identity();
    query::intersection_test(&identity, &a, &identity, &b)
        .expect("parry tests a triangle mesh against a triangle mesh")
        .intersecting
}
