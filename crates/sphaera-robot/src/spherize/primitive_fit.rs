//! The spheres of a link's primitives: analytic layouts, or the grown tree of a mesh
//! inscribed in a box or a cylinder when that is tighter or needs fewer spheres.

use sphaera_mesh::Sphere;
use sphaera_query::Surface;

use super::mesh_fit::{mesh_count, mesh_tolerance};
use super::{PartFit, SpherizeOptions};
use crate::primitive::Primitive;
/// At most `count` spheres for a primitive: its analytic layout, or exactly `count`
/// from a one-level tree of a mesh inside it grown by the mesh's gap (a box or a
/// cylinder) when that is no looser. The protrusion is exact either way (the primitive
/// is convex).
pub(super) fn primitive_count(
    primitive: &Primitive,
    count: usize,
    options: &SpherizeOptions,
) -> PartFit {
    let (layout, reach) = primitive.spherize(count);
    let mut best = (layout, reach);
    if let Some((spheres, reach)) = inscribed(primitive, |surface, _| {
        mesh_count(surface, count, options).ok()
    }) && reach <= best.1
    {
        best = (spheres, reach);
    }
    PartFit::of_primitive(primitive, best.0, best.1)
}

/// The fewest spheres within `tolerance` of a primitive (at most
/// [`SpherizeOptions::max_spheres_per_link`]; the protrusion says whether they are
/// within it): its analytic layout, or the leaves of a tolerance tree of a mesh inside
/// it grown by the mesh's gap when they are fewer.
pub(super) fn primitive_tolerance(
    primitive: &Primitive,
    tolerance: f64,
    options: &SpherizeOptions,
) -> PartFit {
    let (layout, reach) = primitive.spherize_within(tolerance, options.max_spheres_per_link);
    let mut best = (layout, reach);
    // Only where the analytic layout meets the tolerance: the tree is then no larger
    // than a few of its sizes, and is taken only when it needs fewer spheres.
    if reach <= tolerance
        && best.0.len() > 1
        && let Some((spheres, reach)) = inscribed(primitive, |surface, gap| {
            (tolerance - gap > 0.0)
                .then(|| mesh_tolerance(surface, tolerance - gap, options).ok())
                .flatten()
        })
        && reach <= tolerance
        && spheres.len() < best.0.len()
    {
        best = (spheres, reach);
    }
    PartFit::of_primitive(primitive, best.0, best.1)
}

/// The spheres `fit` gives for the mesh inside `primitive` (a box or a cylinder), grown
/// by the mesh's gap so that they cover the primitive, with their exact protrusion.
fn inscribed(
    primitive: &Primitive,
    fit: impl FnOnce(&Surface, f64) -> Option<PartFit>,
) -> Option<(Vec<Sphere>, f64)> {
    let (mesh, gap) = primitive.inscribed_mesh()?;
    let surface = Surface::new(&mesh).ok()?;
    let part = fit(&surface, gap)?;
    let grown: Vec<Sphere> = part
        .spheres
        .iter()
        .map(|s| Sphere::new(s.center, s.radius + gap))
        .collect();
    let reach = grown
        .iter()
        .map(|s| primitive.protrusion(s))
        .fold(0.0, f64::max);
    Some((grown, reach))
}
