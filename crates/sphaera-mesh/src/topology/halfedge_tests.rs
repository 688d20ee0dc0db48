//! Tests of the half-edge mesh: construction policy, navigation, collapse and split.

use glam::DVec3;
use proptest::prelude::*;

use super::testing::check_invariants;
use super::{HalfEdgeId, HalfEdgeMesh, VertexId, analyze};
use crate::{MeshError, TriMesh, shapes::fixtures};

#[test]
fn closed_meshes_have_all_twins() {
    for mesh in [
        fixtures::tetrahedron(),
        fixtures::octahedron(),
        fixtures::unit_cube(),
        fixtures::torus(5, 4),
    ] {
        let he = HalfEdgeMesh::from_trimesh(&mesh);
        check_invariants(&he);
        assert_eq!(he.boundary_halfedges().count(), 0);
        assert_eq!(he.vertex_count(), mesh.vertex_count());
        assert_eq!(he.connected_components().0, 1);
        for v in 0..mesh.vertex_count() as u32 {
            let valence = he.neighbors(VertexId(v)).count();
            assert_eq!(valence, he.outgoing(VertexId(v)).count());
            assert!(!he.is_boundary_vertex(VertexId(v)));
        }
        assert_eq!(he.to_trimesh().mesh, mesh);
    }
}

#[test]
fn grid_boundary_and_rings() {
    let mesh = fixtures::grid(3, 2);
    let he = HalfEdgeMesh::from_trimesh(&mesh);
    check_invariants(&he);
    let loops = he.boundary_loops();
    assert_eq!(loops.len(), 1);
    assert_eq!(loops[0].len(), 10);
    // Consecutive loop half-edges chain head to tail.
    for (i, &h) in loops[0].iter().enumerate() {
        let next = loops[0][(i + 1) % loops[0].len()];
        assert_eq!(he.target(h), he.origin(next));
    }
    // Corner vertex 0 has neighbours 1, 5, 4 (grid row width 4).
    let ring: Vec<u32> = he.neighbors(VertexId(0)).map(|v| v.0).collect();
    assert_eq!(ring, vec![1, 5, 4]);
    // An interior vertex: 6 neighbours, 6 faces.
    assert_eq!(he.neighbors(VertexId(5)).count(), 6);
    assert_eq!(he.vertex_faces(VertexId(5)).count(), 6);
}

#[test]
fn non_manifold_edge_keeps_first_consistent_pair() {
    // Three faces on edge (0, 1): faces 0 and 1 pair, face 2 is left unpaired.
    let mesh = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_Y],
        vec![[0, 1, 2], [1, 0, 3], [1, 0, 4]],
    )
    .unwrap();
    let he = HalfEdgeMesh::from_trimesh(&mesh);
    check_invariants(&he);
    assert_eq!(he.twin(HalfEdgeId(0)), Some(HalfEdgeId(3)));
    assert!(he.is_unpaired_halfedge(HalfEdgeId(6)));
    assert!(he.is_non_manifold_vertex(VertexId(0)));
    assert!(he.is_non_manifold_vertex(VertexId(1)));
    // Face 2's fan is separate at both ends: vertices 0 and 1 get copies.
    assert_eq!(he.vertex_count(), 7);
    assert_eq!(he.connected_components().0, 2);
    // Copies merge back on export.
    let live = he.to_trimesh();
    assert_eq!(live.mesh.vertex_count(), 5);
    assert_eq!(live.mesh.triangles(), mesh.triangles());
}

#[test]
fn flipped_neighbours_are_left_unpaired() {
    let mesh = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::NEG_Y],
        vec![[0, 1, 2], [0, 1, 3]],
    )
    .unwrap();
    let he = HalfEdgeMesh::from_trimesh(&mesh);
    check_invariants(&he);
    assert!(he.is_unpaired_halfedge(HalfEdgeId(0)));
    assert!(he.is_unpaired_halfedge(HalfEdgeId(3)));
    assert_eq!(he.twin(HalfEdgeId(0)), None);
}

#[test]
fn isolated_and_degenerate_are_tolerated() {
    let mesh = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE],
        vec![[0, 0, 0], [0, 1, 2], [2, 2, 1]],
    )
    .unwrap();
    let he = HalfEdgeMesh::from_trimesh(&mesh);
    check_invariants(&he);
    assert_eq!(he.skipped_triangle_count(), 2);
    assert_eq!(he.face_count(), 1);
    assert_eq!(he.original_face(super::FaceId(0)), 1);
    assert_eq!(he.outgoing(VertexId(3)).count(), 0);
    assert_eq!(he.neighbors(VertexId(3)).count(), 0);
    assert!(!he.is_boundary_vertex(VertexId(3)));
}

