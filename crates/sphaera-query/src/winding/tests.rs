//! Tests of the accelerated evaluator against the brute-force winding number and against
//! ray parity.

use std::sync::OnceLock;

use glam::DVec3;
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::*;
use sphaera_mesh::{TriMesh, shapes, shapes::fixtures};

/// Distance from `p` to the triangle `a`, `b`, `c` (test reference).
fn distance_to_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let segment = |s: DVec3, e: DVec3| {
        let d = e - s;
        let t = if d.length_squared() > 0.0 {
            ((p - s).dot(d) / d.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(s + t * d)
    };
    let edges = segment(a, b).min(segment(b, c)).min(segment(c, a));
    let Some(n) = (b - a).cross(c - a).try_normalize() else {
        return edges;
    };
    let height = (p - a).dot(n);
    let q = p - height * n;
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(s, e)| (e - s).cross(q - s).dot(n) >= 0.0);
    if inside { height.abs() } else { edges }
}

/// Distance from `p` to the mesh (test reference).
fn distance_to_mesh(mesh: &TriMesh, p: DVec3) -> f64 {
    mesh.triangle_iter()
        .map(|t| distance_to_triangle(p, t.corners()))
        .fold(f64::INFINITY, f64::min)
}

/// The closed shapes, an open sphere, a flat sheet and two nested spheres.
fn all_shapes() -> Vec<(&'static str, TriMesh)> {
    let mut shapes = fixtures::closed_shapes();
    shapes.push(("open sphere", fixtures::sphere_with_hole(32, 45.0)));
    shapes.push(("sheet", fixtures::unit_sheet(12)));
    shapes.push(("nested spheres", nested_spheres()));
    shapes
}

fn nested_spheres() -> TriMesh {
    fixtures::union(
        &shapes::sphere(1.0, 24).unwrap(),
        &shapes::sphere(0.5, 16).unwrap(),
    )
}

/// `count` random points in the mesh's bounding box grown by 30% on each side, with their
/// distance to the surface.
fn random_points(mesh: &TriMesh, count: usize, seed: u64) -> Vec<(DVec3, f64)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let bounds = mesh.bounding_box();
    let margin = 0.3 * bounds.extent().max(DVec3::splat(0.5 * bounds.diagonal()));
    let (lo, hi) = (bounds.min - margin, bounds.max + margin);
    (0..count)
        .map(|_| {
            let p = DVec3::new(
                rng.random_range(lo.x..hi.x),
                rng.random_range(lo.y..hi.y),
                rng.random_range(lo.z..hi.z),
            );
            (p, distance_to_mesh(mesh, p))
        })
        .collect()
}

/// The evaluators of all shapes, built once.
fn shapes_with_evaluators() -> &'static [(&'static str, TriMesh, WindingNumber)] {
    static SHAPES: OnceLock<Vec<(&'static str, TriMesh, WindingNumber)>> = OnceLock::new();
    SHAPES.get_or_init(|| {
        all_shapes()
            .into_iter()
            .map(|(name, mesh)| {
                let winding = WindingNumber::new(&mesh).unwrap();
                (name, mesh, winding)
            })
            .collect()
    })
}

/// The documented accuracy of the default evaluator (`beta = 2`, third order) for points
/// at least `1e-3 · diagonal` from the surface.
const DEFAULT_TOLERANCE: f64 = 2e-2;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(256)))]

    /// The accelerated winding number is within the documented tolerance of brute force,
    /// and within its own certified error bound.
    #[test]
    fn fast_matches_brute_force(
        shape in 0..8usize,
        unit in prop::array::uniform3(-0.3..1.3f64),
    ) {
        let shapes = shapes_with_evaluators();
        let (name, mesh, winding) = &shapes[shape % shapes.len()];
        let bounds = mesh.bounding_box();
        let extent = bounds.extent().max(DVec3::splat(0.5 * bounds.diagonal()));
        let p = bounds.min + DVec3::from(unit) * extent;
        let brute = winding_number_brute(mesh, p);
        let estimate = winding.winding_number_with_bound(p);
        prop_assert!(
            (estimate.value - brute).abs() <= estimate.error_bound + 1e-12,
            "{name} at {p}: {estimate:?} vs {brute}"
        );
        prop_assert!((winding.winding_number(p).to_bits() == estimate.value.to_bits()));
        prop_assume!(distance_to_mesh(mesh, p) >= 1e-3 * bounds.diagonal());
        prop_assert!(
            (estimate.value - brute).abs() <= DEFAULT_TOLERANCE,
            "{name} at {p}: {} vs {brute}", estimate.value
        );
        // Away from the surface the classification is the exact one, and on closed shapes
        // it is the ray-parity one.
        prop_assert_eq!(winding.is_inside(p), brute > 0.5);
        if shape % shapes.len() < 5 {
            prop_assert_eq!(inside_by_ray_parity(mesh, p), Some(winding.is_inside(p)));
        }
    }
}

