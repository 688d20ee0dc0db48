//! Distance labels (sections 3.1.2–3.1.4 and 3.2): for each view, the binary image of the
//! mapped mesh with its internal silhouettes cut out, its distance transform, and the
//! distances carried back to the vertices, edges and faces; for a new view, the labels of
//! the nearest precomputed view or the average of the `n` nearest.

use glam::{DVec2, DVec3};
use sphaera_mesh::topology::{TopologyOptions, analyze_with};
use sphaera_mesh::{Sphere, TriMesh};

use crate::SilhouetteError;
use crate::camera::{ViewCamera, face_normal};
use crate::caps::{check_label_count, check_resolution};
use crate::coverage::bounding_sphere;
use crate::distance::{DistanceTransform, Workspace};
use crate::label_file::MeshFingerprint;
use crate::raster::{cell_index, mark_triangle, rows_of_triangle};
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
    /// one away from it; a zero-area face faces neither way). With [`Contours::All`],
    /// only those no other face hides: these are the ones that cut the image, and their
    /// label is 0.
    pub silhouette: Vec<bool>,
}

/// The labels of one view of `mesh`, looking from `direction` (toward the camera).
///
/// # Errors
///
/// [`SilhouetteError::EmptyMesh`], [`SilhouetteError::InvalidResolution`],
/// [`SilhouetteError::InvalidDirection`], [`SilhouetteError::CameraInside`];
/// [`SilhouetteError::InvalidParameter`] for a resolution above
/// [`MAX_RESOLUTION`](crate::MAX_RESOLUTION).
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
    check_resolution(resolution)?;
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
    /// preserved"): labels measure the distance to the mesh's outline in the image. The
    /// default: measured against the plain simplifier, it keeps the outline best for its
    /// triangles (`silhouette_error_vs_triangles` and `silhouette_vs_simplify` in
    /// `docs/benchmarks.md`).
    #[default]
    External,
    /// The outline and the internal silhouettes the camera sees (the paper's Fig. 2):
    /// cells under faces holding a silhouette vertex are background too, unless another
    /// face hides that vertex (a depth buffer per view; the paper cuts hidden contours
    /// too). On a bumpy scan every bump is a silhouette somewhere, so much of the mesh
    /// gets small labels.
    All,
}

impl Contours {
    /// The name users type and reports show (`"outline"`, …), as
    /// [`Display`](std::fmt::Display) writes it and [`FromStr`](std::str::FromStr) reads it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::External => "outline",
            Self::All => "all",
        }
    }
}

impl std::fmt::Display for Contours {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Contours {
    type Err = sphaera_mesh::ParseNameError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "outline" => Ok(Self::External),
            "all" => Ok(Self::All),
            _ => Err(sphaera_mesh::ParseNameError::new(
                "set of contours",
                s,
                "outline or all",
            )),
        }
    }
}

/// One view's projection and binary image, in buffers kept from view to view.
#[derive(Debug, Default)]
struct Frame {
    /// Per vertex: its image point.
    image: Vec<DVec2>,
    /// Per vertex: bit 1 when a face toward the camera holds it, bit 2 when one away from
    /// it does; both make a silhouette vertex.
    sides: Vec<u8>,
    /// Per cell: 0 when no face touches it, 2 when a face holding a silhouette vertex
    /// does (with [`Contours::All`]), else 1 (an object cell).
    marks: Vec<u8>,
    /// The faces holding no silhouette vertex (mark 1), marked after the others.
    later: Vec<usize>,
    /// With [`Contours::All`]: the silhouette vertices by bucket of a coarse grid, bucket
    /// `k`'s being `bucketed[start[k]..start[k + 1]]`.
    start: Vec<u32>,
    bucketed: Vec<u32>,
    /// Per vertex (with [`Contours::All`]): a silhouette vertex no other face hides.
    visible: Vec<bool>,
    /// Per cell: whether it is an object cell.
    object: Vec<bool>,
    /// Per cell: the distance transform of `object`.
    distances: Vec<f32>,
    workspace: Workspace,
}

/// `sides` bits of a vertex held by faces toward and away from the camera.
const BOTH_SIDES: u8 = 3;

