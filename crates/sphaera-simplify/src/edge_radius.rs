//! The error-sphere radius of a full-edge collapse (the merged vertex moves to a new
//! position), for `Placement::Optimal`.
//!
//! Collapsing the interior edge `h = (u → v)` with the merged vertex at `t` replaces the
//! *region* `R = star(u) ∪ star(v)` (every triangle touching `u` or `v`) by the *new fan*
//! `N`: the link polygon of the edge (the boundary of `R`, vertices `w` with their radii
//! `r_w` unchanged) coned from `t`. The result is stored at `v` with a new radius `r_t`;
//! triangles outside `R` touch neither `u` nor `v` and do not change.
//!
//! # Why a map suffices
//!
//! Let `φ: R → N` be onto, fix the link polygon, and satisfy
//! `r_new(φ(p)) ≥ |p − φ(p)| + r_old(p)` for every `p ∈ R` (`r_old`, `r_new` the radii
//! interpolated over the old and new triangles). Then, for the crate's invariants:
//!
//! - **(A)** a point `x` of the original surface covered by an old triangle of `R` has a
//!   point `p` there with `|x − p| ≤ r_old(p)`, so `|x − φ(p)| ≤ |x − p| + |p − φ(p)| ≤
//!   r_new(φ(p))`: it is in the tolerance volume of the new triangle holding `φ(p)`;
//! - **(B)** every `y ∈ N` is some `φ(p)`, and `dist(y, M0) ≤ |y − p| + dist(p, M0) ≤
//!   |y − p| + r_old(p) ≤ r_new(y)`.
//!
//! # The simple map (always available)
//!
//! `φ` is affine on each old triangle, sends `u` and `v` to `t` and fixes the link
//! vertices. An old triangle `(u, a, b)` or `(v, a, b)` goes onto the new triangle
//! `(t, a, b)` (every new triangle is hit, so `φ` is onto), and the two triangles on the
//! edge, `(u, v, w)`, flatten onto the new spoke `t–w`. A point with weights `λ` moves by
//! `|p − φ(p)| = |λ_u (u − t) + λ_v (v − t)| ≤ λ_u |u − t| + λ_v |v − t|`, and the
//! radius needed is `r_new(φ(p)) = (λ_u + λ_v) r_t + Σ_w λ_w r_w` against `r_old(p) +
//! |p − φ(p)| ≤ λ_u (r_u + |u − t|) + λ_v (r_v + |v − t|) + Σ_w λ_w r_w`, so
//!
//! `r_t ≥ max(r_u + |u − t|, r_v + |v − t|)` suffices.
//!
//! It is rigorous but loose: it grows with the distance moved even on a flat region.
//!
//! # The tight projected map
//!
//! Project `R` and `N` onto a plane (normal `n`). When both projections are injective,
//! `φ` pairs the points with the same projection; it fixes the link polygon and is affine
//! on each cell of the overlay of the two projected triangulations (both affine in the
//! projected coordinates there), as are `r_old` and `r_new`. The slack
//! `s(p) = |p − φ(p)| + r_old(p) − r_new(φ(p))` is then convex on each (convex) cell: a
//! norm of an affine map plus an affine map. So `s ≤ 0` everywhere iff `s ≤ 0` at the
//! overlay vertices:
//!
//! - the link vertices (`φ(w) = w`, equal radii: `s = 0`, nothing to check);
//! - `u` and `v`, lifted into the new fan;
//! - `t`, located in the old region;
//! - every crossing of an old interior edge (`u–w`, `v–w`, `u–v`) with a new spoke `t–x`
//!   (`x ≠ w`: a shared link endpoint is a link vertex).
//!
//! At an overlay vertex `p ↦ q`, with `q` in the new triangle `(t, a, b)` with weights
//! `λ`, `r_new(q) = λ_t r_t + λ_a r_a + λ_b r_b` is affine in the one unknown `r_t`, so
//! `s ≤ 0` iff `r_t ≥ (|p − q| + r_old(p) − λ_a r_a − λ_b r_b) / λ_t`. Unlike the
//! half-edge collapse (where `v` keeps triangles outside the moved fan and so keeps at
//! least its old radius), every triangle of `u` and `v` is replaced here: the old `r_u`
//! and `r_v` only enter through `r_old`, and the answer is the maximum of these bounds
//! over the overlay vertices (and 0).
//!
//! *Injectivity.* Every projected old triangle is positively oriented and the projected
//! angles around `u` and around `v` each sum to one turn, so the projection of the disk
//! `R` is a local homeomorphism; every projected new triangle is positively oriented and
//! the angles around `t` sum to one turn, so the projected link polygon is star-shaped
//! from `t`, hence a simple closed curve, and `N` projects injectively onto its inside. A
//! local homeomorphism of a closed disk whose boundary goes to a simple closed curve is a
//! homeomorphism onto that curve's inside (each inside point has as many preimages as
//! the curve's winding number around it, which is 1), so both projections are bijections
//! onto the same polygon. (Checking only the angle sums around `u` and `v` is not enough:
//! a long spike of `star(u)` can overlap `star(v)`.)
//!
//! *Planes.* Any plane with injective projections gives a valid bound, so three are
//! tried and the smallest result kept: the region's area-weighted normal, and those of
//! `star(u)` and `star(v)`. With `t = v`, `star(u)`'s plane reproduces the half-edge
//! collapse of `crate::spheres` (on `v`'s other triangles `φ` is the identity and needs
//! `r_t ≥ r_v` only), so the full-edge radius is never worse there (when `star(v)` also
//! projects injectively onto that plane).
//!
//! # Rounding
//!
//! Each bound adds `ROUNDING_MARGIN` times the region's coordinate scale to the demand
//! before dividing by `λ_t` (rounding in the overlay geometry is amplified by `1 / λ_t`
//! too), and the result gets a final relative margin; `λ_t` below `MIN_WEIGHT_TARGET`
//! makes the tight map give up (the simple one remains).

