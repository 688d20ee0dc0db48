//! Rigid poses of the mesh (Meshsweeper section 5.2): a `DAffine3` validated as a rigid
//! motion by `sphaera-mesh`'s [`Similarity::rigid`], kept as a unit quaternion and a
//! translation, and the bound on how far a pose change moves the mesh.

use glam::{DAffine3, DQuat, DVec3};
use sphaera_mesh::MeshError;
use sphaera_mesh::geometry::{Similarity, TransformDefect};

use crate::SweepError;

/// A rigid pose, mesh coordinates to world coordinates: `x ↦ rotation · x + translation`.
///
/// The rotation is the unit quaternion nearest the validated matrix, so the pose the
/// session uses is exactly rigid (up to rounding) even when the given matrix is slightly
/// off (by at most [`sphaera_mesh::geometry::SIMILARITY_TOLERANCE`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pose {
    rotation: DQuat,
    translation: DVec3,
}

impl Pose {
    /// The identity.
    pub(crate) const IDENTITY: Self = Self {
        rotation: DQuat::IDENTITY,
        translation: DVec3::ZERO,
    };

    /// Validates `pose` as a rotation followed by a translation.
    pub(crate) fn new(pose: DAffine3) -> Result<Self, SweepError> {
        let rigid = Similarity::rigid(pose).map_err(|error| match error {
            MeshError::InvalidTransform(TransformDefect::NotRigid { deviation }) => {
                SweepError::NotRigid { deviation }
            }
            _ => SweepError::NonFinitePose,
        })?;
        Ok(Self {
            rotation: rigid.rotation(),
            translation: rigid.translation(),
        })
    }

    /// The pose as an affine map.
    pub(crate) fn affine(self) -> DAffine3 {
        DAffine3::from_rotation_translation(self.rotation, self.translation)
    }

    /// World coordinates to mesh coordinates.
    pub(crate) fn to_local(self, p: DVec3) -> DVec3 {
        self.rotation.conjugate() * (p - self.translation)
    }

    /// Mesh coordinates to world coordinates.
    pub(crate) fn to_world(self, x: DVec3) -> DVec3 {
        self.rotation * x + self.translation
    }

    /// A bound on how far any point of the box `[lo, hi]` (mesh coordinates) moves in the
    /// world when the pose changes from `self` to `next`: the displacement `|next(x) −
    /// self(x)|` is a convex function of `x` (the norm of an affine map), so its maximum
    /// over the box is at a corner — and every vertex of the mesh is in the box, so this is
    /// at least the paper's δ, the largest vertex displacement, and at most the box's
    /// corners' (plus a rounding slack of a few ulps of the coordinates).
    pub(crate) fn box_displacement(self, next: Self, lo: DVec3, hi: DVec3) -> f64 {
        let mut worst = 0.0_f64;
        let mut scale = self.translation.length() + next.translation.length();
        for i in 0..8_u8 {
            let corner = DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            worst = worst.max((next.to_world(corner) - self.to_world(corner)).length());
            scale = scale.max(corner.length());
        }
        worst + 16.0 * f64::EPSILON * scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotations_pass_and_round_trip() {
        let rotation = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 1.3);
        let pose = Pose::new(DAffine3::from_rotation_translation(
            rotation,
            DVec3::new(3.0, -1.0, 2.0),
        ))
        .expect("a rotation and a translation are rigid");
        let x = DVec3::new(0.3, 0.7, -1.1);
        assert!((pose.to_local(pose.to_world(x)) - x).length() < 1e-14);
        assert!((pose.affine().transform_point3(x) - pose.to_world(x)).length() < 1e-14);
    }

    #[test]
    fn scale_shear_reflection_and_nan_fail() {
        let scale = DAffine3::from_scale(DVec3::new(1.0, 1.0, 1.001));
        assert!(matches!(
            Pose::new(scale),
            Err(SweepError::NotRigid { deviation }) if deviation > 1e-3
        ));
        let reflection = DAffine3::from_scale(DVec3::new(1.0, 1.0, -1.0));
        assert!(matches!(
            Pose::new(reflection),
            Err(SweepError::NotRigid { deviation }) if deviation >= 2.0
        ));
        let mut nan = DAffine3::IDENTITY;
        nan.translation.y = f64::NAN;
        assert!(matches!(Pose::new(nan), Err(SweepError::NonFinitePose)));
    }

    #[test]
    fn box_displacement_bounds_every_inner_point() {
        let a = Pose::IDENTITY;
        let b = Pose::new(DAffine3::from_rotation_translation(
            DQuat::from_rotation_z(0.2),
            DVec3::new(0.1, 0.0, 0.0),
        ))
        .expect("rigid");
        let (lo, hi) = (DVec3::splat(-1.0), DVec3::new(1.0, 2.0, 0.5));
        let bound = a.box_displacement(b, lo, hi);
        for i in 0..=10 {
            for j in 0..=10 {
                let x = lo + (hi - lo) * DVec3::new(f64::from(i) / 10.0, f64::from(j) / 10.0, 0.3);
                assert!((b.to_world(x) - a.to_world(x)).length() <= bound);
            }
        }
    }
}