#[test]
fn evaluator_is_send_and_sync() {
    fn check<T: Send + Sync + Clone>() {}
    check::<WindingNumber>();
}

#[test]
fn exact_mode_equals_brute_force() {
    for (name, mesh) in all_shapes() {
        let exact = WindingNumber::exact(&mesh).unwrap();
        assert!(exact.options().beta().is_infinite());
        for (p, _) in random_points(&mesh, 100, 3) {
            let (fast, brute) = (exact.winding_number(p), winding_number_brute(&mesh, p));
            assert!(
                (fast - brute).abs() < 1e-12,
                "{name} at {p}: {fast} vs {brute}"
            );
        }
    }
}

#[test]
fn classification_agrees_exactly_with_ray_parity_on_closed_shapes() {
    for (name, mesh) in fixtures::closed_shapes() {
        let winding = WindingNumber::new(&mesh).unwrap();
        let diagonal = mesh.bounding_box_diagonal();
        let points: Vec<DVec3> = random_points(&mesh, 1500, 11)
            .into_iter()
            .filter(|&(_, d)| d >= 1e-3 * diagonal)
            .map(|(p, _)| p)
            .collect();
        assert!(points.len() > 1000, "{name}");
        let fast = winding.classify(&points);
        let certified = winding.classify_certified(&points);
        let mut inside = 0;
        for ((p, fast), certified) in points.iter().zip(fast).zip(certified) {
            let parity = inside_by_ray_parity(&mesh, *p);
            assert_eq!(parity, Some(fast), "{name} at {p}");
            assert_eq!(fast, certified, "{name} at {p}");
            inside += usize::from(fast);
        }
        assert!(inside > 50, "{name}: only {inside} points inside");
    }
}

#[test]
fn certified_classification_equals_brute_force_even_near_the_surface() {
    for (name, mesh, winding) in shapes_with_evaluators() {
        let diagonal = mesh.bounding_box_diagonal();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        // Points within 1e-4 to 1e-2 of the diagonal from the centroid of a triangle.
        for _ in 0..300 {
            let t = mesh
                .triangle(rng.random_range(0..mesh.triangle_count()))
                .unwrap();
            let offset = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ) * diagonal
                * 10f64.powf(rng.random_range(-4.0..-2.0));
            let p = t.centroid() + offset;
            let brute = winding_number_brute(mesh, p);
            if (brute - 0.5).abs() < 1e-9 {
                continue;
            }
            assert_eq!(winding.is_inside_certified(p), brute > 0.5, "{name} at {p}");
        }
    }
}

#[test]
fn batch_queries_equal_single_queries_bit_for_bit() {
    let (_, mesh, winding) = &shapes_with_evaluators()[4];
    let points: Vec<DVec3> = random_points(mesh, 300, 2)
        .into_iter()
        .map(|(p, _)| p)
        .collect();
    let batch = winding.winding_numbers(&points);
    let inside = winding.classify(&points);
    for ((p, w), inside) in points.iter().zip(batch).zip(inside) {
        assert_eq!(w.to_bits(), winding.winding_number(*p).to_bits());
        assert_eq!(inside, winding.is_inside(*p));
    }
    // A second build gives the same bits: the build is deterministic.
    let again = WindingNumber::new(mesh).unwrap();
    for p in &points {
        assert_eq!(
            again.winding_number(*p).to_bits(),
            winding.winding_number(*p).to_bits()
        );
    }
}

