//! The error-sphere radius a half-edge collapse needs (the tight, projected map).
//!
//! For a collapse of an interior vertex `u` into a neighbour `v`, both the old fan of `u`
//! and the new fan (the same link polygon, triangulated from `v`) are projected onto the
//! plane of the old fan's area-weighted normal. When both projections are injective, the
//! map φ that sends a point of the old fan to the point of the new fan with the same
//! projection is a bijection fixing the link polygon, affine on every cell of the overlay
//! of the two projected triangulations. The new radius `r_v'` must satisfy
//! `r_new(φ(p)) ≥ |p − φ(p)| + r_old(p)` everywhere; the slack of that inequality is convex
//! on each cell, so checking it at the overlay vertices (the projected fan vertices and the
//! crossings of old spokes `u–w_i` with new spokes `v–w_j`) is exact.
//!
//! The parts that depend only on `u` are computed once per vertex by [`Fan`]; this module
//! holds the entry point for one collapse, the boundary case and the planar helpers.

use glam::DVec2;
use sphaera_mesh::topology::{HalfEdgeId, HalfEdgeMesh, VertexId};

mod fan;

pub(crate) use fan::Fan;

/// The smallest accepted sine of a projected corner angle: below it a projected triangle
/// counts as folded or degenerate and the collapse is refused.
const MIN_SINE: f64 = 1e-9;

/// How far the sum of the projected angles around `u` may be from `2π` (radians).
const ANGLE_SUM_TOLERANCE: f64 = 1e-6;

/// The smallest barycentric weight of `v` accepted at an overlay vertex (below it the
/// needed radius is ill-conditioned and the collapse is refused).
const MIN_WEIGHT_V: f64 = 1e-12;

/// The relative size of the safety margin added to each computed radius, against
/// floating-point rounding (relative to the largest absolute coordinate of the fan).
const ROUNDING_MARGIN: f64 = 1e-12;

/// The radius vertex `v = target(h)` needs after collapsing `h` (its origin `u` into `v`,
/// `v` keeping its position), or `None` when the collapse is refused geometrically: `u` is
/// on the boundary, the projected old or new fan folds, a new triangle would be a sliver or
/// flip its normal, or the computation is ill-conditioned.
///
/// Topology (link condition, locks, non-manifold vertices) is the caller's business
/// ([`HalfEdgeMesh::check_collapse`]). `radii` is indexed by half-edge-mesh vertex.
///
/// The computation lives in [`Fan`]: to evaluate every collapse out of one vertex, build
/// its fan once and use [`Fan::best`] (same radii, bit for bit).
pub(crate) fn collapse_radius(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    h: HalfEdgeId,
    boundary: BoundaryPolicy,
) -> Option<f64> {
    let u = mesh.origin(h);
    if mesh.is_boundary_vertex(u) {
        return match boundary {
            BoundaryPolicy::Lock => None,
            BoundaryPolicy::Collapse => boundary_collapse_radius(mesh, radii, h),
        };
    }
    Fan::new(mesh, radii, u)?.radius(h)
}

/// The radius the engine uses for collapsing `h`: for an interior vertex the smaller of
/// the tight map's [`collapse_radius`] and the simple map's [`simple_map_radius`] (both
/// are rigorous), for a boundary vertex [`collapse_radius`].
pub(crate) fn edge_radius(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    h: HalfEdgeId,
    boundary: BoundaryPolicy,
) -> Option<f64> {
    let tight = collapse_radius(mesh, radii, h, boundary);
    if mesh.is_boundary_vertex(mesh.origin(h)) {
        return tight;
    }
    match (tight, simple_map_radius(mesh, radii, h)) {
        (Some(t), Some(s)) => Some(t.min(s)),
        (t, s) => t.or(s),
    }
}

/// What to do with boundary vertices.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BoundaryPolicy {
    /// Never remove them.
    Lock,
    /// Remove them along boundary edges, with the simple map (see
    /// [`boundary_collapse_radius`]).
    Collapse,
}

/// The radius for collapsing a boundary vertex `u` along its outgoing boundary half-edge
/// `h` into `v`, or `None` if `h` is not a boundary half-edge or a triangle would flip or
/// become a sliver.
///
/// The map is the simple one, affine on each old triangle and sending `u` to `v` (the
/// triangle on the edge degenerates onto the edge `v–w`, which stays in the mesh). It is
/// onto the new fan, which is all the invariants need, and a point with weight `λ_u` on
/// `u` moves by `λ_u |u − v|`, so `r_v' = max(r_v, r_u + |u − v|)` suffices. It is rigorous
/// but loose (it grows with edge length even on flat regions), so the error-driven order
/// takes boundary collapses late.
fn boundary_collapse_radius(mesh: &HalfEdgeMesh, radii: &[f64], h: HalfEdgeId) -> Option<f64> {
    if mesh.twin(h).is_some() {
        return None;
    }
    simple_map_radius(mesh, radii, h)
}

