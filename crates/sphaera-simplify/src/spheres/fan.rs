//! The projected old fan of an interior vertex, built once and shared by every collapse
//! out of that vertex.
//!
//! [`collapse_radius`](super::collapse_radius) documents the computation. Everything
//! in it that depends only on the removed vertex `u` (the fan, its plane, the projections,
//! the injectivity of the old projection, the old triangle normals, the scale of the
//! rounding margin) is computed here once; [`Fan::radius`] then evaluates one target `v`.
//! Every floating-point expression is the one of the per-target formulation, evaluated in
//! the same order, so the radii are bit-for-bit those of evaluating each target from
//! scratch.
//!
//! [`Fan::best`] finds the cheapest target without evaluating every target in full: the
//! needed radius is a maximum over overlay vertices, and the one at the lifted `u` (`O(d)`
//! for valence `d`) is a lower bound of the full one (`O(d²)` with the spoke crossings).
//! Targets are taken in increasing lower bound, and the scan stops at the first lower bound
//! that cannot beat the best full radius found so far; a full evaluation is abandoned as
//! soon as its partial maximum loses. The result is the exact minimum of the full radii.

use glam::{DVec2, DVec3};
use smallvec::SmallVec;
use sphaera_mesh::topology::{HalfEdgeId, HalfEdgeMesh, VertexId};

use super::{
    ANGLE_SUM_TOLERANCE, MIN_SINE, ROUNDING_MARGIN, barycentric, crossing_parts, required,
};

/// The 3D position and error radius of a vertex of the fan, with its projection.
#[derive(Clone, Copy, Debug)]
struct FanVertex {
    id: VertexId,
    position: DVec3,
    radius: f64,
    /// Projection onto the fan's plane (origin at `u`).
    projected: DVec2,
    /// `projected.length()`.
    projected_length: f64,
}

/// One triangle `(u, a, b)` of the old fan, from the outgoing half-edge `u → a`.
#[derive(Clone, Copy, Debug)]
struct Corner {
    halfedge: HalfEdgeId,
    a: FanVertex,
    b: FanVertex,
    /// `(a − u) × (b − u)`.
    old_normal: DVec3,
    /// `|a − b|²`.
    ab_squared: f64,
}

/// The projected old fan of an interior vertex `u` whose projection is injective.
#[derive(Clone, Debug)]
pub(crate) struct Fan {
    pu: DVec3,
    ru: f64,
    /// The largest absolute coordinate of the fan (the scale of the rounding margin).
    scale: f64,
    corners: SmallVec<[Corner; 12]>,
}

/// A target's lower bound: the needed radius at the lifted `u`, before the crossings.
#[derive(Clone, Copy, Debug)]
struct Lift {
    /// Index of the target's corner (its half-edge `u → v`).
    corner: usize,
    needed: f64,
    /// `with_margin(needed)`, a lower bound of the final radius.
    bound: f64,
}

impl Fan {
    /// The fan of `u`, or `None` when no collapse out of `u` can pass the geometric checks
    /// of the projected map: fewer than three triangles, a zero area-weighted normal, or an
    /// old fan that does not project injectively. `u` must be an interior vertex (its fan
    /// closed); `radii` is indexed by half-edge-mesh vertex (missing entries count as
    /// infinite).
    pub(crate) fn new(mesh: &HalfEdgeMesh, radii: &[f64], u: VertexId) -> Option<Self> {
        let radius = |x: VertexId| radii.get(x.0 as usize).copied().unwrap_or(f64::INFINITY);
        let pu = mesh.position(u);
        let raw: SmallVec<[(HalfEdgeId, VertexId, VertexId); 12]> = mesh
            .outgoing(u)
            .map(|g| (g, mesh.target(g), mesh.origin(mesh.prev(g))))
            .collect();
        if raw.len() < 3 {
            return None;
        }
        let normal = raw.iter().fold(DVec3::ZERO, |n, &(_, a, b)| {
            n + (mesh.position(a) - pu).cross(mesh.position(b) - pu)
        });
        let normal = normal.try_normalize()?;
        let (e1, e2) = normal.any_orthonormal_pair();
        let vertex = |x: VertexId| {
            let position = mesh.position(x);
            let projected = DVec2::new((position - pu).dot(e1), (position - pu).dot(e2));
            FanVertex {
                id: x,
                position,
                radius: radius(x),
                projected,
                projected_length: projected.length(),
            }
        };
        let mut scale = pu.abs().max_element();
        let mut corners: SmallVec<[Corner; 12]> = SmallVec::with_capacity(raw.len());
        for &(halfedge, a, b) in &raw {
            let (a, b) = (vertex(a), vertex(b));
            scale = scale
                .max(a.position.abs().max_element())
                .max(b.position.abs().max_element());
            // The old fan must project injectively: every triangle positively oriented
            // (here), and the angles around u summing to one turn (below).
            let cross = a.projected.perp_dot(b.projected);
            if cross <= MIN_SINE * a.projected_length * b.projected_length {
                return None;
            }
            corners.push(Corner {
                halfedge,
                a,
                b,
                old_normal: (a.position - pu).cross(b.position - pu),
                ab_squared: (a.position - b.position).length_squared(),
            });
        }
        if !winds_once(&corners) {
            return None;
        }
        Some(Self {
            pu,
            ru: radius(u),
            scale,
            corners,
        })
    }

