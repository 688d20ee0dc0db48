//! Where Meshsweeper must not fail (issue 4, "Where it must not fail"): every answer is
//! checked against brute force over the input's triangles.

// Distances of exactly 0 and exactly equal points are expected here.
#![allow(clippy::float_cmp)]
#![allow(clippy::print_stderr)] // the worst cases report their split counts

use std::f64::consts::TAU;

use sphaera_mesh::geometry::point_triangle_distance_squared;
use sphaera_mesh::{DVec3, TriMesh, shapes, topology};
use sphaera_sweep::{
    ClosestPoint, Feature, Session, SessionOptions, SweepError, Sweeper, Tolerance, build_hierarchy,
};
use sphaera_tests::SplitMix64;
use sphaera_tests::brute;

// ---------------------------------------------------------------------------------------
// Brute force and checks
// ---------------------------------------------------------------------------------------

/// Whether triangle `t` of `mesh` has three distinct vertex indices (the hierarchy drops the
/// others, see `repeated_index_triangles_are_dropped_zero_area_ones_are_kept`).
fn distinct(mesh: &TriMesh, t: usize) -> bool {
    let [a, b, c] = mesh.triangles()[t];
    a != b && b != c && a != c
}

/// Distance from `p` to triangle `t` of `mesh`.
fn distance_to(mesh: &TriMesh, t: usize, p: DVec3) -> f64 {
    let triangle = mesh.triangle(t).expect("in range");
    point_triangle_distance_squared(p, &triangle).sqrt()
}

/// Distance from `p` to every triangle of `mesh` with distinct indices, sorted.
fn brute_distances(mesh: &TriMesh, p: DVec3) -> Vec<f64> {
    let mut d: Vec<f64> = (0..mesh.triangle_count())
        .filter(|&t| distinct(mesh, t))
        .map(|t| distance_to(mesh, t, p))
        .collect();
    d.sort_by(f64::total_cmp);
    d
}

/// The brute-force distance from `p` to `mesh`.
fn brute(mesh: &TriMesh, p: DVec3) -> f64 {
    brute_distances(mesh, p)[0]
}

/// Checks that `answer` is an exact answer for `p` on `mesh`: the brute-force distance,
/// a point on the reported input triangle at that distance, and a feature made of that
/// triangle's input vertices.
fn check_answer(mesh: &TriMesh, p: DVec3, answer: &ClosestPoint) {
    let expected = brute(mesh, p);
    assert!(
        brute::close(answer.distance, expected),
        "closest({p}) = {} but brute force says {expected}",
        answer.distance
    );
    assert!(
        brute::close((answer.point - p).length(), answer.distance),
        "the point {} is not at the distance {} of {p}",
        answer.point,
        answer.distance
    );
    let t = answer.triangle as usize;
    assert!(t < mesh.triangle_count(), "triangle {t} out of range");
    let on = distance_to(mesh, t, answer.point);
    let scale = answer.point.abs().max_element().max(1.0);
    assert!(on <= 1e-9 * scale, "the point is {on} off triangle {t}");
    let corners = mesh.triangles()[t];
    match answer.feature {
        Feature::Vertex(v) => {
            assert!(corners.contains(&v), "vertex {v} is not a corner of {t}");
            let at = mesh.positions()[v as usize];
            assert!((at - answer.point).length() <= 1e-12 * scale);
        }
        Feature::Edge(a, b) => {
            assert!(a != b && corners.contains(&a) && corners.contains(&b));
        }
        Feature::Face => {}
    }
}

/// `session.closest(p)`, checked against brute force.
fn check(mesh: &TriMesh, session: &mut Session<'_>, p: DVec3) -> ClosestPoint {
    let answer = session
        .closest(p)
        .expect("a finite query on a non-empty mesh");
    check_answer(mesh, p, &answer);
    answer
}

/// Checks `k_closest(p, k)` against brute force: the `k` smallest distances in order, on
/// distinct triangles.
fn check_k_closest(mesh: &TriMesh, session: &mut Session<'_>, p: DVec3, k: usize) {
    let truth = brute_distances(mesh, p);
    let near = session.k_closest(p, k).expect("finite query");
    assert_eq!(near.len(), k.min(truth.len()), "k_closest({p}, {k})");
    for (answer, expected) in near.iter().zip(&truth) {
        assert!(
            brute::close(answer.distance, *expected),
            "{} vs {expected}",
            answer.distance
        );
        assert!(brute::close(
            distance_to(mesh, answer.triangle as usize, p),
            answer.distance
        ));
    }
    let mut triangles: Vec<u32> = near.iter().map(|a| a.triangle).collect();
    triangles.sort_unstable();
    triangles.dedup();
    assert_eq!(triangles.len(), near.len(), "a triangle was returned twice");
}

/// Checks `within(p, d)` against brute force (ties at `d` may round either way).
fn check_within(mesh: &TriMesh, session: &mut Session<'_>, p: DVec3, d: f64) {
    let truth = brute_distances(mesh, p);
    let inside = session.within(p, d).expect("finite query");
    let expected = truth.iter().filter(|&&x| x <= d).count();
    let borderline = truth
        .iter()
        .filter(|&&x| (x - d).abs() <= 1e-9 * d.max(1e-3))
        .count();
    assert!(
        inside.len() + borderline >= expected && inside.len() <= expected + borderline,
        "{} triangles within {d} of {p}, brute force {expected}",
        inside.len()
    );
    assert!(inside.iter().all(|a| a.distance <= d));
    // Nearest first, up to rounding: the order is the queue's (keys shifted by the
    // motion), and near-ties were seen swapped by 1 ulp.
    let found: Vec<f64> = inside.iter().map(|a| a.distance).collect();
    assert!(
        found
            .windows(2)
            .all(|w| w[0] <= w[1] + 1e-12 * w[1].max(1.0)),
        "within({p}, {d}) is not nearest first: {found:?}"
    );
}

