//! Edge collapse and its exact inverse, the vertex split.

use std::fmt;

use glam::DVec3;
use smallvec::SmallVec;

use super::halfedge::{
    DELETED, HalfEdgeId, HalfEdgeMesh, LOCKED, NON_MANIFOLD, NONE, Vertex, VertexId, next_raw,
    prev_raw,
};
use crate::MeshError;

/// Why [`HalfEdgeMesh::check_collapse`] refuses a collapse.
///
/// # Examples
///
/// ```
/// use sphaera_mesh::topology::CollapseRefusal;
///
/// assert_eq!(
///     CollapseRefusal::LinkCondition.to_string(),
///     "the endpoints share a neighbour that is not opposite the edge (the collapse would pinch the surface)"
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CollapseRefusal {
    /// An endpoint is a non-manifold vertex (or a copy of one, or lies on an unpaired
    /// edge). Repair the mesh first, or accept that these vertices stay.
    NonManifold,
    /// An endpoint is locked ([`HalfEdgeMesh::set_locked`]).
    Locked,
    /// The link condition fails: the endpoints have a common neighbour other than the
    /// vertices opposite the edge, so the collapse would glue two sheets together.
    LinkCondition,
    /// The edge is interior but both endpoints are on the boundary: the collapse would
    /// pinch the surface into a non-manifold vertex.
    BoundaryBridge,
    /// The collapse would leave a vertex with too few neighbours (fewer than three inside,
    /// two on the boundary): the component is a tetrahedron, a lone triangle, or the two
    /// faces of the edge share all three vertices.
    TooFewNeighbours,
}

impl fmt::Display for CollapseRefusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::NonManifold => "an endpoint is a non-manifold vertex",
            Self::Locked => "an endpoint is locked",
            Self::LinkCondition => {
                "the endpoints share a neighbour that is not opposite the edge (the collapse would pinch the surface)"
            }
            Self::BoundaryBridge => {
                "the edge is interior but both endpoints are on the boundary (the collapse would pinch the surface)"
            }
            Self::TooFewNeighbours => {
                "a vertex would be left with too few neighbours (tetrahedron, lone triangle or doubled face)"
            }
        })
    }
}

/// Everything [`HalfEdgeMesh::collapse_edge`] changed, so that
/// [`HalfEdgeMesh::split_vertex`] can undo it exactly (same handles, same links): the
/// vertex split of a progressive mesh.
///
/// # Examples
///
/// See [`HalfEdgeMesh::collapse_edge`].
#[derive(Clone, Debug, PartialEq)]
pub struct CollapseRecord {
    halfedge: u32,
    removed: u32,
    kept: u32,
    old_position: DVec3,
    new_position: DVec3,
    /// Faces deleted: the face of the half-edge and (interior edge) of its twin.
    faces: [u32; 2],
    /// Half-edges whose twin changed: (half-edge, twin before, twin the collapse wrote).
    twins: SmallVec<[(u32, u32, u32); 4]>,
    /// Half-edges whose origin moved from `removed` to `kept`.
    moved: SmallVec<[u32; 8]>,
    /// The kept vertex's merge count after the collapse (it counts the applied collapses
    /// into that vertex, so a split cannot undo a collapse that a later one built on).
    merges: u32,
}

impl CollapseRecord {
    /// The collapsed half-edge.
    pub fn halfedge(&self) -> HalfEdgeId {
        HalfEdgeId(self.halfedge)
    }

    /// The vertex the collapse removed (the half-edge's origin); a split restores it.
    pub fn removed_vertex(&self) -> VertexId {
        VertexId(self.removed)
    }

    /// The vertex the collapse kept and moved (the half-edge's target).
    pub fn kept_vertex(&self) -> VertexId {
        VertexId(self.kept)
    }

    /// The kept vertex's position before the collapse.
    pub fn old_position(&self) -> DVec3 {
        self.old_position
    }

    /// The kept vertex's position after the collapse.
    pub fn new_position(&self) -> DVec3 {
        self.new_position
    }

    /// The faces the collapse deleted (one for a boundary edge, two otherwise).
    pub fn removed_faces(&self) -> impl Iterator<Item = super::FaceId> + '_ {
        self.faces
            .iter()
            .filter(|&&f| f != NONE)
            .map(|&f| super::FaceId(f))
    }
}

