//! The "S" swept tube: a circle swept along an S-shaped centre curve, with flat caps.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::{DVec2, DVec3};

use super::loft::{Ring, loft, pieces};
use super::{check_less, check_positive, check_resolution, check_vertex_budget};
use crate::{MeshError, TriMesh};

/// An "S"-shaped tube: a circle of `tube_radius` swept along a centre curve made of two
/// half circles of `bend_radius` in the xy-plane, with flat disc caps at both ends.
///
/// The centre curve starts at `(0, bend_radius, 0)`, turns counter-clockwise around the
/// origin to `(0, −bend_radius, 0)`, then clockwise around `(0, −2·bend_radius, 0)` to
/// `(0, −3·bend_radius, 0)`: length `2π · bend_radius`, tangent continuous, curvature
/// `1/bend_radius` throughout. The volume is therefore `π r² · 2π R` (Pappus). Genus 0.
///
/// `resolution` segments around the tube (at least 3); rings along the curve and on the
/// caps are spaced about as far apart as the vertices of a ring.
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::s_tube(0.25, 1.0, 16)?;
/// let b = mesh.bounding_box();
/// assert!((b.max.y - 1.25).abs() < 1e-9 && (b.min.y + 3.25).abs() < 1e-9);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if a radius is not finite and positive,
/// `tube_radius ≥ bend_radius` (the tube would intersect itself) or `resolution < 3`;
/// [`MeshError::ShapeTooLarge`] beyond [`super::MAX_VERTICES`].
///
/// # Panics
///
/// Never.
pub fn s_tube(tube_radius: f64, bend_radius: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("tube_radius", tube_radius)?;
    check_positive("bend_radius", bend_radius)?;
    check_less(
        "tube_radius",
        tube_radius,
        bend_radius,
        "less than `bend_radius`",
    )?;
    check_resolution(resolution, 3, "at least 3")?;
    let spacing = TAU * tube_radius / resolution as f64;
    let ring_estimate = (TAU * bend_radius + 2.0 * tube_radius) / spacing + 6.0;
    check_vertex_budget("s_tube", ring_estimate * resolution as f64)?;

    let cap = pieces(tube_radius, spacing);
    let half = pieces(PI * bend_radius, spacing);
    let mut rings = Vec::with_capacity(2 * cap + 2 * half + 2);

    // The ring of the tube at centre-curve point `c` with unit tangent `t`, spanned by the
    // in-plane normal `u = (−t.y, t.x, 0)` and `v = z`: `u × v = t`, the loft's convention
    // for outward triangles.
    let ring_at = |c: DVec2, t: DVec2, radius: f64| Ring {
        center: c.extend(0.0),
        u: DVec3::new(-t.y, t.x, 0.0),
        v: DVec3::Z,
        radius,
    };
    // Centre curve point and tangent at arc length fraction `s ∈ [0, 2]` (one per half).
    let curve = |s: f64| -> (DVec2, DVec2) {
        if s <= 1.0 {
            // Counter-clockwise around the origin from angle π/2 to 3π/2.
            let angle = FRAC_PI_2 + PI * s;
            let dir = DVec2::new(angle.cos(), angle.sin());
            (bend_radius * dir, DVec2::new(-dir.y, dir.x))
        } else {
            // Clockwise around (0, −2R) from angle π/2 to −π/2.
            let angle = FRAC_PI_2 - PI * (s - 1.0);
            let dir = DVec2::new(angle.cos(), angle.sin());
            let center = DVec2::new(0.0, -2.0 * bend_radius);
            (center + bend_radius * dir, DVec2::new(dir.y, -dir.x))
        }
    };

    // Start cap: the pole, then growing circles in the end plane.
    let (c0, t0) = curve(0.0);
    rings.extend((0..cap).map(|i| ring_at(c0, t0, tube_radius * i as f64 / cap as f64)));
    // The tube itself.
    let steps = 2 * half;
    rings.extend((0..=steps).map(|i| {
        let (c, t) = curve(2.0 * i as f64 / steps as f64);
        ring_at(c, t, tube_radius)
    }));
    // End cap: shrinking circles, then the pole.
    let (c1, t1) = curve(2.0);
    rings.extend(
        (0..cap)
            .rev()
            .map(|i| ring_at(c1, t1, tube_radius * i as f64 / cap as f64)),
    );
    loft("s_tube", &rings, false, resolution)
}