    /// The radius the target of `h` needs (see
    /// [`collapse_radius`](super::collapse_radius)), or `None` if the collapse is
    /// refused; `h` must leave `u`.
    pub(crate) fn radius(&self, h: HalfEdgeId) -> Option<f64> {
        let corner = self.corners.iter().position(|c| c.halfedge == h)?;
        let lift = self.lift(corner)?;
        if !self.new_fan_is_valid(corner) {
            return None;
        }
        self.finish(lift, |_| true)
    }

    /// The cheapest target for which `legal` holds: `(radius, half-edge)`, ties to the
    /// lowest half-edge; exactly the minimum of [`Fan::radius`] over the legal outgoing
    /// half-edges.
    pub(crate) fn best(
        &self,
        mut legal: impl FnMut(HalfEdgeId) -> bool,
    ) -> Option<(f64, HalfEdgeId)> {
        let mut lifts: SmallVec<[Lift; 12]> = (0..self.corners.len())
            .filter_map(|c| self.lift(c))
            .collect();
        let key = |l: &Lift| (l.bound, self.corners[l.corner].halfedge.0);
        lifts.sort_unstable_by(|x, y| {
            let (kx, ky) = (key(x), key(y));
            kx.0.total_cmp(&ky.0).then(kx.1.cmp(&ky.1))
        });
        let mut best: Option<(f64, HalfEdgeId)> = None;
        // Whether `(cost, g)` comes strictly before the best so far.
        let beats = |best: Option<(f64, HalfEdgeId)>, cost: f64, g: HalfEdgeId| {
            best.is_none_or(|(c, b)| cost.total_cmp(&c).then(g.0.cmp(&b.0)).is_lt())
        };
        for lift in lifts {
            let g = self.corners[lift.corner].halfedge;
            // The final radius is at least `lift.bound`, and later targets have larger
            // bounds: nothing from here on can win.
            if !beats(best, lift.bound, g) {
                break;
            }
            if !self.new_fan_is_valid(lift.corner) {
                continue;
            }
            let Some(r) = self.finish(lift, |partial| beats(best, partial, g)) else {
                continue;
            };
            if beats(best, r, g) && legal(g) {
                best = Some((r, g));
            }
        }
        best
    }

    /// `needed` plus the rounding margin (nondecreasing in `needed`).
    fn with_margin(&self, needed: f64) -> f64 {
        needed + ROUNDING_MARGIN * self.scale.max(needed)
    }

    /// The triangles `(a, b)` of the new fan of the target of corner `j`: the triangles of
    /// `u` not containing `v`, to be re-apexed at `v`.
    fn new_fan(&self, j: usize) -> impl Iterator<Item = &Corner> {
        let v = self.corners[j].a.id;
        self.corners
            .iter()
            .filter(move |c| c.a.id != v && c.b.id != v)
    }

    /// The needed radius at the overlay vertex `u'` (the point `u` of the old fan, lifted
    /// onto the new fan: the triangle where its smallest barycentric weight is largest)
    /// for the target of corner `j`, or `None` if that is refused. The other checks of the
    /// new fan are [`Fan::new_fan_is_valid`]'s.
    fn lift(&self, j: usize) -> Option<Lift> {
        let v = self.corners[j].a;
        let (pv, pv2) = (v.position, v.projected);
        let mut best: Option<(f64, [f64; 3], &Corner)> = None;
        for c in self.new_fan(j) {
            let l = barycentric(DVec2::ZERO, pv2, c.a.projected, c.b.projected)?;
            let worst = l[0].min(l[1]).min(l[2]);
            if best.is_none_or(|(w, _, _)| worst > w) {
                best = Some((worst, l, c));
            }
        }
        let (worst, l, c) = best?;
        if worst < -1e-9 {
            return None;
        }
        let (a, b) = (&c.a, &c.b);
        let lifted = l[0] * pv + l[1] * a.position + l[2] * b.position;
        let needed = v.radius.max(required(
            (self.pu - lifted).length() + self.ru,
            l[1] * a.radius + l[2] * b.radius,
            l[0],
        )?);
        Some(Lift {
            corner: j,
            needed,
            bound: self.with_margin(needed),
        })
    }