impl HalfEdgeMesh {
    /// Whether [`HalfEdgeMesh::collapse_edge`] would accept `h`.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::{HalfEdgeMesh, HalfEdgeId}};
    ///
    /// // No edge of a tetrahedron can be collapsed.
    /// let mesh = TriMesh::new(
    ///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// )?;
    /// let he = HalfEdgeMesh::from_trimesh(&mesh);
    /// assert!((0..12).all(|h| !he.can_collapse(HalfEdgeId(h))));
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    pub fn can_collapse(&self, h: HalfEdgeId) -> bool {
        self.check_collapse(h).is_ok()
    }

    /// Checks that collapsing `h` (its origin into its target) keeps the mesh a manifold
    /// of the same topology.
    ///
    /// The checks, in order: `h` is live; neither endpoint is non-manifold or locked;
    /// for an interior edge, not both endpoints are on the boundary; the link condition
    /// (the common neighbours of the endpoints are exactly the vertices opposite the
    /// edge); and every vertex keeps at least three neighbours (two on the boundary),
    /// which refuses the tetrahedron, a lone triangle and a doubled face.
    ///
    /// # Errors
    ///
    /// [`MeshError::InvalidHandle`] if `h` is out of range or deleted, and
    /// [`MeshError::CollapseRefused`] with the [`CollapseRefusal`] otherwise.
    ///
    /// # Performance
    ///
    /// `O(d²)` in the endpoint valences `d` (small lists, no allocation below 16).
    pub fn check_collapse(&self, h: HalfEdgeId) -> Result<(), MeshError> {
        let h = h.0;
        if h as usize >= self.halfedges.len() || self.faces[(h / 3) as usize].deleted {
            return Err(MeshError::InvalidHandle {
                kind: "half-edge",
                index: h,
            });
        }
        let u = self.halfedges[h as usize].origin;
        let v = self.halfedges[next_raw(h) as usize].origin;
        let refuse = |reason| MeshError::CollapseRefused {
            halfedge: h,
            from: u,
            to: v,
            reason,
        };
        let (fu, fv) = (
            self.vertices[u as usize].flags,
            self.vertices[v as usize].flags,
        );
        if (fu | fv) & NON_MANIFOLD != 0 {
            return Err(refuse(CollapseRefusal::NonManifold));
        }
        if (fu | fv) & LOCKED != 0 {
            return Err(refuse(CollapseRefusal::Locked));
        }
        let twin = self.twin_raw(h);
        let u_boundary = self.is_boundary_vertex(VertexId(u));
        let v_boundary = self.is_boundary_vertex(VertexId(v));
        if twin.is_some() && u_boundary && v_boundary {
            return Err(refuse(CollapseRefusal::BoundaryBridge));
        }
        let w0 = self.halfedges[prev_raw(h) as usize].origin;
        let w1 = twin.map(|t| self.halfedges[prev_raw(t) as usize].origin);
        if w1 == Some(w0) {
            return Err(refuse(CollapseRefusal::TooFewNeighbours));
        }
        let mut ring_u: SmallVec<[u32; 16]> = SmallVec::new();
        let mut ring_v: SmallVec<[u32; 16]> = SmallVec::new();
        self.ring_into(u, &mut ring_u);
        self.ring_into(v, &mut ring_v);
        let mut common = 0;
        for &x in &ring_u {
            if ring_v.contains(&x) {
                if x != w0 && Some(x) != w1 {
                    return Err(refuse(CollapseRefusal::LinkCondition));
                }
                common += 1;
            }
        }
        // Neighbours of the merged vertex: the union minus u and v themselves.
        let merged = ring_u.len() + ring_v.len() - common - 2;
        let minimum = |boundary: bool| if boundary { 2 } else { 3 };
        if merged < minimum(u_boundary || v_boundary) {
            return Err(refuse(CollapseRefusal::TooFewNeighbours));
        }
        for w in std::iter::once(w0).chain(w1) {
            // Only whether the valence reaches `minimum + 1` matters: stop counting there.
            let needed = minimum(self.is_boundary_vertex(VertexId(w))) + 1;
            if self.valence_up_to(w, needed) < needed {
                return Err(refuse(CollapseRefusal::TooFewNeighbours));
            }
        }
        Ok(())
    }

    /// Pushes the neighbours of `x` onto `out`, in the order of
    /// [`HalfEdgeMesh::neighbors`] (a raw loop: this is the inner loop of
    /// [`HalfEdgeMesh::check_collapse`]).
    fn ring_into(&self, x: u32, out: &mut SmallVec<[u32; 16]>) {
        self.walk_ring(x, |y| {
            out.push(y);
            true
        });
    }

    /// The number of neighbours of `x` (`neighbors(x).count()`), counted up to `cap`.
    fn valence_up_to(&self, x: u32, cap: usize) -> usize {
        let mut count = 0;
        self.walk_ring(x, |_| {
            count += 1;
            count < cap
        });
        count
    }

