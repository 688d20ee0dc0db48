//! What a view shows of a mesh's outline: the cells whose centres some face covers, framed
//! on a given sphere so that a simplification is compared with its original in the same
//! frame; and the pixel difference of two such images (the image-space silhouette error).

use glam::{DVec2, DVec3};
use sphaera_mesh::geometry::minimum_enclosing_ball;
use sphaera_mesh::{Sphere, TriMesh};

use crate::camera::ViewCamera;
use crate::caps::check_resolution;
use crate::views::Projection;
use crate::{DistanceTransform, SilhouetteError};

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
/// [`SilhouetteError::CameraInside`]; [`SilhouetteError::InvalidParameter`] for a
/// resolution above [`MAX_RESOLUTION`](crate::MAX_RESOLUTION).
pub fn coverage(
    mesh: &TriMesh,
    frame: Sphere,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
) -> Result<Vec<bool>, SilhouetteError> {
    let camera = checked_camera(frame, direction, projection, resolution)?;
    let image = project_all(mesh, &camera);
    let mut covered = vec![false; resolution * resolution];
    for t in mesh.triangles() {
        for_each_covered_center(t.map(|v| image[v as usize]), resolution, |cell, _| {
            covered[cell] = true;
        });
    }
    Ok(covered)
}

/// The camera of a view after checking its parameters.
pub(crate) fn checked_camera(
    frame: Sphere,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
) -> Result<ViewCamera, SilhouetteError> {
    crate::labels::check(direction, projection, resolution)?;
    Ok(ViewCamera::new(frame, direction.normalize(), projection))
}

/// Every vertex of `mesh` in image coordinates.
pub(crate) fn project_all(mesh: &TriMesh, camera: &ViewCamera) -> Vec<DVec2> {
    mesh.positions()
        .iter()
        .map(|&p| camera.project(p))
        .collect()
}

/// Calls `visit(cell, center)` for every cell (row-major from the bottom) whose centre the
/// image triangle `t` covers, edges included.
pub(crate) fn for_each_covered_center(
    t: [DVec2; 3],
    resolution: usize,
    mut visit: impl FnMut(usize, DVec2),
) {
    let size = 2.0 / resolution as f64;
    let last = resolution as f64 - 1.0;
    // The cell whose centre is at or after `x` (centres at −1 + (i + ½)·size).
    let first_center = |x: f64| ((x + 1.0) / size - 0.5).ceil().clamp(0.0, last + 1.0) as usize;
    let last_center = |x: f64| ((x + 1.0) / size - 0.5).floor().clamp(-1.0, last) as i64;
    let [a, b, c] = t;
    let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
    let (i0, i1) = (first_center(lo.x), last_center(hi.x));
    let (j0, j1) = (first_center(lo.y), last_center(hi.y));
    if i1 < 0 || j1 < 0 {
        return;
    }
    let side = |p: DVec2, q: DVec2, x: DVec2| (q - p).perp_dot(x - p);
    for j in j0..=j1 as usize {
        let y = -1.0 + (j as f64 + 0.5) * size;
        for i in i0..=i1 as usize {
            let x = DVec2::new(-1.0 + (i as f64 + 0.5) * size, y);
            let s = [side(a, b, x), side(b, c, x), side(c, a, x)];
            if s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0) {
                visit(j * resolution + i, x);
            }
        }
    }
}

