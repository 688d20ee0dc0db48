//! Silhouette images made without `sphaera-silhouette`: the judge of the silhouette tests
//! and of `sphaera-eval`'s guided-against-plain experiment.
//!
//! A mesh is drawn as the set of pixel centres some projected triangle covers (its
//! silhouette: every triangle counts, whichever way it faces), on a square image framed
//! by a [`Frame`] — the axis-aligned bounding box's centre and the largest distance of a
//! vertex from it, which is not how `sphaera-silhouette` frames its images (it uses the
//! minimal bounding sphere) — through an orthographic or a pinhole camera. Coverage is
//! decided per pixel centre by the three edge functions of the projected triangle
//! (inclusive: a centre on an edge is covered), not by scanlines.

use sphaera_mesh::TriMesh;
use sphaera_mesh::glam::{DVec2, DVec3};

/// Where the camera looks from and how the image is framed: the bounding ball of the
/// mesh it was made for fills the square `[−1, 1]²`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    center: DVec3,
    radius: f64,
    /// Right, up and toward the camera (orthonormal).
    u: DVec3,
    v: DVec3,
    w: DVec3,
    /// A pinhole camera: its position and the reciprocal of the tangent of the half
    /// field of view that holds the ball.
    eye: Option<(DVec3, f64)>,
}

impl Frame {
    /// The orthographic frame of `mesh` seen from unit-or-not `direction` (toward the
    /// camera).
    ///
    /// # Panics
    ///
    /// For a mesh without vertices or a zero direction.
    #[must_use]
    pub fn orthographic(mesh: &TriMesh, direction: DVec3) -> Self {
        let positions = mesh.positions();
        assert!(!positions.is_empty(), "a mesh with vertices");
        let (lo, hi) = positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let center = (lo + hi) / 2.0;
        let radius = positions
            .iter()
            .map(|&p| p.distance(center))
            .fold(0.0, f64::max);
        let w = direction.normalize();
        assert!(w.is_finite(), "a non-zero direction");
        // Any right-handed frame around `w` will do.
        let helper = if w.x.abs() < 0.6 { DVec3::X } else { DVec3::Y };
        let u = w.cross(helper).normalize();
        let v = w.cross(u);
        Self {
            center,
            radius: if radius > 0.0 { radius } else { 1.0 },
            u,
            v,
            w,
            eye: None,
        }
    }

    /// The same view through a pinhole camera `distance` ball radii from the centre
    /// (more than 1), its field of view just holding the ball.
    ///
    /// # Panics
    ///
    /// Unless `distance > 1`.
    #[must_use]
    pub fn perspective(self, distance: f64) -> Self {
        assert!(distance > 1.0, "a camera outside the ball");
        Self {
            eye: Some((
                self.center + self.w * (distance * self.radius),
                (distance * distance - 1.0).sqrt(),
            )),
            ..self
        }
    }

    /// The image point of `p`.
    #[must_use]
    pub fn project(&self, p: DVec3) -> DVec2 {
        match self.eye {
            None => {
                let d = p - self.center;
                DVec2::new(d.dot(self.u), d.dot(self.v)) / self.radius
            }
            Some((eye, cotangent)) => {
                let d = p - eye;
                DVec2::new(d.dot(self.u), d.dot(self.v)) * (cotangent / -d.dot(self.w))
            }
        }
    }
}

/// The silhouette of `mesh` in `frame` at `resolution²` pixels, row-major from the bottom
/// row: whether each pixel's centre is covered by some projected triangle.
#[must_use]
pub fn render(mesh: &TriMesh, frame: &Frame, resolution: usize) -> Vec<bool> {
    let mut image = vec![false; resolution * resolution];
    let image_points: Vec<DVec2> = mesh.positions().iter().map(|&p| frame.project(p)).collect();
    let size = 2.0 / resolution as f64;
    // The pixel whose centre is at coordinate `x`, rounded down / up to a centre.
    let first = |x: f64| (((x + 1.0) / size) - 0.5).ceil().max(0.0);
    let last = |x: f64| {
        (((x + 1.0) / size) - 0.5)
            .floor()
            .min(resolution as f64 - 1.0)
    };
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|v| image_points[v as usize]);
        let area = (b - a).perp_dot(c - a);
        if !area.is_finite() || area == 0.0 {
            // Edge-on: it covers no area, so no pixel centre but by accident.
            continue;
        }
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let (i0, i1, j0, j1) = (first(lo.x), last(hi.x), first(lo.y), last(hi.y));
        if i0 > i1 || j0 > j1 {
            continue;
        }
        let sign = area.signum();
        // Inside (or on an edge) when every edge function has the triangle's sign or is 0.
        let inside = |p: DVec2| {
            [(a, b), (b, c), (c, a)]
                .iter()
                .all(|&(s, e)| sign * (e - s).perp_dot(p - s) >= 0.0)
        };
        for j in j0 as usize..=j1 as usize {
            let y = -1.0 + (j as f64 + 0.5) * size;
            for i in i0 as usize..=i1 as usize {
                let cell = &mut image[j * resolution + i];
                if !*cell && inside(DVec2::new(-1.0 + (i as f64 + 0.5) * size, y)) {
                    *cell = true;
                }
            }
        }
    }
    image
}

/// Pixels where two images differ.
///
/// # Panics
///
/// When the images differ in size.
#[must_use]
pub fn wrong_pixels(a: &[bool], b: &[bool]) -> usize {
    assert_eq!(a.len(), b.len(), "images of one size");
    a.iter().zip(b).filter(|(x, y)| x != y).count()
}

/// `count` unit directions at `degrees` from unit `direction`, evenly around it (the
/// views a user moving the camera a little would see next).
#[must_use]
pub fn directions_around(direction: DVec3, degrees: f64, count: usize) -> Vec<DVec3> {
    let w = direction.normalize();
    let helper = if w.x.abs() < 0.6 { DVec3::X } else { DVec3::Y };
    let u = w.cross(helper).normalize();
    let v = w.cross(u);
    let (sin, cos) = degrees.to_radians().sin_cos();
    (0..count)
        .map(|k| {
            let turn = std::f64::consts::TAU * k as f64 / count as f64;
            (w * cos + (u * turn.cos() + v * turn.sin()) * sin).normalize()
        })
        .collect()
}