use crate::spheres::crossing;
use glam::{DVec2, DVec3};
use sphaera_mesh::topology::{HalfEdgeId, HalfEdgeMesh, VertexId};

/// The smallest accepted sine of a projected corner angle (and, in 3D, of a new
/// triangle's shape): below it a triangle counts as folded or degenerate.
const MIN_SINE: f64 = 1e-9;

/// How far a sum of projected angles around a vertex may be from `2π` (radians).
const ANGLE_SUM_TOLERANCE: f64 = 1e-6;

/// The smallest weight of `t` accepted at an overlay vertex of the tight map.
const MIN_WEIGHT_TARGET: f64 = 1e-9;

/// The relative safety margin against floating-point rounding (relative to the largest
/// absolute coordinate of the region, and to the radius itself).
const ROUNDING_MARGIN: f64 = 1e-12;

/// How far outside a triangle (in barycentric weight) a located point may fall.
const LOCATE_SLACK: f64 = 1e-9;

/// The radius the merged vertex needs after collapsing the interior edge `h = (u → v)`
/// with the merged vertex placed at `target` (stored at `v`), or `None` when the collapse
/// is refused geometrically.
///
/// The value is the smaller of the tight projected map's bound (when some projection is
/// injective) and the simple map's `max(r_u + |u − t|, r_v + |v − t|)`, plus a rounding
/// margin; see the module docs for the derivation. Both guarantee invariants (A) and (B)
/// over `star(u) ∪ star(v)`.
///
/// `None` when: `u` or `v` is on the boundary (not supported yet), `target` is not
/// finite, a vertex has fewer than three triangles, a new triangle would flip its normal
/// (more than 90° from the old triangle it replaces) or degenerate, or the radius is not
/// finite. `radii` is indexed by half-edge-mesh vertex (a missing entry counts as
/// infinite). Topology (link condition, locks, non-manifold vertices) is the caller's
/// business ([`HalfEdgeMesh::check_collapse`]).
///
/// # Performance
///
/// `O((d_u + d_v)²)` per tried plane (three planes), for the valences `d_u`, `d_v`; a few
/// small allocations.
pub(crate) fn edge_collapse_radius(
    mesh: &HalfEdgeMesh,
    radii: &[f64],
    h: HalfEdgeId,
    target: DVec3,
) -> Option<f64> {
    let region = Region::gather(mesh, radii, h, target)?;
    if !region.new_triangles_keep_their_orientation() {
        return None;
    }
    let mut best = region.simple_radius();
    for normal in region.candidate_normals() {
        if let Some(r) = region.tight_radius(normal) {
            best = best.min(r);
        }
    }
    let r = best + ROUNDING_MARGIN * region.scale.max(best);
    r.is_finite().then_some(r)
}

