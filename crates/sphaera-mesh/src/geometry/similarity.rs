//! Similarity transforms — a rotation or mirror, a uniform scale and a translation — the
//! maps that take spheres to spheres, validated once for every crate that places a mesh
//! or a sphere set in a scene.

use glam::{DAffine3, DMat3, DQuat, DVec3};

use crate::{MeshError, Sphere};

/// How far a matrix may be from a similarity (largest entry of `MᵀM − s²·I`, relative to
/// `s²`) or from a rotation (largest entry of `|MᵀM − I|` and `|det M − 1|`): rounding of
/// composed rotations stays far below this, a scale or shear of one part in a billion
/// does not. A scale within it of 1 is taken as exactly 1.
pub const SIMILARITY_TOLERANCE: f64 = 1e-9;

/// Why an affine map is not a [`Similarity`], in [`MeshError::InvalidTransform`].
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TransformDefect {
    /// An entry is NaN or infinite.
    #[error("it has a NaN or infinite entry")]
    NonFinite,
    /// The linear part is singular (a zero scale).
    #[error("it is singular")]
    Singular,
    /// The linear part shears or scales unevenly.
    #[error(
        "it is not a rotation with a uniform scale (MᵀM deviates from s²·I by {deviation:e}, s² = {scale_squared:e})"
    )]
    NotUniform {
        /// The largest entry of `|MᵀM − s²·I|`.
        deviation: f64,
        /// `s²`, the mean of the diagonal of `MᵀM`.
        scale_squared: f64,
    },
    /// A rigid motion was asked for, and the linear part is not a rotation (it scales,
    /// shears or mirrors).
    #[error("it is not rigid: its linear part is {deviation:e} away from a rotation")]
    NotRigid {
        /// The largest entry of `|MᵀM − I|`, or `|det M − 1|` when larger (2 for a mirror).
        deviation: f64,
    },
    /// A rotation was given as a zero or non-finite quaternion.
    #[error("the rotation is a zero or non-finite quaternion")]
    InvalidQuaternion,
}

/// A similarity transform `x ↦ s·R·x + t` (`R` a rotation or mirror, `s > 0` a uniform
/// scale): where a mesh or sphere set sits in a scene, mapping its own coordinates to
/// the scene's. Spheres map to spheres ([`Similarity::sphere`]).
///
/// # Examples
///
/// ```
/// use glam::{DAffine3, DQuat};
/// use sphaera_mesh::{DVec3, Sphere, geometry::Similarity};
///
/// let p = Similarity::from_rotation_translation(DQuat::from_rotation_z(1.0), DVec3::X)?;
/// assert_eq!(p.scale(), 1.0);
/// let moved = p.sphere(&Sphere::new(DVec3::ZERO, 0.5));
/// assert_eq!(moved, Sphere::new(DVec3::X, 0.5));
///
/// let doubled = Similarity::new(DAffine3::from_scale(DVec3::splat(2.0)))?;
/// assert_eq!(doubled.sphere(&Sphere::new(DVec3::X, 1.0)).radius, 2.0);
///
/// // A non-uniform scale does not map spheres to spheres.
/// assert!(Similarity::new(DAffine3::from_scale(DVec3::new(1.0, 2.0, 1.0))).is_err());
/// // A rigid motion must not scale.
/// assert!(Similarity::rigid(DAffine3::from_scale(DVec3::splat(2.0))).is_err());
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Similarity {
    affine: DAffine3,
    scale: f64,
}

impl Default for Similarity {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Similarity {
    /// The identity.
    pub const IDENTITY: Self = Self {
        affine: DAffine3::IDENTITY,
        scale: 1.0,
    };

