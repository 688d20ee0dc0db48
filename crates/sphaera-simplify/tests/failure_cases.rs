//! Inputs where simplification must not fail.

// Exact values are expected here (a copied maximum, an untouched zero).
#![allow(clippy::float_cmp)]

mod common;

use common::{SLACK, grid, original_samples, worst_containment, worst_coverage};
use glam::DVec3;
use sphaera_mesh::{Length, TriMesh, shapes, topology};
use sphaera_simplify::{Hierarchy, SimplifyError, SimplifyOptions, simplify};

#[test]
fn closed_genus_zero_mesh_reaches_a_tetrahedron_and_no_further() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_triangles(0)).unwrap();
    assert_eq!(out.mesh.triangle_count(), 4);
    assert_eq!(out.mesh.vertex_count(), 4);
    let report = topology::analyze(&out.mesh);
    assert!(report.is_closed && report.is_manifold);
    // Even the tetrahedron keeps the guarantee.
    let xs = original_samples(&mesh, 500, 1);
    assert!(worst_coverage(&out, &xs) <= SLACK);
    assert!(worst_containment(&out, &mesh, 4) <= SLACK);
    // Simplifying the tetrahedron again changes nothing.
    let again = simplify(
        &out.mesh,
        &SimplifyOptions::default().with_target_triangles(0),
    )
    .unwrap();
    assert_eq!(again.mesh.triangle_count(), 4);
    assert_eq!(again.collapses, 0);
}

#[test]
fn open_grid_keeps_its_boundary() {
    let mesh = grid(8, |x, y| 0.05 * x * y);
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_triangles(0)).unwrap();
    assert_eq!(out.locked.boundary, 32);
    let before = topology::analyze(&mesh);
    let after = topology::analyze(&out.mesh);
    assert_eq!(after.boundary_edge_count, before.boundary_edge_count);
    assert_eq!(after.boundary_loop_count, 1);
    // Only boundary vertices can remain when simplified as far as possible... at least
    // every interior vertex that could go went.
    assert!(out.mesh.vertex_count() < mesh.vertex_count());
    let xs = original_samples(&mesh, 500, 2);
    assert!(worst_coverage(&out, &xs) <= SLACK);
    assert!(worst_containment(&out, &mesh, 4) <= SLACK);
}

#[test]
fn flat_grid_collapses_at_almost_no_cost() {
    let mesh = grid(12, |_, _| 0.0);
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.2)).unwrap();
    assert!(out.mesh.triangle_count() <= mesh.triangle_count() / 5 + 1);
    assert!(
        out.error_bound < 1e-9,
        "a flat collapse costs {}",
        out.error_bound
    );
    let report = topology::analyze(&out.mesh);
    assert!(report.is_manifold && report.is_oriented);
    assert!(
        out.mesh
            .triangle_iter()
            .all(|t| t.unit_normal().is_some_and(|n| n.z > 0.0))
    );
    let xs = original_samples(&mesh, 500, 3);
    assert!(worst_coverage(&out, &xs) <= SLACK);
}

/// Two unit cubes sharing an edge (built inline): the shared edge is non-manifold.
fn two_cubes_sharing_an_edge() -> TriMesh {
    let a = shapes::cube(1.0, 3).unwrap();
    let (pa, ta) = a.into_parts();
    let shift = DVec3::new(1.0, 1.0, 0.0);
    let n = pa.len() as u32;
    let mut positions = pa.clone();
    positions.extend(pa.iter().map(|&p| p + shift));
    let mut triangles = ta.clone();
    triangles.extend(ta.iter().map(|t| t.map(|i| i + n)));
    // Weld the coinciding vertices so the edge is shared by four faces.
    let (welded, _) =
        topology::weld_vertices(&TriMesh::new(positions, triangles).unwrap(), 1e-12).unwrap();
    welded
}

#[test]
fn non_manifold_input_simplifies_and_reports_locks() {
    let mesh = two_cubes_sharing_an_edge();
    assert!(!topology::analyze(&mesh).is_manifold);
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.3)).unwrap();
    assert!(out.locked.non_manifold > 0);
    assert!(out.mesh.triangle_count() < mesh.triangle_count());
    let xs = original_samples(&mesh, 500, 4);
    assert!(worst_coverage(&out, &xs) <= SLACK);
    assert!(worst_containment(&out, &mesh, 4) <= SLACK);
}

