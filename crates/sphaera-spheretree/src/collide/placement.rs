//! Where a sphere-tree is in the scene: a rotation (or mirror), a uniform scale and a
//! translation.

use glam::{DAffine3, DMat3, DQuat, DVec3};
use sphaera_mesh::Sphere;

use crate::SphereTreeError;

/// Largest deviation of `MᵀM` from `s²·I`, relative to `s²`, for a matrix `M` taken as a
/// rotation (or mirror) times a uniform scale `s`; a scale within it of 1 is taken as 1.
const SIMILARITY_TOLERANCE: f64 = 1e-9;

/// Where a sphere-tree is in the scene: a rotation (or mirror), a uniform scale and a
/// translation, mapping the tree's coordinates to the scene's.
///
/// # Examples
///
/// ```
/// use sphaera_spheretree::collide::Placement;
/// use sphaera_spheretree::{DVec3, Sphere};
/// use glam::{DAffine3, DQuat};
///
/// let p = Placement::from_rotation_translation(DQuat::from_rotation_z(1.0), DVec3::X)?;
/// assert_eq!(p.scale(), 1.0);
/// let moved = p.sphere(&Sphere::new(DVec3::ZERO, 0.5));
/// assert_eq!(moved, Sphere::new(DVec3::X, 0.5));
///
/// let doubled = Placement::new(DAffine3::from_scale(DVec3::splat(2.0)))?;
/// assert_eq!(doubled.sphere(&Sphere::new(DVec3::X, 1.0)).radius, 2.0);
///
/// // A non-uniform scale does not map spheres to spheres.
/// assert!(Placement::new(DAffine3::from_scale(DVec3::new(1.0, 2.0, 1.0))).is_err());
/// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    affine: DAffine3,
    scale: f64,
}

impl Default for Placement {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Placement {
    /// The identity: the tree where it was built.
    pub const IDENTITY: Self = Self {
        affine: DAffine3::IDENTITY,
        scale: 1.0,
    };

    /// The placement of an affine map that is a rotation or mirror times a uniform scale,
    /// plus a translation.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_spheretree::collide::Placement;
    /// use glam::{DAffine3, DVec3};
    ///
    /// let p = Placement::new(DAffine3::from_translation(DVec3::new(0.0, 0.0, 3.0)))?;
    /// assert_eq!(p.scale(), 1.0);
    /// assert!(Placement::new(DAffine3::from_scale(DVec3::ZERO)).is_err());
    /// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SphereTreeError::InvalidParameter`] when the map has a NaN or infinite entry, is
    /// singular, or shears or scales non-uniformly (`MᵀM` further than 10⁻⁹·s² from
    /// `s²·I`).
    ///
    /// # Panics
    ///
    /// Never.
    pub fn new(affine: DAffine3) -> Result<Self, SphereTreeError> {
        let m = affine.matrix3;
        if !m.is_finite() || !affine.translation.is_finite() {
            return Err(SphereTreeError::InvalidParameter(
                "the placement has a NaN or infinite entry".into(),
            ));
        }
        let gram = m.transpose() * m;
        let s2 = (gram.x_axis.x + gram.y_axis.y + gram.z_axis.z) / 3.0;
        if s2.is_nan() || s2 <= f64::MIN_POSITIVE {
            return Err(SphereTreeError::InvalidParameter(
                "the placement is singular".into(),
            ));
        }
        let deviation = (gram - DMat3::from_diagonal(DVec3::splat(s2)))
            .to_cols_array()
            .iter()
            .fold(0.0_f64, |worst, v| worst.max(v.abs()));
        if deviation > SIMILARITY_TOLERANCE * s2 {
            return Err(SphereTreeError::InvalidParameter(format!(
                "the placement is not a rotation with a uniform scale (MᵀM deviates from \
                 s²·I by {deviation:e}, s² = {s2:e})"
            )));
        }
        let mut scale = s2.sqrt();
        if (scale - 1.0).abs() <= SIMILARITY_TOLERANCE {
            scale = 1.0;
        }
        Ok(Self { affine, scale })
    }

    /// A rotation followed by a translation (`rotation` is normalised first).
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_spheretree::collide::Placement;
    /// use sphaera_spheretree::DVec3;
    /// use glam::DQuat;
    ///
    /// let p = Placement::from_rotation_translation(DQuat::from_rotation_x(0.3), DVec3::Y)?;
    /// assert_eq!(p.scale(), 1.0);
    /// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SphereTreeError::InvalidParameter`] for a zero or non-finite quaternion or a
    /// non-finite translation.
    ///
    /// # Panics
    ///
    /// Never.
    pub fn from_rotation_translation(
        rotation: DQuat,
        translation: DVec3,
    ) -> Result<Self, SphereTreeError> {
        let length = rotation.length();
        if !rotation.is_finite() || length.is_nan() || length <= f64::MIN_POSITIVE {
            return Err(SphereTreeError::InvalidParameter(
                "the rotation is a zero or non-finite quaternion".into(),
            ));
        }
        Self::new(DAffine3::from_rotation_translation(
            rotation / length,
            translation,
        ))
    }

    /// A translation only.
    ///
    /// # Examples
    ///
    /// ```
    /// use sphaera_spheretree::collide::Placement;
    /// use sphaera_spheretree::{DVec3, Sphere};
    ///
    /// let p = Placement::from_translation(DVec3::X)?;
    /// assert_eq!(p.sphere(&Sphere::new(DVec3::ZERO, 1.0)).center, DVec3::X);
    /// # Ok::<(), sphaera_spheretree::SphereTreeError>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`SphereTreeError::InvalidParameter`] for a NaN or infinite translation.
    ///
    /// # Panics
    ///
    /// Never.
    pub fn from_translation(translation: DVec3) -> Result<Self, SphereTreeError> {
        Self::new(DAffine3::from_translation(translation))
    }

    /// The affine map.
    #[must_use]
    pub fn affine(&self) -> DAffine3 {
        self.affine
    }

    /// The uniform scale (exactly 1 for a rotation and translation).
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// `sphere` placed in the scene: its centre mapped, its radius scaled.
    #[must_use]
    pub fn sphere(&self, sphere: &Sphere) -> Sphere {
        Sphere::new(
            self.affine.transform_point3(sphere.center),
            sphere.radius * self.scale,
        )
    }
}