    /// The similarity of an affine map that is a rotation or mirror times a uniform scale,
    /// plus a translation.
    ///
    /// # Errors
    ///
    /// [`MeshError::InvalidTransform`] when the map has a NaN or infinite entry, is
    /// singular, or shears or scales non-uniformly (`MᵀM` further than
    /// [`SIMILARITY_TOLERANCE`]`·s²` from `s²·I`).
    pub fn new(affine: DAffine3) -> Result<Self, MeshError> {
        let m = finite(affine)?;
        let gram = m.transpose() * m;
        let scale_squared = (gram.x_axis.x + gram.y_axis.y + gram.z_axis.z) / 3.0;
        if !scale_squared.is_finite() {
            // Entries so large that `MᵀM` overflows.
            return Err(MeshError::InvalidTransform(TransformDefect::NonFinite));
        }
        if scale_squared <= f64::MIN_POSITIVE {
            return Err(MeshError::InvalidTransform(TransformDefect::Singular));
        }
        let deviation = largest_entry(gram - DMat3::from_diagonal(DVec3::splat(scale_squared)));
        if deviation.is_nan() || deviation > SIMILARITY_TOLERANCE * scale_squared {
            return Err(MeshError::InvalidTransform(TransformDefect::NotUniform {
                deviation,
                scale_squared,
            }));
        }
        let mut scale = scale_squared.sqrt();
        if (scale - 1.0).abs() <= SIMILARITY_TOLERANCE {
            scale = 1.0;
        }
        Ok(Self { affine, scale })
    }

    /// The similarity of a rigid motion: `affine`'s linear part must be a rotation (no
    /// scale, no mirror) within [`SIMILARITY_TOLERANCE`].
    ///
    /// # Errors
    ///
    /// [`MeshError::InvalidTransform`] with [`TransformDefect::NonFinite`] or
    /// [`TransformDefect::NotRigid`].
    pub fn rigid(affine: DAffine3) -> Result<Self, MeshError> {
        let m = finite(affine)?;
        let deviation =
            largest_entry(m.transpose() * m - DMat3::IDENTITY).max((m.determinant() - 1.0).abs());
        if deviation.is_nan() || deviation > SIMILARITY_TOLERANCE {
            return Err(MeshError::InvalidTransform(TransformDefect::NotRigid {
                deviation,
            }));
        }
        Ok(Self { affine, scale: 1.0 })
    }

    /// A rotation followed by a translation (`rotation` is normalised first).
    ///
    /// # Errors
    ///
    /// [`MeshError::InvalidTransform`] for a zero or non-finite quaternion or a
    /// non-finite translation.
    pub fn from_rotation_translation(
        rotation: DQuat,
        translation: DVec3,
    ) -> Result<Self, MeshError> {
        let length = rotation.length();
        if !rotation.is_finite() || length.is_nan() || length <= f64::MIN_POSITIVE {
            return Err(MeshError::InvalidTransform(
                TransformDefect::InvalidQuaternion,
            ));
        }
        Self::new(DAffine3::from_rotation_translation(
            rotation / length,
            translation,
        ))
    }

    /// A translation only.
    ///
    /// # Errors
    ///
    /// [`MeshError::InvalidTransform`] for a NaN or infinite translation.
    pub fn from_translation(translation: DVec3) -> Result<Self, MeshError> {
        Self::new(DAffine3::from_translation(translation))
    }

    /// The affine map.
    #[must_use]
    pub fn affine(&self) -> DAffine3 {
        self.affine
    }

