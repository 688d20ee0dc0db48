//! The sampled (measured) Hausdorff distance: parry's projection against brute force,
//! analytic cases, and the certified bracket of the bunny benchmark pair.

use std::time::Instant;

use glam::DVec3;
use sphaera_io as io;
use sphaera_mesh::{TriMesh, geometry, shapes};
use sphaera_tests::{
    data_dir,
    hausdorff::{
        DistanceToMesh, ReferenceOptions, directed_max, reference_hausdorff,
        reference_hausdorff_with, surface_points,
    },
};

/// Distance from `p` to `mesh` by brute force: our closest point over every triangle.
fn brute_distance(p: DVec3, mesh: &TriMesh) -> f64 {
    mesh.triangle_iter()
        .map(|t| geometry::closest_point_on_triangle(p, &t).distance_squared)
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

/// Largest brute-force distance from `points` to `mesh`, lowest index on ties.
fn brute_directed(points: &[DVec3], mesh: &TriMesh) -> (f64, DVec3) {
    let mut best = (f64::NEG_INFINITY, DVec3::ZERO);
    for &p in points {
        let d = brute_distance(p, mesh);
        if d > best.0 {
            best = (d, p);
        }
    }
    best
}

/// `mesh` with every vertex pushed by a deterministic pseudo-random offset of size up to
/// `amplitude` per coordinate.
fn jittered(mesh: &TriMesh, amplitude: f64) -> TriMesh {
    let positions = mesh
        .positions()
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            let i = i as f64;
            let wave = DVec3::new(
                (i * 0.618_034).fract(),
                (i * 0.414_214).fract(),
                (i * 0.732_051).fract(),
            );
            p + amplitude * (2.0 * wave - DVec3::ONE)
        })
        .collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).expect("the jittered mesh is valid")
}

/// `mesh` uniformly scaled by `factor` about the origin.
fn scaled(mesh: &TriMesh, factor: f64) -> TriMesh {
    let positions = mesh.positions().iter().map(|&p| factor * p).collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).expect("the scaled mesh is valid")
}

/// A small open mesh with two degenerate triangles (one exactly collinear, one a needle)
/// that stick out of a square: they must count as part of the surface.
fn square_with_degenerate_fins() -> TriMesh {
    let positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0), // collinear fin along the x axis
        DVec3::new(0.5, 1.0, 1.0), // needle fin tip, above the square
        DVec3::new(0.499_95, 1.0 + 1e-13, 0.999_9), // ... and a point almost on 3–5
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3], [0, 1, 4], [3, 5, 6]];
    TriMesh::new(positions, triangles).expect("the finned square is valid")
}

#[test]
fn parry_distances_equal_brute_force_on_the_same_samples() {
    let torus = shapes::torus(1.0, 0.35, 16).expect("torus");
    let pairs = [
        (torus.clone(), jittered(&torus, 0.03)),
        (
            shapes::cube(1.0, 3).expect("cube"),
            jittered(&shapes::sphere(0.7, 12).expect("sphere"), 0.02),
        ),
        (
            square_with_degenerate_fins(),
            jittered(&shapes::cube(1.0, 2).expect("cube"), 0.05),
        ),
    ];
    for (k, (a, b)) in pairs.iter().enumerate() {
        for (source, target, name) in [(a, b, "a → b"), (b, a, "b → a")] {
            let points = surface_points(source, 300, 11);
            let oracle = DistanceToMesh::new(target);
            for &p in &points {
                let ours = oracle.distance(p);
                let brute = brute_distance(p, target);
                assert!(
                    (ours - brute).abs() <= 1e-12,
                    "pair {k} {name}: at {p}: parry {ours}, brute force {brute}"
                );
            }
            let (d, at) = directed_max(&points, &oracle).expect("samples");
            let (brute_d, brute_at) = brute_directed(&points, target);
            assert!(
                (d - brute_d).abs() <= 1e-12,
                "pair {k} {name}: max {d} vs {brute_d}"
            );
            assert!(
                at.distance(brute_at) <= 1e-9
                    || (brute_distance(at, target) - brute_d).abs() <= 1e-12,
                "pair {k} {name}: maximum at {at}, brute force at {brute_at}"
            );
        }
        // The refined result is reached at a real point of the source whose brute-force
        // distance is the reported value, and refinement never lowers the estimate.
        let plain = ReferenceOptions {
            samples_per_mesh: 300,
            seed: 11,
            refine_top: 0,
            refine_grid: 8,
        };
        let refined_options = ReferenceOptions {
            refine_top: 8,
            ..plain
        };
        let coarse = reference_hausdorff_with(a, b, &plain);
        let refined = reference_hausdorff_with(a, b, &refined_options);
        assert!(refined.a_to_b >= coarse.a_to_b && refined.b_to_a >= coarse.b_to_a);
        assert!(refined.samples_a > coarse.samples_a && refined.samples_b > coarse.samples_b);
        assert!((brute_distance(refined.a_to_b_at, b) - refined.a_to_b).abs() <= 1e-12);
        assert!((brute_distance(refined.b_to_a_at, a) - refined.b_to_a).abs() <= 1e-12);
        assert!(
            brute_distance(refined.a_to_b_at, a) <= 1e-12,
            "a_to_b_at lies on a"
        );
        assert!(
            brute_distance(refined.b_to_a_at, b) <= 1e-12,
            "b_to_a_at lies on b"
        );
        // Same input, same result.
        assert_eq!(refined, reference_hausdorff_with(a, b, &refined_options));
    }
}