/// The radius of the simple map for collapsing `h` (its origin `u` into its target `v`):
/// `max(r_v, r_u + |u − v|)` plus the rounding margin, or `None` if a new triangle would
/// flip or become a sliver. Valid for any edge (see [`boundary_collapse_radius`] for why):
/// the fallback where the projected map folds, and a cap where it is ill-conditioned
/// (steep or thin fans, where the tight map can be far worse).
pub(crate) fn simple_map_radius(mesh: &HalfEdgeMesh, radii: &[f64], h: HalfEdgeId) -> Option<f64> {
    let u = mesh.origin(h);
    let v = mesh.target(h);
    let radius = |x: VertexId| radii.get(x.0 as usize).copied().unwrap_or(f64::INFINITY);
    let (pu, pv) = (mesh.position(u), mesh.position(v));
    let mut scale = pu.abs().max_element().max(pv.abs().max_element());
    for g in mesh.outgoing(u) {
        let (a, b) = (mesh.target(g), mesh.origin(mesh.prev(g)));
        if a == v || b == v {
            continue;
        }
        let (pa, pb) = (mesh.position(a), mesh.position(b));
        scale = scale
            .max(pa.abs().max_element())
            .max(pb.abs().max_element());
        let new_normal = (pa - pv).cross(pb - pv);
        let old_normal = (pa - pu).cross(pb - pu);
        let longest = (pa - pv)
            .length_squared()
            .max((pb - pv).length_squared())
            .max((pa - pb).length_squared());
        if new_normal.dot(old_normal) <= 0.0 || new_normal.length() <= MIN_SINE * longest {
            return None;
        }
    }
    let needed = radius(v).max(radius(u) + (pu - pv).length());
    Some(needed + ROUNDING_MARGIN * scale.max(needed))
}

/// The radius at `v` for which `weight_v · r + others ≥ demand`, or `None` if the weight
/// of `v` is too small for the computation to be meaningful.
fn required(demand: f64, others: f64, weight_v: f64) -> Option<f64> {
    if weight_v < MIN_WEIGHT_V {
        return None;
    }
    Some(((demand - others) / weight_v).max(0.0))
}