/// Checks that a certified interval for `p` contains the brute-force distance.
fn check_bounds(mesh: &TriMesh, session: &mut Session<'_>, p: DVec3, tolerance: Tolerance) {
    let truth = brute(mesh, p);
    let bounds = session.closest_within(p, tolerance).expect("finite query");
    let slack = 1e-12 * truth.max(1.0);
    assert!(
        bounds.lower <= truth + slack && truth <= bounds.upper + slack,
        "{bounds:?} misses {truth} at {p}"
    );
    assert!(
        bounds.gap() <= tolerance.allowed_gap(bounds.upper) + slack || bounds.closest.is_some()
    );
}

// ---------------------------------------------------------------------------------------
// Meshes
// ---------------------------------------------------------------------------------------

/// A flat annulus in the plane `z = 0` between radii 1 and 2, `n` segments around: the
/// polygonal circle of the paper's worst case, as a surface.
fn annulus(n: usize) -> TriMesh {
    let mut positions = Vec::with_capacity(2 * n);
    for i in 0..n {
        let angle = TAU * i as f64 / n as f64;
        let dir = DVec3::new(angle.cos(), angle.sin(), 0.0);
        positions.push(dir);
        positions.push(2.0 * dir);
    }
    let n = n as u32;
    let mut triangles = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * j + 1, 2 * j);
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    }
    TriMesh::new(positions, triangles).expect("valid annulus")
}

/// An open cylindrical band of radius 1 and height 1 around the z axis, `n` segments
/// around and `rows` rows (no caps).
fn band(n: usize, rows: usize) -> TriMesh {
    let mut positions = Vec::new();
    for r in 0..=rows {
        let z = r as f64 / rows as f64 - 0.5;
        for i in 0..n {
            let angle = TAU * i as f64 / n as f64;
            positions.push(DVec3::new(angle.cos(), angle.sin(), z));
        }
    }
    let n32 = n as u32;
    let mut triangles = Vec::new();
    for r in 0..rows as u32 {
        for i in 0..n32 {
            let j = (i + 1) % n32;
            let (a, b, c, d) = (
                r * n32 + i,
                r * n32 + j,
                (r + 1) * n32 + j,
                (r + 1) * n32 + i,
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::new(positions, triangles).expect("valid band")
}

/// A flat or curved grid of `n × n` squares over `[0, 1]²`, height `z(x, y)`: open.
fn grid(n: usize, z: impl Fn(f64, f64) -> f64) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            positions.push(DVec3::new(x, y, z(x, y)));
        }
    }
    let w = n as u32 + 1;
    let mut triangles = Vec::new();
    for j in 0..n as u32 {
        for i in 0..n as u32 {
            let a = j * w + i;
            triangles.push([a, a + 1, a + w + 1]);
            triangles.push([a, a + w + 1, a + w]);
        }
    }
    TriMesh::new(positions, triangles).expect("valid grid")
}

/// The union of two meshes (no welding).
fn union(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let n = a.vertex_count() as u32;
    let mut positions = a.positions().to_vec();
    positions.extend_from_slice(b.positions());
    let mut triangles = a.triangles().to_vec();
    triangles.extend(b.triangles().iter().map(|t| t.map(|i| i + n)));
    TriMesh::new(positions, triangles).expect("valid union")
}

/// `mesh` moved by `shift`.
fn translated(mesh: &TriMesh, shift: DVec3) -> TriMesh {
    let positions = mesh.positions().iter().map(|&p| p + shift).collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).expect("valid")
}

/// Two unit cubes (3 × 3 squares a face) touching at one corner, welded there: a
/// non-manifold vertex.
fn two_cubes_touching_at_a_vertex() -> TriMesh {
    let a = shapes::cube(1.0, 3).expect("cube");
    let b = translated(&a, DVec3::ONE);
    let (welded, _) = topology::weld_vertices(&union(&a, &b), 1e-12).expect("weld");
    welded
}

/// Two unit cubes sharing an edge, welded: a non-manifold edge with four faces.
fn two_cubes_sharing_an_edge() -> TriMesh {
    let a = shapes::cube(1.0, 3).expect("cube");
    let b = translated(&a, DVec3::new(1.0, 1.0, 0.0));
    let (welded, _) = topology::weld_vertices(&union(&a, &b), 1e-12).expect("weld");
    welded
}

/// Three fans of triangles sharing the segment from `(0, 0, 0)` to `(0, 0, 1)`, like the
/// pages of a book: every triangle on that edge has two others on it.
fn book(pages: usize, rows: usize) -> TriMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    // The spine: rows + 1 points shared by every page.
    for r in 0..=rows {
        positions.push(DVec3::new(0.0, 0.0, r as f64 / rows as f64));
    }
    for page in 0..pages {
        let angle = TAU * page as f64 / pages as f64;
        let dir = DVec3::new(angle.cos(), angle.sin(), 0.0);
        let first = positions.len() as u32;
        for r in 0..=rows {
            positions.push(dir + DVec3::new(0.0, 0.0, r as f64 / rows as f64));
        }
        for r in 0..rows as u32 {
            triangles.push([r, first + r, first + r + 1]);
            triangles.push([r, first + r + 1, r + 1]);
        }
    }
    TriMesh::new(positions, triangles).expect("valid book")
}

// ---------------------------------------------------------------------------------------
// The paper's linear worst case
// ---------------------------------------------------------------------------------------