#[test]
fn degenerate_triangles_stay_in_the_target_surface() {
    let fins = square_with_degenerate_fins();
    let target = DistanceToMesh::new(&fins);
    assert_eq!(target.degenerate_triangle_count(), 2);
    // On the collinear fin and on the needle tip: distance zero.
    assert!(target.distance(DVec3::new(1.7, 0.0, 0.0)) <= 1e-15);
    assert!(target.distance(DVec3::new(0.5, 1.0, 1.0)) <= 1e-15);
    assert!((target.distance(DVec3::new(2.0, 0.0, 0.5)) - 0.5).abs() <= 1e-12);
}

#[test]
fn scaled_cube_has_the_analytic_distances() {
    let cube = shapes::cube(1.0, 4).expect("cube");
    let big = scaled(&cube, 1.1);
    let h = reference_hausdorff(&cube, &big, 2_000, 5);
    // Every point of the unit cube's surface has max |coordinate| = 0.5, so its distance to
    // the surface of the 1.1 cube (half-size 0.55) is 0.55 − 0.5 = 0.05, everywhere.
    assert!((h.a_to_b - 0.05).abs() <= 1e-12, "{h:?}");
    // A corner (±0.55)³ of the big cube is 0.05·√3 from the corner of the small one, the
    // farthest any point of the big surface gets (distance to a box outside it).
    let corner = 0.05 * 3f64.sqrt();
    assert!((h.b_to_a - corner).abs() <= 1e-12, "{h:?}");
    assert!((h.b_to_a_at.abs() - DVec3::splat(0.55)).length() <= 1e-12);
    assert!((h.symmetric() - corner).abs() <= 1e-12);
    // Swapping the meshes swaps the directions.
    let swapped = reference_hausdorff(&big, &cube, 2_000, 5);
    assert!((swapped.a_to_b - corner).abs() <= 1e-12);
    assert!((swapped.b_to_a - 0.05).abs() <= 1e-12);
}

#[test]
fn concentric_spheres_are_the_radius_difference_apart() {
    let inner = shapes::sphere(1.0, 48).expect("sphere");
    let outer = shapes::sphere(1.3, 48).expect("sphere");
    let h = reference_hausdorff(&inner, &outer, 5_000, 9);
    // Polygonal spheres: vertices on the sphere, faces up to the chord sag
    // r (1 − cos(π/48)) ≈ 0.0021 r inside, so both directions are 0.3 within a few 1e-3.
    for d in [h.a_to_b, h.b_to_a] {
        assert!((d - 0.3).abs() <= 0.01, "{h:?}");
    }
    // The faces of the inner sphere sag away from the outer one: inner → outer is at
    // least the vertex-to-vertex gap minus nothing, i.e. ≥ 0.3 − sag of the outer.
    assert!(h.a_to_b >= 0.3 - 1.3 * (1.0 - (std::f64::consts::PI / 48.0).cos()) - 1e-12);
}

#[test]
fn bunny_pair_is_within_the_certified_bracket() {
    let Some(data) = data_dir("bunny_pair_is_within_the_certified_bracket") else {
        return;
    };
    let bunny = io::load(data.join("stanford-bunny.obj")).expect("the bunny loads");
    let qem = io::load(data.join("stanford-bunny-qem15.obj")).expect("the qem15 bunny loads");
    let start = Instant::now();
    let h = reference_hausdorff(&bunny, &qem, 50_000, 2026);
    let elapsed = start.elapsed();
    let coarse = reference_hausdorff_with(
        &bunny,
        &qem,
        &ReferenceOptions {
            samples_per_mesh: 50_000,
            seed: 2026,
            refine_top: 0,
            ..ReferenceOptions::default()
        },
    );
    // Certified brackets from the data README (`## Benchmark pair for Hausdorff distance`).
    let (bq_low, bq_high) = (0.000_474_76, 0.000_477_26);
    let (qb_low, qb_high) = (0.000_472_53, 0.000_472_91);
    #[allow(clippy::print_stderr)] // the figures are the point of this test
    {
        eprintln!(
            "bunny ↔ qem15: h(b→q) = {:.8} ({:.2} % of the lower bound, {} samples), \
             h(q→b) = {:.8} ({:.2} %, {} samples), {:.2?}; without refinement {:.8} and {:.8}",
            h.a_to_b,
            100.0 * h.a_to_b / bq_low,
            h.samples_a,
            h.b_to_a,
            100.0 * h.b_to_a / qb_low,
            h.samples_b,
            elapsed,
            coarse.a_to_b,
            coarse.b_to_a,
        );
    }
    assert!(h.a_to_b <= bq_high + 1e-9, "{h:?}");
    assert!(h.b_to_a <= qb_high + 1e-9, "{h:?}");
    // The brief asks for 90 % of the certified lower bounds; vertices, edge midpoints and
    // the refinement reach them (100.00 % and 100.06 % measured), so ask for 99 %: the
    // result is deterministic, and a drop would mean the sampler lost its maxima.
    assert!(h.a_to_b >= 0.99 * bq_low, "{h:?}");
    assert!(h.b_to_a >= 0.99 * qb_low, "{h:?}");
    assert!(coarse.a_to_b <= h.a_to_b && coarse.b_to_a <= h.b_to_a);
}
