//! Checks of the half-edge structure for the topology tests (the meshes are in
//! `crate::shapes::fixtures`).

use super::halfedge::{HalfEdgeMesh, VertexId};

/// Checks the structural invariants of a half-edge mesh; panics with a message.
pub(crate) fn check_invariants(mesh: &HalfEdgeMesh) {
    let mut live_faces = 0;
    for f in 0..mesh.faces.len() {
        if mesh.faces[f].deleted {
            continue;
        }
        live_faces += 1;
        for h in 3 * f as u32..3 * f as u32 + 3 {
            let origin = mesh.halfedges[h as usize].origin;
            assert!(
                mesh.vertices[origin as usize].flags & super::halfedge::DELETED == 0,
                "half-edge {h} leaves deleted vertex {origin}"
            );
            if let Some(t) = mesh.twin_raw(h) {
                assert!(
                    !mesh.faces[(t / 3) as usize].deleted,
                    "twin of {h} is deleted"
                );
                assert_eq!(mesh.twin_raw(t), Some(h), "twin of twin of {h}");
                let hh = super::HalfEdgeId(h);
                let tt = super::HalfEdgeId(t);
                assert_eq!(mesh.origin(tt), mesh.target(hh), "twin of {h} reversed");
                assert_eq!(mesh.target(tt), mesh.origin(hh), "twin of {h} reversed");
            }
            // The half-edge is in its origin's single fan.
            assert!(
                mesh.outgoing(VertexId(origin)).any(|g| g.0 == h),
                "half-edge {h} not in the fan of its origin {origin}"
            );
        }
    }
    assert_eq!(live_faces, mesh.live_face_count());
    let mut live_vertices = 0;
    for (v, vertex) in mesh.vertices.iter().enumerate() {
        if vertex.flags & super::halfedge::DELETED != 0 {
            continue;
        }
        live_vertices += 1;
        if let Some(anchor) = mesh.vertex_halfedge(VertexId(v as u32)) {
            assert!(
                !mesh.faces[anchor.index() / 3].deleted,
                "anchor of {v} deleted"
            );
            assert_eq!(
                mesh.origin(anchor).0 as usize,
                v,
                "anchor of {v} does not leave it"
            );
            // An open fan must start at its boundary half-edge.
            let last = mesh.outgoing(VertexId(v as u32)).last().unwrap();
            let open = mesh.twin(mesh.prev(last)).is_none();
            assert_eq!(
                open,
                mesh.twin(anchor).is_none(),
                "anchor of {v} not at boundary"
            );
        }
    }
    assert_eq!(live_vertices, mesh.live_vertex_count());
}