#[test]
fn tetrahedron_and_lone_triangle_refuse_every_collapse() {
    for mesh in [
        fixtures::tetrahedron(),
        TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap(),
    ] {
        let he = HalfEdgeMesh::from_trimesh(&mesh);
        for h in 0..he.halfedge_count() as u32 {
            assert!(matches!(
                he.check_collapse(HalfEdgeId(h)),
                Err(MeshError::CollapseRefused { .. })
            ));
        }
    }
}

#[test]
fn locked_and_non_manifold_vertices_refuse() {
    let mut he = HalfEdgeMesh::from_trimesh(&fixtures::octahedron());
    he.set_locked(VertexId(2), true);
    let err = he.collapse_edge(HalfEdgeId(0), DVec3::ZERO).unwrap_err();
    assert_eq!(
        err.to_string(),
        "cannot collapse half-edge 0 (vertex 0 into vertex 2): an endpoint is locked"
    );
    he.set_locked(VertexId(2), false);
    assert!(he.can_collapse(HalfEdgeId(0)));
    assert!(matches!(
        he.collapse_edge(HalfEdgeId(0), DVec3::NAN),
        Err(MeshError::InvalidParameter { .. })
    ));
    assert!(matches!(
        he.check_collapse(HalfEdgeId(999)),
        Err(MeshError::InvalidHandle { index: 999, .. })
    ));
}

#[test]
fn interior_edge_between_boundary_vertices_is_refused() {
    // A strip of two squares: the middle rung's ends are both on the boundary.
    let he = HalfEdgeMesh::from_trimesh(&fixtures::grid(2, 1));
    // Face 0 = [0, 1, 4]; half-edge 1 goes 1 -> 4, the interior rung.
    assert!(he.twin(HalfEdgeId(1)).is_some());
    assert!(matches!(
        he.check_collapse(HalfEdgeId(1)),
        Err(MeshError::CollapseRefused {
            reason: super::CollapseRefusal::BoundaryBridge,
            ..
        })
    ));
}

#[test]
fn split_twice_is_an_error() {
    let mut he = HalfEdgeMesh::from_trimesh(&fixtures::torus(6, 5));
    let a = he.collapse_edge(HalfEdgeId(0), DVec3::ZERO).unwrap();
    let h = (0..he.halfedge_count() as u32)
        .map(HalfEdgeId)
        .find(|&h| he.can_collapse(h))
        .unwrap();
    let b = he.collapse_edge(h, DVec3::ONE).unwrap();
    // Undo b, then try b again: its vertex is no longer deleted.
    he.split_vertex(&b).unwrap();
    assert!(matches!(
        he.split_vertex(&b),
        Err(MeshError::SplitMismatch { .. })
    ));
    he.split_vertex(&a).unwrap();
    assert_eq!(he, HalfEdgeMesh::from_trimesh(&fixtures::torus(6, 5)));
}

#[test]
fn split_under_a_later_collapse_into_its_kept_vertex_is_an_error() {
    let original = HalfEdgeMesh::from_trimesh(&crate::shapes::torus(1.0, 0.4, 12).unwrap());
    let mut he = original.clone();
    let a = he.collapse_edge(HalfEdgeId(0), DVec3::ZERO).unwrap();
    let kept = a.kept_vertex();
    // Collapse B: some neighbour into A's kept vertex.
    let h = he
        .outgoing(kept)
        .filter_map(|g| he.twin(g))
        .find(|&g| he.can_collapse(g))
        .unwrap();
    assert_eq!(he.target(h), kept);
    let b = he.collapse_edge(h, DVec3::ONE).unwrap();
    let after_both = he.clone();
    assert!(matches!(
        he.split_vertex(&a),
        Err(MeshError::SplitMismatch { .. })
    ));
    assert_eq!(he, after_both);
    he.split_vertex(&b).unwrap();
    he.split_vertex(&a).unwrap();
    assert_eq!(he, original);
}

