//! Unit tests of [`TriangleTree`] against brute force.

#![allow(clippy::float_cmp)]

use super::*;
use sphaera_mesh::geometry::point_triangle_distance_squared;
use sphaera_mesh::shapes;

fn brute(mesh: &TriMesh, p: DVec3) -> f64 {
    (0..mesh.triangle_count())
        .filter_map(|t| mesh.triangle(t))
        .map(|t| point_triangle_distance_squared(p, &t))
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

#[test]
fn agrees_with_brute_force_on_a_torus() -> Result<(), Box<dyn std::error::Error>> {
    let mesh = shapes::torus(1.0, 0.3, 20)?;
    let tree = TriangleTree::new(&mesh)?;
    assert_eq!(tree.triangle_count(), mesh.triangle_count());
    for i in 0..200 {
        let f = f64::from(i);
        let p = DVec3::new(
            (f * 0.37).sin() * 1.7,
            (f * 0.91).cos() * 1.6,
            (f * 0.13).sin(),
        );
        let answer = tree.closest(p)?;
        assert!((answer.distance - brute(&mesh, p)).abs() < 1e-12);
        assert!((tree.distance(p)? - answer.distance).abs() <= 1e-15 * (1.0 + answer.distance));
        let t = mesh.triangle(answer.triangle as usize).ok_or("triangle")?;
        assert!((point_triangle_distance_squared(answer.point, &t)).sqrt() < 1e-12);
    }
    Ok(())
}

#[test]
fn points_on_the_surface_are_at_distance_zero() -> Result<(), Box<dyn std::error::Error>> {
    let cube = shapes::cube(2.0, 3)?;
    let tree = TriangleTree::new(&cube)?;
    for &p in cube.positions() {
        assert!(tree.distance(p)? < 1e-12);
    }
    Ok(())
}

#[test]
fn a_bound_prunes_and_is_inclusive() -> Result<(), Box<dyn std::error::Error>> {
    let mesh = shapes::cube(2.0, 2)?;
    let tree = TriangleTree::new(&mesh)?;
    let p = DVec3::new(0.5, 0.0, 0.0);
    assert!(tree.closest_within(p, 0.4)?.is_none());
    let at = tree.closest_within(p, 0.5)?.ok_or("inclusive bound")?;
    assert_eq!(at.distance, 0.5);
    Ok(())
}

#[test]
fn bad_queries_are_errors() -> Result<(), Box<dyn std::error::Error>> {
    let tree = TriangleTree::new(&shapes::cube(2.0, 2)?)?;
    assert!(matches!(
        tree.closest(DVec3::new(f64::NAN, 0.0, 0.0)),
        Err(QueryError::NonFiniteQuery { .. })
    ));
    assert!(matches!(
        tree.closest_within(DVec3::ZERO, -1.0),
        Err(QueryError::InvalidParameter { .. })
    ));
    assert!(matches!(
        tree.closest_within(DVec3::ZERO, f64::NAN),
        Err(QueryError::InvalidParameter { .. })
    ));
    let empty = TriMesh::new(vec![DVec3::ZERO], Vec::new())?;
    assert!(matches!(
        TriangleTree::new(&empty),
        Err(QueryError::EmptyMesh)
    ));
    Ok(())
}
