//! Distance labels (sections 3.1.2–3.1.4 and 3.2): for each view, the binary image of the
//! mapped mesh with its internal silhouettes cut out, its distance transform, and the
//! distances carried back to the vertices, edges and faces; for a new view, the labels of
//! the nearest precomputed view or the average of the `n` nearest.

use glam::{DVec2, DVec3};
use sphaera_mesh::{Sphere, TriMesh};

use crate::SilhouetteError;
use crate::camera::Camera;
use crate::coverage::bounding_sphere;
use crate::distance::DistanceTransform;
use crate::raster::{cell_index, cells_of_triangle, cells_of_triangle_into};
use crate::views::{Projection, ViewSet};

/// Stored labels are `round(distance · LABEL_SCALE)` in a `u16` (saturating): a sixteenth
/// of a cell, up to 4,095 cells.
pub const LABEL_SCALE: f32 = 16.0;

/// Everything one view gives: the grid's distances and the labels of every vertex, edge
/// and face, in cells.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewLabels {
    /// Cells a side.
    pub resolution: usize,
    /// Per cell (row-major from the bottom row): the distance to the nearest background
    /// cell, 0 on the background.
    pub cells: Vec<f32>,
    /// Per vertex: the distance of the cell its projection falls in. A silhouette vertex's
    /// cell is background, so its label is 0; the label then grows with the vertex's
    /// distance to the contour in the image, which is what the label is for. (The minimum
    /// over the incident faces would be smaller everywhere and blur that distance by a
    /// face's width.)
    pub vertices: Vec<f32>,
    /// The mesh's edges, each `(low, high)`, ascending.
    pub edges: Vec<[u32; 2]>,
    /// Per edge: the smallest distance over the cells its projection touches.
    pub edge_labels: Vec<f32>,
    /// Per face: the smallest distance over the cells its projection touches (the paper).
    pub faces: Vec<f32>,
    /// Per vertex: whether it is on a silhouette (shared by a face toward the camera and
    /// one away from it).
    pub silhouette: Vec<bool>,
}

/// The labels of one view of `mesh`, looking from `direction` (toward the camera).
///
/// # Errors
///
/// [`SilhouetteError::EmptyMesh`], [`SilhouetteError::InvalidResolution`],
/// [`SilhouetteError::InvalidDirection`], [`SilhouetteError::CameraInside`].
pub fn label_view(
    mesh: &TriMesh,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
    transform: DistanceTransform,
    contours: Contours,
) -> Result<ViewLabels, SilhouetteError> {
    check(direction, projection, resolution)?;
    let sphere = bounding_sphere(mesh)?;
    Ok(label_in_frame(
        mesh, sphere, direction, projection, resolution, transform, contours,
    ))
}

/// Checks a view's parameters.
pub(crate) fn check(
    direction: DVec3,
    projection: Projection,
    resolution: usize,
) -> Result<(), SilhouetteError> {
    if resolution == 0 {
        return Err(SilhouetteError::InvalidResolution { resolution });
    }
    let length = direction.length();
    if !(length.is_finite() && length > 0.0) {
        return Err(SilhouetteError::InvalidDirection {
            direction: direction.to_array(),
        });
    }
    if let Projection::Perspective { distance } = projection
        && !(distance.is_finite() && distance > 1.0)
    {
        return Err(SilhouetteError::CameraInside { distance });
    }
    Ok(())
}

/// Which silhouettes the binary image brings out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Contours {
    /// The outline only (the paper: "in the case that only the external contour has to be
    /// preserved"): labels measure the distance to the mesh's outline in the image.
    External,
    /// The outline and the internal silhouettes (the paper's Fig. 2): cells under faces
    /// holding a silhouette vertex are background too. On a bumpy scan every bump is a
    /// silhouette somewhere, so much of the mesh gets small labels.
    #[default]
    All,
}

/// One view's projection and binary image: the vertices' image points, each face's
/// cells, and the object cells (under some face, and not under a face holding a
/// silhouette vertex).
struct Mapped {
    image: Vec<DVec2>,
    silhouette: Vec<bool>,
    object: Vec<bool>,
}

