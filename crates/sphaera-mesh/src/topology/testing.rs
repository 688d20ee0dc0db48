//! Small closed and open meshes built inline for the topology tests.

use glam::DVec3;

use super::halfedge::{HalfEdgeMesh, VertexId};
use crate::TriMesh;

pub(crate) fn tetrahedron() -> TriMesh {
    TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap()
}

pub(crate) fn octahedron() -> TriMesh {
    TriMesh::new(
        vec![
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
        ],
        vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    )
    .unwrap()
}

/// The unit cube, two triangles per side, outward.
pub(crate) fn cube() -> TriMesh {
    let p = (0..8)
        .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let t = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    TriMesh::new(p, t).unwrap()
}

/// An `n × m` torus grid (genus 1), `n, m ≥ 3`, offset by `shift` along x.
pub(crate) fn torus(n: u32, m: u32, shift: f64) -> TriMesh {
    let mut p = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b) = (
                std::f64::consts::TAU * f64::from(i) / f64::from(n),
                std::f64::consts::TAU * f64::from(j) / f64::from(m),
            );
            let r = 2.0 + 0.7 * b.cos();
            p.push(DVec3::new(r * a.cos() + shift, r * a.sin(), 0.7 * b.sin()));
        }
    }
    let id = |i: u32, j: u32| (j % m) * n + (i % n);
    let mut t = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    TriMesh::new(p, t).unwrap()
}

/// An open `n × m` grid of squares in the plane (a disc).
pub(crate) fn grid(n: u32, m: u32) -> TriMesh {
    let mut p = Vec::new();
    for j in 0..=m {
        for i in 0..=n {
            p.push(DVec3::new(f64::from(i), f64::from(j), 0.0));
        }
    }
    let mut t = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let a = j * (n + 1) + i;
            t.push([a, a + 1, a + n + 2]);
            t.push([a, a + n + 2, a + n + 1]);
        }
    }
    TriMesh::new(p, t).unwrap()
}

/// `mesh` moved by `shift` along x.
pub(crate) fn shifted(mesh: &TriMesh, shift: f64) -> TriMesh {
    let (p, t) = mesh.clone().into_parts();
    TriMesh::new(p.into_iter().map(|x| x + DVec3::X * shift).collect(), t).unwrap()
}

/// Two meshes side by side, as one.
pub(crate) fn union(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let offset = a.vertex_count() as u32;
    let mut p = a.positions().to_vec();
    p.extend_from_slice(b.positions());
    let mut t = a.triangles().to_vec();
    t.extend(b.triangles().iter().map(|tri| tri.map(|v| v + offset)));
    TriMesh::new(p, t).unwrap()
}

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
