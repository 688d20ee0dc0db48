//! Unit tests of the certificate's steps and the near-ties search.

use glam::DVec3;

use super::embedding::certify;
use super::signed::{closest_with_ties, side_of_ties};
use super::{EmbeddingDefect, Surface};
use crate::closest::TriangleTree;
use crate::winding::WindingNumber;
use sphaera_mesh::{TriMesh, shapes};

fn certified(mesh: &TriMesh) -> Result<(), EmbeddingDefect> {
    let tree = TriangleTree::new(mesh).unwrap();
    let winding = WindingNumber::new(mesh).unwrap();
    let bounds = mesh.bounding_box();
    let scale = bounds.min.abs().max(bounds.max.abs()).max_element();
    certify(mesh, &tree, &winding, scale)
}

#[test]
fn near_ties_give_the_closest_point_bit_for_bit() {
    let mesh = shapes::torus(1.0, 0.3, 24).unwrap();
    let tree = TriangleTree::new(&mesh).unwrap();
    for i in 0..500 {
        let t = f64::from(i);
        let p = DVec3::new((t * 0.37).sin(), (t * 0.91).cos(), 0.4 * (t * 0.13).sin()) * 1.6;
        let (closest, ties) = closest_with_ties(&tree, p, 1.6).unwrap();
        assert_eq!(closest, tree.closest(p).unwrap());
        // The triangle of the answer is a tie, and every tie is about as near.
        let order = tree.boxes().order();
        assert!(ties.iter().any(|&i| order[i as usize] == closest.triangle));
        for &i in &ties {
            let [a, b, c] = tree.corners()[i as usize];
            let d = sphaera_mesh::geometry::point_triangle_distance_squared(
                p,
                &sphaera_mesh::geometry::Triangle::new(a, b, c),
            )
            .sqrt();
            assert!(d <= closest.distance * (1.0 + 1e-10) + 1e-10);
        }
    }
}

#[test]
fn the_centre_of_a_sphere_ties_with_every_triangle_and_is_decided() {
    // Every vertex of the octahedron-based sphere is at distance 1 from the centre; the
    // nearest triangles tie, and all their planes have the centre behind them.
    let mesh = shapes::fixtures::octahedron();
    let tree = TriangleTree::new(&mesh).unwrap();
    let (_, ties) = closest_with_ties(&tree, DVec3::ZERO, 1.0).unwrap();
    assert_eq!(ties.len(), 8);
    assert_eq!(side_of_ties(&tree, &ties, DVec3::ZERO), Some(true));
    let surface = Surface::new(&mesh).unwrap();
    assert!(surface.signed_closest(DVec3::ZERO).unwrap().inside);
}

#[test]
fn a_point_on_a_plane_of_a_tie_is_left_to_the_winding_number() {
    let mesh = shapes::fixtures::unit_cube();
    let tree = TriangleTree::new(&mesh).unwrap();
    // Beyond the edge x = 1, y = 1, in the plane x = 1 of one of its faces.
    let p = DVec3::new(1.0, 1.5, 0.5);
    let (_, ties) = closest_with_ties(&tree, p, 1.0).unwrap();
    assert_eq!(side_of_ties(&tree, &ties, p), None);
    let surface = Surface::new(&mesh).unwrap();
    let answer = surface.signed_closest(p).unwrap();
    assert!(!answer.inside);
}

#[test]
fn shapes_and_small_solids_are_certified() {
    for mesh in [
        shapes::fixtures::tetrahedron(),
        shapes::fixtures::octahedron(),
        shapes::fixtures::unit_cube(),
        shapes::cylinder(1.0, 2.0, 12).unwrap(),
        shapes::cone(1.0, 2.0, 12).unwrap(),
        shapes::thick_tube(0.8, 1.0, 2.0, 12).unwrap(),
        shapes::s_tube(0.3, 1.0, 12).unwrap(),
        shapes::ellipsoid(DVec3::new(1.5, 1.0, 0.5), 12).unwrap(),
    ] {
        assert_eq!(certified(&mesh), Ok(()));
    }
}

#[test]
fn a_duplicate_triangle_is_a_contact() {
    // A tetrahedron plus one face and its reverse: every edge of that pair still has two
    // triangles, but the new pair coincides with the face.
    let mut mesh = shapes::fixtures::tetrahedron();
    let positions = mesh.positions().to_vec();
    let mut triangles = mesh.triangles().to_vec();
    let extra = positions.len() as u32;
    let mut more = positions.clone();
    more.extend([
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(4.0, 0.0, 0.0),
        DVec3::new(3.0, 1.0, 0.0),
    ]);
    triangles.push([extra, extra + 1, extra + 2]);
    triangles.push([extra, extra + 2, extra + 1]);
    mesh = TriMesh::new(more, triangles).unwrap();
    assert!(matches!(
        certified(&mesh),
        Err(EmbeddingDefect::SelfIntersection { .. })
    ));
}