    /// The uniform scale (exactly 1 for a rigid motion).
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The rotation of the linear part, as the unit quaternion nearest to it (for a
    /// mirror, the rotation of the matrix's proper part is not meaningful).
    #[must_use]
    pub fn rotation(&self) -> DQuat {
        DQuat::from_mat3(&(self.affine.matrix3 * (1.0 / self.scale))).normalize()
    }

    /// The translation.
    #[must_use]
    pub fn translation(&self) -> DVec3 {
        self.affine.translation
    }

    /// `p` mapped.
    #[must_use]
    pub fn point(&self, p: DVec3) -> DVec3 {
        self.affine.transform_point3(p)
    }

    /// `sphere` mapped: its centre mapped, its radius scaled.
    #[must_use]
    pub fn sphere(&self, sphere: &Sphere) -> Sphere {
        Sphere::new(
            self.affine.transform_point3(sphere.center),
            sphere.radius * self.scale,
        )
    }
}

/// The linear part of `affine`, if every entry is finite.
fn finite(affine: DAffine3) -> Result<DMat3, MeshError> {
    let m = affine.matrix3;
    if m.is_finite() && affine.translation.is_finite() {
        Ok(m)
    } else {
        Err(MeshError::InvalidTransform(TransformDefect::NonFinite))
    }
}

/// The largest absolute entry of `m` (NaN if any entry is NaN).
fn largest_entry(m: DMat3) -> f64 {
    m.to_cols_array().iter().fold(0.0_f64, |worst, v| {
        if v.is_nan() {
            f64::NAN
        } else {
            worst.max(v.abs())
        }
    })
}

#[cfg(test)]
mod tests {
    // Exact values are expected: a scale snapped to 1, exact images.
    #![allow(clippy::float_cmp)]

    use super::*;

    #[test]
    fn rotations_are_rigid_and_round_trip() {
        let rotation = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 1.3);
        let affine = DAffine3::from_rotation_translation(rotation, DVec3::new(3.0, -1.0, 2.0));
        let rigid = Similarity::rigid(affine).expect("a rotation and a translation are rigid");
        assert_eq!(rigid.scale(), 1.0);
        assert!((rigid.rotation().dot(rotation).abs() - 1.0).abs() < 1e-12);
        assert_eq!(Similarity::new(affine).expect("a similarity").scale(), 1.0);
    }

    #[test]
    fn scale_shear_mirror_and_nan_are_named() {
        let stretched = DAffine3::from_scale(DVec3::new(1.0, 1.0, 1.001));
        assert!(matches!(
            Similarity::rigid(stretched),
            Err(MeshError::InvalidTransform(TransformDefect::NotRigid { deviation })) if deviation > 1e-3
        ));
        assert!(matches!(
            Similarity::new(stretched),
            Err(MeshError::InvalidTransform(
                TransformDefect::NotUniform { .. }
            ))
        ));
        let mirror = DAffine3::from_scale(DVec3::new(1.0, 1.0, -1.0));
        assert!(matches!(
            Similarity::rigid(mirror),
            Err(MeshError::InvalidTransform(TransformDefect::NotRigid { deviation })) if deviation >= 2.0
        ));
        assert_eq!(
            Similarity::new(mirror)
                .expect("a mirror is a similarity")
                .scale(),
            1.0
        );
        let mut nan = DAffine3::IDENTITY;
        nan.translation.y = f64::NAN;
        for result in [Similarity::new(nan), Similarity::rigid(nan)] {
            assert!(matches!(
                result,
                Err(MeshError::InvalidTransform(TransformDefect::NonFinite))
            ));
        }
        assert!(matches!(
            Similarity::new(DAffine3::from_scale(DVec3::ZERO)),
            Err(MeshError::InvalidTransform(TransformDefect::Singular))
        ));
        assert!(matches!(
            Similarity::from_rotation_translation(
                DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0),
                DVec3::ZERO
            ),
            Err(MeshError::InvalidTransform(
                TransformDefect::InvalidQuaternion
            ))
        ));
    }

    #[test]
    fn uniform_scales_map_spheres() {
        let s = Similarity::new(DAffine3::from_scale_rotation_translation(
            DVec3::splat(3.0),
            DQuat::from_rotation_y(0.4),
            DVec3::Y,
        ))
        .expect("a similarity");
        assert!((s.scale() - 3.0).abs() < 1e-15);
        let mapped = s.sphere(&Sphere::new(DVec3::ZERO, 0.5));
        assert_eq!(mapped.center, DVec3::Y);
        assert!((mapped.radius - 1.5).abs() < 1e-15);
        assert_eq!(s.point(DVec3::ZERO), DVec3::Y);
    }
}