impl Frame {
    /// Projects `mesh` (whose faces have the normals `normals`), finds its silhouette
    /// vertices and builds the binary image and its distance transform.
    fn map(
        &mut self,
        surface: &Surface<'_>,
        camera: &ViewCamera,
        resolution: usize,
        transform: DistanceTransform,
        contours: Contours,
    ) {
        let (mesh, normals) = (surface.mesh, surface.normals.as_slice());
        let positions = mesh.positions();
        self.image.clear();
        self.image
            .extend(positions.iter().map(|&p| camera.project(p)));
        // Silhouette vertices: shared by a face toward the camera and one away from it.
        self.sides.clear();
        self.sides.resize(positions.len(), 0);
        for (t, &normal) in mesh.triangles().iter().zip(normals) {
            // A zero-area face faces neither way: counted as facing away, it would make
            // every vertex of a sliver a silhouette vertex.
            if normal == DVec3::ZERO {
                continue;
            }
            let toward = camera.normal_faces_camera(normal, positions[t[0] as usize]);
            let side = if toward { 1 } else { 2 };
            for &v in t {
                self.sides[v as usize] |= side;
            }
        }
        if contours == Contours::All {
            self.find_visible(surface, camera, resolution);
        }
        // Occupancy (mark 1), with every cell under a face holding a visible silhouette
        // vertex cut out (mark 2). Cut faces go first, so that more rows of the others are already
        // marked and skipped; the marks do not depend on the order.
        self.marks.clear();
        self.marks.resize(resolution * resolution, 0);
        self.later.clear();
        for (f, t) in mesh.triangles().iter().enumerate() {
            let cut = contours == Contours::All && t.iter().any(|&v| self.visible[v as usize]);
            if cut {
                let corners = t.map(|v| self.image[v as usize]);
                mark_triangle(corners, resolution, &mut self.marks, 2);
            } else {
                self.later.push(f);
            }
        }
        for &f in &self.later {
            let corners = mesh.triangles()[f].map(|v| self.image[v as usize]);
            mark_triangle(corners, resolution, &mut self.marks, 1);
        }
        self.object.clear();
        self.object.extend(self.marks.iter().map(|&m| m == 1));
        transform.apply_into(
            &self.object,
            resolution,
            resolution,
            &mut self.workspace,
            &mut self.distances,
        );
    }