#[test]
fn duplicate_vertices_simplify_without_error() {
    // A sphere whose vertices are all duplicated (every triangle uses the copies of the
    // first half of its corners): the seams become boundaries, which stay.
    let mesh = shapes::sphere(1.0, 10).unwrap();
    let (p, t) = mesh.into_parts();
    let n = p.len() as u32;
    let mut positions = p.clone();
    positions.extend_from_slice(&p);
    let triangles: Vec<[u32; 3]> = t
        .iter()
        .enumerate()
        .map(|(i, tri)| if i % 2 == 0 { *tri } else { tri.map(|x| x + n) })
        .collect();
    let mesh = TriMesh::new(positions, triangles).unwrap();
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.5)).unwrap();
    assert!(out.mesh.triangle_count() <= mesh.triangle_count());
    let xs = original_samples(&mesh, 300, 5);
    assert!(worst_coverage(&out, &xs) <= SLACK);
    assert!(worst_containment(&out, &mesh, 3) <= SLACK);
}

#[test]
fn zero_area_triangles_simplify_without_error() {
    // A grid with a column of vertices moved onto their neighbours: zero-area triangles.
    let mut mesh = grid(8, |x, y| 0.1 * (x + y));
    let mut p = mesh.positions().to_vec();
    for j in 0..=8 {
        let i = 9 * j + 4;
        p[i] = p[i - 1];
    }
    mesh.set_positions(p).unwrap();
    assert!(mesh.triangle_iter().any(|t| t.area() == 0.0));
    let out = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.2)).unwrap();
    assert!(out.mesh.triangle_count() < mesh.triangle_count());
    let xs = original_samples(&mesh, 300, 6);
    assert!(worst_coverage(&out, &xs) <= SLACK);
    assert!(worst_containment(&out, &mesh, 4) <= SLACK);
}

#[test]
fn target_above_the_input_returns_it_unchanged() {
    let mesh = shapes::torus(1.0, 0.4, 8).unwrap();
    let out = simplify(
        &mesh,
        &SimplifyOptions::default().with_target_triangles(mesh.triangle_count()),
    )
    .unwrap();
    assert_eq!(out.mesh, mesh);
    assert_eq!(out.error_bound, 0.0);
    assert_eq!(out.collapses, 0);
    assert!(out.vertex_radii.iter().all(|&r| r == 0.0));
    assert_eq!(
        out.original_vertex,
        (0..mesh.vertex_count() as u32).collect::<Vec<_>>()
    );
    let full = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(1.0)).unwrap();
    assert_eq!(full.mesh, mesh);
}

#[test]
fn nan_and_out_of_range_parameters_are_errors() {
    let mesh = shapes::cube(1.0, 2).unwrap();
    for ratio in [f64::NAN, 0.0, -0.5, 1.5, f64::INFINITY] {
        let err =
            simplify(&mesh, &SimplifyOptions::default().with_target_ratio(ratio)).unwrap_err();
        assert!(
            matches!(
                err,
                SimplifyError::InvalidParameter {
                    name: "target_ratio",
                    ..
                }
            ),
            "{err}"
        );
    }
    for bound in [
        Length::Absolute(f64::NAN),
        Length::Absolute(-1.0),
        Length::RelativeToDiagonal(f64::INFINITY),
        Length::RelativeToDiagonal(f64::NAN),
    ] {
        let err = simplify(&mesh, &SimplifyOptions::default().with_max_error(bound)).unwrap_err();
        assert!(
            matches!(
                err,
                SimplifyError::InvalidParameter {
                    name: "max_error",
                    ..
                }
            ),
            "{err}"
        );
        assert!(err.to_string().starts_with("invalid `max_error`"));
    }
}

#[test]
fn empty_mesh_is_an_error() {
    let mesh = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
    let err = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.5)).unwrap_err();
    assert!(matches!(err, SimplifyError::EmptyMesh));
}

