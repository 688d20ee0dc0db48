//! The 3D ground work against brute force: validation (open, non-manifold, several
//! components, a torus), the root ball, shortest edge paths against Bellman–Ford, and the
//! patches the root's three paths cut.

use sphaera_hal::{GenusZeroSurface, HalError};
use sphaera_mesh::{DVec3, TriMesh, shapes};

fn tetrahedron() -> TriMesh {
    TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap()
}

/// An octahedron stretched along z: its smallest enclosing ball is the poles' diametral
/// ball, touching two vertices only, so the root's centre must move to touch a third.
fn spindle() -> TriMesh {
    TriMesh::new(
        vec![
            DVec3::new(0.0, 0.0, 2.0),
            DVec3::new(0.0, 0.0, -2.0),
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(-0.5, 0.0, 0.0),
            DVec3::new(0.0, -0.5, 0.0),
        ],
        vec![
            [0, 2, 3],
            [0, 3, 4],
            [0, 4, 5],
            [0, 5, 2],
            [1, 3, 2],
            [1, 4, 3],
            [1, 5, 4],
            [1, 2, 5],
        ],
    )
    .unwrap()
}

/// Shortest edge-path lengths from `from` by Bellman–Ford.
fn brute_distances(mesh: &TriMesh, from: u32) -> Vec<f64> {
    let p = mesh.positions();
    let mut d = vec![f64::INFINITY; p.len()];
    d[from as usize] = 0.0;
    loop {
        let mut changed = false;
        for &[a, b, c] in mesh.triangles() {
            for (u, v) in [(a, b), (b, c), (c, a), (b, a), (c, b), (a, c)] {
                let next = d[u as usize] + p[u as usize].distance(p[v as usize]);
                if next < d[v as usize] {
                    d[v as usize] = next;
                    changed = true;
                }
            }
        }
        if !changed {
            return d;
        }
    }
}

#[test]
fn genus_zero_meshes_are_accepted_and_others_refused_by_name() {
    for mesh in [
        tetrahedron(),
        shapes::cube(1.0, 3).unwrap(),
        shapes::sphere(1.0, 12).unwrap(),
        shapes::capsule(0.3, 2.0, 10).unwrap(),
    ] {
        GenusZeroSurface::new(&mesh).expect("genus 0");
    }
    let torus = shapes::torus(1.0, 0.3, 16).unwrap();
    let error = GenusZeroSurface::new(&torus).unwrap_err();
    assert!(
        matches!(error, HalError::NotGenusZero { genus: 1 }),
        "{error}"
    );
    assert!(
        error.to_string().contains("sphere-tree"),
        "the message says what to use"
    );

    let open = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2]],
    )
    .unwrap();
    assert!(matches!(
        GenusZeroSurface::new(&open),
        Err(HalError::NotClosed { boundary_edges: 3 })
    ));

    // Two closed tetrahedra sharing an edge: no boundary, but that edge has four
    // triangles; the error says non-manifold, not open.
    let t = tetrahedron();
    let mut positions = t.positions().to_vec();
    positions.push(DVec3::new(0.3, 0.3, -1.0));
    positions.push(DVec3::new(-1.0, -1.0, -1.0));
    let shared = t.triangles()[0];
    let (a, b) = (shared[0], shared[1]);
    let mut triangles = t.triangles().to_vec();
    triangles.extend([[b, a, 4], [a, b, 5], [a, 4, 5], [b, 5, 4]]);
    let pinched = TriMesh::new(positions, triangles).unwrap();
    let error = GenusZeroSurface::new(&pinched).unwrap_err();
    assert!(
        matches!(error, HalError::NonManifold { edges, .. } if edges >= 1),
        "{error}"
    );

    let mut positions = t.positions().to_vec();
    positions.extend(t.positions().iter().map(|&p| p + DVec3::splat(5.0)));
    let mut triangles = t.triangles().to_vec();
    triangles.extend(t.triangles().iter().map(|&[a, b, c]| [a + 4, b + 4, c + 4]));
    let two = TriMesh::new(positions, triangles).unwrap();
    assert!(matches!(
        GenusZeroSurface::new(&two),
        Err(HalError::Components { count: 2 })
    ));
}

