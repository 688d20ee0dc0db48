//! The 3D HAL tree's structure: the children of every node partition its patch, the
//! leaves are the original faces (each once), the deepest level is the mesh, and each
//! patch's vertices lie in its bounding volume; on procedural and real genus-0 meshes.

use sphaera_hal::{HalTree3, Node3};
use sphaera_mesh::{DVec3, TriMesh, shapes, topology::analyze};

fn tetrahedron() -> TriMesh {
    TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap()
}

fn meshes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("tetrahedron", tetrahedron()),
        ("cube", shapes::cube(1.0, 3).unwrap()),
        ("sphere", shapes::sphere(1.0, 12).unwrap()),
        ("capsule", shapes::capsule(0.3, 2.0, 10).unwrap()),
        (
            "ellipsoid",
            shapes::ellipsoid(DVec3::new(2.0, 1.0, 0.5), 10).unwrap(),
        ),
        // Very long thin triangles.
        (
            "needle",
            shapes::ellipsoid(DVec3::new(100.0, 0.5, 0.5), 8).unwrap(),
        ),
        // Tiny and huge coordinates, far from the origin.
        ("tiny", moved(&shapes::sphere(1.0, 10).unwrap(), 1e-7, 3e-6)),
        ("huge", moved(&shapes::cube(1.0, 2).unwrap(), 1e7, -4e9)),
    ]
}

/// `mesh` scaled by `scale` and moved by `offset` along every axis.
fn moved(mesh: &TriMesh, scale: f64, offset: f64) -> TriMesh {
    TriMesh::new(
        mesh.positions()
            .iter()
            .map(|&p| p * scale + DVec3::splat(offset))
            .collect(),
        mesh.triangles().to_vec(),
    )
    .unwrap()
}

fn check(name: &str, mesh: &TriMesh, tree: &HalTree3) {
    let nodes = tree.nodes();
    // The roots partition the faces.
    let mut root_faces: Vec<u32> = tree
        .roots()
        .iter()
        .flat_map(|&r| nodes[r as usize].faces.clone())
        .collect();
    root_faces.sort_unstable();
    assert_eq!(
        root_faces,
        (0..mesh.triangle_count() as u32).collect::<Vec<_>>(),
        "{name}: the roots partition the faces"
    );
    let mut leaves = Vec::new();
    for (i, node) in nodes.iter().enumerate() {
        if node.children.is_empty() {
            assert_eq!(node.faces.len(), 1, "{name}: leaf {i} is one face");
            let face = mesh.triangles()[node.faces[0] as usize];
            let mut a = face;
            let mut b = node.corners;
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "{name}: leaf {i}'s corners are its face's");
            leaves.push(node.faces[0]);
            continue;
        }
        let mut faces: Vec<u32> = node
            .children
            .iter()
            .flat_map(|&c| nodes[c as usize].faces.clone())
            .collect();
        faces.sort_unstable();
        assert_eq!(
            faces, node.faces,
            "{name}: node {i}'s children partition its patch"
        );
        check_bound(name, mesh, node);
    }
    leaves.sort_unstable();
    assert_eq!(
        leaves,
        (0..mesh.triangle_count() as u32).collect::<Vec<_>>(),
        "{name}: leaves"
    );
    // Every level and adaptive approximation is closed; the deepest level is the mesh.
    for level in 0..=tree.depth() {
        assert_closed(name, &format!("level {level}"), &tree.level(level).unwrap());
    }
    let diagonal = mesh.bounding_box().diagonal();
    for tolerance in [0.3, 0.1, 0.03, 0.01, 0.0] {
        let approximation = tree.approximate(tolerance * diagonal).unwrap();
        assert_closed(name, &format!("tolerance {tolerance}"), &approximation);
    }
    let deepest = tree.level(tree.depth()).unwrap();
    assert!(
        analyze(&deepest).is_closed,
        "{name}: the deepest level is closed"
    );
    assert_eq!(
        tree.level(tree.depth()).unwrap().triangle_count(),
        mesh.triangle_count()
    );
}

/// Every edge of `mesh` has as many triangles along it one way as the other (no crack, no
/// hole): the approximations are closed oriented surfaces.
fn assert_closed(name: &str, what: &str, mesh: &TriMesh) {
    let mut net: std::collections::HashMap<(u32, u32), i64> = std::collections::HashMap::new();
    for t in mesh.triangles() {
        for (u, v) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            if u != v {
                *net.entry((u.min(v), u.max(v))).or_default() += if u < v { 1 } else { -1 };
            }
        }
    }
    let open: Vec<_> = net.iter().filter(|&(_, &c)| c != 0).collect();
    assert!(open.is_empty(), "{name}, {what}: open edges {open:?}");
}

