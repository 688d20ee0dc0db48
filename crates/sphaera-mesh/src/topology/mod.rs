//! Mesh topology: a report of defects and invariants ([`analyze`]), an editable half-edge
//! mesh ([`HalfEdgeMesh`]) with edge collapse and vertex split, and repair helpers.
//!
//! # Topology report
//!
//! [`analyze`] works on any [`TriMesh`](crate::TriMesh): open, non-manifold, with
//! degenerate or duplicate triangles and unreferenced vertices. By default it first merges
//! vertices with identical coordinates (OBJ files split vertices at uv seams), which makes
//! its closed / 2-manifold / components / boundary edges / genus / `χ` numbers those of
//! trimesh and pymeshlab in `shared/data/README.md` (all 39 meshes of that table agree).
//! Components are edge-connected; a triangle with a repeated index counts as a face, and
//! its repeated side as a (self-loop) edge, as in trimesh.
//!
//! ```
//! use glam::DVec3;
//! use sphaera_mesh::{TriMesh, topology};
//!
//! // An open box (a cube without its top): one hole, genus 0.
//! let p: Vec<DVec3> = (0..8)
//!     .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
//!     .collect();
//! let t = vec![
//!     [0, 2, 1], [1, 2, 3], // bottom
//!     [0, 1, 5], [0, 5, 4], [2, 6, 7], [2, 7, 3], // front, back
//!     [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5], // sides
//! ];
//! let report = topology::analyze(&TriMesh::new(p, t)?);
//! assert!(!report.is_closed && report.is_manifold && report.is_oriented);
//! assert_eq!((report.boundary_edge_count, report.boundary_loop_count), (4, 1));
//! assert_eq!((report.euler_characteristic, report.genus), (1, Some(0)));
//! # Ok::<(), sphaera_mesh::MeshError>(())
//! ```
//!
//! # The half-edge mesh
//!
//! [`HalfEdgeMesh`] stores three plain arrays with `u32` links:
//!
//! - **half-edges**: face `f` owns half-edges `3f`, `3f + 1`, `3f + 2` (corner `i` to
//!   corner `i + 1`), so `next`, `prev` and `face` are arithmetic and a half-edge stores
//!   only its origin and its twin (8 bytes);
//! - **vertices**: position, one outgoing *anchor* half-edge, the source vertex, flags;
//! - **faces**: the source triangle and a deleted flag.
//!
//! A boundary half-edge simply has no twin ([`HalfEdgeMesh::twin`] is `None`); there are
//! no half-edges in the holes. The anchor of a boundary vertex is its outgoing boundary
//! half-edge, so [`HalfEdgeMesh::outgoing`] (rotating with `twin(prev(h))`) visits its
//! whole fan, and [`HalfEdgeMesh::neighbors`] ends with the far vertex of the incoming
//! boundary edge. Vertex `i` of the half-edge mesh is vertex `i` of the source mesh.
//!
//! ## Non-manifold policy
//!
//! Construction never fails; the indices are taken as given (weld first if needed):
//!
//! - triangles with a repeated index are **skipped** and counted
//!   ([`HalfEdgeMesh::skipped_triangle_count`]); face handles map back with
//!   [`HalfEdgeMesh::original_face`];
//! - on an edge with more than two faces, the first consistently oriented pair (lowest
//!   half-edge of each direction) becomes twins and the other half-edges are left
//!   **unpaired** (boundary-like, [`HalfEdgeMesh::is_unpaired_halfedge`]); two faces
//!   traversing an edge in the same direction are both left unpaired; the endpoints of
//!   such edges are flagged non-manifold;
//! - a vertex whose faces form several fans is **split**: the first fan (in half-edge
//!   order) keeps the vertex, each other fan gets a copy at the same position
//!   ([`HalfEdgeMesh::original_vertex`] gives the source vertex); the vertex and its copies
//!   are flagged ([`HalfEdgeMesh::is_non_manifold_vertex`]).
//!
//! Collapses refuse flagged and locked vertices, so editing never makes a defect worse,
//! and [`HalfEdgeMesh::to_trimesh`] merges the copies back.
//!
//! ## Editing
//!
//! [`HalfEdgeMesh::collapse_edge`] removes the origin of a half-edge after checking the
//! link condition and the small special cases (tetrahedron, lone triangle, boundary
//! bridge); it returns a [`CollapseRecord`], and [`HalfEdgeMesh::split_vertex`] undoes it
//! exactly, handles included, as a progressive mesh needs. Deleted elements are
//! tombstoned; [`HalfEdgeMesh::to_trimesh`] returns the live mesh and the vertex map.
//!
//! ```
//! use glam::DVec3;
//! use sphaera_mesh::{TriMesh, topology::{HalfEdgeMesh, HalfEdgeId}};
//!
//! // A 3 x 3 grid of squares (16 vertices, 18 triangles), open.
//! let mut p = Vec::new();
//! for j in 0..4 { for i in 0..4 { p.push(DVec3::new(f64::from(i), f64::from(j), 0.0)); } }
//! let mut t = Vec::new();
//! for j in 0..3u32 { for i in 0..3u32 {
//!     let a = 4 * j + i;
//!     t.push([a, a + 1, a + 5]);
//!     t.push([a, a + 5, a + 4]);
//! } }
//! let mut mesh = HalfEdgeMesh::from_trimesh(&TriMesh::new(p, t)?);
//! let mut records = Vec::new();
//! for h in 0..mesh.halfedge_count() as u32 {
//!     let h = HalfEdgeId(h);
//!     if mesh.can_collapse(h) {
//!         let target = mesh.position(mesh.target(h));
//!         records.push(mesh.collapse_edge(h, target)?);
//!     }
//! }
//! assert!(mesh.live_face_count() < 18);
//! assert_eq!(mesh.boundary_loops().len(), 1);
//! for record in records.iter().rev() {
//!     mesh.split_vertex(record)?;
//! }
//! assert_eq!(mesh.live_face_count(), 18);
//! # Ok::<(), sphaera_mesh::MeshError>(())
//! ```
//!
//! # Repair
//!
//! [`weld_vertices`] (tolerance-based, hash grid), [`drop_degenerate_triangles`],
//! [`drop_duplicate_triangles`] and [`drop_unreferenced_vertices`] each return the new
//! mesh and a report of what changed.

mod collapse;
mod edge_table;
mod halfedge;
mod halfedge_queries;
#[cfg(test)]
mod halfedge_tests;
mod repair;
mod report;
#[cfg(test)]
mod testing;
mod union_find;
mod weld;

pub use collapse::{CollapseRecord, CollapseRefusal};
pub use edge_table::{EdgeTable, halfedge_vertices};
pub use halfedge::{FaceId, HalfEdgeId, HalfEdgeMesh, Neighbors, Outgoing, VertexId};
pub use halfedge_queries::LiveMesh;
pub use repair::{
    TriangleFilterReport, UnreferencedReport, drop_degenerate_triangles, drop_duplicate_triangles,
    drop_unreferenced_vertices,
};
pub use report::{TopologyOptions, TopologyReport, analyze, analyze_with};
pub use weld::{WeldReport, weld_vertices};