/// Times the certificate alone on the shared meshes and large shapes (release build):
/// `cargo test --release -p sphaera-mesh --lib certificate_timings -- --ignored --nocapture`.
#[test]
#[ignore = "a report, not a test"]
#[allow(clippy::print_stderr)]
fn certificate_timings() {
    let data = std::env::var_os("SPHAERA_DATA").map_or_else(
        || std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data")),
        std::path::PathBuf::from,
    );
    let mut meshes: Vec<(String, TriMesh)> = Vec::new();
    for file in [
        "bunny_lowres.obj",
        "fandisk.obj",
        "rocker-arm.obj",
        "stanford-bunny.obj",
        "dragon_vrip.ply",
    ] {
        if let Ok(mesh) = sphaera_io::load(data.join(file)) {
            meshes.push((file.to_owned(), mesh));
        }
    }
    meshes.push((
        "torus 20k".to_owned(),
        shapes::torus(1.0, 0.3, 183).unwrap(),
    ));
    meshes.push((
        "torus 1M".to_owned(),
        shapes::torus(1.0, 0.3, 1290).unwrap(),
    ));
    for (name, mesh) in &meshes {
        let tree = TriangleTree::new(mesh).unwrap();
        let winding = WindingNumber::new(mesh).unwrap();
        let bounds = mesh.bounding_box();
        let scale = bounds.min.abs().max(bounds.max.abs()).max_element();
        let start = std::time::Instant::now();
        let result = certify(mesh, &tree, &winding, scale);
        let certificate = start.elapsed().as_secs_f64();
        let start = std::time::Instant::now();
        let _normals = super::pseudo_normal::VertexNormals::new(mesh);
        let normals = start.elapsed().as_secs_f64();
        eprintln!(
            "{name} ({} triangles): certificate {:.1} ms ({result:?}), pseudo-normals {:.1} ms",
            mesh.triangle_count(),
            certificate * 1e3,
            normals * 1e3
        );
    }
}

/// The smallest pair of triangles in improper contact, by testing every pair.
fn brute_first_contact(mesh: &TriMesh) -> Option<(u32, u32)> {
    let corners: Vec<[DVec3; 3]> = mesh.triangle_iter().map(|t| t.corners()).collect();
    let triangles = mesh.triangles();
    for i in 0..triangles.len() {
        for j in i + 1..triangles.len() {
            if super::intersect::improper_contact(
                corners[i],
                triangles[i],
                corners[j],
                triangles[j],
            ) {
                return Some((i as u32, j as u32));
            }
        }
    }
    None
}

fn merged(a: &TriMesh, b: &TriMesh, by: DVec3) -> TriMesh {
    let offset = a.vertex_count() as u32;
    let mut positions = a.positions().to_vec();
    positions.extend(b.positions().iter().map(|&p| p + by));
    let mut triangles = a.triangles().to_vec();
    triangles.extend(b.triangles().iter().map(|t| t.map(|v| v + offset)));
    TriMesh::new(positions, triangles).unwrap()
}

#[test]
fn the_contact_search_finds_the_smallest_pair_of_all_pairs() {
    let sphere = shapes::sphere(1.0, 16).unwrap();
    let torus = shapes::torus(1.0, 0.3, 24).unwrap();
    let cube = shapes::cube(2.0, 2).unwrap();
    for (a, b, by) in [
        (&sphere, &torus, DVec3::new(0.5, 0.0, 0.1)),
        (&torus, &sphere, DVec3::new(0.5, 0.0, 0.1)),
        (&cube, &cube, DVec3::new(2.0, 0.3, 0.0)),
        (&cube, &cube, DVec3::new(2.0, 2.0, 2.0)),
        (&cube, &sphere, DVec3::new(3.0, 0.0, 0.0)),
        (&sphere, &sphere, DVec3::new(1.9, 0.0, 0.0)),
    ] {
        let mesh = merged(a, b, by);
        let tree = TriangleTree::new(&mesh).unwrap();
        assert_eq!(
            super::contacts::first_contact(&tree),
            brute_first_contact(&mesh),
            "offset {by}"
        );
    }
}