    /// Calls `visit` on each neighbour of `x`, exactly as [`HalfEdgeMesh::neighbors`]
    /// yields them (the target of every outgoing half-edge, then, for an open fan, the
    /// origin of the last face's incoming edge), until it returns `false`.
    #[inline]
    fn walk_ring(&self, x: u32, mut visit: impl FnMut(u32) -> bool) {
        let vertex = &self.vertices[x as usize];
        if vertex.halfedge == NONE || vertex.flags & DELETED != 0 {
            return;
        }
        let start = vertex.halfedge;
        let mut h = start;
        loop {
            if !visit(self.halfedges[next_raw(h) as usize].origin) {
                return;
            }
            let incoming = prev_raw(h);
            match self.twin_raw(incoming) {
                Some(n) if n != start => h = n,
                Some(_) => return,
                None => {
                    visit(self.halfedges[incoming as usize].origin);
                    return;
                }
            }
        }
    }

    /// Collapses half-edge `h`: its origin `u` is removed, its target `v` moves to
    /// `new_position`, and the one or two faces on the edge are deleted (tombstoned:
    /// handles of everything else stay valid). Pass `position(target(h))` for a half-edge
    /// collapse, or an optimal position.
    ///
    /// Only topology is checked ([`HalfEdgeMesh::check_collapse`]); geometric checks
    /// (normal flips, error bounds) belong to the caller.
    ///
    /// # Errors
    ///
    /// Those of [`HalfEdgeMesh::check_collapse`], and [`MeshError::InvalidParameter`] if
    /// `new_position` is not finite. The mesh is unchanged on error.
    ///
    /// # Examples
    ///
    /// ```
    /// use glam::DVec3;
    /// use sphaera_mesh::{TriMesh, topology::{self, HalfEdgeMesh, HalfEdgeId}};
    ///
    /// // An octahedron: collapse one edge, check the result, undo it.
    /// let p = vec![DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y, DVec3::Z, -DVec3::Z];
    /// let t = vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
    /// let mesh = TriMesh::new(p, t)?;
    /// let mut he = HalfEdgeMesh::from_trimesh(&mesh);
    /// let before = he.clone();
    /// let h = HalfEdgeId(0); // vertex 0 into vertex 2
    /// let record = he.collapse_edge(h, he.position(he.target(h)))?;
    /// assert_eq!((he.live_vertex_count(), he.live_face_count()), (5, 6));
    /// let live = he.to_trimesh();
    /// let report = topology::analyze(&live.mesh);
    /// assert!(report.is_closed && report.is_manifold);
    /// assert_eq!(report.euler_characteristic, 2);
    ///
    /// he.split_vertex(&record)?;
    /// assert_eq!(he, before);
    /// # Ok::<(), sphaera_mesh::MeshError>(())
    /// ```
    pub fn collapse_edge(
        &mut self,
        h: HalfEdgeId,
        new_position: DVec3,
    ) -> Result<CollapseRecord, MeshError> {
        self.check_collapse(h)?;
        if !new_position.is_finite() {
            let value = [new_position.x, new_position.y, new_position.z]
                .into_iter()
                .find(|c| !c.is_finite())
                .unwrap_or(f64::NAN);
            return Err(MeshError::InvalidParameter {
                name: "new_position",
                value,
                requirement: "finite",
            });
        }
        let h = h.0;
        let (n0, p0) = (next_raw(h), prev_raw(h));
        let u = self.halfedges[h as usize].origin;
        let v = self.halfedges[n0 as usize].origin;
        let w0 = self.halfedges[p0 as usize].origin;
        let twin = self.twin_raw(h);
        let f0 = h / 3;
        let f1 = twin.map_or(NONE, |t| t / 3);
        let w1 = twin.map(|t| self.halfedges[prev_raw(t) as usize].origin);

        // Rings before the change: the moved half-edges and the anchor seeds.
        let moved: SmallVec<[u32; 8]> = self
            .outgoing(VertexId(u))
            .map(|x| x.0)
            .filter(|&x| x / 3 != f0 && x / 3 != f1)
            .collect();
        let mut affected: SmallVec<[(u32, SmallVec<[u32; 16]>); 3]> = SmallVec::new();
        for x in std::iter::once(v).chain(std::iter::once(w0)).chain(w1) {
            let ring = self
                .outgoing(VertexId(x))
                .map(|g| g.0)
                .filter(|&g| g / 3 != f0 && g / 3 != f1)
                .collect();
            affected.push((x, ring));
        }

        // Glue the outer edges of each deleted face.
        let mut twins: SmallVec<[(u32, u32, u32); 4]> = SmallVec::new();
        let mut glue = |mesh: &mut Self, a: u32, b: u32| {
            let (ta, tb) = (mesh.twin_raw(a), mesh.twin_raw(b));
            for (x, other) in [(ta, tb), (tb, ta)] {
                if let Some(x) = x {
                    let new = other.unwrap_or(NONE);
                    twins.push((x, mesh.halfedges[x as usize].twin, new));
                    mesh.halfedges[x as usize].twin = new;
                }
            }
        };
        glue(self, n0, p0);
        if let Some(t) = twin {
            glue(self, next_raw(t), prev_raw(t));
        }
        for &x in &moved {
            self.halfedges[x as usize].origin = v;
        }
        self.faces[f0 as usize].deleted = true;
        if f1 != NONE {
            self.faces[f1 as usize].deleted = true;
        }
        self.live_face_count -= if f1 == NONE { 1 } else { 2 };
        self.vertices[u as usize].flags |= DELETED;
        self.live_vertex_count -= 1;
        let old_position = self.vertices[v as usize].position;
        self.vertices[v as usize].position = new_position;
        // At most one collapse per removed vertex is applied at a time, so the count stays
        // below the vertex count (invariant); wrapping only guards the arithmetic.
        let merges = self.vertices[v as usize].merges.wrapping_add(1);
        self.vertices[v as usize].merges = merges;

        // Moved half-edges now leave v too, so they seed v's new anchor as well.
        // Anchors are canonical (a function of the connectivity), so a split restores
        // them by recomputing them whatever order splits come in.
        for (x, ring) in &affected {
            let seed = ring
                .first()
                .copied()
                .or_else(|| (*x == v).then(|| moved.first().copied()).flatten());
            // The checks guarantee every affected vertex keeps a live face (invariant);
            // without a seed the vertex would become isolated.
            self.vertices[*x as usize].halfedge = seed.map_or(NONE, |s| self.canonical_anchor(s));
        }

        Ok(CollapseRecord {
            halfedge: h,
            removed: u,
            kept: v,
            old_position,
            new_position,
            faces: [f0, f1],
            twins,
            moved,
            merges,
        })
    }

