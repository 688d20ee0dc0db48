//! The builder every reader feeds, with the vertex and face checks the readers share.
//!
//! Readers parse their own syntax and report errors at their own locations; the checks on
//! what they found (finite coordinates, vertex count within `u32`, faces of at least three
//! vertices) live here and return the [`ParseReason`] for the reader to place.

use glam::DVec3;

use super::polygon::triangulate;
use super::{Format, LoadReport, LoadedMesh, ParseReason};
use crate::IoError;
use sphaera_mesh::TriMesh;

/// `xyz` as a point, or [`ParseReason::NonFiniteCoordinate`] naming vertex `vertex` and the
/// first axis that is NaN or infinite.
#[inline]
pub(crate) fn finite_point(xyz: [f64; 3], vertex: usize) -> Result<DVec3, ParseReason> {
    if xyz.iter().all(|v| v.is_finite()) {
        Ok(DVec3::from_array(xyz))
    } else {
        Err(non_finite(xyz, vertex))
    }
}

/// The error for a point with a NaN or infinite coordinate (kept out of the readers' loops).
#[cold]
fn non_finite(xyz: [f64; 3], vertex: usize) -> ParseReason {
    let (axis, value) = ['x', 'y', 'z']
        .into_iter()
        .zip(xyz)
        .find(|(_, v)| !v.is_finite())
        .unwrap_or(('x', xyz[0]));
    ParseReason::NonFiniteCoordinate {
        vertex,
        axis,
        value,
    }
}

/// The error for vertex `vertex` when it does not fit a `u32` index.
#[cold]
fn too_many_vertices(vertex: usize) -> ParseReason {
    ParseReason::TooManyVertices {
        count: vertex as u64 + 1,
    }
}

/// The error for a face of `count < 3` vertices.
#[cold]
fn too_few_face_vertices(count: usize) -> ParseReason {
    ParseReason::TooFewFaceVertices { count }
}

/// A polygon whose triangulation waits for all positions to be known.
struct PendingPolygon {
    /// First triangle slot reserved for it.
    slot: usize,
    /// Its vertex indices in `MeshBuilder::pending_indices`.
    start: usize,
    len: usize,
}

/// Collects positions and faces while a reader parses, then triangulates and validates.
///
/// Readers check every index against the vertex count before calling [`Self::push_face`]
/// (so errors carry the file location); [`Self::finish`] still validates through
/// [`TriMesh::new`].
#[derive(Default)]
pub(crate) struct MeshBuilder {
    pub(crate) positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    pending: Vec<PendingPolygon>,
    pending_indices: Vec<u32>,
    /// Face records read.
    pub(crate) faces: usize,
}

impl MeshBuilder {
    /// Adds the vertex `xyz` (the next one, numbered `self.positions.len()`).
    ///
    /// Refuses a NaN or infinite coordinate ([`ParseReason::NonFiniteCoordinate`]) and a
    /// vertex that would not fit a `u32` index ([`ParseReason::TooManyVertices`]).
    #[inline]
    pub(crate) fn push_vertex(&mut self, xyz: [f64; 3]) -> Result<(), ParseReason> {
        let vertex = self.positions.len();
        let point = finite_point(xyz, vertex)?;
        if vertex >= u32::MAX as usize {
            return Err(too_many_vertices(vertex));
        }
        self.positions.push(point);
        Ok(())
    }

    /// Adds a face (vertex indices the reader has checked against the vertex count);
    /// polygons are triangulated by [`Self::finish`].
    ///
    /// Refuses a face of fewer than three vertices ([`ParseReason::TooFewFaceVertices`]).
    #[inline]
    pub(crate) fn push_face(&mut self, indices: &[u32]) -> Result<(), ParseReason> {
        match *indices {
            [a, b, c] => self.triangles.push([a, b, c]),
            _ if indices.len() > 3 => {
                self.pending.push(PendingPolygon {
                    slot: self.triangles.len(),
                    start: self.pending_indices.len(),
                    len: indices.len(),
                });
                self.pending_indices.extend_from_slice(indices);
                let placeholders = indices.len() - 2;
                self.triangles
                    .extend(std::iter::repeat_n([0, 0, 0], placeholders));
            }
            _ => return Err(too_few_face_vertices(indices.len())),
        }
        self.faces += 1;
        Ok(())
    }

    /// Reserves room for about `faces` triangles.
    pub(crate) fn reserve_triangles(&mut self, faces: usize) {
        self.triangles.reserve(faces);
    }

    /// Triangulates the polygons and builds the mesh. `report` comes in with the format's
    /// own counts; the polygon counts are filled in here.
    pub(crate) fn finish(mut self, mut report: LoadReport) -> Result<LoadedMesh, IoError> {
        report.faces_in_file = self.faces;
        let mut points = Vec::new();
        let mut local = Vec::new();
        for polygon in &self.pending {
            let Some(indices) = self
                .pending_indices
                .get(polygon.start..polygon.start + polygon.len)
            else {
                continue;
            };
            points.clear();
            for &i in indices {
                // Readers check indices before `push_face`; a bad one is still handled
                // (TriMesh::new reports it) rather than panicking.
                points.push(
                    self.positions
                        .get(i as usize)
                        .copied()
                        .unwrap_or(DVec3::ZERO),
                );
            }
            local.clear();
            let shape = triangulate(&points, &mut local);
            report.polygons_triangulated += 1;
            report.non_planar_polygons += usize::from(shape.non_planar);
            report.non_convex_polygons += usize::from(shape.non_convex);
            report.fan_fallbacks += usize::from(shape.fan_fallback);
            for (k, tri) in local.iter().enumerate() {
                if let Some(slot) = self.triangles.get_mut(polygon.slot + k) {
                    *slot = tri.map(|j| indices.get(j).copied().unwrap_or(0));
                }
            }
        }
        let mesh = TriMesh::new(self.positions, self.triangles)?;
        Ok(LoadedMesh { mesh, report })
    }

    /// A report with the format's counts, for [`Self::finish`].
    pub(crate) fn report(format: Format, vertex_records: usize) -> LoadReport {
        LoadReport {
            format,
            vertex_records,
            faces_in_file: 0,
            polygons_triangulated: 0,
            non_convex_polygons: 0,
            non_planar_polygons: 0,
            fan_fallbacks: 0,
            welded_vertices: 0,
            primitives_read: 0,
            primitives_skipped: 0,
            mirrored_primitives: 0,
        }
    }
}