/// The coverage image of triangles already projected: `image` holds each vertex's image
/// point (the square `[−1, 1]²` is the picture), `triangles` index it; `resolution²`
/// cells, row-major from the bottom, `true` where a triangle covers the cell's centre
/// (edges included). For cameras this crate does not model (a scene's camera, a
/// renderer's): project with them, then compare with [`silhouette_difference`] and
/// [`contour_displacement`].
///
/// # Examples
///
/// ```
/// use sphaera_mesh::glam::DVec2;
/// use sphaera_silhouette::coverage_of_projection;
///
/// // A square over the right half of a 4 × 4 picture.
/// let image = [DVec2::new(0.0, -1.0), DVec2::new(1.0, -1.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
/// let covered = coverage_of_projection(&image, &[[0, 1, 2], [0, 2, 3]], 4)?;
/// assert_eq!(covered.iter().filter(|&&c| c).count(), 8);
/// assert!(covered[3] && !covered[0]);
/// # Ok::<(), sphaera_silhouette::SilhouetteError>(())
/// ```
///
/// # Errors
///
/// [`SilhouetteError::InvalidResolution`]; [`SilhouetteError::InvalidParameter`] for a
/// resolution above [`MAX_RESOLUTION`](crate::MAX_RESOLUTION) or a triangle naming a
/// point `image` does not have.
pub fn coverage_of_projection(
    image: &[DVec2],
    triangles: &[[u32; 3]],
    resolution: usize,
) -> Result<Vec<bool>, SilhouetteError> {
    check_resolution(resolution)?;
    if let Some(&v) = triangles
        .iter()
        .flatten()
        .find(|&&v| v as usize >= image.len())
    {
        return Err(SilhouetteError::InvalidParameter {
            name: "vertex",
            value: f64::from(v),
            requirement: "the index of one of the projected points",
        });
    }
    let mut covered = vec![false; resolution * resolution];
    for t in triangles {
        for_each_covered_center(t.map(|v| image[v as usize]), resolution, |cell, _| {
            covered[cell] = true;
        });
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

/// The largest displacement between two silhouettes, in cells: the farthest a cell
/// covered by one image (and not the other) lies from the nearest cell covered by the
/// other (the Hausdorff distance between the covered regions, between cell centres).
/// `Some(0.0)` for equal images, `None` when exactly one is empty.
///
/// # Panics
///
/// If the images are not both `resolution²` cells.
#[must_use]
pub fn contour_displacement(a: &[bool], b: &[bool], resolution: usize) -> Option<f64> {
    let n = resolution.checked_mul(resolution);
    assert!(
        n == Some(a.len()) && n == Some(b.len()),
        "two images of resolution² cells"
    );
    displacement(a, b, resolution, |_| true)
}

/// [`contour_displacement`] over the cells a viewer sees: the farthest a cell covered by
/// one image (and not the other) *where `seen` is true* lies from the nearest cell
/// covered by the other, seen or not (what is shown moved at most this far; a part
/// drawn beyond the frame does not count, the frame cutting the silhouettes adds
/// nothing). `Some(0.0)` when neither image covers a seen cell, `None` when one covers a
/// seen cell and the other nothing at all.
///
/// # Panics
///
/// If the images and `seen` are not all `resolution²` cells.
#[must_use]
pub fn contour_displacement_seen(
    a: &[bool],
    b: &[bool],
    resolution: usize,
    seen: &[bool],
) -> Option<f64> {
    let n = resolution.checked_mul(resolution);
    assert!(
        n == Some(a.len()) && n == Some(b.len()) && n == Some(seen.len()),
        "two images and a mask of resolution² cells"
    );
    displacement(a, b, resolution, |cell| seen[cell])
}

/// The farthest a cell where `counts` holds, covered by one of `a` and `b` and not the
/// other, lies from the other's nearest covered cell.
fn displacement(
    a: &[bool],
    b: &[bool],
    resolution: usize,
    counts: impl Fn(usize) -> bool + Copy,
) -> Option<f64> {
    let shows = |image: &[bool]| (0..image.len()).any(|c| image[c] && counts(c));
    match (shows(a), shows(b)) {
        (false, false) => return Some(0.0),
        (true, _) if !b.contains(&true) => return None,
        (_, true) if !a.contains(&true) => return None,
        _ => {}
    }
    Some(one_way(a, b, resolution, counts).max(one_way(b, a, resolution, counts)))
}

/// The farthest a cell of `a` outside `b` where `counts` holds lies from `b`'s nearest
/// cell (`b` covers at least one cell when such a cell exists).
fn one_way(a: &[bool], b: &[bool], resolution: usize, counts: impl Fn(usize) -> bool) -> f64 {
    let mut cells = (0..a.len())
        .filter(|&c| a[c] && !b[c] && counts(c))
        .peekable();
    if cells.peek().is_none() {
        return 0.0;
    }
    // Distances to the nearest cell of `b`, or to the ring of cells around the image when
    // that is nearer (the transform counts it as background): below the distance to that
    // ring the answer is exact, at it `b`'s cells are searched directly.
    let outside_b: Vec<bool> = b.iter().map(|&x| !x).collect();
    let distance = DistanceTransform::Euclidean.apply(&outside_b, resolution, resolution);
    let mut boundary: Option<Vec<(f64, f64)>> = None;
    let mut worst = 0.0_f64;
    for cell in cells {
        let (i, j) = (cell % resolution, cell / resolution);
        let ring = (i.min(j).min(resolution - 1 - i).min(resolution - 1 - j) + 1) as f64;
        let d = f64::from(distance[cell]);
        let d = if d < ring {
            d
        } else {
            let cells = boundary.get_or_insert_with(|| boundary_cells(b, resolution));
            let (x, y) = (i as f64, j as f64);
            cells
                .iter()
                .map(|&(u, v)| (u - x).hypot(v - y))
                .fold(f64::INFINITY, f64::min)
        };
        worst = worst.max(d);
    }
    worst
}

/// The covered cells of `image` next to an uncovered one or to the image's edge (where a
/// nearest covered cell always lies), as `(column, row)`.
fn boundary_cells(image: &[bool], resolution: usize) -> Vec<(f64, f64)> {
    let covered = |i: usize, j: usize| image[j * resolution + i];
    let mut cells = Vec::new();
    for j in 0..resolution {
        for i in 0..resolution {
            if !covered(i, j) {
                continue;
            }
            let edge = i == 0 || j == 0 || i + 1 == resolution || j + 1 == resolution;
            if edge
                || !covered(i - 1, j)
                || !covered(i + 1, j)
                || !covered(i, j - 1)
                || !covered(i, j + 1)
            {
                cells.push((i as f64, j as f64));
            }
        }
    }
    cells
}