    /// Undoes the collapse `record` describes, restoring the removed vertex, the two
    /// faces, every link and the kept vertex's position exactly as they were (the mesh
    /// compares equal to its state before the collapse).
    ///
    /// Splits need not follow the reverse collapse order (selective refinement of a
    /// progressive mesh splits in any order the neighbourhoods allow): a split is accepted
    /// exactly when the collapse's neighbourhood is still as the collapse left it. Every
    /// twin and origin the collapse wrote must still hold the value it wrote, the
    /// removed vertex and faces must still be deleted, the other corners of those faces
    /// must be live, and no later collapse into the kept
    /// vertex may still be applied (those must be split first). The reverse collapse order
    /// always qualifies. The kept vertex goes back to its old position whatever its
    /// current position is (moving it in between, for a geomorph, is allowed).
    ///
    /// # Errors
    ///
    /// [`MeshError::SplitMismatch`] if the record does not fit the mesh's current state
    /// (a record from another mesh, a split whose neighbourhood a later collapse changed,
    /// or a record applied twice); the mesh is unchanged on error.
    ///
    /// # Performance
    ///
    /// Proportional to the record's size (the removed vertex's valence).
    ///
    /// # Examples
    ///
    /// See [`HalfEdgeMesh::collapse_edge`].
    pub fn split_vertex(&mut self, record: &CollapseRecord) -> Result<(), MeshError> {
        let mismatch = MeshError::SplitMismatch {
            removed: record.removed,
            kept: record.kept,
        };
        if !self.split_fits(record) {
            return Err(mismatch);
        }
        // The corners of the revived faces (the removed vertex first) and how many
        // half-edges each must leave once the split is done; the values are checked
        // after the split, which is rolled back if they do not hold.
        let revived: SmallVec<[u32; 6]> = record
            .faces
            .iter()
            .filter(|&&f| f != NONE)
            .flat_map(|&f| 3 * f..3 * f + 3)
            .collect();
        let mut corners: SmallVec<[(u32, usize); 4]> = SmallVec::new();
        for &h in &revived {
            let x = self.halfedges[h as usize].origin;
            if let Some(entry) = corners.iter_mut().find(|c| c.0 == x) {
                entry.1 += 1;
            } else {
                let before = if x == record.removed {
                    record.moved.len()
                } else if x == record.kept {
                    self.outgoing_count(x).saturating_sub(record.moved.len())
                } else {
                    self.outgoing_count(x)
                };
                corners.push((x, before + 1));
            }
        }
        let saved_vertices: SmallVec<[(u32, Vertex); 4]> = corners
            .iter()
            .map(|&(x, _)| (x, self.vertices[x as usize]))
            .collect();
        let saved_twins: SmallVec<[(u32, u32); 4]> = record
            .twins
            .iter()
            .map(|&(x, _, _)| (x, self.halfedges[x as usize].twin))
            .collect();

        let kept = &mut self.vertices[record.kept as usize];
        kept.position = record.old_position;
        kept.merges = record.merges.wrapping_sub(1);
        self.vertices[record.removed as usize].flags &= !DELETED;
        self.set_faces_deleted(record, false);
        for &x in &record.moved {
            self.halfedges[x as usize].origin = record.removed;
        }
        for &(x, old, _) in record.twins.iter().rev() {
            self.halfedges[x as usize].twin = old;
        }
        // Every corner of a revived face gets its canonical anchor back; a half-edge of
        // that face seeds it (the faces are live and their corners too, checked above).
        for &h in &revived {
            let x = self.halfedges[h as usize].origin;
            self.vertices[x as usize].halfedge = self.canonical_anchor(h);
        }
        // Each corner must have one fan holding all its half-edges.
        if corners.iter().any(|&(x, n)| self.outgoing_count(x) != n) {
            for &(x, twin) in saved_twins.iter().rev() {
                self.halfedges[x as usize].twin = twin;
            }
            for &x in &record.moved {
                self.halfedges[x as usize].origin = record.kept;
            }
            self.set_faces_deleted(record, true);
            for &(x, vertex) in &saved_vertices {
                self.vertices[x as usize] = vertex;
            }
            return Err(mismatch);
        }
        self.live_vertex_count += 1;
        Ok(())
    }

