//! What a view shows of a mesh's outline: the cells whose centres some face covers, framed
//! on a given sphere so that a simplification is compared with its original in the same
//! frame; and the pixel difference of two such images (the image-space silhouette error).

use glam::{DVec2, DVec3};
use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_mesh::{Sphere, TriMesh};

use crate::SilhouetteError;
use crate::camera::Camera;
use crate::views::Projection;

/// The sphere views of `mesh` are framed on: the smallest ball holding its vertices.
///
/// # Errors
///
/// [`SilhouetteError::EmptyMesh`] for a mesh without triangles.
pub fn bounding_sphere(mesh: &TriMesh) -> Result<Sphere, SilhouetteError> {
    if mesh.triangles().is_empty() {
        return Err(SilhouetteError::EmptyMesh);
    }
    minimum_enclosing_ball(mesh.positions()).map_err(|_| SilhouetteError::EmptyMesh)
}

/// The coverage image of `mesh` seen from `direction` (toward the camera), framed on
/// `frame`: `resolution²` cells, row-major from the bottom, `true` where a face covers the
/// cell's centre (edges included), as a renderer would draw it.
///
/// # Errors
///
/// [`SilhouetteError::InvalidResolution`], [`SilhouetteError::InvalidDirection`],
/// [`SilhouetteError::CameraInside`].
pub fn coverage(
    mesh: &TriMesh,
    frame: Sphere,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
) -> Result<Vec<bool>, SilhouetteError> {
    crate::labels::check(direction, projection, resolution)?;
    let camera = Camera::new(frame, direction.normalize(), projection);
    let image: Vec<DVec2> = mesh
        .positions()
        .iter()
        .map(|&p| camera.project(p))
        .collect();
    let size = 2.0 / resolution as f64;
    let last = resolution as f64 - 1.0;
    // The cell whose centre is at or after `x` (centres at −1 + (i + ½)·size).
    let first_centre = |x: f64| ((x + 1.0) / size - 0.5).ceil().clamp(0.0, last + 1.0) as usize;
    let last_centre = |x: f64| ((x + 1.0) / size - 0.5).floor().clamp(-1.0, last) as i64;
    let mut covered = vec![false; resolution * resolution];
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|v| image[v as usize]);
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let (i0, i1) = (first_centre(lo.x), last_centre(hi.x));
        let (j0, j1) = (first_centre(lo.y), last_centre(hi.y));
        if i1 < 0 || j1 < 0 {
            continue;
        }
        let side = |p: DVec2, q: DVec2, x: DVec2| (q - p).perp_dot(x - p);
        for j in j0..=j1 as usize {
            let y = -1.0 + (j as f64 + 0.5) * size;
            for i in i0..=i1 as usize {
                let x = DVec2::new(-1.0 + (i as f64 + 0.5) * size, y);
                let s = [side(a, b, x), side(b, c, x), side(c, a, x)];
                if s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0) {
                    covered[j * resolution + i] = true;
                }
            }
        }
    }
    Ok(covered)
}

/// The number of cells where two coverage images of the same size differ.
///
/// # Panics
///
/// If the images differ in size.
#[must_use]
pub fn silhouette_difference(a: &[bool], b: &[bool]) -> usize {
    assert_eq!(a.len(), b.len(), "two images of one size");
    a.iter().zip(b).filter(|(x, y)| x != y).count()
}