    /// Whether the new fan of the target of corner `j` projects injectively (every
    /// projected triangle positively oriented) and has no sliver and no triangle whose
    /// normal turns by more than 90° from the old one.
    fn new_fan_is_valid(&self, j: usize) -> bool {
        let v = self.corners[j].a;
        let (pv, pv2) = (v.position, v.projected);
        self.new_fan(j).all(|c| {
            let (a, b) = (&c.a, &c.b);
            let (da, db) = (a.projected - pv2, b.projected - pv2);
            if da.perp_dot(db) <= MIN_SINE * da.length() * db.length() {
                return false;
            }
            let new_normal = (a.position - pv).cross(b.position - pv);
            let longest = (a.position - pv)
                .length_squared()
                .max((b.position - pv).length_squared())
                .max(c.ab_squared);
            new_normal.dot(c.old_normal) > 0.0 && new_normal.length() > MIN_SINE * longest
        })
    }

    /// Completes `lift` with the overlay vertices where an old spoke `u–w` crosses a new
    /// spoke `v–x`: the final radius, or `None` if the collapse is refused or `keep_going`
    /// returns `false` for a partial result (with the margin; the final one is at least
    /// that).
    fn finish(&self, lift: Lift, keep_going: impl Fn(f64) -> bool) -> Option<f64> {
        let v = self.corners[lift.corner].a;
        let (pv, pv2) = (v.position, v.projected);
        let (pu, ru) = (self.pu, self.ru);
        // The parts of `crossing(0, w, pv2, x)` that depend on one spoke only.
        let parts: SmallVec<[(DVec2, f64, f64, f64); 12]> = self
            .corners
            .iter()
            .map(|c| {
                let db = c.a.projected - pv2;
                (
                    db,
                    db.length(),
                    pv2.perp_dot(db),
                    pv2.perp_dot(c.a.projected),
                )
            })
            .collect();
        let mut needed = lift.needed;
        // Every pair of distinct spokes other than v, in any order: the maximum and the
        // refusal do not depend on the order.
        for (cw, &(_, _, _, d_perp_da)) in self.corners.iter().zip(&parts) {
            let w = &cw.a;
            if w.id == v.id {
                continue;
            }
            for (cx, &(db, db_length, d_perp_db, _)) in self.corners.iter().zip(&parts) {
                let x = &cx.a;
                if x.id == v.id || x.id == w.id {
                    continue;
                }
                let denom = w.projected.perp_dot(db);
                let Some((s, t)) =
                    crossing_parts(denom, w.projected_length, db_length, d_perp_db, d_perp_da)
                else {
                    continue;
                };
                let p = pu + s * (w.position - pu);
                let r_old = (1.0 - s) * ru + s * w.radius;
                let q = pv + t * (x.position - pv);
                needed = needed.max(required((p - q).length() + r_old, t * x.radius, 1.0 - t)?);
            }
            if !keep_going(self.with_margin(needed)) {
                return None;
            }
        }
        Some(self.with_margin(needed))
    }
}

/// Whether the projected corners, each positively oriented (checked by the caller), wind
/// once around `u` (the origin): the old fan's projection is then injective.
///
/// This is the test "the angles `atan2(a × b, a · b)` sum to `2π` within
/// [`ANGLE_SUM_TOLERANCE`]", decided without trigonometry: every angle is in `(0, π)`, so
/// when the corners form a closed polygon (`b_i = a_{i+1}`, always so around an interior
/// vertex) the exact sum is `2πk` for the winding number `k`, which is the number of steps
/// `a_i → b_i` going from below the positive x-axis (`y < 0`) to on or above it (a step
/// turning by less than `π` passes angle 0 exactly then). The rounded sum is within
/// about `d · 10⁻¹⁵` of `2πk`, far inside the tolerance, so both tests agree. Should the
/// polygon not close, the sum is computed as before.
fn winds_once(corners: &[Corner]) -> bool {
    let closed = corners
        .iter()
        .zip(corners.iter().cycle().skip(1))
        .all(|(c, next)| c.b.id == next.a.id);
    if closed {
        let up = corners
            .iter()
            .filter(|c| c.a.projected.y < 0.0 && c.b.projected.y >= 0.0)
            .count();
        return up == 1;
    }
    let angle_sum: f64 = corners
        .iter()
        .map(|c| {
            let (a, b) = (c.a.projected, c.b.projected);
            a.perp_dot(b).atan2(a.dot(b))
        })
        .sum();
    (angle_sum - std::f64::consts::TAU).abs() <= ANGLE_SUM_TOLERANCE
}
