//! A perspective camera, and how many pixels a world-space error can become on its image.

use glam::DVec3;
use sphaera_mesh::Sphere;

use crate::SceneError;

/// A pinhole camera: an eye, a viewing direction, a vertical field of view, an image in
/// pixels and a near plane.
///
/// Its one job here is [`Camera::pixels_per_unit`]: a certified bound on how many pixels a
/// displacement of one world unit becomes on the image, anywhere inside a bounding
/// sphere. The roll of the camera (its up vector) does not change that bound, so there is
/// none.
///
/// # Examples
///
/// ```
/// use sphaera_scene::{Camera, DVec3, Sphere};
///
/// let camera = Camera::perspective(DVec3::new(0.0, 0.0, 10.0), DVec3::ZERO, 60.0, 1920, 1080)?;
/// // The image is 1080 px high and sees 2·tan(30°)·10 ≈ 11.5 units at the origin.
/// let near = camera.pixels_per_unit(&Sphere::new(DVec3::ZERO, 0.01)).unwrap();
/// assert!(near > 1080.0 / 11.6 && near < 1.1 * 1080.0 / 11.5);
/// // Twice as far, about half the pixels.
/// let far = camera.pixels_per_unit(&Sphere::new(DVec3::new(0.0, 0.0, -10.0), 0.01)).unwrap();
/// assert!((far / near - 0.5).abs() < 0.01);
/// // Behind the camera: not seen at all.
/// assert_eq!(camera.pixels_per_unit(&Sphere::new(DVec3::new(0.0, 0.0, 20.0), 1.0)), None);
/// # Ok::<(), sphaera_scene::SceneError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    eye: DVec3,
    forward: DVec3,
    fov_y: f64,
    width: u32,
    height: u32,
    near: f64,
}

impl Camera {
    /// A camera at `eye` looking at `target`, with a vertical field of view in degrees
    /// (in `(0, 180)`) and an image of `width × height` pixels. The near plane is at
    /// 1/1000 of the eye–target distance ([`Camera::with_near`] changes it).
    ///
    /// # Errors
    ///
    /// [`SceneError::InvalidCamera`] for a non-finite eye or target, a target at the eye,
    /// a field of view outside `(0, 180)` degrees, or an empty image.
    pub fn perspective(
        eye: DVec3,
        target: DVec3,
        fov_y_degrees: f64,
        width: u32,
        height: u32,
    ) -> Result<Self, SceneError> {
        let invalid = |name, value, requirement| SceneError::InvalidCamera {
            name,
            value,
            requirement,
        };
        for (name, v) in [("eye", eye), ("target", target)] {
            if !v.is_finite() {
                let bad = v.to_array().into_iter().find(|x| !x.is_finite());
                return Err(invalid(name, bad.unwrap_or(f64::NAN), "finite"));
            }
        }
        let offset = target - eye;
        let distance = offset.length();
        if !(distance > 0.0 && distance.is_finite()) {
            return Err(invalid(
                "target",
                distance,
                "away from the eye (a positive, finite distance)",
            ));
        }
        if !(fov_y_degrees > 0.0 && fov_y_degrees < 180.0) {
            return Err(invalid(
                "fov_y_degrees",
                fov_y_degrees,
                "in (0, 180) degrees",
            ));
        }
        for (name, v) in [("width", width), ("height", height)] {
            if v == 0 {
                return Err(invalid(name, 0.0, "at least 1 pixel"));
            }
        }
        Ok(Self {
            eye,
            forward: offset / distance,
            fov_y: fov_y_degrees.to_radians(),
            width,
            height,
            near: distance * 1e-3,
        })
    }

    /// The same camera with its near plane at `near` (nothing closer is drawn).
    ///
    /// # Errors
    ///
    /// [`SceneError::InvalidCamera`] unless `near` is positive and finite.
    pub fn with_near(mut self, near: f64) -> Result<Self, SceneError> {
        if !(near > 0.0 && near.is_finite()) {
            return Err(SceneError::InvalidCamera {
                name: "near",
                value: near,
                requirement: "positive and finite",
            });
        }
        self.near = near;
        Ok(self)
    }

    /// The eye.
    #[must_use]
    pub fn eye(&self) -> DVec3 {
        self.eye
    }