/// Every vertex of the node's patch lies in its bounding volume (up to rounding).
fn check_bound(name: &str, mesh: &TriMesh, node: &Node3) {
    let Some(bound) = node.bound else { return };
    if !bound.is_intersection() {
        return;
    }
    let p = mesh.positions();
    let [a, b, c] = node.corners.map(|v| p[v as usize]);
    let normal = (b - a).cross(c - a);
    if normal.length() == 0.0 {
        return;
    }
    let n = normal.normalize();
    // Circumcentre.
    let (ab, ac) = (b - a, c - a);
    let center = a
        + (normal.cross(ab) * ac.length_squared() + ac.cross(normal) * ab.length_squared())
            / (2.0 * normal.length_squared());
    let r = center.distance(a);
    let inside = |k: f64, x: DVec3| {
        let power = x.distance_squared(center) - r * r;
        let h = (x - center).dot(n);
        if k == f64::INFINITY {
            return h >= -1e-9 * r;
        }
        if k == f64::NEG_INFINITY {
            return h <= 1e-9 * r;
        }
        power <= 2.0 * k * r * h + 1e-9 * r * r * (1.0 + k.abs())
    };
    for &f in &node.faces {
        for v in mesh.triangles()[f as usize] {
            let x = p[v as usize];
            assert!(
                inside(bound.above, x) && inside(bound.below, x),
                "{name}: vertex {v} outside the bound of {:?}",
                node.corners
            );
        }
    }
}

