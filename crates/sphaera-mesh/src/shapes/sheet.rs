//! Sheets: open surfaces of zero thickness (a square, a disc, a ring), the shapes a
//! [`Surface::shell`](sphaera_query::Surface::shell) stands for (a sign, a cloth, a plate modelled
//! as one surface). Unlike the other builders these are not closed: they have no inside.

use glam::DVec3;

use super::{check_less, check_positive, check_resolution, check_vertex_budget};
use crate::{MeshError, TriMesh};

/// A flat square of edge `size` in the plane z = 0, centred at the origin, cut into
/// `resolution × resolution` squares (two triangles each), facing +z.
///
/// # Examples
///
/// ```
/// let square = sphaera_mesh::shapes::square_sheet(2.0, 3)?;
/// assert_eq!(square.triangle_count(), 2 * 3 * 3);
/// assert!((square.surface_area() - 4.0).abs() < 1e-12);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `size` is not finite and positive or `resolution`
/// is 0; [`MeshError::ShapeTooLarge`] beyond [`super::MAX_VERTICES`].
///
/// # Panics
///
/// Never.
pub fn square_sheet(size: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("size", size)?;
    check_resolution(resolution, 1, "at least 1")?;
    let n = resolution;
    // In `f64`: `(n + 1)²` overflows `usize` (to as little as 0) for a huge `n`.
    check_vertex_budget("square sheet", (n as f64 + 1.0) * (n as f64 + 1.0))?;
    let at = |i: usize| -0.5 * size + size * i as f64 / n as f64;
    let mut positions = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            positions.push(DVec3::new(at(i), at(j), 0.0));
        }
    }
    let index = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles)
}

/// A flat ring in the plane z = 0, centred at the origin, between radii `inner` and
/// `outer`, with `resolution` segments around (at least 3) and rings of about square
/// cells across; facing +z. `inner = 0` gives a disc (a fan at the centre).
///
/// # Examples
///
/// ```
/// use std::f64::consts::PI;
///
/// let disc = sphaera_mesh::shapes::ring_sheet(1.0, 0.0, 64)?;
/// assert!((disc.surface_area() - PI).abs() < 0.01);
/// let ring = sphaera_mesh::shapes::ring_sheet(1.0, 0.5, 64)?; // a sheet with a hole
/// assert!((ring.surface_area() - 0.75 * PI).abs() < 0.01);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
///
/// # Errors
///
/// [`MeshError::InvalidParameter`] if `outer` is not finite and positive, `inner` is
/// negative or not below `outer`, or `resolution` is below 3;
/// [`MeshError::ShapeTooLarge`] beyond [`super::MAX_VERTICES`].
///
/// # Panics
///
/// Never.
pub fn ring_sheet(outer: f64, inner: f64, resolution: usize) -> Result<TriMesh, MeshError> {
    check_positive("outer", outer)?;
    super::check_non_negative("inner", inner)?;
    check_less("inner", inner, outer, "below outer")?;
    check_resolution(resolution, 3, "at least 3")?;
    let segments = resolution;
    // Rings of cells about as long across as around at the outer edge.
    let cell = std::f64::consts::TAU * outer / segments as f64;
    let rings = (((outer - inner) / cell).ceil() as usize).max(1);
    // In `f64`, so that a huge resolution cannot overflow the count.
    check_vertex_budget("ring sheet", (rings as f64 + 1.0) * segments as f64 + 1.0)?;
    let mut positions = Vec::new();
    let center = inner == 0.0;
    if center {
        positions.push(DVec3::ZERO);
    }
    let first_ring = usize::from(center);
    for r in first_ring..=rings {
        let radius = inner + (outer - inner) * r as f64 / rings as f64;
        for s in 0..segments {
            let angle = std::f64::consts::TAU * s as f64 / segments as f64;
            positions.push(DVec3::new(radius * angle.cos(), radius * angle.sin(), 0.0));
        }
    }
    let ring_start = |r: usize| u32::from(center) + ((r - first_ring) * segments) as u32;
    let at = |r: usize, s: usize| ring_start(r) + (s % segments) as u32;
    let mut triangles = Vec::new();
    if center {
        for s in 0..segments {
            triangles.push([0, at(1, s), at(1, s + 1)]);
        }
    }
    for r in first_ring.max(usize::from(center))..rings {
        for s in 0..segments {
            let (a, b, c, d) = (at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles)
}