#[test]
fn center_of_a_sphere_mesh_is_exact() {
    // 64 segments: 2 · 64 · 31 = 3968 triangles, every one at almost the same distance.
    let sphere = shapes::sphere(1.0, 64).expect("sphere");
    let hierarchy = build_hierarchy(&sphere).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    // The paper's way, then the tree's (where every box holds the query too).
    for by_tree in [false, true] {
        let options = SessionOptions::default().with_exact_by_tree(by_tree);
        let mut session = sweeper.session_with(&options);
        let answer = check(&sphere, &mut session, DVec3::ZERO);
        let stats = session.stats();
        // Measured (2026-11-21): 765 splits and 13,385 distance evaluations for 3968
        // triangles: linear, as the paper predicts for this query.
        eprintln!(
            "sphere center: {} triangles, distance {}, {stats:?}",
            sphere.triangle_count(),
            answer.distance
        );
        assert!(answer.distance > 0.99 && answer.distance < 1.0);
        // Slightly off the centre too, in the same session and fresh.
        let p = DVec3::new(1e-3, -2e-3, 5e-4);
        check(&sphere, &mut session, p);
        check(&sphere, &mut sweeper.session_with(&options), p);
    }
}

#[test]
fn center_of_a_polygonal_circle_is_exact() {
    // A flat annulus: the query at its centre is at the same distance cos(π/n) from the
    // middle of every inner edge.
    let n = 512;
    let ring = annulus(n);
    let hierarchy = build_hierarchy(&ring).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    let answer = check(&ring, &mut session, DVec3::ZERO);
    assert!((answer.distance - (std::f64::consts::PI / n as f64).cos()).abs() < 1e-12);
    assert!(matches!(answer.feature, Feature::Edge(..)));
    // Measured (2026-11-21): 1001 splits and 4560 distance evaluations for the 1024
    // triangles: every collapse is undone.
    eprintln!("annulus center: {n} segments, {:?}", session.stats());
    // Above the centre, and on the axis of an open cylindrical band (a circle in 3D).
    check(&ring, &mut session, DVec3::new(0.0, 0.0, 0.5));
    let tube = band(256, 4);
    let hierarchy = build_hierarchy(&tube).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    for z in [0.0, 0.25, -0.5, 0.9] {
        check(&tube, &mut session, DVec3::new(0.0, 0.0, z));
    }
    // Measured (2026-11-21): 2038 splits and 18,295 evaluations for the 4 queries on 2048
    // triangles (one reset: the jump policy).
    eprintln!("band axis: 256 segments, {:?}", session.stats());
}

// ---------------------------------------------------------------------------------------
// Queries on the surface, far away, and not finite
// ---------------------------------------------------------------------------------------

#[test]
fn query_on_a_face_is_at_distance_zero() {
    let cube = shapes::cube(2.0, 4).expect("cube"); // faces at ±1, exactly
    let hierarchy = build_hierarchy(&cube).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    for p in [
        // Off the squares' diagonals (the squares are 0.5 wide).
        DVec3::new(1.0, 0.1, -0.37),
        DVec3::new(-0.41, -1.0, 0.77),
        DVec3::new(0.1, 0.2, 1.0),
    ] {
        let answer = check(&cube, &mut session, p);
        // 0 up to the rounding of the triangle's plane (2.8e-17 was seen).
        assert!(answer.distance <= 1e-15, "{p}: {}", answer.distance);
        assert!((answer.point - p).length() <= 1e-15);
        assert_eq!(answer.feature, Feature::Face);
    }
    // A centroid of a curved mesh's triangle: 0 up to rounding.
    let sphere = shapes::sphere(1.0, 20).expect("sphere");
    let hierarchy = build_hierarchy(&sphere).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    for t in [0, 17, 101, sphere.triangle_count() - 1] {
        let p = sphere.triangle(t).expect("in range").centroid();
        let answer = check(&sphere, &mut session, p);
        assert!(answer.distance <= 1e-15, "{}", answer.distance);
    }
}

#[test]
fn query_on_an_edge_midpoint_is_at_distance_zero() {
    let cube = shapes::cube(2.0, 4).expect("cube");
    let hierarchy = build_hierarchy(&cube).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    // Every edge of a few triangles, interior ones and those on the cube's own edges.
    for t in [0, 5, 31, 64, 190] {
        let corners = cube.triangles()[t];
        for e in 0..3 {
            let (a, b) = (corners[e], corners[(e + 1) % 3]);
            let p = 0.5 * (cube.positions()[a as usize] + cube.positions()[b as usize]);
            let answer = check(&cube, &mut session, p);
            assert_eq!(answer.distance, 0.0, "{p}");
            assert_eq!(answer.point, p);
            // Any triangle on that edge may answer, with that edge as the feature.
            match answer.feature {
                Feature::Edge(x, y) => assert!(
                    (x, y) == (a, b) || (x, y) == (b, a),
                    "edge ({x}, {y}) instead of ({a}, {b})"
                ),
                other => panic!("{other:?} for the midpoint of edge ({a}, {b})"),
            }
        }
    }
}

#[test]
fn query_on_a_vertex_returns_that_input_vertex() {
    for mesh in [
        shapes::cube(2.0, 4).expect("cube"),
        shapes::sphere(1.0, 16).expect("sphere"),
        shapes::torus(1.0, 0.3, 12).expect("torus"),
    ] {
        let hierarchy = build_hierarchy(&mesh).expect("hierarchy");
        let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
        let mut session = sweeper.session();
        let mut fresh_answers = Vec::new();
        for v in (0..mesh.vertex_count()).step_by(7) {
            let p = mesh.positions()[v];
            for answer in [
                check(&mesh, &mut session, p),
                check(&mesh, &mut sweeper.session(), p),
            ] {
                assert_eq!(answer.distance, 0.0, "vertex {v}");
                assert_eq!(answer.point, p);
                assert_eq!(answer.feature, Feature::Vertex(v as u32), "vertex {v}");
                fresh_answers.push(answer);
            }
        }
        assert!(!fresh_answers.is_empty());
    }
}

