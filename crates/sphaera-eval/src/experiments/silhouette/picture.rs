//! `silhouette_labels.png`, the paper's Fig. 3 made by code: the 69k bunny from a view
//! between the cameras, 512² pixels a panel, the camera rolled half a turn so that the
//! bunny stands upright (image up is the world's −z; the bunny's up is +y). Top left, the labels of the outline alone
//! (nearest camera) as grey levels on the visible surface, black at the outline; top
//! right, the labels with the internal silhouettes as well. Bottom, the silhouettes of the
//! original and of a level of detail overlaid (grey both, red original only, blue level
//! only), magnified 4× on the quarter of the view where the unweighted level is most
//! wrong: left the extraction guided by the outline labels at 4 % of the diagonal (factor
//! 0.1, 2 cells), right the unweighted level with as many triangles.

use std::path::Path;

use anyhow::{Context, Result};
use image::{ImageEncoder, RgbImage, codecs::png::PngEncoder};
use sphaera::mesh::{DVec3, TriMesh};
use sphaera::silhouette::{
    ContourTolerance, Interpolation, Labels, Picture, Projection, ViewDependent, bounding_sphere,
    coverage, overlay_picture, shaded_picture,
};
use sphaera::simplify::Hierarchy;

use crate::chart::write_atomically;

/// The picture's file name.
pub const FILE: &str = "silhouette_labels.png";

/// The view: between the 15° cameras, the bunny seen from its side.
pub const VIEW: DVec3 = DVec3::new(0.31, 0.44, 0.84);

/// White pixels between panels.
const GAP: u32 = 8;

/// Writes the picture into `out`. `labels` are the outline labels and those with the
/// internal silhouettes, in that order.
pub fn write(
    out: &Path,
    mesh: &TriMesh,
    hierarchy: &Hierarchy,
    labels: [&Labels; 2],
    resolution: usize,
) -> Result<()> {
    let frame = bounding_sphere(mesh)?;
    let projection = Projection::Orthographic;
    let mut panels = Vec::new();
    for l in [labels[0], labels[1]] {
        let values = l.for_view(VIEW, Interpolation::Nearest)?;
        let scale = values.iter().copied().fold(1.0_f32, f32::max);
        panels.push(shaded_picture(
            mesh, frame, VIEW, projection, resolution, &values, scale,
        )?);
    }
    let extraction = ViewDependent::new(hierarchy, labels[0])?.extract(
        VIEW,
        Interpolation::Nearest,
        ContourTolerance {
            error: 0.04 * mesh.bounding_box_diagonal(),
            factor: 0.1,
            threshold: 2.0,
            cells: f64::INFINITY,
        },
    )?;
    let result = &extraction.simplified.mesh;
    let uniform = hierarchy.level_by_triangles(result.triangle_count()).mesh;
    let picture = |m: &TriMesh| coverage(m, frame, VIEW, projection, resolution);
    let original = picture(mesh)?;
    let (ours, theirs) = (picture(result)?, picture(&uniform)?);
    let window = worst_window(&original, &theirs, resolution);
    for level in [&ours, &theirs] {
        panels.push(magnify(
            &overlay_picture(&original, level, resolution),
            window,
        ));
    }
    let side = u32::try_from(resolution).context("a panel too large")?;
    let whole = 2 * side + GAP;
    let mut canvas = RgbImage::from_pixel(whole, whole, image::Rgb([255, 255, 255]));
    for (k, panel) in panels.iter().enumerate() {
        let (x0, y0) = ((k as u32 % 2) * (side + GAP), (k as u32 / 2) * (side + GAP));
        paste(&mut canvas, panel, x0, y0);
    }
    let mut bytes = Vec::new();
    PngEncoder::new(&mut bytes)
        .write_image(
            canvas.as_raw(),
            whole,
            whole,
            image::ExtendedColorType::Rgb8,
        )
        .context("cannot encode the picture")?;
    write_atomically(&out.join(FILE), &bytes)?;
    eprintln!(
        "{FILE}: {} triangles guided by labels, as many unweighted",
        result.triangle_count()
    );
    Ok(())
}

/// Magnification of the overlays.
const ZOOM: usize = 4;

/// The `(column, row)` from the bottom-left of the `resolution / ZOOM` square window
/// (on a grid of an eighth of the resolution) where `a` and `b` differ most.
fn worst_window(a: &[bool], b: &[bool], resolution: usize) -> (usize, usize) {
    let side = (resolution / ZOOM).max(1);
    let step = (resolution / 8).max(1);
    let mut best = ((0, 0), 0);
    for j in (0..=resolution - side).step_by(step) {
        for i in (0..=resolution - side).step_by(step) {
            let wrong = (j..j + side)
                .flat_map(|y| (i..i + side).map(move |x| y * resolution + x))
                .filter(|&c| a[c] != b[c])
                .count();
            if wrong > best.1 {
                best = ((i, j), wrong);
            }
        }
    }
    best.0
}

/// The window at `(column, row)` from the bottom-left of `picture` (whose rows are top
/// first), `ZOOM` times larger, as a picture of the same size.
fn magnify(picture: &Picture, (i0, j0): (usize, usize)) -> Picture {
    let n = picture.size;
    let mut rgb = Vec::with_capacity(picture.rgb.len());
    for y in 0..n {
        // Output row `y` from the top shows window row `(n − 1 − y) / ZOOM` from its bottom.
        let row = n - 1 - (j0 + (n - 1 - y) / ZOOM);
        for x in 0..n {
            let k = 3 * (row * n + i0 + x / ZOOM);
            rgb.extend_from_slice(&picture.rgb[k..k + 3]);
        }
    }
    Picture { size: n, rgb }
}

/// Copies `panel`, turned half a turn, into `canvas` with its top-left corner at
/// `(x0, y0)`.
fn paste(canvas: &mut RgbImage, panel: &Picture, x0: u32, y0: u32) {
    let last = panel.size.saturating_sub(1);
    for (i, pixel) in panel.rgb.chunks_exact(3).enumerate() {
        let (x, y) = (
            (last - i % panel.size) as u32,
            (last - i / panel.size) as u32,
        );
        canvas.put_pixel(x0 + x, y0 + y, image::Rgb([pixel[0], pixel[1], pixel[2]]));
    }
}