/// A vertex of the region.
#[derive(Clone, Copy, Debug)]
struct Node {
    position: DVec3,
    radius: f64,
}

/// The region of a full-edge collapse, with local vertex indices: 0 is `u`, 1 is `v`, the
/// others the link polygon.
#[derive(Clone, Debug)]
struct Region {
    nodes: Vec<Node>,
    /// The old triangles `(u, a, b)`, counter-clockwise: the whole fan of `u`.
    fan_u: Vec<(usize, usize)>,
    /// The old triangles `(v, a, b)`: the whole fan of `v` (two are also in `fan_u`).
    fan_v: Vec<(usize, usize)>,
    /// The new triangles `(t, a, b)` and the apex (0 or 1) of the old triangle each
    /// replaces.
    new: Vec<(usize, usize, usize)>,
    target: DVec3,
    /// The largest absolute coordinate of the region and `target`.
    scale: f64,
}

impl Region {
    /// Collects the region, or `None` if `h` touches the boundary, `target` is not finite
    /// or a fan has fewer than three triangles.
    fn gather(mesh: &HalfEdgeMesh, radii: &[f64], h: HalfEdgeId, target: DVec3) -> Option<Self> {
        let (u, v) = (mesh.origin(h), mesh.target(h));
        if u == v || !target.is_finite() || mesh.is_boundary_vertex(u) {
            return None;
        }
        if mesh.is_boundary_vertex(v) {
            return None;
        }
        let mut ids = vec![u, v];
        let mut fan = |x: VertexId| -> Vec<(usize, usize)> {
            mesh.outgoing(x)
                .map(|g| {
                    let a = local_index(&mut ids, mesh.target(g));
                    let b = local_index(&mut ids, mesh.origin(mesh.prev(g)));
                    (a, b)
                })
                .collect()
        };
        let fan_u = fan(u);
        let fan_v = fan(v);
        if fan_u.len() < 3 || fan_v.len() < 3 || !fan_u.iter().any(|&(a, _)| a == 1) {
            return None;
        }
        let new = fan_u
            .iter()
            .filter(|&&(a, b)| a != 1 && b != 1)
            .map(|&(a, b)| (a, b, 0))
            .chain(
                fan_v
                    .iter()
                    .filter(|&&(a, b)| a != 0 && b != 0)
                    .map(|&(a, b)| (a, b, 1)),
            )
            .collect();
        let nodes: Vec<Node> = ids
            .iter()
            .map(|&x| Node {
                position: mesh.position(x),
                radius: radii.get(x.0 as usize).copied().unwrap_or(f64::INFINITY),
            })
            .collect();
        let scale = nodes
            .iter()
            .map(|n| n.position)
            .chain([target])
            .fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
        Some(Self {
            nodes,
            fan_u,
            fan_v,
            new,
            target,
            scale,
        })
    }

    fn position(&self, i: usize) -> DVec3 {
        self.nodes.get(i).map_or(DVec3::NAN, |n| n.position)
    }

    fn radius(&self, i: usize) -> f64 {
        self.nodes.get(i).map_or(f64::INFINITY, |n| n.radius)
    }