#[test]
fn far_away_queries_are_exact() {
    let torus = shapes::torus(1.0, 0.3, 16).expect("torus");
    let size = torus.bounding_box_diagonal();
    let hierarchy = build_hierarchy(&torus).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    let mut rng = SplitMix64::new(11);
    for _ in 0..20 {
        let p = 1e6 * size * rng.direction();
        check(&torus, &mut session, p);
        check(&torus, &mut sweeper.session(), p);
        // And a step along, far away (coherent).
        check(&torus, &mut session, p + 0.01 * size * rng.direction());
    }
    // Along the axes too (many ties).
    for p in [1e6 * DVec3::X, -1e6 * DVec3::Z, DVec3::new(0.0, 3e6, 3e6)] {
        check(&torus, &mut session, p);
    }
}

#[test]
fn non_finite_queries_are_errors_and_the_session_survives() {
    let sphere = shapes::sphere(1.0, 12).expect("sphere");
    let hierarchy = build_hierarchy(&sphere).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    check(&sphere, &mut session, DVec3::new(0.5, 1.5, 0.0));
    let bad = [
        DVec3::new(f64::NAN, 0.0, 0.0),
        DVec3::new(0.0, f64::INFINITY, 0.0),
        DVec3::new(0.0, 0.0, f64::NEG_INFINITY),
        DVec3::splat(f64::NAN),
    ];
    let non_finite = |e: SweepError| matches!(e, SweepError::NonFiniteQuery { .. });
    for p in bad {
        assert!(non_finite(session.closest(p).unwrap_err()), "{p}");
        assert!(non_finite(
            session
                .closest_within(p, Tolerance::Absolute(0.1))
                .unwrap_err()
        ));
        assert!(non_finite(session.closest_with_budget(p, 3).unwrap_err()));
        assert!(non_finite(session.k_closest(p, 3).unwrap_err()));
        assert!(non_finite(session.within(p, 0.5).unwrap_err()));
        // The session still answers (near the last good query: the safe ball, and far).
        check(&sphere, &mut session, DVec3::new(0.5, 1.5, 0.0));
        check(&sphere, &mut session, DVec3::new(-0.2, 0.1, -3.0));
        check_k_closest(&sphere, &mut session, DVec3::new(0.1, 0.0, 0.0), 4);
    }
    let error = session.closest(DVec3::new(f64::NAN, 1.0, 2.0)).unwrap_err();
    assert!(error.to_string().contains("not finite"), "{error}");
}

// ---------------------------------------------------------------------------------------
// Unusual meshes
// ---------------------------------------------------------------------------------------

/// Random queries (uniform in 3× the bounding box, and on the vertices) against brute
/// force, fresh and in one session.
fn check_random_queries(mesh: &TriMesh, seed: u64, count: usize) {
    let hierarchy = build_hierarchy(mesh).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    let bbox = mesh.bounding_box();
    let (center, extent) = (bbox.center(), bbox.extent().max(DVec3::splat(1e-3)));
    let mut rng = SplitMix64::new(seed);
    for i in 0..count {
        let p = if i % 4 == 3 {
            mesh.positions()[rng.index(mesh.vertex_count())]
        } else {
            center
                + 1.5
                    * DVec3::new(
                        rng.range(-1.0, 1.0) * extent.x,
                        rng.range(-1.0, 1.0) * extent.y,
                        rng.range(-1.0, 1.0) * extent.z,
                    )
        };
        check(mesh, &mut session, p);
        check(mesh, &mut sweeper.session(), p);
        if i % 8 == 0 {
            check_k_closest(mesh, &mut session, p, 3);
            check_bounds(mesh, &mut session, p, Tolerance::RelativeToUpper(0.05));
        }
    }
}

#[test]
fn single_triangle() {
    let mesh = TriMesh::new(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.5),
            DVec3::new(0.3, 1.0, -0.2),
        ],
        vec![[0, 1, 2]],
    )
    .expect("valid");
    let hierarchy = build_hierarchy(&mesh).expect("hierarchy");
    assert_eq!(hierarchy.triangle_count(), 1);
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    assert_eq!(sweeper.base_triangles(), &[0]);
    let mut session = sweeper.session();
    let answer = check(&mesh, &mut session, DVec3::new(5.0, 5.0, 5.0));
    assert_eq!(answer.triangle, 0);
    assert_eq!(
        check(&mesh, &mut session, mesh.positions()[1]).feature,
        Feature::Vertex(1)
    );
    check_k_closest(&mesh, &mut session, DVec3::ZERO, 5);
    check_within(&mesh, &mut session, DVec3::new(0.5, 0.3, 1.0), 2.0);
    let budget = session
        .closest_with_budget(DVec3::new(0.0, 0.0, 1.0), 0)
        .expect("ok");
    assert_eq!(
        budget.lower, budget.upper,
        "a single input triangle is exact"
    );
    check_random_queries(&mesh, 1, 40);
}

#[test]
fn two_disjoint_triangles() {
    let mesh = TriMesh::new(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(3.0, 0.0, 1.0),
            DVec3::new(3.0, 1.0, 1.0),
            DVec3::new(4.0, 0.5, 2.0),
        ],
        vec![[0, 1, 2], [3, 4, 5]],
    )
    .expect("valid");
    let hierarchy = build_hierarchy(&mesh).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    // Alternating sides, so the answer changes triangle every time.
    for i in 0..20 {
        let x = if i % 2 == 0 { -1.0 } else { 5.0 };
        let answer = check(&mesh, &mut session, DVec3::new(x, 0.1 * f64::from(i), 0.3));
        assert_eq!(answer.triangle, u32::from(i % 2 != 0));
    }
    // Exactly half-way between them (a tie): either one, at the right distance.
    check(&mesh, &mut session, DVec3::new(2.0, 0.5, 0.5));
    check_k_closest(&mesh, &mut session, DVec3::new(2.0, 0.5, 0.5), 3);
    check_random_queries(&mesh, 2, 60);
}