#[test]
fn independent_collapses_split_in_any_order() {
    let original = HalfEdgeMesh::from_trimesh(&crate::shapes::torus(1.0, 0.4, 12).unwrap());
    let mut he = original.clone();
    let a = he.collapse_edge(HalfEdgeId(0), DVec3::ZERO).unwrap();
    // A collapse whose endpoints are outside the 2-ring of A's kept vertex.
    let mut near: Vec<VertexId> = vec![a.kept_vertex()];
    for _ in 0..2 {
        let ring: Vec<VertexId> = near.iter().flat_map(|&v| he.neighbors(v)).collect();
        near.extend(ring);
    }
    let h = (0..he.halfedge_count() as u32)
        .map(HalfEdgeId)
        .find(|&g| {
            he.can_collapse(g) && !near.contains(&he.origin(g)) && !near.contains(&he.target(g))
        })
        .unwrap();
    let b = he.collapse_edge(h, DVec3::ONE).unwrap();
    he.split_vertex(&a).unwrap();
    check_invariants(&he);
    he.split_vertex(&b).unwrap();
    assert_eq!(he, original);
}

#[test]
fn set_position_rejects_non_finite_so_to_trimesh_never_empties() {
    let mut he = HalfEdgeMesh::from_trimesh(&fixtures::octahedron());
    let before = he.clone();
    for bad in [DVec3::NAN, DVec3::new(0.0, 0.0, f64::INFINITY)] {
        assert!(matches!(
            he.set_position(VertexId(3), bad),
            Err(MeshError::NonFiniteCoordinate { vertex: 3, .. })
        ));
    }
    assert!(matches!(
        he.set_position(VertexId(99), DVec3::ZERO),
        Err(MeshError::InvalidHandle { index: 99, .. })
    ));
    assert_eq!(he, before);
    he.set_position(VertexId(3), DVec3::ONE).unwrap();
    let live = he.to_trimesh();
    assert_eq!(live.mesh.triangle_count(), 8);
    assert_eq!(live.mesh.positions()[3], DVec3::ONE);
}

#[test]
fn moving_one_copy_of_a_non_manifold_vertex_keeps_the_first_copy_position() {
    // A bow tie: vertex 0 is split into two copies, 0 and 5.
    let mesh = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y],
        vec![[0, 1, 2], [0, 3, 4]],
    )
    .unwrap();
    let mut he = HalfEdgeMesh::from_trimesh(&mesh);
    he.set_position(VertexId(5), DVec3::Z).unwrap();
    let live = he.to_trimesh();
    assert_eq!(live.mesh.vertex_count(), 5);
    assert_eq!(live.mesh.positions()[0], DVec3::ZERO);
}

#[test]
fn handle_arithmetic_at_u32_max_does_not_overflow() {
    let he = HalfEdgeMesh::from_trimesh(&fixtures::octahedron());
    let h = HalfEdgeId(u32::MAX);
    assert!(!he.is_valid_halfedge(he.prev(h)));
    assert!(!he.is_valid_halfedge(he.next(h)));
    assert!(!he.is_valid_halfedge(he.face_halfedge(super::FaceId(u32::MAX))));
    assert!(!he.is_valid_face(he.face(h)));
    assert!(!he.is_valid_vertex(VertexId(u32::MAX)));
    assert!(he.is_valid_halfedge(he.prev(HalfEdgeId(0))));
    assert_eq!(he.prev(HalfEdgeId(0)), HalfEdgeId(2));
    assert_eq!(he.next(HalfEdgeId(2)), HalfEdgeId(0));
}

#[test]
#[should_panic(expected = "index out of bounds")]
fn out_of_range_halfedge_hits_the_documented_panic() {
    let he = HalfEdgeMesh::from_trimesh(&fixtures::octahedron());
    let _ = he.target(he.prev(HalfEdgeId(u32::MAX)));
}