    /// Marks the record's faces deleted or live, keeping the live count.
    fn set_faces_deleted(&mut self, record: &CollapseRecord, deleted: bool) {
        for &f in record.faces.iter().filter(|&&f| f != NONE) {
            self.faces[f as usize].deleted = deleted;
            if deleted {
                self.live_face_count -= 1;
            } else {
                self.live_face_count += 1;
            }
        }
    }

    /// The number of half-edges in the fan of `x` (bounded, in case the fan does not
    /// close on a structure a wrong split left inconsistent).
    fn outgoing_count(&self, x: u32) -> usize {
        self.outgoing(VertexId(x))
            .take(self.halfedges.len() + 1)
            .count()
    }

    /// Whether `record` can be undone on the current state: all indices in range, the
    /// removed vertex and faces deleted, their other corners live, the kept vertex live
    /// with the record's merge count, and every origin and twin the collapse wrote still
    /// in place (anchors are recomputed, not restored).
    fn split_fits(&self, record: &CollapseRecord) -> bool {
        let vertex_ok = |x: u32| (x as usize) < self.vertices.len();
        let halfedge_ok = |x: u32| (x as usize) < self.halfedges.len();
        let link_ok = |x: u32| x >= super::halfedge::UNPAIRED || halfedge_ok(x);
        let live = |x: u32| vertex_ok(x) && self.vertices[x as usize].flags & DELETED == 0;
        // A slot written twice by the collapse holds its last value.
        let last_twin = |i: usize, x: u32| record.twins[i + 1..].iter().all(|e| e.0 != x);
        vertex_ok(record.removed)
            && self.vertices[record.removed as usize].flags & DELETED != 0
            && live(record.kept)
            && self.vertices[record.kept as usize].merges == record.merges
            && record.faces[0] != NONE
            && record
                .faces
                .iter()
                .filter(|&&f| f != NONE)
                .all(|&f| (f as usize) < self.faces.len() && self.faces[f as usize].deleted)
            // The revived faces' other corners must still be live (not collapsed away).
            && record
                .faces
                .iter()
                .filter(|&&f| f != NONE)
                .flat_map(|&f| 3 * f..3 * f + 3)
                .all(|h| {
                    let x = self.halfedges[h as usize].origin;
                    x == record.removed || live(x)
                })
            && record.moved.iter().all(|&x| {
                halfedge_ok(x)
                    && !self.faces[(x / 3) as usize].deleted
                    && self.halfedges[x as usize].origin == record.kept
            })
            && record.twins.iter().enumerate().all(|(i, &(x, old, new))| {
                halfedge_ok(x)
                    && link_ok(old)
                    && (!last_twin(i, x) || self.halfedges[x as usize].twin == new)
            })
    }
}