    /// Marks the silhouette vertices that no face hides: a vertex is hidden when a face
    /// that is not one of its own covers its image point nearer the camera than it by
    /// more than two cells' length (a fold or another part hiding a contour is farther
    /// in front than that; a neighbour of a vertex seen edge-on is not). The silhouette
    /// vertices are put in buckets of a coarse grid, and each face tests only those in
    /// the buckets its image's bounding box meets: silhouette vertices are few, so this
    /// costs little more than a pass over the faces.
    fn find_visible(&mut self, surface: &Surface<'_>, camera: &ViewCamera, resolution: usize) {
        let (mesh, normals) = (surface.mesh, surface.normals.as_slice());
        let positions = mesh.positions();
        self.visible.clear();
        self.visible
            .extend(self.sides.iter().map(|&sides| sides == BOTH_SIDES));
        // Buckets of silhouette vertices, counted then filled (a counting sort).
        let side = (resolution / 8).clamp(1, 64);
        let bucket =
            |x: f64| ((x + 1.0) * 0.5 * side as f64).clamp(0.0, side as f64 - 1.0) as usize;
        self.start.clear();
        self.start.resize(side * side + 1, 0);
        for (v, &on) in self.visible.iter().enumerate() {
            if on {
                let p = self.image[v];
                self.start[bucket(p.y) * side + bucket(p.x) + 1] += 1;
            }
        }
        if self.start.iter().all(|&n| n == 0) {
            return;
        }
        for k in 0..side * side {
            self.start[k + 1] += self.start[k];
        }
        self.bucketed.clear();
        self.bucketed.resize(self.start[side * side] as usize, 0);
        let mut fill = self.start.clone();
        for (v, &on) in self.visible.iter().enumerate() {
            if on {
                let p = self.image[v];
                let k = bucket(p.y) * side + bucket(p.x);
                self.bucketed[fill[k] as usize] = v as u32;
                fill[k] += 1;
            }
        }
        let slack = 2.0 * camera.cell_length(resolution);
        for (t, &normal) in mesh.triangles().iter().zip(normals) {
            if normal == DVec3::ZERO {
                continue;
            }
            // On a closed, oriented surface the last face a ray crosses toward the camera
            // leaves the solid, so faces it: one facing away never hides alone.
            if surface.closed && !camera.normal_faces_camera(normal, positions[t[0] as usize]) {
                continue;
            }
            let [a, b, c] = t.map(|v| self.image[v as usize]);
            let area = (b - a).perp_dot(c - a);
            if area == 0.0 || !area.is_finite() {
                continue;
            }
            let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
            let [za, zb, zc] = t.map(|v| camera.nearness(positions[v as usize]));
            for j in bucket(lo.y)..=bucket(hi.y) {
                for i in bucket(lo.x)..=bucket(hi.x) {
                    let k = j * side + i;
                    for &v in &self.bucketed[self.start[k] as usize..self.start[k + 1] as usize] {
                        if !self.visible[v as usize] || t.contains(&v) {
                            continue;
                        }
                        let x = self.image[v as usize];
                        if x.x < lo.x || x.x > hi.x || x.y < lo.y || x.y > hi.y {
                            continue;
                        }
                        let wa = (b - x).perp_dot(c - x) / area;
                        let wb = (c - x).perp_dot(a - x) / area;
                        let wc = 1.0 - wa - wb;
                        if wa < 0.0 || wb < 0.0 || wc < 0.0 {
                            continue;
                        }
                        let z = wa * za + wb * zb + wc * zc;
                        if z > camera.nearness(positions[v as usize]) + slack {
                            self.visible[v as usize] = false;
                        }
                    }
                }
            }
        }
    }

    /// The distance of the cell holding image point `p`.
    fn distance_at(&self, p: DVec2, resolution: usize) -> f32 {
        self.distances[cell_index(p, resolution)]
    }
}

/// A mesh with what every view needs of it: its faces' normals and, for the internal
/// silhouettes, whether it is closed and oriented.
struct Surface<'a> {
    mesh: &'a TriMesh,
    normals: Vec<DVec3>,
    closed: bool,
}

impl<'a> Surface<'a> {
    fn new(mesh: &'a TriMesh, contours: Contours) -> Self {
        let closed = contours == Contours::All && {
            let report = analyze_with(mesh, &TopologyOptions::indices_as_given());
            report.is_closed && report.is_oriented
        };
        Self {
            mesh,
            normals: face_normals(mesh),
            closed,
        }
    }
}