/// Meshes for the collapse properties: closed and open, genus 0 to 2.
fn base_mesh(kind: u8, n: u32) -> TriMesh {
    match kind {
        0 => fixtures::octahedron(),
        1 => fixtures::unit_cube(),
        2 => fixtures::torus(n + 3, 3 + n % 3),
        3 => fixtures::grid(n + 1, 2),
        _ => fixtures::union(
            &fixtures::torus(4, 3),
            &fixtures::shifted(&fixtures::torus(4, 4), 9.0),
        ),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// Random legal collapses keep the structure valid, manifold, of the same Euler
    /// characteristic, genus and holes; undoing them restores the mesh exactly.
    #[test]
    fn collapses_keep_topology_and_splits_restore(
        kind in 0u8..5,
        n in 0u32..5,
        picks in prop::collection::vec(any::<prop::sample::Index>(), 1..40),
        optimal in any::<bool>(),
    ) {
        let mesh = base_mesh(kind, n);
        let before = analyze(&mesh);
        let original = HalfEdgeMesh::from_trimesh(&mesh);
        let mut he = original.clone();
        let mut records = Vec::new();
        let mut states = vec![he.clone()];
        for pick in picks {
            let candidates: Vec<HalfEdgeId> = (0..he.halfedge_count() as u32)
                .map(HalfEdgeId)
                .filter(|&h| he.can_collapse(h))
                .collect();
            if candidates.is_empty() {
                break;
            }
            let h = candidates[pick.index(candidates.len())];
            let target = if optimal {
                (he.position(he.origin(h)) + he.position(he.target(h))) / 2.0
            } else {
                he.position(he.target(h))
            };
            let record = he.collapse_edge(h, target).unwrap();
            check_invariants(&he);
            let after = analyze(&he.to_trimesh().mesh);
            prop_assert!(after.is_manifold && after.is_oriented);
            prop_assert_eq!(after.euler_characteristic, before.euler_characteristic);
            prop_assert_eq!(after.genus, before.genus);
            prop_assert_eq!(after.boundary_loop_count, before.boundary_loop_count);
            prop_assert_eq!(after.component_count, before.component_count);
            prop_assert_eq!(he.boundary_loops().len(), before.boundary_loop_count);
            records.push(record);
            states.push(he.clone());
        }
        while let Some(record) = records.pop() {
            states.pop();
            he.split_vertex(&record).unwrap();
            prop_assert_eq!(&he, states.last().unwrap());
        }
        prop_assert_eq!(he, original);
    }

    /// Splits in a random order either fail and leave the mesh unchanged, or succeed and
    /// leave a valid structure; undoing the rest in reverse collapse order then restores
    /// the mesh exactly.
    #[test]
    fn splits_out_of_order_fail_cleanly_or_succeed(
        kind in 0u8..5,
        n in 0u32..5,
        picks in prop::collection::vec(any::<prop::sample::Index>(), 1..30),
        order in prop::collection::vec(any::<prop::sample::Index>(), 0..40),
        optimal in any::<bool>(),
    ) {
        let original = HalfEdgeMesh::from_trimesh(&base_mesh(kind, n));
        let mut he = original.clone();
        let mut records = Vec::new();
        for pick in picks {
            let candidates: Vec<HalfEdgeId> = (0..he.halfedge_count() as u32)
                .map(HalfEdgeId)
                .filter(|&h| he.can_collapse(h))
                .collect();
            if candidates.is_empty() {
                break;
            }
            let h = candidates[pick.index(candidates.len())];
            let target = if optimal {
                (he.position(he.origin(h)) + he.position(he.target(h))) / 2.0
            } else {
                he.position(he.target(h))
            };
            records.push(Some(he.collapse_edge(h, target).unwrap()));
        }
        for pick in order {
            if records.is_empty() {
                break;
            }
            let i = pick.index(records.len());
            let Some(record) = &records[i] else { continue };
            let before = he.clone();
            if he.split_vertex(record).is_ok() {
                check_invariants(&he);
                records[i] = None;
            } else {
                prop_assert_eq!(&he, &before);
            }
        }
        for record in records.iter().rev().flatten() {
            he.split_vertex(record).unwrap();
            check_invariants(&he);
        }
        prop_assert_eq!(he, original);
    }

    /// Construction from arbitrary soups never panics and satisfies the invariants.
    #[test]
    fn any_soup_builds_a_valid_structure(
        n in 1usize..9,
        tris in prop::collection::vec((0u32..9, 0u32..9, 0u32..9), 0..16),
    ) {
        let p = (0..n).map(|i| DVec3::new(i as f64, (i * i) as f64, 1.0)).collect();
        let t: Vec<[u32; 3]> = tris
            .into_iter()
            .map(|(a, b, c)| [a % n as u32, b % n as u32, c % n as u32])
            .collect();
        let mesh = TriMesh::new(p, t).unwrap();
        let he = HalfEdgeMesh::from_trimesh(&mesh);
        check_invariants(&he);
        let report = analyze(&mesh);
        prop_assert_eq!(he.skipped_triangle_count(), report.repeated_index_triangle_count);
        // Every boundary half-edge lies on exactly one loop.
        let on_loops: usize = he.boundary_loops().iter().map(Vec::len).sum();
        prop_assert_eq!(on_loops, he.boundary_halfedges().count());
        // Collapses on the result stay valid whatever the input was.
        let mut he = he;
        for h in 0..he.halfedge_count() as u32 {
            if he.can_collapse(HalfEdgeId(h)) {
                let p = he.position(he.target(HalfEdgeId(h)));
                he.collapse_edge(HalfEdgeId(h), p).unwrap();
                check_invariants(&he);
            }
        }
    }
}