#[test]
fn open_sphere_with_a_small_hole_is_about_one_inside() {
    // The hole is the cap above 22.5° from the pole; from the centre it subtends
    // 2π (1 − cos 22.5°) ≈ 0.478 sr, so w(0) ≈ 1 − 0.038.
    let mesh = fixtures::sphere_with_hole(32, 22.5);
    let winding = WindingNumber::new(&mesh).unwrap();
    let center = winding.winding_number(DVec3::ZERO);
    assert!((center - 0.962).abs() < 1e-2, "{center}");
    for p in [
        DVec3::new(0.5, 0.0, -0.5),
        DVec3::new(0.0, -0.7, 0.0),
        DVec3::splat(-0.4),
    ] {
        let w = winding.winding_number(p);
        assert!(w > 0.9 && w < 1.0 + 1e-9, "{p}: {w}");
        assert!(winding.is_inside(p));
    }
    assert!(!winding.is_inside(DVec3::new(0.0, 0.0, 1.5)));
}

#[test]
fn nested_spheres_have_winding_two_in_the_core() {
    let mesh = nested_spheres();
    let winding = WindingNumber::new(&mesh).unwrap();
    let core = winding.winding_number(DVec3::splat(0.05));
    assert!((winding_number_brute(&mesh, DVec3::splat(0.05)) - 2.0).abs() < 1e-9);
    assert!((core - 2.0).abs() < DEFAULT_TOLERANCE, "{core}");
    assert!((winding.winding_number(DVec3::new(0.0, 0.75, 0.0)) - 1.0).abs() < 1e-2);
}

#[test]
fn flat_sheet_winding_stays_within_one_half() {
    let (_, mesh, winding) = &shapes_with_evaluators()[6];
    for (p, d) in random_points(mesh, 300, 9) {
        if d > 1e-6 {
            assert!(winding.winding_number(p).abs() <= 0.5 + 1e-2, "{p}");
        }
    }
}

#[test]
fn inward_oriented_mesh_has_winding_minus_one_inside() {
    let (positions, triangles) = fixtures::unit_cube().into_parts();
    let flipped = triangles.into_iter().map(|[a, b, c]| [a, c, b]).collect();
    let mesh = TriMesh::new(positions, flipped).unwrap();
    let winding = WindingNumber::new(&mesh).unwrap();
    assert!((winding.winding_number(DVec3::splat(0.5)) + 1.0).abs() < 1e-9);
    assert!(!winding.is_inside(DVec3::splat(0.5)));
}

#[test]
fn non_finite_points_are_nan_and_outside() {
    let (_, _, winding) = &shapes_with_evaluators()[1];
    for p in [DVec3::NAN, DVec3::new(f64::INFINITY, 0.0, 0.0)] {
        assert!(winding.winding_number(p).is_nan());
        assert!(!winding.is_inside(p));
        assert!(!winding.is_inside_certified(p));
        assert!(winding.winding_number_with_bound(p).error_bound.is_nan());
    }
}

#[test]
fn invalid_parameters_are_rejected() {
    let mesh = fixtures::unit_cube();
    for beta in [1.0, 0.5, -2.0, f64::NAN, f64::NEG_INFINITY] {
        let options = WindingOptions::default().with_beta(beta);
        let err = WindingNumber::with_options(&mesh, &options).unwrap_err();
        assert!(
            matches!(
                err,
                crate::QueryError::InvalidParameter { name: "beta", .. }
            ),
            "{beta}"
        );
    }
    assert!(matches!(
        WindingNumber::new(&TriMesh::default()),
        Err(crate::QueryError::EmptyMesh)
    ));
}

#[test]
fn single_triangle_mesh_works() {
    let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    let winding = WindingNumber::new(&mesh).unwrap();
    let p = DVec3::new(0.2, 0.2, -0.1);
    assert!((winding.winding_number(p) - winding_number_brute(&mesh, p)).abs() < 1e-12);
}

/// Prints the measured error table of the module documentation:
/// `cargo test -p sphaera-query --lib winding::tests::error_table -- --ignored --nocapture`.
#[test]
#[ignore = "prints the accuracy table of the documentation"]
#[allow(clippy::print_stderr)]
fn error_table() {
    for expansion in [
        Expansion::FirstOrder,
        Expansion::SecondOrder,
        Expansion::ThirdOrder,
    ] {
        for beta in [1.5, 2.0, 3.0, 4.0] {
            let mut worst: f64 = 0.0;
            let mut sum = 0.0;
            let mut count = 0;
            for (_, mesh) in all_shapes() {
                let winding = WindingNumber::with_options(
                    &mesh,
                    &WindingOptions::default()
                        .with_beta(beta)
                        .with_expansion(expansion),
                )
                .unwrap();
                let diagonal = mesh.bounding_box_diagonal();
                for (p, d) in random_points(&mesh, 500, 7) {
                    if d < 1e-3 * diagonal {
                        continue;
                    }
                    let err = (winding.winding_number(p) - winding_number_brute(&mesh, p)).abs();
                    worst = worst.max(err);
                    sum += err;
                    count += 1;
                }
            }
            eprintln!(
                "| {expansion:?} | {beta} | {:.1e} | {worst:.1e} |",
                sum / f64::from(count)
            );
        }
    }
}

