//! Lofting: a sequence of circles (rings) joined into a closed triangle surface.
//!
//! Every round shape of [`crate::shapes`] is a loft: a surface of revolution is a loft of
//! circles around the z axis, a swept tube is a loft of circles along its centre curve.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::{MAX_VERTICES, check_vertex_budget};
use crate::{MeshError, TriMesh};

/// One circle of a loft: `center + radius (cos θ u + sin θ v)`, or a single pole vertex
/// when `radius` is zero.
///
/// The orientation convention: rings are listed along a direction `d` with `u × v = d`
/// (θ turns counter-clockwise seen from the tip of `d`) for a swept tube; for a surface
/// of revolution (`u = x`, `v = y`) the profile runs counter-clockwise in the `(ρ, z)`
/// half-plane. Either way the triangles face outward.
#[derive(Clone, Copy, Debug)]
pub(super) struct Ring {
    pub center: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub radius: f64,
}

impl Ring {
    fn is_pole(&self) -> bool {
        self.radius == 0.0
    }
}

/// Joins `rings` (each with `segments` vertices, poles with one) into a mesh.
///
/// `closed` joins the last ring to the first (a torus); otherwise the first and last rings
/// must be poles (cap centres) so the surface is closed. Poles never appear elsewhere and
/// two poles are never adjacent (an invariant of the callers in this module).
pub(super) fn loft(
    shape: &'static str,
    rings: &[Ring],
    closed: bool,
    segments: usize,
) -> Result<TriMesh, MeshError> {
    // Both counts were bounded by `check_vertex_budget` in the callers; checking again
    // here keeps this function safe on its own.
    check_vertex_budget(shape, rings.len() as f64 * segments as f64)?;
    let mut positions = Vec::with_capacity(rings.len() * segments);
    let mut first_vertex = Vec::with_capacity(rings.len());
    for ring in rings {
        first_vertex.push(positions.len() as u32);
        if ring.is_pole() {
            positions.push(ring.center);
        } else {
            positions.extend((0..segments).map(|k| {
                let theta = TAU * k as f64 / segments as f64;
                ring.center + ring.radius * (theta.cos() * ring.u + theta.sin() * ring.v)
            }));
        }
    }
    debug_assert!(positions.len() <= MAX_VERTICES);

    let pair_count = if closed {
        rings.len()
    } else {
        rings.len().saturating_sub(1)
    };
    let mut triangles = Vec::with_capacity(2 * pair_count * segments);
    let seg = segments as u32;
    for i in 0..pair_count {
        let j = (i + 1) % rings.len();
        let (a, b) = (first_vertex[i], first_vertex[j]);
        for k in 0..seg {
            let k1 = (k + 1) % seg;
            match (rings[i].is_pole(), rings[j].is_pole()) {
                (false, false) => {
                    triangles.push([a + k, a + k1, b + k1]);
                    triangles.push([a + k, b + k1, b + k]);
                }
                (true, false) => triangles.push([a, b + k1, b + k]),
                (false, true) => triangles.push([a + k, a + k1, b]),
                // Two adjacent poles would make degenerate triangles; callers never
                // produce them (invariant), and emitting nothing keeps the mesh valid.
                (true, true) => {}
            }
        }
    }
    TriMesh::new(positions, triangles)
}

/// A profile in the `(ρ, z)` half-plane, built from points, lines and arcs with a target
/// spacing between consecutive points.
#[derive(Debug, Default)]
pub(super) struct Profile {
    pub points: Vec<DVec2>,
}

impl Profile {
    /// Starts the profile at `p`.
    pub fn start(p: DVec2) -> Self {
        Self { points: vec![p] }
    }

    /// The last point (the origin for an empty profile).
    fn last(&self) -> DVec2 {
        self.points.last().copied().unwrap_or(DVec2::ZERO)
    }

    /// Appends the straight line from the last point to `to`, in `pieces` equal steps
    /// (the end point included, the start point not).
    pub fn line_to(&mut self, to: DVec2, pieces: usize) {
        let from = self.last();
        let pieces = pieces.max(1);
        self.points
            .extend((1..=pieces).map(|i| from.lerp(to, i as f64 / pieces as f64)));
    }

    /// Appends the arc of the circle `center`, `radius` from angle `from` to angle `to`
    /// (radians, from the ρ axis towards z), in `pieces` equal steps (end included).
    pub fn arc(&mut self, center: DVec2, radius: f64, from: f64, to: f64, pieces: usize) {
        let pieces = pieces.max(1);
        self.points.extend((1..=pieces).map(|i| {
            let angle = from + (to - from) * i as f64 / pieces as f64;
            center + radius * DVec2::new(angle.cos(), angle.sin())
        }));
    }

    /// Revolves the profile around the z axis with `segments` vertices per circle.
    ///
    /// Points with `ρ = 0` become poles; `closed` joins the last point to the first.
    pub fn revolve(
        &self,
        shape: &'static str,
        closed: bool,
        segments: usize,
    ) -> Result<TriMesh, MeshError> {
        let rings: Vec<Ring> = self
            .points
            .iter()
            .map(|p| Ring {
                center: DVec3::new(0.0, 0.0, p.y),
                u: DVec3::X,
                v: DVec3::Y,
                // Snap tiny radii from rounding to an exact pole.
                radius: if p.x.abs() <= 1e-15 * p.y.abs().max(1.0) {
                    0.0
                } else {
                    p.x
                },
            })
            .collect();
        loft(shape, &rings, closed, segments)
    }
}

/// Number of pieces so that `length` is cut into steps of at most about `spacing`
/// (at least one).
pub(super) fn pieces(length: f64, spacing: f64) -> usize {
    // Both are finite and positive (validated by callers) and the vertex budget bounds the
    // ratio before any allocation, so the conversion saturates at worst.
    ((length / spacing).round() as usize).max(1)
}