    /// Every old triangle once, as `(apex, a, b)` with apex 0 or 1.
    fn old_triangles(&self) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        let from_u = self.fan_u.iter().map(|&(a, b)| (0, a, b));
        let from_v = self
            .fan_v
            .iter()
            .filter(|&&(a, b)| a != 0 && b != 0)
            .map(|&(a, b)| (1, a, b));
        from_u.chain(from_v)
    }

    /// Whether every new triangle keeps its normal within 90° of the old triangle it
    /// replaces and is not degenerate.
    fn new_triangles_keep_their_orientation(&self) -> bool {
        let t = self.target;
        self.new.iter().all(|&(a, b, apex)| {
            let (pa, pb, po) = (self.position(a), self.position(b), self.position(apex));
            let new_normal = (pa - t).cross(pb - t);
            let old_normal = (pa - po).cross(pb - po);
            let longest = (pa - t)
                .length_squared()
                .max((pb - t).length_squared())
                .max((pa - pb).length_squared());
            new_normal.dot(old_normal) > 0.0 && new_normal.length() > MIN_SINE * longest
        })
    }

    /// The simple map's radius (module docs), without margin.
    fn simple_radius(&self) -> f64 {
        let t = self.target;
        (self.radius(0) + (self.position(0) - t).length())
            .max(self.radius(1) + (self.position(1) - t).length())
    }

    /// The normals of the planes tried for the tight map: the region's, `star(u)`'s and
    /// `star(v)`'s (area-weighted).
    fn candidate_normals(&self) -> [DVec3; 3] {
        let normal = |tris: &mut dyn Iterator<Item = (usize, usize, usize)>| {
            tris.fold(DVec3::ZERO, |n, (o, a, b)| {
                let po = self.position(o);
                n + (self.position(a) - po).cross(self.position(b) - po)
            })
        };
        [
            normal(&mut self.old_triangles()),
            normal(&mut self.fan_u.iter().map(|&(a, b)| (0, a, b))),
            normal(&mut self.fan_v.iter().map(|&(a, b)| (1, a, b))),
        ]
    }

    /// The tight projected map's radius for the plane of `normal` (module docs), or
    /// `None` if a projection is not injective or the computation is ill-conditioned.
    fn tight_radius(&self, normal: DVec3) -> Option<f64> {
        let normal = normal.try_normalize()?;
        let (e1, e2) = normal.any_orthonormal_pair();
        let origin = 0.5 * (self.position(0) + self.position(1));
        let project = |p: DVec3| DVec2::new((p - origin).dot(e1), (p - origin).dot(e2));
        let flat: Vec<DVec2> = self.nodes.iter().map(|n| project(n.position)).collect();
        let at = |i: usize| flat.get(i).copied().unwrap_or(DVec2::NAN);
        let t2 = project(self.target);
        let t = self.target;

        // Both projections injective (module docs).
        let old_u = self.fan_u.iter().map(|&(a, b)| (at(a), at(b)));
        let old_v = self.fan_v.iter().map(|&(a, b)| (at(a), at(b)));
        let new = self.new.iter().map(|&(a, b, _)| (at(a), at(b)));
        if !is_one_turn(at(0), old_u) || !is_one_turn(at(1), old_v) || !is_one_turn(t2, new) {
            return None;
        }

        let margin = ROUNDING_MARGIN * self.scale;
        let mut needed = 0.0_f64;
        // u and v, lifted into the new fan.
        for apex in [0, 1] {
            let (l, (a, b, _)) = locate(
                at(apex),
                self.new
                    .iter()
                    .map(|&(a, b, o)| ([t2, at(a), at(b)], (a, b, o))),
            )?;
            let q = l[0] * t + l[1] * self.position(a) + l[2] * self.position(b);
            let demand = (self.position(apex) - q).length() + self.radius(apex)
                - l[1] * self.radius(a)
                - l[2] * self.radius(b);
            needed = needed.max(required(demand + margin, l[0])?);
        }
        // t, located in the old region (weight 1 on t).
        let (l, (o, a, b)) = locate(
            t2,
            self.old_triangles()
                .map(|(o, a, b)| ([at(o), at(a), at(b)], (o, a, b))),
        )?;
        let p = l[0] * self.position(o) + l[1] * self.position(a) + l[2] * self.position(b);
        let r_old = l[0] * self.radius(o) + l[1] * self.radius(a) + l[2] * self.radius(b);
        needed = needed.max((p - t).length() + r_old + margin);

        // Old interior edges crossing new spokes.
        let old_edges = self.fan_u.iter().map(|&(a, _)| (0, a)).chain(
            self.fan_v
                .iter()
                .filter(|&&(a, _)| a != 0)
                .map(|&(a, _)| (1, a)),
        );
        for (e0, e1) in old_edges {
            for &(x, _, _) in &self.new {
                if x == e1 {
                    continue;
                }
                let Some((s, tau)) = crossing(at(e0), at(e1), t2, at(x)) else {
                    continue;
                };
                let p = self.position(e0) + s * (self.position(e1) - self.position(e0));
                let r_old = (1.0 - s) * self.radius(e0) + s * self.radius(e1);
                let q = t + tau * (self.position(x) - t);
                let demand = (p - q).length() + r_old - tau * self.radius(x);
                needed = needed.max(required(demand + margin, 1.0 - tau)?);
            }
        }
        Some(needed)
    }
}

