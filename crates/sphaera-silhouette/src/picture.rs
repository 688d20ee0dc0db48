//! Pictures of a view, made by code: per-vertex values shaded in grey on the visible
//! surface (the paper's Fig. 3, labels dark at the silhouette), and two silhouettes
//! overlaid. The pictures are RGB, top row first, ready for any image encoder; the crate
//! itself writes no file format.

use glam::{DVec2, DVec3};
use sphaera_mesh::{Sphere, TriMesh};

use crate::SilhouetteError;
use crate::coverage::{checked_camera, for_each_covered_center, project_all};
use crate::views::Projection;

/// A square RGB picture, 8 bits a channel, top row first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Picture {
    /// Pixels a side.
    pub size: usize,
    /// `size² × 3` bytes: red, green, blue, row by row from the top.
    pub rgb: Vec<u8>,
}

/// The background of a shaded picture.
const BACKGROUND: [u8; 3] = [255, 255, 255];

impl Picture {
    /// A picture of `size²` pixels from per-cell colours in row-major order from the
    /// bottom (the order of [`crate::coverage`] and the labels' cells).
    fn from_cells_bottom_up(size: usize, colour: impl Fn(usize) -> [u8; 3]) -> Self {
        let mut rgb = Vec::with_capacity(size * size * 3);
        for row in (0..size).rev() {
            for column in 0..size {
                rgb.extend_from_slice(&colour(row * size + column));
            }
        }
        Self { size, rgb }
    }
}

/// The surface of `mesh` seen from `direction` (toward the camera), framed on `frame`,
/// each pixel the grey of the front-most face's value there: `values` per vertex,
/// interpolated across the face, black at 0 and light grey at `scale` and beyond;
/// background white. Pixels are cell centres, so the picture's silhouette is
/// [`crate::coverage`]'s. Depth is interpolated in the image (exact for orthographic
/// views, close for perspective ones: a picture, not a measurement).
///
/// # Errors
///
/// [`SilhouetteError::ValueCountMismatch`] unless there is one value per vertex;
/// [`SilhouetteError::InvalidParameter`] for a `scale` that is not positive and finite;
/// as [`crate::coverage`] (a resolution of at most
/// [`MAX_RESOLUTION`](crate::MAX_RESOLUTION)).
pub fn shaded_picture(
    mesh: &TriMesh,
    frame: Sphere,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
    values: &[f32],
    scale: f32,
) -> Result<Picture, SilhouetteError> {
    if values.len() != mesh.vertex_count() {
        return Err(SilhouetteError::ValueCountMismatch {
            values: values.len(),
            vertices: mesh.vertex_count(),
        });
    }
    if !(scale.is_finite() && scale > 0.0) {
        return Err(SilhouetteError::InvalidParameter {
            name: "scale",
            value: f64::from(scale),
            requirement: "positive and finite",
        });
    }
    let camera = checked_camera(frame, direction, projection, resolution)?;
    let image = project_all(mesh, &camera);
    let toward = direction.normalize();
    let depth: Vec<f64> = mesh.positions().iter().map(|p| p.dot(toward)).collect();
    // Per cell: the nearest depth so far (larger is nearer the camera) and its value.
    let mut nearest = vec![(f64::NEG_INFINITY, f32::NAN); resolution * resolution];
    for t in mesh.triangles() {
        let corners = t.map(|v| image[v as usize]);
        let [a, b, c] = corners;
        let area = (b - a).perp_dot(c - a);
        if area == 0.0 {
            // Edge-on: no pixel shows it.
            continue;
        }
        let weights = |x: DVec2| {
            let wa = (b - x).perp_dot(c - x) / area;
            let wb = (c - x).perp_dot(a - x) / area;
            [wa, wb, 1.0 - wa - wb]
        };
        let [za, zb, zc] = t.map(|v| depth[v as usize]);
        let [va, vb, vc] = t.map(|v| f64::from(values[v as usize]));
        for_each_covered_center(corners, resolution, |cell, x| {
            let [wa, wb, wc] = weights(x);
            let z = wa * za + wb * zb + wc * zc;
            if z > nearest[cell].0 {
                nearest[cell] = (z, (wa * va + wb * vb + wc * vc) as f32);
            }
        });
    }
    Ok(Picture::from_cells_bottom_up(resolution, |cell| {
        let (z, value) = nearest[cell];
        if z == f64::NEG_INFINITY {
            BACKGROUND
        } else {
            let grey = (220.0 * (value / scale).clamp(0.0, 1.0)).round() as u8;
            [grey, grey, grey]
        }
    }))
}

/// Two silhouettes of one view overlaid (coverage images of `resolution²` cells, as
/// [`crate::coverage`] makes): grey where both cover, red where only `original` does
/// (the result lost it), blue where only `result` does (the result added it), white
/// elsewhere.
///
/// # Panics
///
/// If the images are not both `resolution²` cells.
#[must_use]
pub fn overlay_picture(original: &[bool], result: &[bool], resolution: usize) -> Picture {
    let n = resolution.checked_mul(resolution);
    assert!(
        n == Some(original.len()) && n == Some(result.len()),
        "two images of resolution² cells"
    );
    Picture::from_cells_bottom_up(resolution, |cell| match (original[cell], result[cell]) {
        (true, true) => [190, 190, 190],
        (true, false) => [215, 40, 40],
        (false, true) => [40, 90, 215],
        (false, false) => BACKGROUND,
    })
}
