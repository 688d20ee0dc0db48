//! Candidate centres: medial balls found by shrinking (Ma, Bae, Choi and Sengupta 2012,
//! *3D medial axis point approximation using nearest neighbors and the normal field*),
//! here against the exact surface instead of a point cloud.
//!
//! The medial ball touching the surface at `p` is the largest ball tangent to the surface
//! at `p`, on the inner side, that holds no surface point. Start from a large ball tangent
//! at `p`; while the surface point `q` nearest its centre lies inside it, replace it by the
//! ball tangent at `p` through `q` (smaller, since `q` was inside). Each step is one exact
//! closest-point query; a few steps reach a ball whose centre is farther from the surface
//! than the tolerance allows below its radius. Centres of such balls lie near the medial
//! axis, where a sphere reaches far from the surface it must cover while poking out
//! least: the right places to try centres.
//!
//! On a shell (no inside) the candidates are the surface points themselves.

use glam::DVec3;
use sphaera_query::Surface;

use crate::SphereTreeError;

/// Shrinking steps at most per candidate (the radius falls fast; a handful is typical).
const MAX_STEPS: usize = 32;

/// A candidate centre with its signed depth: the distance to the surface, positive
/// inside the object and negative outside (a sphere of radius `r` about it then reaches at
/// most `r − depth` beyond the surface: the paper's eq. 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Candidate {
    /// The centre.
    pub(crate) center: DVec3,
    /// Its signed depth.
    pub(crate) depth: f64,
}

/// The signed depth of `center` ([`Candidate::depth`]): exact distance, certified side.
pub(crate) fn signed_depth(surface: &Surface, center: DVec3) -> Result<f64, SphereTreeError> {
    let signed = surface.signed_closest(center)?;
    Ok(-signed.signed_distance())
}

/// The signed depth of `center` with the fast side (the winding number's approximation
/// where the pseudo-normal test does not decide): for searches, whose results are then
/// measured with [`signed_depth`].
pub(crate) fn signed_depth_fast(surface: &Surface, center: DVec3) -> Result<f64, SphereTreeError> {
    let signed = surface.signed_closest_approx(center)?;
    Ok(-signed.signed_distance())
}

/// The medial candidate touching the surface at `p`, whose outward normal is `normal`
/// (unit, or zero for a degenerate triangle), starting the shrinking from radius `start`;
/// on a shell, `p` itself. Returns the candidate and the radius of its ball (the start of
/// the next candidate nearby).
pub(crate) fn medial_candidate(
    surface: &Surface,
    p: DVec3,
    normal: DVec3,
    start: f64,
) -> Result<(Candidate, f64), SphereTreeError> {
    if !surface.has_inside() || normal == DVec3::ZERO {
        let depth = if surface.has_inside() {
            signed_depth_fast(surface, p)?
        } else {
            0.0
        };
        return Ok((Candidate { center: p, depth }, start));
    }
    let inward = -normal;
    let (center, radius) = shrink(surface, p, inward, start)?;
    let depth = signed_depth_fast(surface, center)?;
    if depth >= 0.0 {
        return Ok((Candidate { center, depth }, radius));
    }
    // The normal points inward here (a locally inverted patch): try the other side.
    let (other, other_radius) = shrink(surface, p, normal, start)?;
    let other_depth = signed_depth_fast(surface, other)?;
    Ok(if other_depth > depth {
        (
            Candidate {
                center: other,
                depth: other_depth,
            },
            other_radius,
        )
    } else {
        (Candidate { center, depth }, radius)
    })
}

/// The centre and radius of the largest ball tangent at `p` along `direction` (unit) that
/// holds no surface point, of radius at most the surface's diagonal: grown from radius
/// `start` by doubling while it holds none, then shrunk.
fn shrink(
    surface: &Surface,
    p: DVec3,
    direction: DVec3,
    start: f64,
) -> Result<(DVec3, f64), SphereTreeError> {
    let cap = surface.diagonal();
    let mut radius = if start > 0.0 { start.min(cap) } else { cap };
    // Whether the ball of `radius` holds no surface point, and else the surface point
    // nearest its centre (the search is bounded by the radius).
    let empty = |radius: f64| -> Result<(DVec3, bool, DVec3), SphereTreeError> {
        let center = p + direction * radius;
        let inner = radius * (1.0 - 1e-9);
        match surface.tree().closest_within(center, inner)? {
            Some(nearest) if nearest.distance < inner => Ok((center, false, nearest.point)),
            _ => Ok((center, true, center)),
        }
    };
    let (mut center, mut clear, mut q) = empty(radius)?;
    while clear && radius < cap {
        radius = (2.0 * radius).min(cap);
        (center, clear, q) = empty(radius)?;
    }
    for _ in 0..MAX_STEPS {
        if clear {
            break;
        }
        // The ball tangent at p through q: |q − p − u r|² = r².
        let along = direction.dot(q - p);
        if along.is_nan() || along <= 0.0 {
            break;
        }
        let next = p.distance_squared(q) / (2.0 * along);
        if !next.is_finite() || next >= radius {
            break;
        }
        radius = next;
        (center, clear, q) = empty(radius)?;
    }
    Ok((center, radius))
}
