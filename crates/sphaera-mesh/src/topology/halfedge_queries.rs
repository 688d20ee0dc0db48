//! Whole-mesh queries on a [`HalfEdgeMesh`]: boundaries, components, export.

use super::halfedge::{DELETED, FaceId, HalfEdgeId, HalfEdgeMesh, NONE, VertexId, next_raw};
use crate::TriMesh;

/// The live part of a [`HalfEdgeMesh`] as an indexed mesh ([`HalfEdgeMesh::to_trimesh`]).
///
/// # Examples
///
/// ```
/// use glam::DVec3;
/// use sphaera_mesh::{TriMesh, topology::HalfEdgeMesh};
///
/// let mesh = TriMesh::new(vec![DVec3::ONE, DVec3::ZERO, DVec3::X, DVec3::Y], vec![[1, 2, 3]])?;
/// let live = HalfEdgeMesh::from_trimesh(&mesh).to_trimesh();
/// assert_eq!(live.mesh.triangles(), &[[0, 1, 2]]);
/// assert_eq!(live.vertex_map.iter().map(|v| v.0).collect::<Vec<_>>(), vec![1, 2, 3]);
/// # Ok::<(), sphaera_mesh::MeshError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LiveMesh {
    /// The live faces and the vertices they use.
    pub mesh: TriMesh,
    /// For each vertex of `mesh`, the half-edge-mesh vertex it comes from (for merged
    /// non-manifold copies, the lowest-numbered copy).
    pub vertex_map: Vec<VertexId>,
    /// For each triangle of `mesh`, the face it comes from.
    pub face_map: Vec<FaceId>,
}