#[test]
fn the_root_ball_touches_three_vertices_and_holds_every_vertex() {
    // The cube's enclosing ball touches all eight corners; the capsule's only its two
    // poles (the case where the centre must move); the tetrahedron is the smallest case.
    for (name, mesh) in [
        ("tetrahedron", tetrahedron()),
        ("cube", shapes::cube(1.0, 3).unwrap()),
        ("capsule", shapes::capsule(0.3, 2.0, 10).unwrap()),
        ("sphere", shapes::sphere(1.0, 9).unwrap()),
        ("spindle", spindle()),
    ] {
        let surface = GenusZeroSurface::new(&mesh).unwrap();
        let root = surface.root().unwrap();
        let [a, b, c] = root.vertices;
        assert!(a < b && b < c, "{name}: three distinct vertices");
        let r = root.sphere.radius;
        for v in root.vertices {
            let d = mesh.positions()[v as usize].distance(root.sphere.center);
            assert!(
                (d - r).abs() <= 1e-9 * r,
                "{name}: vertex {v} at {d}, radius {r}"
            );
        }
        for p in mesh.positions() {
            assert!(
                p.distance(root.sphere.center) <= r * (1.0 + 1e-12),
                "{name}"
            );
        }
    }
}

#[test]
fn shortest_paths_are_shortest_and_deterministic() {
    let mesh = shapes::sphere(1.0, 10).unwrap();
    let surface = GenusZeroSurface::new(&mesh).unwrap();
    let p = mesh.positions();
    for (a, b) in [(0_u32, 17_u32), (40, 3), (5, 30), (12, 12)] {
        let path = surface.shortest_path(a, b);
        assert_eq!((path[0], *path.last().unwrap()), (a, b));
        // Consecutive vertices share an edge.
        for pair in path.windows(2) {
            assert!(
                mesh.triangles()
                    .iter()
                    .any(|t| t.contains(&pair[0]) && t.contains(&pair[1]))
            );
        }
        let length: f64 = path
            .windows(2)
            .map(|w| p[w[0] as usize].distance(p[w[1] as usize]))
            .sum();
        let brute = brute_distances(&mesh, a)[b as usize];
        assert!(
            (length - brute).abs() <= 1e-12 * (1.0 + brute),
            "{a}→{b}: {length} against {brute}"
        );
        // The same path both ways (the search always runs from the lower index).
        let mut back = surface.shortest_path(b, a);
        back.reverse();
        assert_eq!(path, back);
    }
}

#[test]
fn the_root_paths_cut_the_surface_into_one_or_two_patches() {
    for mesh in [
        tetrahedron(),
        shapes::cube(1.0, 3).unwrap(),
        shapes::sphere(1.0, 12).unwrap(),
        shapes::capsule(0.3, 2.0, 10).unwrap(),
    ] {
        let surface = GenusZeroSurface::new(&mesh).unwrap();
        let [i, j, k] = surface.root().unwrap().vertices;
        let paths = [
            surface.shortest_path(i, j),
            surface.shortest_path(j, k),
            surface.shortest_path(k, i),
        ];
        let refs: Vec<&[u32]> = paths.iter().map(Vec::as_slice).collect();
        let patches = surface.patches(&refs);
        assert!(
            (1..=2).contains(&patches.len()),
            "{} patches",
            patches.len()
        );
        let mut all: Vec<u32> = patches.concat();
        all.sort_unstable();
        assert_eq!(all, (0..mesh.triangle_count() as u32).collect::<Vec<_>>());
    }
}

#[test]
fn triangles_meet_exactly() {
    use sphaera_hal::triangles_meet;
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    // Crossing through the interior.
    assert!(triangles_meet(
        t,
        [
            DVec3::new(0.2, 0.2, -1.0),
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.3, 0.1, 1.0)
        ]
    ));
    // Touching at a vertex, at an edge point, coplanar overlap, coplanar apart, parallel.
    assert!(triangles_meet(
        t,
        [
            DVec3::X,
            DVec3::new(2.0, 0.0, 1.0),
            DVec3::new(2.0, 1.0, 0.0)
        ]
    ));
    assert!(triangles_meet(
        t,
        [
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(0.5, -1.0, 1.0),
            DVec3::new(0.5, -1.0, -1.0)
        ]
    ));
    assert!(triangles_meet(
        t,
        [
            DVec3::new(0.1, 0.1, 0.0),
            DVec3::new(2.0, 0.1, 0.0),
            DVec3::new(0.1, 2.0, 0.0)
        ]
    ));
    assert!(!triangles_meet(
        t,
        [
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0)
        ]
    ));
    assert!(!triangles_meet(t, t.map(|p| p + DVec3::Z)));
}

#[test]
fn brute_references_take_empty_meshes() {
    use sphaera_hal::{Containment, contains3_brute, intersects3_brute};
    let empty = TriMesh::default();
    assert!(!intersects3_brute(&empty, &tetrahedron()));
    assert_eq!(contains3_brute(&empty, DVec3::ZERO), Containment::Outside);
    assert!(matches!(
        sphaera_hal::HalTree3::build(&empty),
        Err(HalError::NotClosed { .. })
    ));
    // One triangle: open.
    let one = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    assert!(matches!(
        sphaera_hal::HalTree3::build(&one),
        Err(HalError::NotClosed { boundary_edges: 3 })
    ));
}
