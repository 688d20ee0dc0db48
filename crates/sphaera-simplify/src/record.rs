//! Recording the collapse sequence while the engine runs: what each collapse read and
//! wrote, from which the fixed tables of the [`Hierarchy`](crate::Hierarchy) are built.
//!
//! A collapse of `u` into `v` *reads* the radii of the closed one-ring of `u` (they enter
//! its radius) and the faces around `u` and `v`; a full-edge collapse, which moves `v`,
//! also reads the positions and radii of `v`'s one-ring (the triangles around `v` move); it *writes* the radius of `v` and the
//! faces of `u`'s fan that survive (they now have `v` as a corner). It depends on the
//! latest earlier collapse that wrote anything it read. Undoing a collapse requires
//! undoing every applied collapse that depends on it first; with that rule, every
//! reachable state of a selective refinement is locally identical to a state of the
//! original sequence, so every stored radius, face list and position stays exact.

use glam::DVec3;
use smallvec::SmallVec;
use sphaera_mesh::topology::{FaceId, HalfEdgeId, HalfEdgeMesh, VertexId};

/// "No collapse" in the last-writer tables.
pub(crate) const NONE: u32 = u32::MAX;

/// One recorded collapse.
#[derive(Clone, Debug)]
pub(crate) struct CollapseEntry {
    /// The removed vertex.
    pub removed: u32,
    /// The vertex it was collapsed into.
    pub parent: u32,
    /// The parent's radius after the collapse.
    pub radius: f64,
    /// The parent's position after the collapse (equal to its old position for Subset
    /// placement).
    pub position: DVec3,
    /// The faces around `removed` before the collapse: first the one or two faces on the
    /// collapsed edge (they die), then the others (they survive with `parent` as a corner).
    pub fan: SmallVec<[u32; 8]>,
    /// How many of `fan` die (1 on a boundary edge, 2 inside).
    pub dying: u8,
    /// The faces around `parent` after the collapse that are not in `fan` (their bounding
    /// volumes change with the parent's radius).
    pub affected: SmallVec<[u32; 8]>,
    /// Earlier collapses this one depends on (sorted, unique).
    pub depends_on: SmallVec<[u32; 8]>,
}

/// Collects [`CollapseEntry`]s; the engine calls [`Recorder::before`] and
/// [`Recorder::after`] around every applied collapse.
#[derive(Clone, Debug)]
pub(crate) struct Recorder {
    pub entries: Vec<CollapseEntry>,
    /// Per vertex: the latest collapse into it.
    last_vertex_writer: Vec<u32>,
    /// Per face: the latest collapse that changed its corners.
    last_face_writer: Vec<u32>,
    /// The entry being recorded (between `before` and `after`).
    pending: Option<CollapseEntry>,
}

impl Recorder {
    /// A recorder for a run on `mesh`.
    pub fn new(mesh: &HalfEdgeMesh) -> Self {
        Self {
            entries: Vec::new(),
            last_vertex_writer: vec![NONE; mesh.vertex_count()],
            last_face_writer: vec![NONE; mesh.face_count()],
            pending: None,
        }
    }

    /// Records what collapsing `h` reads, just before the collapse; `moves_parent` says
    /// whether the collapse moves the kept vertex (a full-edge collapse), in which case it
    /// also reads the kept vertex's one-ring.
    pub fn before(&mut self, mesh: &HalfEdgeMesh, h: HalfEdgeId, moves_parent: bool) {
        let u = mesh.origin(h);
        let v = mesh.target(h);
        let edge_faces: SmallVec<[u32; 2]> = std::iter::once(h)
            .chain(mesh.twin(h))
            .map(|g| mesh.face(g).0)
            .collect();
        let mut fan: SmallVec<[u32; 8]> = edge_faces.iter().copied().collect();
        fan.extend(
            mesh.vertex_faces(u)
                .map(|f| f.0)
                .filter(|f| !edge_faces.contains(f)),
        );
        let mut depends_on: SmallVec<[u32; 8]> = SmallVec::new();
        let vertex_writer = |x: VertexId| self.last_vertex_writer[x.0 as usize];
        depends_on.push(vertex_writer(u));
        depends_on.push(vertex_writer(v));
        depends_on.extend(mesh.neighbors(u).map(vertex_writer));
        if moves_parent {
            depends_on.extend(mesh.neighbors(v).map(vertex_writer));
        }
        let face_writer = |f: FaceId| self.last_face_writer[f.0 as usize];
        depends_on.extend(mesh.vertex_faces(u).map(face_writer));
        depends_on.extend(mesh.vertex_faces(v).map(face_writer));
        depends_on.retain(|c| *c != NONE);
        depends_on.sort_unstable();
        depends_on.dedup();
        self.pending = Some(CollapseEntry {
            removed: u.0,
            parent: v.0,
            radius: 0.0,
            position: mesh.position(v),
            dying: edge_faces.len() as u8,
            fan,
            affected: SmallVec::new(),
            depends_on,
        });
    }

    /// Completes the entry begun by [`Recorder::before`], after the collapse, with the
    /// parent's new radius.
    pub fn after(&mut self, mesh: &HalfEdgeMesh, radius: f64) {
        let Some(mut entry) = self.pending.take() else {
            return;
        };
        let index = self.entries.len() as u32;
        let v = VertexId(entry.parent);
        entry.radius = radius;
        entry.position = mesh.position(v);
        entry.affected = mesh
            .vertex_faces(v)
            .map(|f| f.0)
            .filter(|f| !entry.fan.contains(f))
            .collect();
        entry.affected.sort_unstable();
        self.last_vertex_writer[v.0 as usize] = index;
        for &f in entry.fan.iter().skip(usize::from(entry.dying)) {
            self.last_face_writer[f as usize] = index;
        }
        self.entries.push(entry);
    }
}