/// The (unnormalized) normal of every face of `mesh`.
fn face_normals(mesh: &TriMesh) -> Vec<DVec3> {
    let positions = mesh.positions();
    mesh.triangles()
        .iter()
        .map(|t| face_normal(t.map(|v| positions[v as usize])))
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
    let camera = ViewCamera::new(sphere, direction.normalize(), projection);
    let mut frame = Frame::default();
    frame.map(
        &Surface::new(mesh, contours),
        &camera,
        resolution,
        transform,
        contours,
    );
    let (image, distances) = (&frame.image, &frame.distances);
    // The smallest distance over the cells a triangle touches.
    let smallest = |t: [DVec2; 3]| {
        let mut min = f32::INFINITY;
        rows_of_triangle(t, resolution, |j, a, b| {
            let row = j * resolution;
            min = distances[row + a..=row + b]
                .iter()
                .fold(min, |m, &d| m.min(d));
        });
        min
    };
    let faces = mesh
        .triangles()
        .iter()
        .map(|t| smallest(t.map(|v| image[v as usize])))
        .collect();
    let mut edges: Vec<[u32; 2]> = mesh
        .triangles()
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .map(|[u, v]| [u.min(v), u.max(v)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let edge_labels = edges
        .iter()
        .map(|&[u, v]| {
            let (a, b) = (image[u as usize], image[v as usize]);
            smallest([a, b, b])
        })
        .collect();
    let vertices = image
        .iter()
        .map(|&p| frame.distance_at(p, resolution))
        .collect();
    let silhouette = if contours == Contours::All {
        frame.visible.clone()
    } else {
        frame.sides.iter().map(|&s| s == BOTH_SIDES).collect()
    };
    ViewLabels {
        resolution,
        cells: frame.distances,
        vertices,
        edges,
        edge_labels,
        faces,
        silhouette,
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
    contours: Contours,
    /// The mesh labelled: its counts and fingerprint (label files are checked against it).
    mesh: MeshFingerprint,
    vertex_count: usize,
    /// View-major: view `k`'s labels are `values[k · vertex_count..][..vertex_count]`.
    values: Vec<u16>,
}

fn quantize(d: f32) -> u16 {
    (d * LABEL_SCALE).round().clamp(0.0, f32::from(u16::MAX)) as u16
}

/// How [`Labels::compute`] labels the views: the image resolution, the distance transform
/// and which silhouettes count.
///
/// # Examples
///
/// ```
/// use sphaera_silhouette::{Contours, DistanceTransform, LabelOptions};
///
/// let options = LabelOptions::default();
/// assert_eq!(options.resolution, 512);
/// assert_eq!(options.transform, DistanceTransform::Euclidean);
/// assert_eq!(options.contours, Contours::External);
/// let coarse = options.with_resolution(64).with_contours(Contours::All);
/// assert_eq!((coarse.resolution, coarse.contours), (64, Contours::All));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct LabelOptions {
    /// The cells across each view's image (default 512, the paper's; at most
    /// [`MAX_RESOLUTION`](crate::MAX_RESOLUTION), 4,096).
    pub resolution: usize,
    /// The distance transform (default the exact Euclidean one).
    pub transform: DistanceTransform,
    /// Which silhouettes the labels measure the distance to (default the outline).
    pub contours: Contours,
}

impl Default for LabelOptions {
    fn default() -> Self {
        Self {
            resolution: 512,
            transform: DistanceTransform::Euclidean,
            contours: Contours::External,
        }
    }
}

impl LabelOptions {
    /// With `resolution²` cells per view (at most
    /// [`MAX_RESOLUTION`](crate::MAX_RESOLUTION) a side, checked by [`Labels::compute`]).
    #[must_use]
    pub fn with_resolution(mut self, resolution: usize) -> Self {
        self.resolution = resolution;
        self
    }

    /// With the given distance transform.
    #[must_use]
    pub fn with_transform(mut self, transform: DistanceTransform) -> Self {
        self.transform = transform;
        self
    }

    /// With the given silhouettes.
    #[must_use]
    pub fn with_contours(mut self, contours: Contours) -> Self {
        self.contours = contours;
        self
    }
}

impl Labels {
    /// Labels every view of `views` at `options.resolution²` cells (in parallel with the
    /// `parallel` feature; identical results either way).
    ///
    /// The labels take 2 bytes per vertex per view, at most
    /// [`MAX_LABELS`](crate::MAX_LABELS) of them (1 GiB); each worker thread keeps about
    /// 10 bytes per cell of one view's grid.
    ///
    /// # Errors
    ///
    /// As [`label_view`]; [`SilhouetteError::InvalidParameter`] named
    /// `"vertices × views"` for more than [`MAX_LABELS`](crate::MAX_LABELS) labels,
    /// checked before they are allocated.
    pub fn compute(
        mesh: &TriMesh,
        views: &ViewSet,
        options: &LabelOptions,
    ) -> Result<Self, SilhouetteError> {
        Self::compute_with_progress(mesh, views, options, &|_| {})
    }

    /// [`Labels::compute`], calling `progress` on the calling thread with the number of
    /// views labelled so far, increasing, after each batch of views (a few per core) and
    /// once at the end with the number of views.
    ///
    /// # Examples
    ///
    /// ```
    /// use std::sync::Mutex;
    /// use sphaera_mesh::shapes;
    /// use sphaera_silhouette::{LabelOptions, Labels, ViewSet};
    ///
    /// let mesh = shapes::sphere(1.0, 8)?;
    /// let views = ViewSet::regular(45.0)?;
    /// let counts = Mutex::new(Vec::new());
    /// let labels = Labels::compute_with_progress(
    ///     &mesh,
    ///     &views,
    ///     &LabelOptions::default().with_resolution(16),
    ///     &|done| counts.lock().expect("not poisoned").push(done),
    /// )?;
    /// let counts = counts.into_inner()?;
    /// assert_eq!(counts.last(), Some(&views.len()));
    /// assert!(counts.windows(2).all(|w| w[0] < w[1]));
    /// assert_eq!(labels.views().len(), views.len());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`Labels::compute`].
    pub fn compute_with_progress(
        mesh: &TriMesh,
        views: &ViewSet,
        options: &LabelOptions,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Self, SilhouetteError> {
        let LabelOptions {
            resolution,
            transform,
            contours,
        } = *options;
        check(DVec3::Z, views.projection(), resolution)?;
        let sphere = bounding_sphere(mesh)?;
        let vertex_count = mesh.positions().len();
        check_label_count(vertex_count, views.len())?;
        let surface = Surface::new(mesh, contours);
        // View k's vertex labels into `out`, with `frame`'s buffers.
        let one = |frame: &mut Frame, k: usize, out: &mut [u16]| {
            let camera =
                ViewCamera::new(sphere, views.direction(k).normalize(), views.projection());
            frame.map(&surface, &camera, resolution, transform, contours);
            for (q, &p) in out.iter_mut().zip(&frame.image) {
                *q = quantize(frame.distance_at(p, resolution));
            }
        };
        let mut values = vec![0_u16; views.len() * vertex_count];
        // A mesh with triangles has vertices; `max(1)` only keeps the chunk size valid.
        let chunk = vertex_count.max(1);
        // Views are labelled a batch at a time, a few per core, and progress is reported
        // between batches, on this thread.
        #[cfg(feature = "parallel")]
        let batch = 4 * rayon::current_num_threads().max(1);
        #[cfg(not(feature = "parallel"))]
        let batch = 4;
        #[cfg(not(feature = "parallel"))]
        let mut frame = Frame::default();
        let mut done = 0;
        for views_out in values.chunks_mut(chunk * batch) {
            let first = done;
            #[cfg(feature = "parallel")]
            {
                use rayon::prelude::*;
                views_out
                    .par_chunks_mut(chunk)
                    .enumerate()
                    .for_each_init(Frame::default, |frame, (k, out)| one(frame, first + k, out));
            }
            #[cfg(not(feature = "parallel"))]
            for (k, out) in views_out.chunks_mut(chunk).enumerate() {
                one(&mut frame, first + k, out);
            }
            done += views_out.len() / chunk;
            progress(done);
        }
        if views.is_empty() {
            progress(0);
        }
        Ok(Self {
            views: views.clone(),
            resolution,
            transform,
            contours,
            mesh: MeshFingerprint::of(mesh),
            vertex_count,
            values,
        })
    }

    /// Labels read from a file: `values` holds `views.len() · mesh.vertices` labels,
    /// view-major (the reader checked it).
    pub(crate) fn from_parts(
        views: ViewSet,
        options: LabelOptions,
        mesh: MeshFingerprint,
        values: Vec<u16>,
    ) -> Self {
        Self {
            views,
            resolution: options.resolution,
            transform: options.transform,
            contours: options.contours,
            mesh,
            vertex_count: mesh.vertices,
            values,
        }
    }

    /// Every stored label, view-major.
    pub(crate) fn values(&self) -> &[u16] {
        &self.values
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

    /// The silhouettes the labels measure the distance to.
    #[must_use]
    pub fn contours(&self) -> Contours {
        self.contours
    }

    /// The options the labels were computed with (resolution, transform, contours).
    #[must_use]
    pub fn options(&self) -> LabelOptions {
        LabelOptions {
            resolution: self.resolution,
            transform: self.transform,
            contours: self.contours,
        }
    }

    /// The mesh the labels were computed for: its counts and fingerprint.
    #[must_use]
    pub fn mesh_fingerprint(&self) -> MeshFingerprint {
        self.mesh
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
