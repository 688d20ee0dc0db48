//! The editable half-edge mesh: construction from any [`TriMesh`] and navigation.

use glam::DVec3;

use super::edge_table::{EdgeTable, halfedge_vertices};
use crate::{MeshError, TriMesh};

/// Marker for "no element" in `u32` links.
pub(crate) const NONE: u32 = u32::MAX;
/// Twin value of a half-edge left without twin by the non-manifold policy (a third face
/// on an edge, or two faces traversing the edge in the same direction).
pub(crate) const UNPAIRED: u32 = u32::MAX - 1;

pub(crate) const DELETED: u8 = 1;
pub(crate) const NON_MANIFOLD: u8 = 2;
pub(crate) const LOCKED: u8 = 4;

/// Handle of a vertex of a [`HalfEdgeMesh`]. Vertex `i < n` is vertex `i` of the source
/// [`TriMesh`]; copies made at non-manifold vertices follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VertexId(pub u32);

/// Handle of a half-edge of a [`HalfEdgeMesh`]: half-edge `3 f + i` of face `f` goes from
/// its corner `i` to corner `(i + 1) % 3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct HalfEdgeId(pub u32);

/// Handle of a face of a [`HalfEdgeMesh`] (faces are the source triangles without the
/// skipped ones, in order; [`HalfEdgeMesh::original_face`] maps back).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FaceId(pub u32);

macro_rules! handle_index {
    ($($t:ty),*) => {$(
        impl $t {
            /// The handle as a `usize` index.
            pub const fn index(self) -> usize {
                self.0 as usize
            }
        }
    )*};
}
handle_index!(VertexId, HalfEdgeId, FaceId);

#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Vertex {
    pub(crate) position: DVec3,
    /// Anchor: an outgoing half-edge; for a boundary vertex, the one without twin.
    pub(crate) halfedge: u32,
    pub(crate) original: u32,
    /// Collapses into this vertex currently applied (see `CollapseRecord`).
    pub(crate) merges: u32,
    pub(crate) flags: u8,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct HalfEdge {
    pub(crate) origin: u32,
    /// Twin half-edge, or [`NONE`] (boundary) or [`UNPAIRED`] (non-manifold policy).
    pub(crate) twin: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Face {
    pub(crate) original: u32,
    pub(crate) deleted: bool,
}

/// An editable half-edge mesh of triangles, built from any [`TriMesh`].
///
/// See the [module documentation](super) for the layout, the non-manifold policy and the
/// boundary conventions.
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology::{HalfEdgeMesh, VertexId}};
///
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )?;
/// let he = HalfEdgeMesh::from_trimesh(&mesh);
/// let mut ring: Vec<u32> = he.neighbors(VertexId(0)).map(|v| v.0).collect();
/// ring.sort_unstable();
/// assert_eq!(ring, vec![1, 2, 3]);
/// assert!(!he.is_boundary_vertex(VertexId(0)));
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct HalfEdgeMesh {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) halfedges: Vec<HalfEdge>,
    pub(crate) faces: Vec<Face>,
    pub(crate) skipped_triangle_count: usize,
    pub(crate) live_vertex_count: usize,
    pub(crate) live_face_count: usize,
}

