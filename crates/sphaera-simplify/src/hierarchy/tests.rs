//! Exactness of selective refinement: every reachable state equals replaying its applied
//! collapses in build order on the finest mesh, with the same corners and radii.

use proptest::prelude::*;
use sphaera_mesh::shapes;
use sphaera_mesh::topology::{FaceId, HalfEdgeMesh, VertexId};

use crate::spheres::{BoundaryPolicy, edge_radius};
use crate::{Hierarchy, Refinement, SimplifyOptions};

/// Replays the applied collapses of `state` in build order and compares.
fn assert_state_is_a_replay(mesh: &sphaera_mesh::TriMesh, h: &Hierarchy, state: &Refinement<'_>) {
    let mut he = HalfEdgeMesh::from_trimesh(mesh);
    let mut radii = vec![0.0; he.vertex_count()];
    for c in 0..h.collapse_count() as u32 {
        if !state.is_applied(c) {
            continue;
        }
        let (u, v) = (h.removed_vertex(c).unwrap(), h.kept_vertex(c).unwrap());
        let edge = he
            .outgoing(VertexId(u))
            .find(|&g| he.target(g) == VertexId(v))
            .unwrap_or_else(|| panic!("collapse {c}: edge {u}->{v} missing in the replay"));
        he.check_collapse(edge)
            .unwrap_or_else(|e| panic!("collapse {c} refused in the replay: {e}"));
        let r = edge_radius(&he, &radii, edge, BoundaryPolicy::Collapse)
            .unwrap_or_else(|| panic!("collapse {c}: no radius in the replay"));
        let stored = h.radius_after(c).unwrap();
        assert!(
            (r - stored).abs() <= 1e-9 * stored.max(1e-300) + 1e-15,
            "collapse {c}: replayed radius {r}, stored {stored}"
        );
        radii[v as usize] = stored;
        he.collapse_edge(edge, he.position(VertexId(v))).unwrap();
    }
    for t in 0..h.triangle_count() as u32 {
        let replayed =
            (!he.is_deleted_face(FaceId(t))).then(|| he.face_vertices(FaceId(t)).map(|x| x.0));
        assert_eq!(state.corners(t), replayed, "triangle {t}");
    }
    for v in 0..h.vertex_count() as u32 {
        if state.is_present(v) {
            assert!(!he.is_deleted_vertex(VertexId(v)));
            assert_eq!(
                state.radius(v).to_bits(),
                radii[v as usize].to_bits(),
                "vertex {v}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(32), ..ProptestConfig::default() })]

    #[test]
    fn every_refined_state_is_a_replay_of_the_build(
        kind in 0u8..3,
        resolution in 4usize..9,
        lock_boundary: bool,
        picks in prop::collection::vec(any::<u32>(), 1..16),
    ) {
        let mesh = match kind {
            0 => shapes::sphere(1.0, resolution).unwrap(),
            1 => shapes::torus(1.0, 0.4, resolution.max(6)).unwrap(),
            _ => {
                // An open sphere: a cap of triangles removed.
                let (p, t) = shapes::sphere(1.0, resolution).unwrap().into_parts();
                let keep = t.len() - t.len() / 8;
                sphaera_mesh::TriMesh::new(p, t[..keep].to_vec()).unwrap()
            }
        };
        let h = Hierarchy::build(&mesh, &SimplifyOptions::default().with_lock_boundary(lock_boundary)).unwrap();
        let mut state = h.refinement();
        assert_state_is_a_replay(&mesh, &h, &state);
        for pick in picks {
            let splittable: Vec<u32> =
                (0..h.vertex_count() as u32).filter(|&v| state.can_split(v)).collect();
            if splittable.is_empty() {
                break;
            }
            state.split_vertex(splittable[pick as usize % splittable.len()]).unwrap();
            assert_state_is_a_replay(&mesh, &h, &state);
        }
    }
}
