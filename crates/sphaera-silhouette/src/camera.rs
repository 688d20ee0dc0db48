//! Projecting a mesh for one view: the camera frame, the image coordinates (the bounding
//! sphere's image is the square `[−1, 1]²`), and which faces face the camera.

use glam::{DVec2, DVec3};
use sphaera_mesh::{Sphere, TriMesh};

use crate::views::Projection;

/// One view of one mesh: where its camera is and how it maps points to the image plane.
#[derive(Clone, Copy, Debug)]
pub struct ViewCamera {
    /// The bounding sphere's centre.
    center: DVec3,
    /// The bounding radius (1 for a mesh that is a single point).
    radius: f64,
    /// Right, up and toward the camera (orthonormal).
    u: DVec3,
    v: DVec3,
    w: DVec3,
    /// For a perspective camera: its position and `√(D² − 1)` (the reciprocal of the
    /// tangent of the half field of view that holds the sphere).
    eye: Option<(DVec3, f64)>,
}

impl ViewCamera {
    /// The camera of `projection` looking from unit `direction` at the sphere `bounds`.
    #[must_use]
    pub fn new(bounds: Sphere, direction: DVec3, projection: Projection) -> Self {
        let w = direction.normalize();
        let helper = if w.z.abs() < 0.9 { DVec3::Z } else { DVec3::X };
        let u = helper.cross(w).normalize();
        let v = w.cross(u);
        let radius = if bounds.radius > 0.0 {
            bounds.radius
        } else {
            1.0
        };
        let eye = match projection {
            Projection::Orthographic => None,
            Projection::Perspective { distance } => Some((
                bounds.center + w * (distance * radius),
                (distance * distance - 1.0).sqrt(),
            )),
        };
        Self {
            center: bounds.center,
            radius,
            u,
            v,
            w,
            eye,
        }
    }

    /// The image coordinates of `p` (the bounding sphere's image fits in `[−1, 1]²`).
    #[must_use]
    pub fn project(&self, p: DVec3) -> DVec2 {
        match self.eye {
            None => {
                let d = p - self.center;
                DVec2::new(d.dot(self.u), d.dot(self.v)) / self.radius
            }
            Some((eye, cotangent)) => {
                let d = p - eye;
                let depth = -d.dot(self.w);
                DVec2::new(d.dot(self.u), d.dot(self.v)) * (cotangent / depth)
            }
        }
    }

    /// How near `p` is to the camera along the view axis (larger is nearer): the
    /// coordinate along the direction toward the camera.
    pub(crate) fn nearness(&self, p: DVec3) -> f64 {
        match self.eye {
            None => (p - self.center).dot(self.w),
            Some((eye, _)) => (p - eye).dot(self.w),
        }
    }

    /// The length a cell of a `resolution`-wide image spans at the frame's centre.
    pub(crate) fn cell_length(&self, resolution: usize) -> f64 {
        let across = match self.eye {
            None => 2.0 * self.radius,
            // The image's half width is the depth over the cotangent.
            Some((eye, cotangent)) => 2.0 * (eye - self.center).length() / cotangent,
        };
        across / resolution as f64
    }

    /// Whether triangle `t` of `mesh` faces the camera (its counter-clockwise normal
    /// points toward it; an edge-on face does not).
    #[must_use]
    pub fn faces_camera(&self, mesh: &TriMesh, t: [u32; 3]) -> bool {
        let [a, b, c] = t.map(|i| mesh.positions()[i as usize]);
        self.normal_faces_camera(face_normal([a, b, c]), a)
    }

    /// Whether a face with (unnormalized) normal `normal` and first corner `corner` faces
    /// the camera, as [`ViewCamera::faces_camera`].
    pub(crate) fn normal_faces_camera(&self, normal: DVec3, corner: DVec3) -> bool {
        let toward = match self.eye {
            None => self.w,
            Some((eye, _)) => eye - corner,
        };
        normal.dot(toward) > 0.0
    }
}

/// The counter-clockwise normal of the triangle with corners `[a, b, c]`, unnormalized.
pub(crate) fn face_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a)
}