    /// The unit viewing direction.
    #[must_use]
    pub fn forward(&self) -> DVec3 {
        self.forward
    }

    /// The vertical field of view, in radians.
    #[must_use]
    pub fn fov_y(&self) -> f64 {
        self.fov_y
    }

    /// The image size in pixels, `(width, height)`.
    #[must_use]
    pub fn image_size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The near-plane distance.
    #[must_use]
    pub fn near(&self) -> f64 {
        self.near
    }

    /// The focal length in pixels: `height / (2·tan(fov_y / 2))`.
    #[must_use]
    pub fn focal_pixels(&self) -> f64 {
        f64::from(self.height) / (2.0 * (self.fov_y / 2.0).tan())
    }

    /// The angle between the viewing direction and a corner of the image: every point the
    /// camera sees is within this angle of its axis.
    #[must_use]
    pub fn half_diagonal_angle(&self) -> f64 {
        let aspect = f64::from(self.width) / f64::from(self.height);
        ((self.fov_y / 2.0).tan() * aspect.hypot(1.0)).atan()
    }

    /// A certified bound on the pixels one world unit becomes on the image, for any
    /// displacement between two points of `bound` that the camera sees (inside the image
    /// and beyond the near plane); `None` when the camera sees no point of `bound`.
    ///
    /// A point at depth `z` and angle `φ` off the axis moves on the image by at most
    /// `f / (z·cos φ)` pixels per unit it moves in the world (`f` the
    /// [focal length](Camera::focal_pixels); the `1/cos φ` is the stretch of perspective
    /// towards the image's corners). With `z = ρ·cos φ` at distance `ρ` from the eye,
    /// that is `f / (ρ·cos² φ)`. Inside the sphere, `ρ` is at least the distance from the
    /// eye to the sphere, and `φ` at most the sphere's largest angle off the axis (never
    /// more than [`Camera::half_diagonal_angle`] for a point seen); `z` is at least the
    /// near distance. The bound is the smaller of the two: exact for a sphere on the axis,
    /// conservative elsewhere.
    #[must_use]
    pub fn pixels_per_unit(&self, bound: &Sphere) -> Option<f64> {
        let to_center = bound.center - self.eye;
        let distance = to_center.length();
        let r = bound.radius.max(0.0);
        // Entirely behind the near plane.
        if to_center.dot(self.forward) + r < self.near {
            return None;
        }
        let frame = self.half_diagonal_angle();
        let f = self.focal_pixels();
        let mut widest = frame;
        let mut by_distance = f64::INFINITY;
        if distance > r {
            let off_axis = (to_center.dot(self.forward) / distance)
                .clamp(-1.0, 1.0)
                .acos();
            let spread = (r / distance).asin();
            if off_axis - spread > frame {
                return None;
            }
            widest = (off_axis + spread).min(frame);
            let cos = widest.cos();
            by_distance = f / ((distance - r) * cos * cos);
        }
        let by_near = f / (self.near * widest.cos());
        Some(by_distance.min(by_near))
    }

    /// The pixels an error of `error` world units can become for a surface within
    /// `bound`: [`Camera::pixels_per_unit`] of `bound` grown by `error` (the displaced
    /// surface lies there), times `error`; `None` when nothing of it is seen.
    #[must_use]
    pub fn projected_error(&self, bound: &Sphere, error: f64) -> Option<f64> {
        let grown = Sphere::new(bound.center, bound.radius + error.max(0.0));
        self.pixels_per_unit(&grown).map(|k| k * error)
    }

    /// Where a point lands on the image, in pixels from the image's centre (x along any
    /// fixed axis perpendicular to the view), and its depth; `None` at or behind the eye
    /// plane. For tests and pictures.
    #[must_use]
    pub fn project(&self, p: DVec3) -> Option<(glam::DVec2, f64)> {
        let (right, up) = self.forward.any_orthonormal_pair();
        let v = p - self.eye;
        let z = v.dot(self.forward);
        if z <= 0.0 {
            return None;
        }
        let f = self.focal_pixels();
        Some((glam::DVec2::new(v.dot(right), v.dot(up)) * (f / z), z))
    }
}