#[test]
fn open_meshes() {
    // A cube with one face's triangles and a few scattered ones removed.
    let cube = shapes::cube(1.0, 4).expect("cube");
    let triangles: Vec<[u32; 3]> = cube
        .triangles()
        .iter()
        .enumerate()
        .filter(|&(t, _)| t >= 32 && t % 13 != 0)
        .map(|(_, &t)| t)
        .collect();
    let open_cube = TriMesh::new(cube.positions().to_vec(), triangles).expect("valid");
    assert!(topology::analyze(&open_cube).boundary_edge_count > 0);
    check_random_queries(&open_cube, 3, 80);
    // Queries inside the cube, through the hole.
    let hierarchy = build_hierarchy(&open_cube).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    for z in [-0.4, -0.1, 0.0, 0.2, 0.45] {
        check(&open_cube, &mut session, DVec3::new(0.1, -0.05, z));
    }
    // Flat and curved grids.
    check_random_queries(&grid(10, |_, _| 0.0), 4, 80);
    check_random_queries(&grid(12, |x, y| 0.2 * (3.0 * x).sin() * y), 5, 80);
}

#[test]
fn non_manifold_meshes() {
    let touching = two_cubes_touching_at_a_vertex();
    assert!(!topology::analyze(&touching).is_manifold);
    check_random_queries(&touching, 6, 80);
    // Exactly at the shared corner, and on the diagonal through it.
    let hierarchy = build_hierarchy(&touching).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    let corner = check(&touching, &mut session, DVec3::splat(0.5));
    assert_eq!(corner.distance, 0.0);
    assert!(matches!(corner.feature, Feature::Vertex(_)));
    for t in [0.3, 0.45, 0.5, 0.55, 0.7] {
        check(&touching, &mut session, DVec3::new(t, t, 1.0 - t));
    }

    let sharing = two_cubes_sharing_an_edge();
    assert!(!topology::analyze(&sharing).is_manifold);
    check_random_queries(&sharing, 7, 80);

    let pages = book(3, 6);
    assert!(!topology::analyze(&pages).is_manifold);
    check_random_queries(&pages, 8, 80);
    // On the spine and between the pages.
    let hierarchy = build_hierarchy(&pages).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    for z in [0.0, 0.5, 1.0, 1.5] {
        let answer = check(&pages, &mut session, DVec3::new(0.0, 0.0, z));
        assert_eq!(answer.distance, (z - 1.0).max(0.0));
        check(&pages, &mut session, DVec3::new(-0.3, 0.01, z));
    }
}

#[test]
fn duplicate_vertices() {
    // A sphere whose odd triangles use copies of the vertices: seams everywhere, and every
    // vertex position twice. Queries on a vertex may answer either copy.
    let sphere = shapes::sphere(1.0, 10).expect("sphere");
    let (p, t) = sphere.into_parts();
    let n = p.len() as u32;
    let mut positions = p.clone();
    positions.extend_from_slice(&p);
    let triangles: Vec<[u32; 3]> = t
        .iter()
        .enumerate()
        .map(|(i, tri)| if i % 2 == 0 { *tri } else { tri.map(|x| x + n) })
        .collect();
    let mesh = TriMesh::new(positions, triangles).expect("valid");
    check_random_queries(&mesh, 9, 80);
    // The same triangle twice (same indices) is kept twice: k_closest sees both.
    let single = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        vec![[0, 1, 2], [0, 1, 2], [2, 1, 0]],
    )
    .expect("valid");
    let hierarchy = build_hierarchy(&single).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    check(&single, &mut session, DVec3::new(0.2, 0.2, 1.0));
    check_k_closest(&single, &mut session, DVec3::new(0.2, 0.2, 1.0), 5);
}