/// Barycentric coordinates of `p` in the planar triangle `(a, b, c)`, or `None` if it is
/// degenerate.
fn barycentric(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> Option<[f64; 3]> {
    let area = (b - a).perp_dot(c - a);
    if area.abs() <= f64::MIN_POSITIVE {
        return None;
    }
    let la = (b - p).perp_dot(c - p) / area;
    let lb = (c - p).perp_dot(a - p) / area;
    Some([la, lb, 1.0 - la - lb])
}

/// Where the planar segments `a0–a1` and `b0–b1` cross, as the parameters `(s, t)` along
/// each (clamped to `[0, 1]`), or `None` if they do not cross or are parallel (parallel
/// overlaps add no overlay vertex beyond the endpoints, which are checked separately).
/// The fan code shares parts between pairs through [`crossing_parts`]; this is the
/// one-pair entry point (the full-edge collapse radius and the tests use it).
pub(crate) fn crossing(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2) -> Option<(f64, f64)> {
    let (da, db) = (a1 - a0, b1 - b0);
    let d = b0 - a0;
    crossing_parts(
        da.perp_dot(db),
        da.length(),
        db.length(),
        d.perp_dot(db),
        d.perp_dot(da),
    )
}

/// Where the planar segments `a0–a1` and `b0–b1` cross, as the parameters `(s, t)` along
/// each (clamped to `[0, 1]`), or `None` if they do not cross or are parallel (parallel
/// overlaps add no overlay vertex beyond the endpoints, which are checked separately);
/// computed from parts that callers share between many pairs: with
/// `da = a1 − a0`, `db = b1 − b0` and `d = b0 − a0`, the arguments are `da ⟂ db`, `|da|`,
/// `|db|`, `d ⟂ db` and `d ⟂ da` (`⟂` the perp-dot product).
fn crossing_parts(
    denom: f64,
    da_length: f64,
    db_length: f64,
    d_perp_db: f64,
    d_perp_da: f64,
) -> Option<(f64, f64)> {
    const SLACK: f64 = 1e-9;
    // Cheap rejection without dividing: a quotient clearly outside
    // `[−2·SLACK, 1 + 2·SLACK]` rounds to a value outside `[−SLACK, 1 + SLACK]` too (the
    // margin is orders of magnitude above the rounding of the products), so this only
    // skips pairs the exact test below rejects. Most pairs of spokes do not cross.
    let (lo, hi) = (-2.0 * SLACK, 1.0 + 2.0 * SLACK);
    let clearly_outside = |num: f64| {
        if denom > 0.0 {
            num < lo * denom || num > hi * denom
        } else if denom < 0.0 {
            num > lo * denom || num < hi * denom
        } else {
            false
        }
    };
    if clearly_outside(d_perp_db) || clearly_outside(d_perp_da) {
        return None;
    }
    let s = d_perp_db / denom;
    let t = d_perp_da / denom;
    let inside = |x: f64| (-SLACK..=1.0 + SLACK).contains(&x);
    // Tested after the range (the cheap rejection of most pairs); a zero `denom` gives
    // an infinite or NaN parameter, which is not inside either.
    if !(inside(s) && inside(t)) || denom.abs() <= 1e-14 * da_length * db_length {
        return None;
    }
    Some((s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use glam::DVec3;

    /// A hexagonal fan around the origin lifted by `height` at the centre.
    fn hexagon(height: f64) -> HalfEdgeMesh {
        let mut p = vec![DVec3::new(0.0, 0.0, height)];
        for k in 0..6 {
            let a = f64::from(k) * std::f64::consts::TAU / 6.0;
            p.push(DVec3::new(a.cos(), a.sin(), 0.0));
        }
        let t: Vec<[u32; 3]> = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        HalfEdgeMesh::from_trimesh(&sphaera_mesh::TriMesh::new(p, t).unwrap())
    }

    /// The half-edge from the centre to rim vertex 1.
    fn center_to_rim(mesh: &HalfEdgeMesh) -> HalfEdgeId {
        mesh.outgoing(VertexId(0))
            .find(|&g| mesh.target(g) == VertexId(1))
            .unwrap()
    }

    #[test]
    fn flat_fan_collapses_at_the_rounding_margin_only() {
        let mesh = hexagon(0.0);
        let h = center_to_rim(&mesh);
        let r = collapse_radius(&mesh, &[0.0; 7], h, BoundaryPolicy::Lock).unwrap();
        // Only the rounding margin (1e-12 of the coordinates); the simple map would need 1.
        assert!(r < 2e-12, "flat collapse costs {r}");
    }

    #[test]
    fn raised_centre_needs_at_least_its_height() {
        let height = 0.3;
        let mesh = hexagon(height);
        let h = center_to_rim(&mesh);
        let r = collapse_radius(&mesh, &[0.0; 7], h, BoundaryPolicy::Lock).unwrap();
        // The centre must be covered, and every new point is at least `height` from it.
        assert!(r >= height);
        // And the tight map does no worse than the simple one.
        let simple = (mesh.position(VertexId(0)) - mesh.position(VertexId(1))).length();
        assert!(r <= simple * (1.0 + 1e-9), "tight {r} vs simple {simple}");
    }

    #[test]
    fn boundary_vertex_is_refused_when_locked() {
        let mesh = hexagon(0.0);
        // A rim vertex is on the boundary.
        let h = mesh.outgoing(VertexId(1)).next().unwrap();
        assert!(collapse_radius(&mesh, &[0.0; 7], h, BoundaryPolicy::Lock).is_none());
    }

    #[test]
    fn crossing_of_perpendicular_segments() {
        let (s, t) = crossing(
            DVec2::new(-1.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, -1.0),
            DVec2::new(0.0, 3.0),
        )
        .unwrap();
        assert_relative_eq!(s, 0.5);
        assert_relative_eq!(t, 0.25);
        assert!(crossing(DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::new(1.0, 1.0)).is_none());
    }

    #[test]
    fn barycentric_reconstructs_point() {
        let (a, b, c) = (DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::new(0.0, 3.0));
        let p = DVec2::new(0.5, 0.75);
        let l = barycentric(p, a, b, c).unwrap();
        let back = l[0] * a + l[1] * b + l[2] * c;
        assert_relative_eq!(back.x, p.x, epsilon = 1e-15);
        assert_relative_eq!(back.y, p.y, epsilon = 1e-15);
    }

    #[test]
    fn required_radius_clamps_at_zero_and_refuses_small_weight() {
        assert_eq!(required(1.0, 2.0, 0.5), Some(0.0));
        assert_eq!(required(1.0, 0.0, 0.5), Some(2.0));
        assert_eq!(required(1.0, 0.0, 0.0), None);
    }
}
