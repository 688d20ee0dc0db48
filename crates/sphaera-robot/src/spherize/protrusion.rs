//! The 95th-percentile protrusion of a link's spheres: distances to the link's solid from
//! points spread over the boundary of their union.

use glam::DVec3;
use sphaera_mesh::Sphere;
use sphaera_query::Surface;

use crate::primitive::{Primitive, Shape};
/// The `q` quantile of the distance to the link's solid over points spread by area on
/// the boundary of the union of `spheres` (points inside another sphere are not on it).
pub(super) fn percentile_protrusion(
    spheres: &[Sphere],
    surface: Option<&Surface>,
    primitives: &[Primitive],
    q: f64,
) -> f64 {
    const POINTS: f64 = 6_000.0;
    let total: f64 = spheres.iter().map(|s| s.radius * s.radius).sum();
    if total <= 0.0 {
        return 0.0;
    }
    let unit = Primitive::new(Shape::Sphere { radius: 1.0 }, glam::DAffine3::IDENTITY);
    let mut distances: Vec<f64> = Vec::new();
    for (i, s) in spheres.iter().enumerate() {
        let n = ((POINTS * s.radius * s.radius / total).ceil() as usize).max(4);
        for u in unit.surface_points(n) {
            let p = s.center + u * s.radius;
            let inside_another = spheres
                .iter()
                .enumerate()
                .any(|(j, o)| j != i && o.center.distance(p) < o.radius);
            if inside_another {
                continue;
            }
            distances.push(solid_distance(p, surface, primitives));
        }
    }
    if distances.is_empty() {
        return 0.0;
    }
    distances.sort_by(f64::total_cmp);
    let index = ((q * distances.len() as f64).ceil() as usize).clamp(1, distances.len()) - 1;
    distances[index]
}

/// The distance from `p` to the link's solid (0 inside any part).
fn solid_distance(p: DVec3, surface: Option<&Surface>, primitives: &[Primitive]) -> f64 {
    let mut best = f64::INFINITY;
    if let Some(surface) = surface {
        if surface.is_inside(p) {
            return 0.0;
        }
        if let Ok(c) = surface.closest(p) {
            best = c.distance;
        }
    }
    for primitive in primitives {
        best = best.min(primitive.signed_distance(p).max(0.0));
    }
    if best.is_finite() { best } else { 0.0 }
}
