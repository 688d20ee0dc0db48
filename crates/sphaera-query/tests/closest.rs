//! The closest-point tree against brute force (every triangle), on procedural shapes and
//! random triangle soups with degenerate triangles.

use proptest::prelude::*;
use sphaera_mesh::geometry::point_triangle_distance_squared;
use sphaera_mesh::{DVec3, TriMesh, shapes};
use sphaera_query::closest::{Feature, TriangleTree};
use sphaera_tests::brute;

fn shapes() -> Vec<TriMesh> {
    vec![
        shapes::sphere(1.0, 12).expect("sphere"),
        shapes::torus(1.0, 0.3, 16).expect("torus"),
        shapes::cube(1.0, 5).expect("cube"),
        shapes::s_tube(0.2, 1.0, 12).expect("tube"),
    ]
}

fn point() -> impl Strategy<Value = DVec3> {
    (-3.0..3.0_f64, -3.0..3.0_f64, -3.0..3.0_f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A random triangle soup, with repeated corners (degenerate triangles) on purpose.
fn soup() -> impl Strategy<Value = TriMesh> {
    (
        prop::collection::vec(point(), 3..24),
        prop::collection::vec((0..24_u32, 0..24_u32, 0..24_u32), 1..40),
    )
        .prop_map(|(positions, triangles)| {
            let n = positions.len() as u32;
            let triangles: Vec<[u32; 3]> = triangles
                .into_iter()
                .map(|(a, b, c)| [a % n, b % n, c % n])
                .collect();
            TriMesh::new(positions, triangles).expect("indices in range")
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    #[test]
    fn triangle_tree_matches_brute_force(
        shape in 0..5_usize,
        soup in soup(),
        points in prop::collection::vec(point(), 1..16),
        bound in 0.0..2.0_f64,
    ) {
        let mesh = if shape < 4 { shapes().swap_remove(shape) } else { soup };
        let tree = TriangleTree::new(&mesh).expect("non-empty");
        for &p in &points {
            let expected = brute::distance(&mesh, p);
            let answer = tree.closest(p).expect("finite query");
            prop_assert!(brute::close(answer.distance, expected), "{} vs {expected}", answer.distance);
            let [a, b, c] = mesh.triangles()[answer.triangle as usize];
            let triangle = mesh.triangle(answer.triangle as usize).expect("in range");
            prop_assert!(point_triangle_distance_squared(answer.point, &triangle).sqrt() <= 1e-9);
            // The feature names vertices of the answer's triangle, and a vertex answer is
            // that vertex.
            match answer.feature {
                Feature::Vertex(v) => {
                    prop_assert!([a, b, c].contains(&v));
                    prop_assert_eq!(answer.point, mesh.positions()[v as usize]);
                }
                Feature::Edge(u, v) => {
                    prop_assert!([[a, b], [b, c], [c, a]].contains(&[u, v]));
                }
                Feature::Face => {}
            }
            let within = tree.closest_within(p, bound).expect("valid bound");
            prop_assert_eq!(within.is_some(), expected <= bound);
        }
    }
}

/// A walk: steps of every size from 1e-9 to 1, in a seeded order.
fn walk() -> impl Strategy<Value = Vec<DVec3>> {
    (point(), prop::collection::vec((point(), -9..1_i32), 1..40)).prop_map(|(start, steps)| {
        let mut p = start;
        let mut out = vec![p];
        for (direction, exponent) in steps {
            p += direction.normalize_or_zero() * 10f64.powi(exponent);
            out.push(p);
        }
        out
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// The cursor answers every step of a walk exactly (its shortcut and its seeded
    /// descent both), and a batch answers exactly what independent queries do.
    #[test]
    fn cursor_and_batch_match_brute_force(
        shape in 0..5_usize,
        soup in soup(),
        points in walk(),
    ) {
        let mesh = if shape < 4 { shapes().swap_remove(shape) } else { soup };
        let tree = TriangleTree::new(&mesh).expect("non-empty");
        let mut cursor = tree.cursor();
        for &p in &points {
            let expected = brute::distance(&mesh, p);
            let answer = cursor.closest(p).expect("finite query");
            prop_assert!(brute::close(answer.distance, expected), "{} vs {expected}", answer.distance);
            let triangle = mesh.triangle(answer.triangle as usize).expect("in range");
            prop_assert!(point_triangle_distance_squared(answer.point, &triangle).sqrt() <= 1e-9);
        }
        prop_assert_eq!(cursor.queries(), points.len());
        let batch = tree.closest_many(&points).expect("finite queries");
        for (p, answer) in points.iter().zip(batch) {
            prop_assert_eq!(answer, tree.closest(*p).expect("finite query"));
        }
    }
}

#[test]
fn the_cursor_takes_its_shortcut_on_small_steps_and_refuses_bad_points() {
    // Inside a cube, near the middle of a face: the nearest face is clear of the others.
    let cube = shapes::cube(2.0, 2).expect("cube");
    let tree = TriangleTree::new(&cube).expect("non-empty");
    let mut cursor = tree.cursor();
    for i in 0..100 {
        let p = DVec3::new(0.55 + 1e-4 * f64::from(i), 0.1, 0.05);
        let answer = cursor.closest(p).expect("finite");
        assert!((answer.distance - (1.0 - p.x)).abs() < 1e-12);
    }
    assert!(cursor.shortcuts() >= 90, "{}", cursor.shortcuts());
    assert!(cursor.closest(DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
    assert!(tree.closest_many(&[DVec3::ZERO, DVec3::INFINITY]).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(64)))]

    /// The approximate query's interval holds the true distance and is no wider than
    /// asked, absolute or relative; its point lies on the mesh at the upper end; a gap of
    /// 0 is the exact query (to rounding).
    #[test]
    fn approximate_intervals_are_certified(
        shape in 0..5_usize,
        soup in soup(),
        points in prop::collection::vec(point(), 1..16),
        absolute in 0.0..0.5_f64,
        relative in 0.0..0.5_f64,
    ) {
        let mesh = if shape < 4 { shapes().swap_remove(shape) } else { soup };
        let tree = TriangleTree::new(&mesh).expect("non-empty");
        let gap = |upper: f64| absolute + relative * upper;
        for &p in &points {
            let expected = brute::distance(&mesh, p);
            let slack = 1e-12 * (1.0 + expected);
            let approx = tree.closest_approx(p, &gap).expect("finite query");
            prop_assert!(approx.lower <= expected + slack && expected <= approx.upper + slack,
                "{} <= {expected} <= {}", approx.lower, approx.upper);
            prop_assert!(approx.upper - approx.lower <= gap(approx.upper) + slack);
            // The same number, by construction.
            prop_assert!(approx.nearest.distance.to_bits() == approx.upper.to_bits());
            let triangle = mesh.triangle(approx.nearest.triangle as usize).expect("in range");
            prop_assert!(point_triangle_distance_squared(approx.nearest.point, &triangle).sqrt() <= 1e-9);
            let exact = tree.closest_approx(p, &|_| 0.0).expect("finite query");
            // Within rounding: a tie's distance computed on another triangle can be an ulp
            // below.
            prop_assert!(exact.upper - exact.lower <= slack);
            prop_assert_eq!(exact.nearest, tree.closest(p).expect("finite query"));
        }
    }

    /// A cursor's approximate answers along a walk (seeded by the previous answer, mixed
    /// with exact ones) are certified the same way.
    #[test]
    fn cursor_approximate_intervals_are_certified(
        shape in 0..5_usize,
        soup in soup(),
        points in walk(),
        absolute in 0.0..0.5_f64,
        relative in 0.0..0.5_f64,
    ) {
        let mesh = if shape < 4 { shapes().swap_remove(shape) } else { soup };
        let tree = TriangleTree::new(&mesh).expect("non-empty");
        let gap = |upper: f64| absolute + relative * upper;
        let mut cursor = tree.cursor();
        for (i, &p) in points.iter().enumerate() {
            let expected = brute::distance(&mesh, p);
            let slack = 1e-12 * (1.0 + expected);
            if i % 3 == 2 {
                let answer = cursor.closest(p).expect("finite query");
                prop_assert!(brute::close(answer.distance, expected));
                continue;
            }
            let approx = cursor.closest_approx(p, &gap).expect("finite query");
            prop_assert!(approx.lower <= expected + slack && expected <= approx.upper + slack,
                "step {i}: {} <= {expected} <= {}", approx.lower, approx.upper);
            prop_assert!(approx.upper - approx.lower <= gap(approx.upper) + slack);
            prop_assert!(approx.nearest.distance.to_bits() == approx.upper.to_bits());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(48)))]

    /// A tree refit to moved vertices answers exactly on the moved mesh, as a new tree
    /// does, however far the vertices moved.
    #[test]
    fn a_refit_tree_answers_on_the_moved_mesh(
        shape in 0..5_usize,
        soup in soup(),
        offsets in prop::collection::vec(point(), 1..8),
        scale in 0.0..1.0_f64,
        points in prop::collection::vec(point(), 1..12),
    ) {
        let mesh = if shape < 4 { shapes().swap_remove(shape) } else { soup };
        let mut tree = TriangleTree::new(&mesh).expect("non-empty");
        let moved: Vec<DVec3> = mesh
            .positions()
            .iter()
            .enumerate()
            .map(|(i, &p)| p + scale * offsets[i % offsets.len()])
            .collect();
        let moved_mesh = TriMesh::new(moved.clone(), mesh.triangles().to_vec()).expect("valid");
        tree.refit(&moved).expect("one position per vertex");
        let fresh = TriangleTree::new(&moved_mesh).expect("non-empty");
        for &p in &points {
            let expected = brute::distance(&moved_mesh, p);
            let answer = tree.closest(p).expect("finite query");
            prop_assert!(brute::close(answer.distance, expected), "{} vs {expected}", answer.distance);
            prop_assert!(brute::close(fresh.closest(p).expect("finite").distance, answer.distance));
        }
    }
}

#[test]
fn a_refit_refuses_wrong_positions_and_keeps_the_tree() {
    let cube = shapes::cube(2.0, 2).expect("cube");
    let mut tree = TriangleTree::new(&cube).expect("non-empty");
    let p = DVec3::new(3.0, 0.0, 0.0);
    let before = tree.closest(p).expect("finite");
    assert!(tree.refit(&cube.positions()[1..]).is_err());
    let mut bad = cube.positions().to_vec();
    bad[3].y = f64::NAN;
    assert!(matches!(
        tree.refit(&bad),
        Err(sphaera_query::QueryError::Mesh(
            sphaera_mesh::MeshError::NonFiniteCoordinate {
                vertex: 3,
                axis: 'y',
                ..
            }
        ))
    ));
    assert_eq!(tree.closest(p).expect("finite"), before);
}

/// Scaling by a power of two scales every answer exactly: the tree's splits, the cursor's
/// shortcuts and the approximate intervals all see the same numbers, scaled. A rotation
/// changes the answers by rounding only.
#[test]
fn powers_of_two_scale_the_answers_exactly_and_rotations_by_rounding() {
    let mesh = shapes::torus(1.0, 0.3, 24).expect("torus");
    let queries: Vec<DVec3> = (0..300)
        .map(|i| {
            let t = f64::from(i) * 0.05;
            DVec3::new(1.6 * t.cos(), 1.4 * t.sin(), 0.4 * (3.0 * t).sin())
        })
        .collect();
    let answers = |mesh: &TriMesh, scale: f64| {
        let tree = TriangleTree::new(mesh).expect("non-empty");
        let mut cursor = tree.cursor();
        queries
            .iter()
            .map(|&q| {
                let p = q * scale;
                let approx = tree.closest_approx(p, &|_| 0.05 * scale).expect("finite");
                (
                    tree.closest(p).expect("finite"),
                    cursor.closest(p).expect("finite").distance,
                    (approx.lower, approx.upper),
                )
            })
            .collect::<Vec<_>>()
    };
    let reference = answers(&mesh, 1.0);
    for scale in [2f64.powi(40), 2f64.powi(-40)] {
        let scaled = TriMesh::new(
            mesh.positions().iter().map(|&p| p * scale).collect(),
            mesh.triangles().to_vec(),
        )
        .expect("valid");
        for ((a, ca, (la, ua)), (b, cb, (lb, ub))) in reference.iter().zip(answers(&scaled, scale))
        {
            assert_eq!(a.triangle, b.triangle);
            assert_eq!(a.feature, b.feature);
            assert_eq!(a.point * scale, b.point);
            assert_eq!((a.distance * scale).to_bits(), b.distance.to_bits());
            assert_eq!((ca * scale).to_bits(), cb.to_bits());
            assert_eq!(
                ((la * scale).to_bits(), (ua * scale).to_bits()),
                (lb.to_bits(), ub.to_bits())
            );
        }
    }
    // A quarter turn about z and a shift: the same distances to rounding.
    let turned = TriMesh::new(
        mesh.positions()
            .iter()
            .map(|p| DVec3::new(-p.y, p.x, p.z) + DVec3::splat(1e3))
            .collect(),
        mesh.triangles().to_vec(),
    )
    .expect("valid");
    let tree = TriangleTree::new(&turned).expect("non-empty");
    for (q, (a, _, _)) in queries.iter().zip(&reference) {
        let p = DVec3::new(-q.y, q.x, q.z) + DVec3::splat(1e3);
        let d = tree.closest(p).expect("finite").distance;
        assert!((d - a.distance).abs() <= 1e-9, "{d} vs {}", a.distance);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: sphaera_tests::cases(48), ..ProptestConfig::default() })]

    /// The triangle bound is brute force's smallest largest-corner distance, and with
    /// `enough` it stops at a triangle within it (or finds the smallest).
    #[test]
    fn triangle_upper_bound_matches_brute_force(
        mesh in prop_oneof![soup(), (0..4usize).prop_map(|i| shapes()[i].clone())],
        corners in [point(), point(), point()],
        enough in 0.0..3.0_f64,
    ) {
        let tree = TriangleTree::new(&mesh).expect("non-empty");
        let brute = (0..mesh.triangle_count())
            .filter_map(|t| mesh.triangle(t))
            .map(|t| {
                corners
                    .iter()
                    .map(|&p| point_triangle_distance_squared(p, &t))
                    .fold(0.0_f64, f64::max)
            })
            .fold(f64::INFINITY, f64::min)
            .sqrt();
        let exact = tree.triangle_upper_bound(corners, 0.0).expect("finite");
        prop_assert!((exact - brute).abs() <= 1e-12 * (1.0 + brute), "{exact} vs {brute}");
        let early = tree.triangle_upper_bound(corners, enough).expect("finite");
        prop_assert!(early >= exact - 1e-12);
        prop_assert!(early <= enough || (early - brute).abs() <= 1e-12 * (1.0 + brute));
        // The bound holds for every point of the triangle (dense barycentric samples).
        for i in 0..=6 {
            for j in 0..=(6 - i) {
                let (u, v) = (f64::from(i) / 6.0, f64::from(j) / 6.0);
                let p = u * corners[0] + v * corners[1] + (1.0 - u - v) * corners[2];
                prop_assert!(brute::distance(&mesh, p) <= early + 1e-12 * (1.0 + early));
            }
        }
        prop_assert!(tree.triangle_upper_bound([DVec3::NAN, corners[1], corners[2]], 0.0).is_err());
    }
}