/// The local index of `x`, appending it if new.
fn local_index(ids: &mut Vec<VertexId>, x: VertexId) -> usize {
    if let Some(i) = ids.iter().position(|&y| y == x) {
        i
    } else {
        ids.push(x);
        ids.len() - 1
    }
}

/// Whether the planar fan of triangles `(center, a, b)` is positively oriented (corner
/// sines above [`MIN_SINE`]) and turns exactly once around `center`.
fn is_one_turn(center: DVec2, fan: impl Iterator<Item = (DVec2, DVec2)>) -> bool {
    let mut sum = 0.0;
    for (a, b) in fan {
        let (da, db) = (a - center, b - center);
        let cross = da.perp_dot(db);
        if cross.is_nan() || cross <= MIN_SINE * da.length() * db.length() {
            return false;
        }
        sum += cross.atan2(da.dot(db));
    }
    (sum - std::f64::consts::TAU).abs() <= ANGLE_SUM_TOLERANCE
}

/// The triangle of `tris` holding `p` best (largest smallest weight) and `p`'s weights
/// there, or `None` if `p` is outside all of them by more than [`LOCATE_SLACK`].
fn locate<T>(p: DVec2, tris: impl Iterator<Item = ([DVec2; 3], T)>) -> Option<([f64; 3], T)> {
    let mut best: Option<(f64, [f64; 3], T)> = None;
    for (corners, tag) in tris {
        let Some(l) = barycentric(p, corners) else {
            continue;
        };
        let worst = l[0].min(l[1]).min(l[2]);
        if best.as_ref().is_none_or(|(w, _, _)| worst > *w) {
            best = Some((worst, l, tag));
        }
    }
    let (worst, l, tag) = best?;
    (worst >= -LOCATE_SLACK).then_some((l, tag))
}

/// Barycentric coordinates of `p` in the planar triangle `c`, or `None` if degenerate.
fn barycentric(p: DVec2, c: [DVec2; 3]) -> Option<[f64; 3]> {
    let area = (c[1] - c[0]).perp_dot(c[2] - c[0]);
    if area.is_nan() || area.abs() <= f64::MIN_POSITIVE {
        return None;
    }
    let l0 = (c[1] - p).perp_dot(c[2] - p) / area;
    let l1 = (c[2] - p).perp_dot(c[0] - p) / area;
    Some([l0, l1, 1.0 - l0 - l1])
}

/// The radius of `t` for which `weight · r ≥ demand` (others already subtracted), or
/// `None` when the weight is too small to trust.
fn required(demand: f64, weight: f64) -> Option<f64> {
    (weight >= MIN_WEIGHT_TARGET).then(|| (demand / weight).max(0.0))
}

#[cfg(test)]
mod tests;