#[test]
fn repeated_index_triangles_are_dropped_zero_area_ones_are_kept() {
    // What happens (documented here): the hierarchy drops triangles with a repeated vertex
    // index (`[a, a, b]`: a segment or a point, no surface), so they are never an answer,
    // even when the segment they span is nearer than every real triangle; the answer is
    // exact over the other triangles and `triangle` is still the input's index. Zero-area
    // triangles with three distinct indices (collinear or coincident corners) are kept
    // and answered like any other.
    let positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        // A segment far from the triangle, as a repeated-index triangle.
        DVec3::new(5.0, 0.0, 0.0),
        DVec3::new(6.0, 0.0, 0.0),
        // A collinear (zero-area) triangle with distinct indices.
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::new(0.0, 0.0, 6.0),
        DVec3::new(0.0, 0.0, 7.0),
        // A triangle with three coincident corners (a point) with distinct indices.
        DVec3::new(-4.0, 0.0, 0.0),
        DVec3::new(-4.0, 0.0, 0.0),
        DVec3::new(-4.0, 0.0, 0.0),
    ];
    let triangles = vec![[3, 3, 4], [0, 1, 2], [5, 6, 7], [8, 9, 10]];
    let mesh = TriMesh::new(positions, triangles).expect("valid");
    let hierarchy = build_hierarchy(&mesh).expect("hierarchy");
    assert_eq!(
        hierarchy.triangle_count(),
        3,
        "the repeated-index one is dropped"
    );
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();

    // Near the dropped segment: the answer is the real triangle (brute force over the
    // distinct-index triangles), not the segment at distance 0.1.
    let p = DVec3::new(5.5, 0.1, 0.0);
    let answer = check(&mesh, &mut session, p);
    assert_eq!(answer.triangle, 1, "the input's index, not the hierarchy's");
    assert!(distance_to(&mesh, 0, p) < answer.distance);

    // Near the collinear triangle: it answers, on its "edge".
    let p = DVec3::new(0.3, 0.0, 6.2);
    let answer = check(&mesh, &mut session, p);
    assert_eq!(answer.triangle, 2);
    assert!((answer.distance - 0.3).abs() < 1e-12);

    // Near the point triangle: it answers, at its vertex.
    let p = DVec3::new(-4.0, 0.5, 0.0);
    let answer = check(&mesh, &mut session, p);
    assert_eq!(answer.triangle, 3);
    assert_eq!(answer.point, DVec3::new(-4.0, 0.0, 0.0));
    check_k_closest(&mesh, &mut session, DVec3::new(1.0, 1.0, 1.0), 10);
    check_random_queries(&mesh, 10, 60);

    // A grid with a column of vertices moved onto their neighbours: zero-area triangles
    // inside a surface.
    let mut zero = grid(8, |x, y| 0.1 * (x + y));
    let mut moved = zero.positions().to_vec();
    for j in 0..=8 {
        let i = 9 * j + 4;
        moved[i] = moved[i - 1];
    }
    zero.set_positions(moved).expect("finite");
    assert!(zero.triangle_iter().any(|t| t.area() == 0.0));
    check_random_queries(&zero, 11, 80);
}

#[test]
fn a_hierarchy_with_no_triangle_cannot_be_built() {
    // `Sweeper::new` rejects an empty base with `SweepError::EmptyMesh`, but no empty
    // hierarchy can reach it: the simplifier refuses a mesh without triangles, and one
    // whose triangles all repeat a vertex index.
    let empty = TriMesh::new(vec![DVec3::ZERO], Vec::new()).expect("valid");
    assert!(build_hierarchy(&empty).is_err());
    let segments =
        TriMesh::new(vec![DVec3::ZERO, DVec3::X], vec![[0, 0, 1], [1, 1, 0]]).expect("valid");
    match build_hierarchy(&segments) {
        Err(_) => {}
        Ok(hierarchy) => {
            assert_eq!(hierarchy.triangle_count(), 0);
            assert!(matches!(
                Sweeper::new(&hierarchy).unwrap_err(),
                SweepError::EmptyMesh
            ));
        }
    }
}

// ---------------------------------------------------------------------------------------
// Parameters
// ---------------------------------------------------------------------------------------

#[test]
fn negative_and_nan_parameters_are_errors() {
    let cube = shapes::cube(1.0, 3).expect("cube");
    let hierarchy = build_hierarchy(&cube).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    let p = DVec3::new(0.2, 0.9, 0.1);
    let invalid = |e: &SweepError, expected: &str| matches!(e, SweepError::InvalidParameter { name, .. } if *name == expected);
    for value in [-1.0, -1e-300, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for tolerance in [
            Tolerance::Absolute(value),
            Tolerance::RelativeToUpper(value),
        ] {
            let error = session.closest_within(p, tolerance).unwrap_err();
            assert!(invalid(&error, "tolerance"), "{error}");
        }
        let error = session.within(p, value).unwrap_err();
        assert!(invalid(&error, "distance"), "{error}");
        assert!(error.to_string().starts_with("invalid `distance`"));
        // The session is unharmed.
        check(&cube, &mut session, p);
    }
    // Zero is valid for both.
    let exact = session
        .closest_within(p, Tolerance::Absolute(0.0))
        .expect("ok");
    assert_eq!(exact.lower, exact.upper);
    assert!(brute::close(exact.lower, brute(&cube, p)));
    assert!(session.within(p, 0.0).expect("ok").is_empty());
}

#[test]
fn k_closest_with_zero_and_more_than_every_triangle() {
    let torus = shapes::torus(1.0, 0.3, 8).expect("torus");
    let hierarchy = build_hierarchy(&torus).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    let p = DVec3::new(0.4, 1.1, 0.2);
    assert!(session.k_closest(p, 0).expect("ok").is_empty());
    check(&torus, &mut session, p);
    for k in [
        torus.triangle_count(),
        torus.triangle_count() + 1,
        usize::MAX,
    ] {
        check_k_closest(&torus, &mut session, p, k);
        let all = session.k_closest(p, k).expect("ok");
        let mut triangles: Vec<u32> = all.iter().map(|a| a.triangle).collect();
        triangles.sort_unstable();
        assert_eq!(
            triangles,
            (0..torus.triangle_count() as u32).collect::<Vec<_>>()
        );
    }
    // The session still answers afterwards (the taken leaves were put back).
    check(&torus, &mut session, p);
    check(&torus, &mut session, -p);
    check_k_closest(&torus, &mut session, -p, 0);
    check_within(&torus, &mut session, -p, 0.7);
}

#[test]
fn within_zero_on_the_surface_finds_the_triangles_through_the_point() {
    let cube = shapes::cube(2.0, 4).expect("cube");
    let hierarchy = build_hierarchy(&cube).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session();
    // Inside a face (off the squares' diagonals): one triangle.
    let p = DVec3::new(1.0, 0.1, -0.37);
    let inside = session.within(p, 0.0).expect("ok");
    assert_eq!(inside.len(), 1);
    assert_eq!(inside[0].distance, 0.0);
    // On an edge between two triangles of a face: two.
    let on_edge = DVec3::new(1.0, 0.25, 0.0);
    check_within(&cube, &mut session, on_edge, 0.0);
    // On vertices: every triangle around each (6 inside a face, 3–6 on the cube's edges
    // and corners depending on the diagonals).
    for v in [0, 10, 25, cube.vertex_count() - 1] {
        let q = cube.positions()[v];
        let around = cube
            .triangles()
            .iter()
            .filter(|t| t.contains(&(v as u32)))
            .count();
        let found = session.within(q, 0.0).expect("ok");
        assert_eq!(found.len(), around, "vertex {v}");
        assert!(found.iter().all(|a| a.distance == 0.0 && a.point == q));
        assert!(found.iter().all(|a| a.feature == Feature::Vertex(v as u32)));
    }
}