/// Projects `mesh`, finds its silhouette vertices and builds the binary image, calling
/// `each_face(f, cells)` with every face's cells.
fn map_view(
    mesh: &TriMesh,
    sphere: Sphere,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
    contours: Contours,
    mut each_face: impl FnMut(usize, &[usize]),
) -> Mapped {
    let camera = Camera::new(sphere, direction.normalize(), projection);
    let image: Vec<DVec2> = mesh
        .positions()
        .iter()
        .map(|&p| camera.project(p))
        .collect();
    // Silhouette vertices: shared by a face toward the camera and one away from it.
    let mut toward = vec![false; image.len()];
    let mut away = vec![false; image.len()];
    for &t in mesh.triangles() {
        let seen = if camera.faces_camera(mesh, t) {
            &mut toward
        } else {
            &mut away
        };
        for v in t {
            seen[v as usize] = true;
        }
    }
    let silhouette: Vec<bool> = toward.iter().zip(&away).map(|(&a, &b)| a && b).collect();
    // Occupancy, with every cell under a face holding a silhouette vertex cut out.
    let cells = resolution * resolution;
    let mut occupied = vec![false; cells];
    let mut cut = vec![false; cells];
    let mut list = Vec::new();
    for (f, t) in mesh.triangles().iter().enumerate() {
        cells_of_triangle_into(t.map(|v| image[v as usize]), resolution, &mut list);
        let on_silhouette = contours == Contours::All && t.iter().any(|&v| silhouette[v as usize]);
        for &c in &list {
            occupied[c] = true;
            cut[c] |= on_silhouette;
        }
        each_face(f, &list);
    }
    let object = occupied.iter().zip(&cut).map(|(&o, &c)| o && !c).collect();
    Mapped {
        image,
        silhouette,
        object,
    }
}

/// Vertex labels only (what [`Labels`] stores).
fn vertex_labels_in_frame(
    mesh: &TriMesh,
    sphere: Sphere,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
    transform: DistanceTransform,
    contours: Contours,
) -> Vec<f32> {
    let mapped = map_view(
        mesh,
        sphere,
        direction,
        projection,
        resolution,
        contours,
        |_, _| {},
    );
    let distances = transform.apply(&mapped.object, resolution, resolution);
    mapped
        .image
        .iter()
        .map(|&p| distances[cell_index(p, resolution)])
        .collect()
}

fn label_in_frame(
    mesh: &TriMesh,
    sphere: Sphere,
    direction: DVec3,
    projection: Projection,
    resolution: usize,
    transform: DistanceTransform,
    contours: Contours,
) -> ViewLabels {
    let mut face_cells: Vec<Vec<usize>> = vec![Vec::new(); mesh.triangle_count()];
    let mapped = map_view(
        mesh,
        sphere,
        direction,
        projection,
        resolution,
        contours,
        |f, cells| {
            face_cells[f] = cells.to_vec();
        },
    );
    let distances = transform.apply(&mapped.object, resolution, resolution);
    let smallest = |cells: &[usize]| {
        cells
            .iter()
            .map(|&c| distances[c])
            .fold(f32::INFINITY, f32::min)
    };
    let faces = face_cells.iter().map(|cells| smallest(cells)).collect();
    let mut edges: Vec<[u32; 2]> = mesh
        .triangles()
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .map(|[u, v]| [u.min(v), u.max(v)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let image = &mapped.image;
    let edge_labels = edges
        .iter()
        .map(|&[u, v]| {
            let (a, b) = (image[u as usize], image[v as usize]);
            smallest(&cells_of_triangle([a, b, b], resolution))
        })
        .collect();
    let vertices = image
        .iter()
        .map(|&p| distances[cell_index(p, resolution)])
        .collect();
    ViewLabels {
        resolution,
        cells: distances,
        vertices,
        edges,
        edge_labels,
        faces,
        silhouette: mapped.silhouette,
    }
}

/// How labels for a view that was not precomputed are made (section 3.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// The labels of the nearest precomputed view.
    Nearest,
    /// The average of the labels of the `n` nearest views.
    Average(usize),
}

/// The vertex labels of a mesh for every view of a [`ViewSet`]: one `u16` per vertex per
/// view (the paper's memory figure), in units of `1 / LABEL_SCALE` cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Labels {
    views: ViewSet,
    resolution: usize,
    transform: DistanceTransform,
    vertex_count: usize,
    /// View-major: view `k`'s labels are `values[k · vertex_count..][..vertex_count]`.
    values: Vec<u16>,
}