impl HalfEdgeMesh {
    /// Iterator over the live half-edges without twin, in index order.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::HalfEdgeMesh};
    ///
    /// let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]])?;
    /// assert_eq!(HalfEdgeMesh::from_trimesh(&mesh).boundary_halfedges().count(), 3);
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    pub fn boundary_halfedges(&self) -> impl Iterator<Item = HalfEdgeId> + '_ {
        (0..self.halfedges.len() as u32)
            .filter(|&h| !self.faces[(h / 3) as usize].deleted && self.twin_raw(h).is_none())
            .map(HalfEdgeId)
    }

    /// The boundary loops: each a cycle of half-edges without twin, in face orientation
    /// (the hole is on the right), starting at its lowest half-edge; loops are ordered by
    /// their first half-edge.
    ///
    /// The loop continues from boundary half-edge `h` with the outgoing boundary half-edge
    /// of `target(h)`, which is unique because every vertex copy has one fan.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::HalfEdgeMesh};
    ///
    /// // A square of two triangles: one loop of four edges.
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let loops = HalfEdgeMesh::from_trimesh(&mesh).boundary_loops();
    /// assert_eq!(loops.len(), 1);
    /// assert_eq!(loops[0].len(), 4);
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    ///
    /// # Performance
    ///
    /// Linear in the number of half-edges.
    pub fn boundary_loops(&self) -> Vec<Vec<HalfEdgeId>> {
        let mut seen = vec![false; self.halfedges.len()];
        let mut loops = Vec::new();
        for start in self.boundary_halfedges() {
            if seen[start.index()] {
                continue;
            }
            let mut cycle = Vec::new();
            let mut h = start.0;
            // Bounded by the half-edge count: each step visits a new boundary half-edge.
            for _ in 0..self.halfedges.len() {
                seen[h as usize] = true;
                cycle.push(HalfEdgeId(h));
                let target = self.halfedges[next_raw(h) as usize].origin;
                let anchor = self.vertices[target as usize].halfedge;
                if anchor == NONE || seen[anchor as usize] || self.twin_raw(anchor).is_some() {
                    break;
                }
                h = anchor;
            }
            loops.push(cycle);
        }
        loops
    }

    /// Connected components of the live faces (faces sharing a paired edge): the number
    /// of components and, for each face slot, its component (`u32::MAX` for deleted
    /// faces). Components are numbered by their lowest face.
    ///
    /// Faces joined only through an unpaired (non-manifold) edge or a split non-manifold
    /// vertex are in different components.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::HalfEdgeMesh};
    ///
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE, DVec3::NEG_ONE],
    ///     vec![[0, 1, 2], [3, 4, 5]],
    /// )?;
    /// let (count, labels) = HalfEdgeMesh::from_trimesh(&mesh).connected_components();
    /// assert_eq!((count, labels), (2, vec![0, 1]));
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    pub fn connected_components(&self) -> (usize, Vec<u32>) {
        let mut label = vec![u32::MAX; self.faces.len()];
        let mut count = 0u32;
        let mut stack = Vec::new();
        for f in 0..self.faces.len() {
            if self.faces[f].deleted || label[f] != u32::MAX {
                continue;
            }
            label[f] = count;
            stack.push(f as u32);
            while let Some(g) = stack.pop() {
                for h in 3 * g..3 * g + 3 {
                    if let Some(t) = self.twin_raw(h) {
                        let n = (t / 3) as usize;
                        if label[n] == u32::MAX && !self.faces[n].deleted {
                            label[n] = count;
                            stack.push(n as u32);
                        }
                    }
                }
            }
            count += 1;
        }
        (count as usize, label)
    }

    /// The live mesh as an indexed mesh, with maps back to this mesh's handles.
    ///
    /// Output vertices are the live vertices used by a live face, in handle order, except
    /// that copies of one non-manifold source vertex are merged back into one vertex, at
    /// the position of the lowest-numbered copy a live face uses. Collapses refuse
    /// non-manifold vertices, so only [`HalfEdgeMesh::set_position`] can move a copy: a
    /// copy moved away from the others is still merged, and its own position is ignored.
    /// Isolated vertices are dropped; triangles are the live faces in handle order.
    ///
    /// # Panics
    ///
    /// Never: positions are finite (construction, collapses and
    /// [`HalfEdgeMesh::set_position`] keep them so) and every corner of a live face is a
    /// live vertex.
    ///
    /// # Performance
    ///
    /// Linear in the number of slots; call it once at the end of an editing session.
    pub fn to_trimesh(&self) -> LiveMesh {
        let mut used = vec![false; self.vertices.len()];
        let mut face_map = Vec::with_capacity(self.live_face_count);
        for (f, face) in self.faces.iter().enumerate() {
            if !face.deleted {
                face_map.push(FaceId(f as u32));
                for i in 0..3 {
                    used[self.halfedges[3 * f + i].origin as usize] = true;
                }
            }
        }
        // Copies share their source vertex: index outputs by source vertex first.
        let mut by_original = vec![NONE; self.vertices.len()];
        let mut new_index = vec![NONE; self.vertices.len()];
        let mut positions = Vec::new();
        let mut vertex_map = Vec::new();
        for (v, vertex) in self.vertices.iter().enumerate() {
            if !used[v] || vertex.flags & DELETED != 0 {
                continue;
            }
            let slot = &mut by_original[vertex.original as usize];
            if *slot == NONE {
                *slot = positions.len() as u32;
                positions.push(vertex.position);
                vertex_map.push(VertexId(v as u32));
            }
            new_index[v] = *slot;
        }
        let triangles: Vec<[u32; 3]> = face_map
            .iter()
            .map(|f| {
                let base = 3 * f.index();
                [0, 1, 2].map(|i| new_index[self.halfedges[base + i].origin as usize])
            })
            .collect();
        // Every corner of a live face is a used live vertex, so every index is assigned,
        // and every position is finite: construction cannot fail (invariant).
        let mesh = TriMesh::new(positions, triangles)
            .expect("invariant: live faces name live vertices with finite positions");
        LiveMesh {
            mesh,
            vertex_map,
            face_map,
        }
    }
}