// ---------------------------------------------------------------------------------------
// One session through all of it
// ---------------------------------------------------------------------------------------

#[test]
fn one_session_through_every_case_in_sequence() {
    let mesh = union(
        &two_cubes_touching_at_a_vertex(),
        &translated(&book(3, 4), DVec3::new(4.0, 0.0, 0.0)),
    );
    let size = mesh.bounding_box_diagonal();
    let hierarchy = build_hierarchy(&mesh).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    for options in [
        SessionOptions::default(),
        SessionOptions::default()
            .with_max_triangles(usize::MAX)
            .with_jump_factor(f64::INFINITY),
        SessionOptions::default()
            .with_max_triangles(0)
            .with_jump_factor(0.0),
    ] {
        let mut s = sweeper.session_with(&options);
        let vertex = mesh.positions()[5];
        let cube_center = DVec3::ZERO;
        check(&mesh, &mut s, cube_center);
        check(&mesh, &mut s, vertex);
        assert!(s.closest(DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
        check(&mesh, &mut s, vertex + DVec3::splat(1e-12));
        // Far away (100× the size; farther breaks the bounds of a session that keeps its
        // state, see `far_jumps_keep_the_bounds_of_a_kept_session_certified`).
        check(&mesh, &mut s, 100.0 * size * DVec3::new(0.3, -0.9, 0.1));
        check_within(&mesh, &mut s, vertex, 0.0);
        check_k_closest(&mesh, &mut s, DVec3::new(4.0, 0.0, 0.5), 0);
        check_k_closest(&mesh, &mut s, DVec3::new(4.0, 0.0, 0.5), 7);
        check(&mesh, &mut s, DVec3::new(4.0, 0.0, 0.5));
        assert!(s.within(DVec3::ZERO, -1.0).is_err());
        check_bounds(
            &mesh,
            &mut s,
            DVec3::new(2.0, 2.0, 2.0),
            Tolerance::Absolute(0.05),
        );
        let budget = s
            .closest_with_budget(DVec3::new(1.9, 0.0, 0.1), 0)
            .expect("ok");
        let truth = brute(&mesh, DVec3::new(1.9, 0.0, 0.1));
        assert!(budget.lower <= truth + 1e-12 && truth <= budget.upper + 1e-12);
        assert_eq!(budget.splits, 0);
        check(&mesh, &mut s, DVec3::new(1.9, 0.0, 0.1));
        check_k_closest(&mesh, &mut s, DVec3::new(1.9, 0.0, 0.1), usize::MAX);
        check(&mesh, &mut s, DVec3::new(1.9, 0.0, 0.1));
        s.reset();
        check(&mesh, &mut s, DVec3::new(1.9, 0.0, 0.1));
        check(&mesh, &mut s, cube_center);
        assert!(s.memory_bytes() > 0);
        let stats = s.stats();
        assert!(stats.queries >= 15, "{stats:?}");
    }
}

/// A long random walk mixing big jumps, tiny steps, repeats, vertices and the other
/// queries, every answer compared to brute force.
/// With `very_far`, some jumps go 1e5 times the size away (and back).
/// Run twice: exact queries from the tree of input triangles, then the paper's way.
fn random_walk(mesh: &TriMesh, options: SessionOptions, seed: u64, steps: usize, very_far: bool) {
    for by_tree in [true, false] {
        random_walk_with(
            mesh,
            options.with_exact_by_tree(by_tree),
            seed,
            steps,
            very_far,
        );
    }
}

fn random_walk_with(
    mesh: &TriMesh,
    options: SessionOptions,
    seed: u64,
    steps: usize,
    very_far: bool,
) {
    let hierarchy = build_hierarchy(mesh).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    let mut session = sweeper.session_with(&options);
    let bbox = mesh.bounding_box();
    let (center, size) = (bbox.center(), mesh.bounding_box_diagonal());
    let mut rng = SplitMix64::new(seed);
    let mut p = center;
    for step in 0..steps {
        let roll = rng.unit();
        p = if roll < 0.12 {
            // A big jump anywhere in 3× the box.
            center + 1.5 * size * rng.range(0.0, 1.0) * rng.direction()
        } else if roll < 0.17 && very_far {
            // Very far.
            center + 1e5 * size * rng.direction()
        } else if roll < 0.25 {
            // Exactly on a vertex.
            mesh.positions()[rng.index(mesh.vertex_count())]
        } else if roll < 0.3 {
            p // the same point again
        } else {
            // A tiny step, 1e-12 to 1e-2 of the size.
            p + size * 10f64.powf(rng.range(-12.0, -2.0)) * rng.direction()
        };
        check(mesh, &mut session, p);
        match step % 17 {
            3 => check_k_closest(mesh, &mut session, p, 1 + rng.index(6)),
            7 => check_within(mesh, &mut session, p, brute(mesh, p) + 0.05 * size),
            11 => check_bounds(mesh, &mut session, p, Tolerance::Absolute(1e-3 * size)),
            13 => {
                let truth = brute(mesh, p);
                let b = session
                    .closest_with_budget(p, rng.index(5))
                    .expect("finite query");
                let slack = 1e-12 * truth.max(1.0);
                assert!(
                    b.lower <= truth + slack && truth <= b.upper + slack,
                    "{b:?}"
                );
            }
            _ => {}
        }
    }
    let stats = session.stats();
    assert!(stats.queries >= steps);
}

/// The meshes of the random walks.
fn walk_meshes() -> Vec<TriMesh> {
    vec![
        shapes::sphere(1.0, 16).expect("sphere"),
        shapes::torus(1.0, 0.3, 16).expect("torus"),
        grid(10, |x, y| 0.1 * (x - y) * x),
        two_cubes_touching_at_a_vertex(),
        book(3, 5),
        annulus(64),
    ]
}

#[test]
fn random_walk_with_a_session_that_never_resets() {
    for (i, mesh) in walk_meshes().iter().enumerate() {
        random_walk(
            mesh,
            SessionOptions::default()
                .with_max_triangles(usize::MAX)
                .with_jump_factor(f64::INFINITY),
            100 + i as u64,
            300,
            false,
        );
    }
}

#[test]
fn random_walk_with_a_tiny_refinement_budget() {
    for (i, mesh) in walk_meshes().iter().enumerate() {
        for max_triangles in [0, 1, 8] {
            random_walk(
                mesh,
                SessionOptions::default().with_max_triangles(max_triangles),
                200 + i as u64,
                150,
                true,
            );
        }
    }
}

#[test]
fn random_walk_with_default_options() {
    for (i, mesh) in walk_meshes().iter().enumerate() {
        random_walk(mesh, SessionOptions::default(), 300 + i as u64, 300, false);
    }
}

// ---------------------------------------------------------------------------------------
// Regression (fixed: rounding slack on the shifted keys and a reset past 64 diagonals of
// motion): the key shift used to lose precision as the total motion grew
// ---------------------------------------------------------------------------------------
//
// A session stores every key as `(d − ε) + motion`, `motion` being the total distance the
// query point travelled since the last reset, and reads it back as `key − motion`. Both
// roundings are relative to `motion`, so once the query point has travelled far (far
// jumps in a session that does not reset for motion, or a walk out and back in steps
// smaller than the distance, which no default option resets), every lower bound is only
// known to about `ulp(motion)`: the certified intervals miss the true distance, and
// `closest` returns a leaf that is not the nearest.

#[test]
fn a_walk_out_to_1e12_and_back_stays_exact() {
    // Before the fix: already on the way back in, `closest((1.40625, 1.875, 3.125))` answers
    // 2.9254083020 where brute force says 2.9254082752 (2.7e-8 off); after the walk
    // (243 queries, no reset) the queries near the sphere are up to 1.5e-4 off.
    let sphere = shapes::sphere(1.0, 16).expect("sphere");
    let hierarchy = build_hierarchy(&sphere).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    // The paper's exact path (whose precision rule this is about), then the tree's.
    for by_tree in [false, true] {
        let mut session =
            sweeper.session_with(&SessionOptions::default().with_exact_by_tree(by_tree));
        let dir = DVec3::new(0.36, 0.48, 0.8);
        // Out to 1e12 and back, each step a quarter of the distance: never a reset.
        let mut r = 2.0;
        while r < 1e12 {
            check(&sphere, &mut session, r * dir);
            r *= 1.25;
        }
        while r > 2.0 {
            check(&sphere, &mut session, r * dir);
            r /= 1.25;
        }
        // The precision rule resets the session once the total motion passes 64
        // diagonals (the tree never refines, so it never resets).
        assert_eq!(session.stats().resets > 0, !by_tree);
        for i in 0..50 {
            let i = f64::from(i);
            check(
                &sphere,
                &mut session,
                1.5 * dir + DVec3::new(0.01 * i, -0.013 * i, 0.02),
            );
        }
    }
}

#[test]
fn far_jumps_keep_the_bounds_of_a_kept_session_certified() {
    // Before the fix: after four jumps to ±1e6 the bounds miss by up to 4.5e-10 (at a distance
    // of about 0.5); after jumps to ±1e12 `closest` itself is 7e-4 off.
    let sphere = shapes::sphere(1.0, 16).expect("sphere");
    let hierarchy = build_hierarchy(&sphere).expect("hierarchy");
    let sweeper = Sweeper::new(&hierarchy).expect("non-empty");
    for far in [1e6, 1e12] {
        let mut session = sweeper.session_with(
            &SessionOptions::default()
                .with_max_triangles(usize::MAX)
                .with_jump_factor(f64::INFINITY),
        );
        let q = DVec3::new(0.3, 1.2, -0.4);
        check(&sphere, &mut session, q);
        for sign in [1.0, -1.0, 1.0, -1.0] {
            check(&sphere, &mut session, DVec3::new(sign * far, 0.0, 0.0));
        }
        for i in 0..50 {
            let i = f64::from(i);
            let p = q + DVec3::new(0.01 * i, -0.013 * i, 0.02);
            check(&sphere, &mut session, p);
            check_bounds(&sphere, &mut session, p, Tolerance::Absolute(1e-3));
        }
    }
}

#[test]
fn random_walks_with_very_far_jumps_in_kept_sessions() {
    // The random walk of the tests above, with one jump in twenty 1e5 times the size
    // away: fails (measured: a query 3.2e-10 from the surface answered 4e-12 too far;
    // with other seeds, lower bounds above the true distance by ~1e-11).
    for (i, mesh) in walk_meshes().iter().enumerate() {
        for options in [
            SessionOptions::default(),
            SessionOptions::default()
                .with_max_triangles(usize::MAX)
                .with_jump_factor(f64::INFINITY),
        ] {
            random_walk(mesh, options, 400 + i as u64, 300, true);
        }
    }
}