fn quantize(d: f32) -> u16 {
    (d * LABEL_SCALE).round().clamp(0.0, f32::from(u16::MAX)) as u16
}

impl Labels {
    /// Labels every view of `views` at `resolution²` cells (in parallel with the
    /// `parallel` feature; identical results either way).
    ///
    /// # Errors
    ///
    /// As [`label_view`].
    pub fn compute(
        mesh: &TriMesh,
        views: &ViewSet,
        resolution: usize,
        transform: DistanceTransform,
        contours: Contours,
    ) -> Result<Self, SilhouetteError> {
        check(DVec3::Z, views.projection(), resolution)?;
        let sphere = bounding_sphere(mesh)?;
        let one = |k: usize| -> Vec<u16> {
            vertex_labels_in_frame(
                mesh,
                sphere,
                views.direction(k),
                views.projection(),
                resolution,
                transform,
                contours,
            )
            .into_iter()
            .map(quantize)
            .collect()
        };
        #[cfg(feature = "parallel")]
        let per_view: Vec<Vec<u16>> = {
            use rayon::prelude::*;
            (0..views.len()).into_par_iter().map(one).collect()
        };
        #[cfg(not(feature = "parallel"))]
        let per_view: Vec<Vec<u16>> = (0..views.len()).map(one).collect();
        Ok(Self {
            views: views.clone(),
            resolution,
            transform,
            vertex_count: mesh.positions().len(),
            values: per_view.concat(),
        })
    }

    /// Vertices labelled (the mesh's vertex count).
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// The view set.
    #[must_use]
    pub fn views(&self) -> &ViewSet {
        &self.views
    }

    /// Cells a side of each view's grid.
    #[must_use]
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// The distance transform used.
    #[must_use]
    pub fn transform(&self) -> DistanceTransform {
        self.transform
    }

    /// Bytes of label storage (2 per vertex per view).
    #[must_use]
    pub fn storage_bytes(&self) -> usize {
        self.values.len() * size_of::<u16>()
    }

    /// The stored labels of view `k`, in units of `1 / LABEL_SCALE` cell.
    ///
    /// # Panics
    ///
    /// If `k >= self.views().len()`.
    #[must_use]
    pub fn stored(&self, k: usize) -> &[u16] {
        &self.values[k * self.vertex_count..(k + 1) * self.vertex_count]
    }

    /// The labels of view `k`, in cells.
    #[must_use]
    pub fn view(&self, k: usize) -> Vec<f32> {
        self.stored(k)
            .iter()
            .map(|&q| f32::from(q) / LABEL_SCALE)
            .collect()
    }

    /// The vertex labels (in cells) for a view from `direction`: a precomputed view's own
    /// labels when `direction` is one (within 10⁻¹² in the cosine), else the nearest view's or the average of
    /// the `n` nearest.
    ///
    /// # Errors
    ///
    /// [`SilhouetteError::InvalidDirection`]; [`SilhouetteError::InvalidNearest`] for
    /// `Average(0)` or more views than the set has.
    pub fn for_view(
        &self,
        direction: DVec3,
        interpolation: Interpolation,
    ) -> Result<Vec<f32>, SilhouetteError> {
        let n = match interpolation {
            Interpolation::Nearest => 1,
            Interpolation::Average(n) => n,
        };
        let nearest = self.views.nearest_n(direction, n.max(1))?;
        if n == 0 {
            return Err(SilhouetteError::InvalidNearest {
                asked: 0,
                available: self.views.len(),
            });
        }
        let first = nearest[0];
        // A precomputed view (up to rounding of the direction's length) is its own.
        if n == 1 || self.views.direction(first).dot(direction.normalize()) >= 1.0 - 1e-12 {
            return Ok(self.view(first));
        }
        let mut sum = vec![0_u32; self.vertex_count];
        for &k in &nearest {
            for (s, &q) in sum.iter_mut().zip(self.stored(k)) {
                *s += u32::from(q);
            }
        }
        let scale = LABEL_SCALE * nearest.len() as f32;
        Ok(sum.into_iter().map(|s| s as f32 / scale).collect())
    }
}