impl HalfEdgeMesh {
    /// Builds the half-edge mesh of `mesh`. Never fails: see the module documentation for
    /// what happens to non-manifold edges and vertices and to degenerate triangles.
    ///
    /// Indices are taken as given: weld first ([`weld_vertices`](super::weld_vertices)
    /// with tolerance 0) for meshes whose files split vertices at seams.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::{HalfEdgeMesh, VertexId}};
    ///
    /// // Two triangles touching at vertex 0 only (a bow tie), plus a degenerate one.
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y],
    ///     vec![[0, 1, 2], [0, 3, 4], [1, 1, 2]],
    /// )?;
    /// let he = HalfEdgeMesh::from_trimesh(&mesh);
    /// assert_eq!(he.skipped_triangle_count(), 1);
    /// assert_eq!(he.vertex_count(), 6); // vertex 0 was split into two copies
    /// assert!(he.is_non_manifold_vertex(VertexId(0)));
    /// assert_eq!(he.original_vertex(VertexId(5)), 0);
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Performance
    ///
    /// Linear time and memory (24 bytes per half-edge pair of a face corner, 40 per
    /// vertex). The time on the 871k-triangle dragon is in the section *Loading and
    /// topology (`sphaera-mesh`)* of `docs/benchmarks.md` in the repository (`cargo bench
    /// -p sphaera-io --bench load_topology`).
    pub fn from_trimesh(mesh: &TriMesh) -> Self {
        let mut triangles = Vec::with_capacity(mesh.triangle_count());
        let mut faces = Vec::with_capacity(mesh.triangle_count());
        for (t, tri) in mesh.triangles().iter().enumerate() {
            if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                triangles.push(*tri);
                faces.push(Face {
                    original: t as u32,
                    deleted: false,
                });
            }
        }
        let skipped_triangle_count = mesh.triangle_count() - triangles.len();
        let mut vertices: Vec<Vertex> = mesh
            .positions()
            .iter()
            .enumerate()
            .map(|(i, &position)| Vertex {
                position,
                halfedge: NONE,
                original: i as u32,
                merges: 0,
                flags: 0,
            })
            .collect();
        let mut halfedges: Vec<HalfEdge> = triangles
            .iter()
            .flat_map(|t| t.map(|origin| HalfEdge { origin, twin: NONE }))
            .collect();

        let table = EdgeTable::new(&triangles, vertices.len());
        for group in table.iter() {
            if group.len() < 2 {
                continue;
            }
            let (lo, hi) = halfedge_vertices(&triangles, group[0]);
            let forward = group
                .iter()
                .find(|&&g| halfedge_vertices(&triangles, g).0 == lo);
            let backward = group
                .iter()
                .find(|&&g| halfedge_vertices(&triangles, g).0 == hi);
            let pair = match (forward, backward) {
                (Some(&a), Some(&b)) => Some((a, b)),
                _ => None,
            };
            if let Some((a, b)) = pair {
                halfedges[a as usize].twin = b;
                halfedges[b as usize].twin = a;
            }
            if group.len() > 2 || pair.is_none() {
                for &g in group {
                    if pair.is_none_or(|(a, b)| g != a && g != b) {
                        halfedges[g as usize].twin = UNPAIRED;
                    }
                }
                vertices[lo as usize].flags |= NON_MANIFOLD;
                vertices[hi as usize].flags |= NON_MANIFOLD;
            }
        }

        let mut result = Self {
            live_vertex_count: vertices.len(),
            live_face_count: faces.len(),
            vertices,
            halfedges,
            faces,
            skipped_triangle_count,
        };
        result.assign_fans();
        result
    }

    /// Gives each fan of half-edges around a vertex its own vertex: the first fan (in
    /// half-edge order) keeps the vertex, later fans get flagged copies.
    fn assign_fans(&mut self) {
        let mut visited = vec![false; self.halfedges.len()];
        for start in 0..self.halfedges.len() as u32 {
            if visited[start as usize] {
                continue;
            }
            let anchor = self.fan_anchor(start);
            let v = self.halfedges[start as usize].origin;
            let owner = if self.vertices[v as usize].halfedge == NONE {
                v
            } else {
                let copy = Vertex {
                    halfedge: NONE,
                    flags: NON_MANIFOLD,
                    ..self.vertices[v as usize]
                };
                self.vertices[v as usize].flags |= NON_MANIFOLD;
                self.vertices.push(copy);
                self.live_vertex_count += 1;
                (self.vertices.len() - 1) as u32
            };
            self.vertices[owner as usize].halfedge = anchor;
            let mut h = anchor;
            loop {
                visited[h as usize] = true;
                self.halfedges[h as usize].origin = owner;
                match self.rotate_forward(h) {
                    Some(n) if n != anchor => h = n,
                    _ => break,
                }
            }
        }
    }

    /// The anchor of the fan of outgoing half-edge `h`: the outgoing half-edge without
    /// twin if the fan is open, `h` itself if it is closed.
    pub(crate) fn fan_anchor(&self, h: u32) -> u32 {
        let mut g = h;
        // The backward rotation is injective, so it returns to `h` or reaches a boundary;
        // the bound only guards against a corrupted structure.
        for _ in 0..self.halfedges.len() {
            match self.rotate_backward(g) {
                Some(n) if n != h => g = n,
                Some(_) => return h,
                None => return g,
            }
        }
        h
    }

    /// The canonical anchor of the fan of outgoing half-edge `h`: the outgoing half-edge
    /// without twin if the fan is open, the lowest-numbered one if it is closed (what
    /// construction assigns, so that a vertex split restores anchors exactly).
    pub(crate) fn canonical_anchor(&self, h: u32) -> u32 {
        let anchor = self.fan_anchor(h);
        if self.twin_raw(anchor).is_none() {
            return anchor;
        }
        let (mut lowest, mut g) = (anchor, anchor);
        // Bounded like `fan_anchor`: a closed fan returns to its start.
        for _ in 0..self.halfedges.len() {
            match self.rotate_forward(g) {
                Some(n) if n != anchor => {
                    g = n;
                    lowest = lowest.min(n);
                }
                _ => break,
            }
        }
        lowest
    }

    /// The next outgoing half-edge counter-clockwise: `twin(prev(h))`.
    #[inline]
    pub(crate) fn rotate_forward(&self, h: u32) -> Option<u32> {
        self.twin_raw(prev_raw(h))
    }

    /// The previous outgoing half-edge: `next(twin(h))`.
    #[inline]
    pub(crate) fn rotate_backward(&self, h: u32) -> Option<u32> {
        self.twin_raw(h).map(next_raw)
    }

    #[inline]
    pub(crate) fn twin_raw(&self, h: u32) -> Option<u32> {
        let t = self.halfedges[h as usize].twin;
        (t < UNPAIRED).then_some(t)
    }

    // ------------------------------------------------------------------------------
    // Sizes and per-element data.
    // ------------------------------------------------------------------------------

    /// Number of vertex slots (live, deleted, and non-manifold copies).
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Number of face slots (live and deleted).
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// Number of half-edge slots (three per face slot).
    pub fn halfedge_count(&self) -> usize {
        self.halfedges.len()
    }

    /// Vertices not deleted by a collapse (isolated vertices included).
    pub fn live_vertex_count(&self) -> usize {
        self.live_vertex_count
    }

    /// Faces not deleted by a collapse.
    pub fn live_face_count(&self) -> usize {
        self.live_face_count
    }

    /// Source triangles skipped at construction because of a repeated vertex index.
    pub fn skipped_triangle_count(&self) -> usize {
        self.skipped_triangle_count
    }

    /// The position of `v`.
    ///
    /// # Panics
    ///
    /// If `v` is out of range (handles come from this mesh; this is slice indexing).
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.vertices[v.index()].position
    }

    /// Moves `v` to `position` (no topology change).
    ///
    /// Moving one copy of a split non-manifold vertex moves only that copy;
    /// [`HalfEdgeMesh::to_trimesh`] merges the copies back at the position of the first
    /// one, so move every copy to move the source vertex.
    ///
    /// # Errors
    ///
    /// [`MeshError::InvalidHandle`] if `v` is out of range and
    /// [`MeshError::NonFiniteCoordinate`] if `position` has a NaN or infinite coordinate;
    /// the mesh is unchanged on error.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{MeshError, TriMesh, topology::{HalfEdgeMesh, VertexId}};
    ///
    /// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])?;
    /// let mut he = HalfEdgeMesh::from_trimesh(&mesh);
    /// he.set_position(VertexId(2), DVec3::Z)?;
    /// assert_eq!(he.position(VertexId(2)), DVec3::Z);
    /// assert!(matches!(
    ///     he.set_position(VertexId(1), DVec3::new(0.0, f64::NAN, 0.0)),
    ///     Err(MeshError::NonFiniteCoordinate { vertex: 1, axis: 'y', .. })
    /// ));
    /// assert!(he.set_position(VertexId(3), DVec3::Z).is_err());
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// Never.
    pub fn set_position(&mut self, v: VertexId, position: DVec3) -> Result<(), MeshError> {
        let Some(vertex) = self.vertices.get_mut(v.index()) else {
            return Err(MeshError::InvalidHandle {
                kind: "vertex",
                index: v.0,
            });
        };
        if let Some((axis, value)) = ['x', 'y', 'z']
            .into_iter()
            .zip(position.to_array())
            .find(|(_, c)| !c.is_finite())
        {
            return Err(MeshError::NonFiniteCoordinate {
                vertex: v.index(),
                axis,
                value,
            });
        }
        vertex.position = position;
        Ok(())
    }

    /// Whether `v` names a vertex slot of this mesh (live or deleted): handles that pass
    /// can be given to the accessors without the out-of-range panic.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::{FaceId, HalfEdgeId, HalfEdgeMesh, VertexId}};
    ///
    /// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])?;
    /// let he = HalfEdgeMesh::from_trimesh(&mesh);
    /// assert!(he.is_valid_vertex(VertexId(2)) && !he.is_valid_vertex(VertexId(3)));
    /// assert!(he.is_valid_halfedge(HalfEdgeId(2)) && !he.is_valid_halfedge(HalfEdgeId(u32::MAX)));
    /// assert!(he.is_valid_face(FaceId(0)) && !he.is_valid_face(FaceId(1)));
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    pub fn is_valid_vertex(&self, v: VertexId) -> bool {
        v.index() < self.vertices.len()
    }

    /// Whether `h` names a half-edge slot of this mesh (of a live or deleted face); see
    /// [`HalfEdgeMesh::is_valid_vertex`].
    pub fn is_valid_halfedge(&self, h: HalfEdgeId) -> bool {
        h.index() < self.halfedges.len()
    }

    /// Whether `f` names a face slot of this mesh (live or deleted); see
    /// [`HalfEdgeMesh::is_valid_vertex`].
    pub fn is_valid_face(&self, f: FaceId) -> bool {
        f.index() < self.faces.len()
    }

    /// The source vertex of `v` (itself, except for the copies made at non-manifold
    /// vertices).
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn original_vertex(&self, v: VertexId) -> u32 {
        self.vertices[v.index()].original
    }

    /// The source triangle of face `f`.
    ///
    /// # Panics
    ///
    /// If `f` is out of range.
    pub fn original_face(&self, f: FaceId) -> u32 {
        self.faces[f.index()].original
    }

    /// Whether `v` was deleted by a collapse.
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn is_deleted_vertex(&self, v: VertexId) -> bool {
        self.vertices[v.index()].flags & DELETED != 0
    }

    /// Whether `f` was deleted by a collapse.
    ///
    /// # Panics
    ///
    /// If `f` is out of range.
    pub fn is_deleted_face(&self, f: FaceId) -> bool {
        self.faces[f.index()].deleted
    }

    /// Whether `v` is (a copy of) a non-manifold vertex, or an endpoint of a non-manifold
    /// or inconsistently oriented edge. Collapses touching it are refused.
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn is_non_manifold_vertex(&self, v: VertexId) -> bool {
        self.vertices[v.index()].flags & NON_MANIFOLD != 0
    }

    /// Whether `v` is locked ([`HalfEdgeMesh::set_locked`]); collapses touching it are
    /// refused.
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn is_locked(&self, v: VertexId) -> bool {
        self.vertices[v.index()].flags & LOCKED != 0
    }

    /// Locks or unlocks `v` (simplifiers lock feature or boundary vertices).
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::{HalfEdgeMesh, VertexId}};
    ///
    /// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])?;
    /// let mut he = HalfEdgeMesh::from_trimesh(&mesh);
    /// // Lock the whole boundary.
    /// for v in 0..he.vertex_count() as u32 {
    ///     if he.is_boundary_vertex(VertexId(v)) {
    ///         he.set_locked(VertexId(v), true);
    ///     }
    /// }
    /// assert!(he.is_locked(VertexId(2)));
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn set_locked(&mut self, v: VertexId, locked: bool) {
        let flags = &mut self.vertices[v.index()].flags;
        if locked {
            *flags |= LOCKED;
        } else {
            *flags &= !LOCKED;
        }
    }

    // ------------------------------------------------------------------------------
    // Navigation.
    // ------------------------------------------------------------------------------

    /// The next half-edge around `h`'s face.
    ///
    /// Pure arithmetic: never panics; an out-of-range handle gives an out-of-range
    /// handle (`u32::MAX` stays `u32::MAX`), which the accessors reject with their
    /// documented panic.
    pub fn next(&self, h: HalfEdgeId) -> HalfEdgeId {
        HalfEdgeId(next_raw(h.0))
    }

    /// The previous half-edge around `h`'s face.
    ///
    /// Pure arithmetic: never panics (see [`HalfEdgeMesh::next`]).
    pub fn prev(&self, h: HalfEdgeId) -> HalfEdgeId {
        HalfEdgeId(prev_raw(h.0))
    }

    /// The opposite half-edge, or `None` on a boundary (or an edge left unpaired by the
    /// non-manifold policy).
    ///
    /// # Panics
    ///
    /// If `h` is out of range.
    pub fn twin(&self, h: HalfEdgeId) -> Option<HalfEdgeId> {
        self.twin_raw(h.0).map(HalfEdgeId)
    }

    /// The vertex `h` leaves.
    ///
    /// # Panics
    ///
    /// If `h` is out of range.
    pub fn origin(&self, h: HalfEdgeId) -> VertexId {
        VertexId(self.halfedges[h.index()].origin)
    }

    /// The vertex `h` points to.
    ///
    /// # Panics
    ///
    /// If `h` is out of range.
    pub fn target(&self, h: HalfEdgeId) -> VertexId {
        VertexId(self.halfedges[next_raw(h.0) as usize].origin)
    }

    /// The face `h` belongs to (on its left).
    pub fn face(&self, h: HalfEdgeId) -> FaceId {
        FaceId(h.0 / 3)
    }

    /// The first half-edge of face `f` (from its corner 0 to its corner 1).
    ///
    /// Pure arithmetic: never panics; an out-of-range face gives an out-of-range
    /// half-edge (saturating at `u32::MAX`).
    pub fn face_halfedge(&self, f: FaceId) -> HalfEdgeId {
        HalfEdgeId(f.0.saturating_mul(3))
    }

    /// The corners of face `f`, counter-clockwise.
    ///
    /// # Panics
    ///
    /// If `f` is out of range.
    pub fn face_vertices(&self, f: FaceId) -> [VertexId; 3] {
        let base = 3 * f.index();
        [0, 1, 2].map(|i| VertexId(self.halfedges[base + i].origin))
    }

    /// Whether `h` has no twin.
    ///
    /// # Panics
    ///
    /// If `h` is out of range.
    pub fn is_boundary_halfedge(&self, h: HalfEdgeId) -> bool {
        self.twin_raw(h.0).is_none()
    }

    /// Whether `h` was left without twin by the non-manifold policy (a third face on its
    /// edge, or a face orientation that disagrees with its neighbour).
    ///
    /// # Panics
    ///
    /// If `h` is out of range.
    pub fn is_unpaired_halfedge(&self, h: HalfEdgeId) -> bool {
        self.halfedges[h.index()].twin == UNPAIRED
    }

    /// Whether `v` has an outgoing half-edge without twin (isolated vertices are not
    /// boundary vertices).
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn is_boundary_vertex(&self, v: VertexId) -> bool {
        self.vertex_halfedge(v)
            .is_some_and(|h| self.is_boundary_halfedge(h))
    }

    /// The anchor half-edge of `v`: an outgoing half-edge, the one without twin for a
    /// boundary vertex; `None` for isolated and deleted vertices.
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn vertex_halfedge(&self, v: VertexId) -> Option<HalfEdgeId> {
        let vertex = &self.vertices[v.index()];
        (vertex.halfedge != NONE && vertex.flags & DELETED == 0)
            .then_some(HalfEdgeId(vertex.halfedge))
    }

    /// The half-edges leaving `v`, counter-clockwise, starting (for a boundary vertex)
    /// with the one without twin.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::{HalfEdgeMesh, VertexId}};
    ///
    /// // A fan of two triangles around vertex 0 (a boundary vertex).
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let he = HalfEdgeMesh::from_trimesh(&mesh);
    /// assert_eq!(he.outgoing(VertexId(0)).count(), 2);
    /// let ring: Vec<u32> = he.neighbors(VertexId(0)).map(|v| v.0).collect();
    /// assert_eq!(ring, vec![1, 2, 3]);
    /// let faces: Vec<u32> = he.vertex_faces(VertexId(0)).map(|f| f.0).collect();
    /// assert_eq!(faces, vec![0, 1]);
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn outgoing(&self, v: VertexId) -> Outgoing<'_> {
        let start = self.vertex_halfedge(v).map_or(NONE, |h| h.0);
        Outgoing {
            mesh: self,
            start,
            current: start,
        }
    }

    /// The neighbours of `v`, counter-clockwise; for a boundary vertex, from the target of
    /// its outgoing boundary half-edge to the origin of its incoming one.
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn neighbors(&self, v: VertexId) -> Neighbors<'_> {
        Neighbors {
            outgoing: self.outgoing(v),
            last: None,
            done: false,
        }
    }

    /// The faces around `v`, counter-clockwise.
    ///
    /// # Panics
    ///
    /// If `v` is out of range.
    pub fn vertex_faces(&self, v: VertexId) -> impl Iterator<Item = FaceId> + '_ {
        self.outgoing(v).map(|h| FaceId(h.0 / 3))
    }
}