/// A closed mesh whose vertices are duplicated per triangle (an unwelded soup).
fn unwelded(mesh: &TriMesh) -> TriMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in mesh.triangles() {
        let base = positions.len() as u32;
        positions.extend(t.iter().map(|&v| mesh.positions()[v as usize]));
        triangles.push([base, base + 1, base + 2]);
    }
    TriMesh::new(positions, triangles).unwrap()
}

#[test]
fn closed_meshes_have_an_empty_boundary_even_unwelded() {
    for (name, mesh) in fixtures::closed_shapes() {
        assert!(WindingBoundary::new(&mesh).is_empty(), "{name}");
        assert!(WindingBoundary::new(&unwelded(&mesh)).is_empty(), "{name}");
    }
    assert!(WindingBoundary::new(&nested_spheres()).is_empty());
    let open = WindingBoundary::new(&fixtures::sphere_with_hole(32, 45.0));
    assert!(!open.is_empty());
    // The rim of the hole: a 32-gon of radius sin 45° (up to where the cut falls).
    assert!(
        open.length() > 3.0 && open.length() < 2.0 * std::f64::consts::PI,
        "{}",
        open.length()
    );
}

/// The winding number's change over a short segment clear of the mesh, by brute force,
/// never exceeds the segment's length times the gradient bound of the ball about its
/// midpoint (the bound of the boundary chain, see `boundary.rs`).
#[test]
fn the_boundary_bounds_the_variation_of_the_winding_number() {
    let open_box = {
        let cube = fixtures::unit_cube();
        TriMesh::new(cube.positions().to_vec(), cube.triangles()[2..].to_vec()).unwrap()
    };
    let meshes = [
        ("open sphere", fixtures::sphere_with_hole(24, 45.0)),
        ("small hole", fixtures::sphere_with_hole(24, 15.0)),
        ("open box", open_box),
        ("sheet", fixtures::unit_sheet(4)),
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(36);
    let mut tight = 0.0_f64;
    for (name, mesh) in &meshes {
        let boundary = WindingBoundary::new(mesh);
        assert!(!boundary.is_empty(), "{name}");
        for (p, distance) in random_points(mesh, 300, 7) {
            let half = 0.45 * distance * rng.random_range(0.05..1.0);
            let u = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize_or(DVec3::X);
            let change = (winding_number_brute(mesh, p + half * u)
                - winding_number_brute(mesh, p - half * u))
            .abs();
            let bound = 2.0 * half * boundary.gradient_bound(p, half);
            assert!(change <= bound + 1e-12, "{name}: {p}: {change} > {bound}");
            if bound.is_finite() && bound > 1e-6 {
                tight = tight.max(change / bound);
            }
        }
    }
    // The bound is not vacuous: somewhere it is within a factor 20 of the change.
    assert!(tight > 0.05, "{tight}");
}

#[test]
fn the_margin_is_certified_and_the_side_is_the_certified_one() {
    let mut decided_none = 0_usize;
    for (name, mesh, winding) in shapes_with_evaluators() {
        for (p, _) in random_points(mesh, 200, 11) {
            let exact = winding_number_brute(mesh, p);
            for wanted in [0.0, 0.2, 0.45, f64::INFINITY] {
                let Some(side) = winding.side_with_margin(p, wanted) else {
                    decided_none += 1;
                    continue;
                };
                assert_eq!(side.inside, winding.is_inside_certified(p), "{name}: {p}");
                assert!(side.margin > 0.0, "{name}: {p}");
                assert!(side.margin <= (exact - 0.5).abs() + 1e-12, "{name}: {p}");
            }
        }
    }
    // Random points are almost all decided by a certified traversal.
    assert!(decided_none < 40, "{decided_none}");
}