#[test]
fn trees_partition_their_patches_and_end_at_the_mesh() {
    for (name, mesh) in meshes() {
        let tree = HalTree3::build(&mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
        check(name, &mesh, &tree);
    }
}

#[test]
fn real_genus_zero_meshes_build() {
    let Some(data) = sphaera_tests::data_dir("real_genus_zero_meshes_build") else {
        return;
    };
    for file in ["spot.obj", "bunny_lowres.obj", "fandisk.obj"] {
        let mesh = sphaera_io::load(data.join(file)).unwrap();
        let tree = HalTree3::build(&mesh).unwrap_or_else(|e| panic!("{file}: {e}"));
        check(file, &mesh, &tree);
    }
}

#[test]
fn adaptive_approximations_shrink_with_the_tolerance_and_torus_is_refused() {
    let mesh = shapes::sphere(1.0, 16).unwrap();
    let tree = HalTree3::build(&mesh).unwrap();
    // The tree's own triangles kept (before the gaps are closed) grow as the tolerance
    // shrinks, and none kept but the faces is wider than the tolerance.
    let kept = |tolerance: f64| {
        let nodes = tree.nodes();
        let mut stack = tree.roots().to_vec();
        let mut count = 0;
        while let Some(n) = stack.pop() {
            let node = &nodes[n as usize];
            if node.children.is_empty() || node.width <= tolerance {
                assert!(node.width <= tolerance.max(0.0) || node.children.is_empty());
                count += 1;
            } else {
                stack.extend(node.children.iter().copied());
            }
        }
        count
    };
    let mut previous = 0;
    for tolerance in [1.0, 0.3, 0.1, 0.03, 0.0] {
        let count = kept(tolerance);
        assert!(count >= previous, "{tolerance}: {count} < {previous}");
        previous = count;
        assert!(tree.approximate(tolerance).unwrap().triangle_count() >= count.min(2));
    }
    // Below 0 every node is refined down to the faces: the mesh itself.
    assert_eq!(
        tree.approximate(-1.0).unwrap().triangle_count(),
        mesh.triangle_count()
    );
    let torus = shapes::torus(1.0, 0.3, 12).unwrap();
    assert!(matches!(
        HalTree3::build(&torus),
        Err(sphaera_hal::HalError::NotGenusZero { genus: 1 })
    ));
}

/// Point inclusion equals the reference outside this crate (an exact-sign generalised
/// winding number and exact on-face tests, `sphaera_tests::regions`), and so does the
/// crate's own `contains3_brute`; away from the surface, also the certified winding
/// number of `sphaera-query`; vertices are on the boundary.
#[test]
fn point_inclusion_equals_brute_force_and_the_winding_number() {
    use sphaera_hal::{Containment, contains3_brute};
    use sphaera_tests::random::SplitMix64;
    use sphaera_tests::regions::{self, Side};
    let mut rng = SplitMix64::new(31);
    for (name, mesh) in meshes() {
        let tree = HalTree3::build(&mesh).unwrap();
        let surface = sphaera_query::Surface::new(&mesh).unwrap();
        let (lo, hi) = mesh
            .positions()
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let mut queries: Vec<DVec3> = (0..300)
            .map(|_| {
                let t = DVec3::new(rng.unit(), rng.unit(), rng.unit());
                lo + (hi - lo) * (t * 1.4 - DVec3::splat(0.2))
            })
            .collect();
        queries.extend(mesh.positions().iter().take(20));
        for t in mesh.triangles().iter().take(20) {
            let [a, b, c] = t.map(|v| mesh.positions()[v as usize]);
            queries.push((a + b + c) / 3.0);
        }
        for (k, &x) in queries.iter().enumerate() {
            let answer = tree.contains(x);
            let expected = match regions::locate_in_solid(&mesh, x) {
                Side::Inside => Containment::Inside,
                Side::Boundary => Containment::Boundary,
                Side::Outside => Containment::Outside,
            };
            assert_eq!(answer, expected, "{name}: {x}");
            assert_eq!(
                contains3_brute(&mesh, x),
                expected,
                "{name}: brute force at {x}"
            );
            if k < 300 {
                let near = surface.closest(x).unwrap().distance < 1e-6;
                if !near {
                    let inside = surface.is_inside_certified(x);
                    assert_eq!(
                        answer == Containment::Inside,
                        inside,
                        "{name}: {x} against the winding number"
                    );
                }
            }
        }
        // Vertices lie on the surface.
        for &v in mesh.positions().iter().take(20) {
            assert_eq!(
                tree.contains(v),
                Containment::Boundary,
                "{name}: vertex {v}"
            );
        }
    }
}

/// Intersection of two placed trees equals the reference outside this crate (parry3d's
/// triangle-mesh intersection test and a winding number, `sphaera_tests::regions`) on
/// the mapped mesh, and so does the crate's own `intersects3_brute`: apart,
/// overlapping, nested (one solid inside the other), and touching exactly.
#[test]
fn placed_intersection_equals_brute_force() {
    use sphaera_hal::intersects3_brute;
    use sphaera_mesh::geometry::Similarity;
    use sphaera_mesh::glam::{DAffine3, DQuat, EulerRot};
    use sphaera_tests::random::SplitMix64;
    use sphaera_tests::regions;
    let a = shapes::sphere(1.0, 8).unwrap();
    let b = shapes::cube(1.0, 2).unwrap();
    let (ta, tb) = (HalTree3::build(&a).unwrap(), HalTree3::build(&b).unwrap());
    let mut rng = SplitMix64::new(41);
    let mut outcomes = [0_usize; 2];
    for k in 0..40 {
        let rotation = DQuat::from_euler(
            EulerRot::XYZ,
            rng.range(0.0, 6.3),
            rng.range(0.0, 6.3),
            rng.range(0.0, 6.3),
        );
        let reach = if k < 30 { 2.5 } else { 0.3 };
        let shift = DVec3::new(
            rng.range(-reach, reach),
            rng.range(-reach, reach),
            rng.range(-reach, reach),
        );
        let scale = if k % 5 == 0 { 0.2 } else { 1.0 };
        let placement = Similarity::new(DAffine3::from_scale_rotation_translation(
            DVec3::splat(scale),
            rotation,
            shift,
        ))
        .unwrap();
        let mapped = TriMesh::new(
            b.positions().iter().map(|&p| placement.point(p)).collect(),
            b.triangles().to_vec(),
        )
        .unwrap();
        let expected = regions::solids_meet(&a, &mapped);
        assert_eq!(
            intersects3_brute(&a, &mapped),
            expected,
            "brute force, placement {k}"
        );
        assert_eq!(ta.intersects(&tb, &placement), expected, "placement {k}");
        outcomes[usize::from(expected)] += 1;
    }
    assert!(outcomes[0] > 0 && outcomes[1] > 0, "{outcomes:?}");
    // Touching: the cube face against a copy moved by its size.
    let touching = Similarity::from_translation(DVec3::X).unwrap();
    let moved = TriMesh::new(
        b.positions().iter().map(|&p| p + DVec3::X).collect(),
        b.triangles().to_vec(),
    )
    .unwrap();
    assert!(regions::solids_meet(&b, &moved));
    assert!(intersects3_brute(&b, &moved));
    assert!(tb.intersects(&tb, &touching));
}