#[test]
fn max_error_stops_first_and_is_respected() {
    let mesh = shapes::sphere(1.0, 16).unwrap();
    let loose = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.05)).unwrap();
    let bound = loose.error_bound / 2.0;
    let out = simplify(
        &mesh,
        &SimplifyOptions::default()
            .with_target_ratio(0.05)
            .with_max_error(Length::Absolute(bound)),
    )
    .unwrap();
    assert!(out.error_bound <= bound);
    assert!(out.mesh.triangle_count() > loose.mesh.triangle_count());
    let zero = simplify(
        &mesh,
        &SimplifyOptions::default().with_max_error(Length::Absolute(0.0)),
    )
    .unwrap();
    assert_eq!(zero.collapses, 0);
}

#[test]
fn output_is_deterministic() {
    let mesh = shapes::torus(1.0, 0.3, 12).unwrap();
    let a = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.3)).unwrap();
    let b = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.3)).unwrap();
    assert_eq!(a, b);
}

#[test]
fn all_zero_weights_are_a_clear_error() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    let zeros = vec![0.0; mesh.vertex_count()];
    let err = simplify(
        &mesh,
        &SimplifyOptions::default().with_weights(zeros.to_vec()),
    )
    .unwrap_err();
    assert!(matches!(err, SimplifyError::AllWeightsZero), "{err}");
    assert!(err.to_string().contains("nothing can be simplified"));
    let err = Hierarchy::build(
        &mesh,
        &SimplifyOptions::default().with_weights(zeros.to_vec()),
    )
    .unwrap_err();
    assert!(matches!(err, SimplifyError::AllWeightsZero));
}

#[test]
fn bad_weights_are_errors() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    let n = mesh.vertex_count();
    let err = simplify(
        &mesh,
        &SimplifyOptions::default().with_weights(vec![1.0; n - 1].to_vec()),
    )
    .unwrap_err();
    assert!(matches!(
        err,
        SimplifyError::LengthMismatch { name: "weights", actual, expected } if actual == n - 1 && expected == n
    ));
    for bad in [f64::NAN, -0.5, f64::INFINITY] {
        let mut w = vec![1.0; n];
        w[5] = bad;
        let err =
            simplify(&mesh, &SimplifyOptions::default().with_weights(w.to_vec())).unwrap_err();
        assert!(
            matches!(
                err,
                SimplifyError::InvalidVertexValue {
                    name: "weights",
                    index: 5,
                    ..
                }
            ),
            "{bad}: {err}"
        );
    }
}

#[test]
fn zero_weight_regions_do_not_move_and_small_weights_keep_their_error_small() {
    let mesh = shapes::sphere(1.0, 16).unwrap();
    let p = mesh.positions();
    // Freeze the cap z > 0.5, make z < -0.5 ten times stricter.
    let weights: Vec<f64> = p
        .iter()
        .map(|q| {
            if q.z > 0.5 {
                0.0
            } else if q.z < -0.5 {
                0.1
            } else {
                1.0
            }
        })
        .collect();
    let plain = simplify(&mesh, &SimplifyOptions::default().with_target_ratio(0.2)).unwrap();
    let out = simplify(
        &mesh,
        &SimplifyOptions::default()
            .with_weights(weights.to_vec())
            .with_target_ratio(0.2),
    )
    .unwrap();
    // Every input triangle touching a frozen vertex is still there, unchanged.
    let kept: std::collections::BTreeSet<[u32; 3]> = out
        .mesh
        .triangles()
        .iter()
        .map(|t| t.map(|i| out.original_vertex[i as usize]))
        .collect();
    for t in mesh.triangles() {
        if t.iter().any(|&v| weights[v as usize] == 0.0) {
            assert!(
                kept.contains(t),
                "triangle {t:?} near a frozen vertex changed"
            );
        }
    }
    // The strict region ends with a smaller error than without weights.
    let worst_south = |s: &sphaera_simplify::Simplified| {
        s.original_vertex
            .iter()
            .zip(&s.vertex_radii)
            .filter(|(o, _)| p[**o as usize].z < -0.6)
            .fold(0.0_f64, |m, (_, &r)| m.max(r))
    };
    assert!(worst_south(&out) < worst_south(&plain));
    // With a bound, the strict region stays within a tenth of it.
    let bound = 0.05;
    let bounded = simplify(
        &mesh,
        &SimplifyOptions::default()
            .with_weights(weights.to_vec())
            .with_max_error(Length::Absolute(bound)),
    )
    .unwrap();
    assert!(worst_south(&bounded) <= 0.1 * bound + 1e-12);
}
