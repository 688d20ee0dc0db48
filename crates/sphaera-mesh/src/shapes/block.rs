//! Blocks: a cube and an "L", both extrusions of a set of grid cells.

use std::collections::HashMap;

use glam::DVec3;

use super::{check_less, check_positive, check_resolution, check_vertex_budget};
use crate::{MeshError, TriMesh};

/// A cube of edge length `size` centred at the origin, each face cut into
/// `resolution × resolution` squares (two triangles each).
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::cube(2.0, 4)?;
/// assert_eq!(mesh.triangle_count(), 6 * 4 * 4 * 2);
/// assert_eq!(mesh.vertex_count(), 6 * 4 * 4 + 2);
/// assert!((mesh.surface_area() - 24.0).abs() < 1e-12);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `size` is not finite and positive or
/// `resolution` is 0; [`MeshError::ShapeTooLarge`] beyond [`super::MAX_VERTICES`].
///
/// # Panics
///
/// Never.
pub fn cube(size: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("size", size)?;
    check_resolution(resolution, 1, "at least 1")?;
    let n = resolution as f64;
    check_vertex_budget("cube", 6.0 * n * n + 2.0)?;
    let lines = split(-0.5 * size, 0.5 * size, resolution);
    extrude(&lines, &lines, &lines, |_, _| true)
}

/// An "L"-shaped block: the L with two legs of `leg_length` and width `arm_width` in the
/// xy-plane (corner at the origin, legs along +x and +y), extruded to `depth` along +z.
/// Genus 0, volume `(2·leg_length − arm_width) · arm_width · depth`.
///
/// `resolution` subdivisions across the arm width (at least 1); the other directions get
/// squares of about the same size.
///
/// # Examples
///
/// ```
/// let mesh = sphaera_mesh::shapes::l_block(2.0, 1.0, 1.0, 1)?;
/// // Two faces of 3 squares, 8 side squares, 2 squares per triangle.
/// assert_eq!(mesh.triangle_count(), 2 * (2 * 3 + 8));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if a size is not finite and positive,
/// `arm_width ≥ leg_length` or `resolution` is 0; [`MeshError::ShapeTooLarge`].
///
/// # Panics
///
/// Never.
pub fn l_block(
    leg_length: f64,
    arm_width: f64,
    depth: f64,
    resolution: usize,
) -> Result<TriMesh, MeshError> {
    check_positive("leg_length", leg_length)?;
    check_positive("arm_width", arm_width)?;
    check_positive("depth", depth)?;
    check_less("arm_width", arm_width, leg_length, "less than `leg_length`")?;
    check_resolution(resolution, 1, "at least 1")?;
    let cell = arm_width / resolution as f64;
    let (across, along, deep) = (
        resolution as f64,
        (leg_length - arm_width) / cell,
        depth / cell,
    );
    let face = across * (across + 2.0 * along) + 1.0;
    let side = (4.0 * (across + along) + 1.0) * (deep + 1.0);
    check_vertex_budget("l_block", 2.0 * face + side)?;
    let rest = (
        (along.round() as usize).max(1),
        (deep.round() as usize).max(1),
    );
    let mut lines = split(0.0, arm_width, resolution);
    lines.pop();
    lines.extend(split(arm_width, leg_length, rest.0));
    let z = split(0.0, depth, rest.1);
    extrude(&lines, &lines, &z, |i, j| {
        lines[i] < arm_width || lines[j] < arm_width
    })
}

/// `pieces + 1` evenly spaced values from `from` to `to` (both exact).
fn split(from: f64, to: f64, pieces: usize) -> Vec<f64> {
    (0..=pieces)
        .map(|i| {
            if i == pieces {
                to
            } else {
                from + (to - from) * i as f64 / pieces as f64
            }
        })
        .collect()
}

/// The boundary of the cells `(i, j)` with `inside(i, j)` of the grid with lines `xs`,
/// `ys`, extruded over the layers between `zs`: quads split in two triangles, outward.
///
/// Vertices sit on the grid lines and are shared, so the surface has no T-junctions. The
/// inside cells must form a simply connected region in which no two cells touch only at a
/// corner (true for the square and the L), so the surface is a 2-manifold of genus 0.
fn extrude(
    xs: &[f64],
    ys: &[f64],
    zs: &[f64],
    inside: impl Fn(usize, usize) -> bool,
) -> Result<TriMesh, MeshError> {
    let (nx, ny, nz) = (
        xs.len().saturating_sub(1),
        ys.len().saturating_sub(1),
        zs.len().saturating_sub(1),
    );
    let filled = |i: usize, j: usize| i < nx && j < ny && inside(i, j);
    let mut builder = Builder::default();
    let mut quad = |corners: [[usize; 3]; 4]| {
        let [a, b, c, d] =
            corners.map(|[i, j, k]| builder.vertex([i, j, k], || DVec3::new(xs[i], ys[j], zs[k])));
        builder.triangles.push([a, b, c]);
        builder.triangles.push([a, c, d]);
    };
    for i in 0..nx {
        for j in 0..ny {
            if !filled(i, j) {
                continue;
            }
            // Bottom (−z) and top (+z).
            quad([[i, j, 0], [i, j + 1, 0], [i + 1, j + 1, 0], [i + 1, j, 0]]);
            quad([
                [i, j, nz],
                [i + 1, j, nz],
                [i + 1, j + 1, nz],
                [i, j + 1, nz],
            ]);
            for k in 0..nz {
                if i == 0 || !filled(i - 1, j) {
                    quad([[i, j, k], [i, j, k + 1], [i, j + 1, k + 1], [i, j + 1, k]]);
                }
                if !filled(i + 1, j) {
                    let x = i + 1;
                    quad([[x, j, k], [x, j + 1, k], [x, j + 1, k + 1], [x, j, k + 1]]);
                }
                if j == 0 || !filled(i, j - 1) {
                    quad([[i, j, k], [i + 1, j, k], [i + 1, j, k + 1], [i, j, k + 1]]);
                }
                if !filled(i, j + 1) {
                    let y = j + 1;
                    quad([[i, y, k], [i, y, k + 1], [i + 1, y, k + 1], [i + 1, y, k]]);
                }
            }
        }
    }
    TriMesh::new(builder.positions, builder.triangles)
}

/// Vertices keyed by grid coordinates, numbered in order of first use (deterministic).
#[derive(Default)]
struct Builder {
    index: HashMap<[usize; 3], u32>,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

impl Builder {
    fn vertex(&mut self, key: [usize; 3], position: impl FnOnce() -> DVec3) -> u32 {
        *self.index.entry(key).or_insert_with(|| {
            self.positions.push(position());
            // The vertex budget keeps the count far below u32::MAX.
            (self.positions.len() - 1) as u32
        })
    }
}
