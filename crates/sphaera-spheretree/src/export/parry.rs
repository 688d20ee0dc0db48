//! A `parry3d-f64` compound of balls, for rapier and parry users.

use parry3d_f64::math::Pose;
use parry3d_f64::shape::{Compound, SharedShape};
use sphaera_mesh::Sphere;

use crate::SphereTreeError;

/// The spheres as a `parry3d-f64` [`Compound`] of balls, one part per sphere in the
/// given order (use a level's spheres, or a cut's).
///
/// Available with the crate's `parry` feature (off by default).
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::export::to_parry_compound;
/// use sphaera_spheretree::{DVec3, Sphere};
///
/// let spheres = [Sphere::new(DVec3::ZERO, 1.0), Sphere::new(DVec3::X, 0.5)];
/// let compound = to_parry_compound(&spheres)?;
/// assert_eq!(compound.shapes().len(), 2);
/// let (pose, shape) = &compound.shapes()[1];
/// assert_eq!(pose.translation, DVec3::X);
/// assert_eq!(shape.as_ball().map(|b| b.radius), Some(0.5));
/// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
/// ```
///
/// # Errors
///
/// - [`SphereTreeError::EmptySphereSet`] without spheres (a parry compound needs a part).
/// - [`SphereTreeError::InvalidSphere`] for a NaN or infinite centre or radius, or a
///   negative radius.
///
/// # Panics
///
/// Never.
pub fn to_parry_compound(spheres: &[Sphere]) -> Result<Compound, SphereTreeError> {
    if spheres.is_empty() {
        return Err(SphereTreeError::EmptySphereSet);
    }
    if let Some(index) = spheres.iter().position(|s| !s.is_valid()) {
        return Err(SphereTreeError::InvalidSphere { index });
    }
    let parts = spheres
        .iter()
        .map(|s| {
            (
                Pose::from_translation(s.center),
                SharedShape::ball(s.radius),
            )
        })
        .collect();
    Ok(Compound::new(parts))
}