/// Iterator over the outgoing half-edges of a vertex ([`HalfEdgeMesh::outgoing`]).
#[derive(Clone, Debug)]
pub struct Outgoing<'a> {
    mesh: &'a HalfEdgeMesh,
    start: u32,
    current: u32,
}

impl Iterator for Outgoing<'_> {
    type Item = HalfEdgeId;

    fn next(&mut self) -> Option<HalfEdgeId> {
        if self.current == NONE {
            return None;
        }
        let h = self.current;
        self.current = match self.mesh.rotate_forward(h) {
            Some(n) if n != self.start => n,
            _ => NONE,
        };
        Some(HalfEdgeId(h))
    }
}

/// Iterator over the neighbours of a vertex ([`HalfEdgeMesh::neighbors`]).
#[derive(Clone, Debug)]
pub struct Neighbors<'a> {
    outgoing: Outgoing<'a>,
    last: Option<u32>,
    done: bool,
}

impl Iterator for Neighbors<'_> {
    type Item = VertexId;

    fn next(&mut self) -> Option<VertexId> {
        let mesh = self.outgoing.mesh;
        if let Some(h) = self.outgoing.next() {
            self.last = Some(h.0);
            return Some(mesh.target(h));
        }
        if self.done {
            return None;
        }
        self.done = true;
        // An open fan ends with a face whose incoming edge at the vertex has no twin:
        // that edge's origin is the last neighbour.
        let incoming = prev_raw(self.last?);
        mesh.twin_raw(incoming)
            .is_none()
            .then(|| VertexId(mesh.halfedges[incoming as usize].origin))
    }
}

#[inline]
pub(crate) const fn next_raw(h: u32) -> u32 {
    // Saturating: the last face of the `u32` range is out of range for every mesh, and
    // must not wrap around to a valid handle.
    if h % 3 == 2 {
        h - 2
    } else {
        h.saturating_add(1)
    }
}

#[inline]
pub(crate) const fn prev_raw(h: u32) -> u32 {
    if h.is_multiple_of(3) {
        h.saturating_add(2)
    } else {
        h - 1
    }
}
