//! Tests of the sample set and the maxima, and a property test against brute force.

// The maxima are selections, not computations: equal means bit-identical here.
#![allow(clippy::float_cmp)]

use std::collections::BTreeSet;

use glam::DVec3;
use proptest::prelude::*;

use super::*;
use sphaera_mesh::geometry::closest_point_on_triangle;
use sphaera_mesh::{shapes, shapes::fixtures};

/// Distance from `p` to `mesh` by brute force: our closest point over every triangle.
fn brute_distance(mesh: &TriMesh, p: DVec3) -> f64 {
    mesh.triangle_iter()
        .map(|t| closest_point_on_triangle(p, &t).distance_squared)
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

fn scaled(mesh: &TriMesh, factor: f64) -> TriMesh {
    let positions = mesh.positions().iter().map(|&p| factor * p).collect();
    TriMesh::new(positions, mesh.triangles().to_vec()).unwrap()
}

fn no_random() -> SampleOptions {
    SampleOptions::default().with_random_points(0)
}

#[test]
fn samples_are_vertices_then_midpoints_then_random_points() {
    let cube = shapes::cube(1.0, 1).unwrap(); // 8 vertices, 12 triangles, 18 edges
    let options = SampleOptions::default().with_random_points(50).with_seed(3);
    let samples = SurfaceSamples::new(&cube, &options).unwrap();
    assert_eq!(samples.len(), 8 + 18 + 50);
    assert_eq!(
        (
            samples.vertex_count(),
            samples.edge_midpoint_count(),
            samples.random_point_count()
        ),
        (8, 18, 50)
    );
    let positions = cube.positions();
    let mut last_edge = None;
    for (i, (&p, &origin)) in samples.points().iter().zip(samples.origins()).enumerate() {
        match origin {
            SampleOrigin::Vertex(v) => {
                assert_eq!(v as usize, i);
                assert_eq!(p, positions[i]);
            }
            SampleOrigin::EdgeMidpoint(u, w) => {
                assert!((8..26).contains(&i) && u < w);
                assert!(last_edge < Some((u, w)), "edges sorted and distinct");
                last_edge = Some((u, w));
                assert_eq!(p, 0.5 * (positions[u as usize] + positions[w as usize]));
            }
            SampleOrigin::Random { triangle } => {
                assert!(i >= 26);
                let t = cube.triangle(triangle).unwrap();
                assert!(closest_point_on_triangle(p, &t).distance_squared < 1e-24);
            }
        }
    }
    // The random points are `sampling::random`'s, with the seed.
    let random = crate::sampling::random(&cube, 50, 3).unwrap();
    assert!(
        random
            .iter()
            .zip(&samples.points()[26..])
            .all(|(s, &p)| s.position == p)
    );
    assert_eq!(samples, SurfaceSamples::new(&cube, &options).unwrap());
    assert_ne!(
        samples,
        SurfaceSamples::new(&cube, &options.with_seed(4)).unwrap()
    );
}

#[test]
fn each_part_of_the_sample_set_is_optional() {
    let cube = shapes::cube(1.0, 1).unwrap();
    let count = |options: SampleOptions| SurfaceSamples::new(&cube, &options).unwrap().len();
    let none = SampleOptions::default()
        .with_vertices(false)
        .with_edge_midpoints(false)
        .with_random_points(0);
    assert_eq!(count(none), 0);
    assert_eq!(count(none.with_vertices(true)), 8);
    assert_eq!(count(none.with_vertices(true).with_vertex_stride(3)), 3);
    assert_eq!(count(none.with_vertices(true).with_vertex_stride(100)), 1);
    assert_eq!(count(none.with_edge_midpoints(true)), 18);
    assert_eq!(count(none.with_random_points(7)), 7);
    let strided = SurfaceSamples::new(&cube, &none.with_vertices(true).with_vertex_stride(3));
    let origins: Vec<_> = strided.unwrap().origins().to_vec();
    assert_eq!(
        origins,
        [0, 3, 6].map(SampleOrigin::Vertex).to_vec(),
        "every third vertex, from the first"
    );
}

#[test]
fn unreferenced_vertices_and_repeated_corners_are_not_samples() {
    // Vertex 3 is unreferenced; triangle [0, 0, 1] has no edge 0–0.
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::splat(9.0)];
    let mesh = TriMesh::new(positions, vec![[0, 1, 2], [0, 0, 1]]).unwrap();
    let samples = SurfaceSamples::new(&mesh, &no_random()).unwrap();
    assert_eq!(
        samples.origins(),
        &[
            SampleOrigin::Vertex(0),
            SampleOrigin::Vertex(1),
            SampleOrigin::Vertex(2),
            SampleOrigin::EdgeMidpoint(0, 1),
            SampleOrigin::EdgeMidpoint(0, 2),
            SampleOrigin::EdgeMidpoint(1, 2),
        ]
    );
}

#[test]
fn a_surface_without_area_gets_no_random_points() {
    let positions = vec![DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
    let flat = TriMesh::new(positions, vec![[0, 1, 2]]).unwrap();
    let samples = SurfaceSamples::new(&flat, &SampleOptions::default()).unwrap();
    assert_eq!((samples.len(), samples.random_point_count()), (6, 0));
    let empty = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
    assert!(
        SurfaceSamples::new(&empty, &SampleOptions::default())
            .unwrap()
            .is_empty()
    );
}

#[test]
fn bad_sample_options_are_errors() {
    let cube = shapes::cube(1.0, 1).unwrap();
    let err = SurfaceSamples::new(&cube, &SampleOptions::default().with_vertex_stride(0));
    assert!(matches!(
        err,
        Err(QueryError::InvalidParameter {
            name: "vertex_stride",
            ..
        })
    ));
    let too_many = SampleOptions::default().with_random_points(crate::sampling::MAX_SAMPLES + 1);
    let err = SurfaceSamples::new(&cube, &too_many);
    assert!(matches!(
        err,
        Err(QueryError::InvalidParameter {
            name: "random_points",
            ..
        })
    ));
    let options = MeasureOptions::default().with_samples(too_many);
    assert!(sampled_hausdorff(&cube, &cube, &options).is_err());
}

#[test]
fn the_maximum_is_the_first_of_a_tie_and_never_nan() {
    let points = [DVec3::X, DVec3::Y, DVec3::Z, -DVec3::X];
    let directed = DirectedDistance::from_distances(&points, &[1.0, 3.0, 3.0, 2.0]);
    assert_eq!(directed.distance, 3.0);
    assert_eq!(
        directed.farthest,
        Some(Farthest {
            index: 1,
            point: DVec3::Y
        })
    );
    let nan_first = DirectedDistance::from_distances(&points, &[f64::NAN, 0.5, f64::NAN, 0.25]);
    assert_eq!(nan_first.distance, 0.5);
    assert_eq!(nan_first.farthest.map(|f| f.index), Some(1));
    assert_eq!(nan_first.measured, 4);
    let all_nan = DirectedDistance::from_distances(&points[..1], &[f64::NAN]);
    assert_eq!((all_nan.distance, all_nan.farthest), (0.0, None));
    assert_eq!(all_nan.measured, 1);
    // Zero is a distance like any other: the first point reaching it is the farthest.
    let zeros = DirectedDistance::from_distances(&points, &[0.0; 4]);
    assert_eq!(zeros.farthest.map(|f| f.index), Some(0));
}

#[test]
fn parallel_and_single_thread_measurements_agree() {
    let sphere = shapes::sphere(1.0, 12).unwrap();
    let samples = SurfaceSamples::new(&sphere, &SampleOptions::default()).unwrap();
    let tree = TriangleTree::new(&shapes::cube(1.7, 3).unwrap()).unwrap();
    let oracle = |p: DVec3| tree.distance(p).unwrap();
    let parallel = DirectedDistance::measure(samples.points(), oracle);
    assert_eq!(
        parallel,
        DirectedDistance::measure_on_this_thread(samples.points(), oracle)
    );
    let all = distances(samples.points(), oracle);
    assert_eq!(
        parallel,
        DirectedDistance::from_distances(samples.points(), &all)
    );
    let cube = shapes::cube(1.7, 3).unwrap();
    let options = MeasureOptions::default();
    assert_eq!(
        sampled_hausdorff(&sphere, &cube, &options).unwrap(),
        sampled_hausdorff(&sphere, &cube, &options.with_parallel(false)).unwrap()
    );
}

#[test]
fn identical_meshes_are_at_distance_zero() {
    let torus = shapes::torus(1.0, 0.3, 12).unwrap();
    let h = sampled_hausdorff(&torus, &torus, &MeasureOptions::default()).unwrap();
    assert!(h.symmetric() < 1e-12, "{h:?}");
}

#[test]
fn scaled_cube_distances_are_analytic_both_ways() {
    let small = shapes::cube(1.0, 3).unwrap();
    let big = scaled(&small, 1.1);
    let options = MeasureOptions::default();
    let h = sampled_hausdorff(&small, &big, &options).unwrap();
    assert!((h.a_to_b.distance - 0.05).abs() < 1e-12, "{h:?}");
    let corner = 0.05 * 3f64.sqrt();
    assert!((h.b_to_a.distance - corner).abs() < 1e-12, "{h:?}");
    let swapped = sampled_hausdorff(&big, &small, &options).unwrap();
    assert!((swapped.a_to_b.distance - corner).abs() < 1e-12);
    assert!((swapped.symmetric() - h.symmetric()).abs() < 1e-15);
}

#[test]
fn the_second_surface_uses_the_offset_seed() {
    let a = fixtures::octahedron();
    let b = scaled(&a, 1.5);
    let options = MeasureOptions::default()
        .with_samples(
            SampleOptions::default()
                .with_random_points(300)
                .with_seed(9),
        )
        .with_second_seed_offset(1);
    assert_eq!(options.second_samples().seed, 10);
    let h = sampled_hausdorff(&a, &b, &options).unwrap();
    let tree = TriangleTree::new(&a).unwrap();
    let b_samples = SurfaceSamples::new(&b, &options.samples.with_seed(10)).unwrap();
    let expected = DirectedDistance::measure(b_samples.points(), |p| tree.distance(p).unwrap());
    assert_eq!(h.b_to_a, expected);
    // The default offset.
    let default = MeasureOptions::default().with_samples(SampleOptions::default().with_seed(1));
    assert_eq!(
        default.second_samples().seed,
        1u64.wrapping_add(DEFAULT_SECOND_SEED_OFFSET)
    );
}

#[test]
fn a_mesh_without_triangles_is_an_error() {
    let empty = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
    let cube = shapes::cube(1.0, 1).unwrap();
    for (a, b) in [(&empty, &cube), (&cube, &empty)] {
        assert!(matches!(
            sampled_hausdorff(a, b, &MeasureOptions::default()),
            Err(QueryError::EmptyMesh)
        ));
        assert!(matches!(
            sampled_hausdorff_by(a, b, &MeasureOptions::default(), |_| 0.0, |_| 0.0),
            Err(QueryError::EmptyMesh)
        ));
    }
}

/// A small random mesh: vertices on a grid in `[-1, 1]³` (so coincident and collinear
/// corners happen), triangles with any indices (repeated corners too).
fn small_mesh() -> impl Strategy<Value = TriMesh> {
    (3usize..10).prop_flat_map(|n| {
        let n32 = u32::try_from(n).unwrap();
        (
            prop::collection::vec((-8i32..=8, -8i32..=8, -8i32..=8), n),
            prop::collection::vec([0..n32, 0..n32, 0..n32], 1..8),
        )
            .prop_map(|(coordinates, triangles)| {
                let positions = coordinates
                    .into_iter()
                    .map(|(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)) / 8.0)
                    .collect();
                TriMesh::new(positions, triangles).unwrap()
            })
    })
}

fn sample_options() -> impl Strategy<Value = SampleOptions> {
    (
        any::<bool>(),
        1usize..4,
        any::<bool>(),
        0usize..40,
        any::<u64>(),
    )
        .prop_map(|(vertices, stride, midpoints, random, seed)| {
            SampleOptions::default()
                .with_vertices(vertices)
                .with_vertex_stride(stride)
                .with_edge_midpoints(midpoints)
                .with_random_points(random)
                .with_seed(seed)
        })
}

/// The sample set, counted by brute force.
fn expected_counts(mesh: &TriMesh, options: &SampleOptions) -> (usize, usize, usize) {
    let referenced: BTreeSet<u32> = mesh.triangles().iter().flatten().copied().collect();
    let edges: BTreeSet<(u32, u32)> = mesh
        .triangles()
        .iter()
        .flat_map(|&[i, j, k]| [(i, j), (j, k), (k, i)])
        .filter(|(u, w)| u != w)
        .map(|(u, w)| (u.min(w), u.max(w)))
        .collect();
    let vertices = if options.vertices {
        referenced.len().div_ceil(options.vertex_stride)
    } else {
        0
    };
    let midpoints = if options.edge_midpoints {
        edges.len()
    } else {
        0
    };
    let random = if mesh.surface_area() > 0.0 {
        options.random_points
    } else {
        0
    };
    (vertices, midpoints, random)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(96)))]

    #[test]
    fn sampled_hausdorff_matches_brute_force(
        a in small_mesh(),
        b in small_mesh(),
        samples in sample_options(),
        offset in any::<u64>(),
    ) {
        let options = MeasureOptions::default()
            .with_samples(samples)
            .with_second_seed_offset(offset);
        let h = sampled_hausdorff(&a, &b, &options).unwrap();
        let by_brute = sampled_hausdorff_by(
            &a,
            &b,
            &options.with_parallel(false),
            |p| brute_distance(&a, p),
            |p| brute_distance(&b, p),
        )
        .unwrap();
        for (source, target, sample_options, tree, brute) in [
            (&a, &b, options.samples, h.a_to_b, by_brute.a_to_b),
            (&b, &a, options.second_samples(), h.b_to_a, by_brute.b_to_a),
        ] {
            let set = SurfaceSamples::new(source, &sample_options).unwrap();
            let counts = (set.vertex_count(), set.edge_midpoint_count(), set.random_point_count());
            prop_assert_eq!(counts, expected_counts(source, &sample_options));
            prop_assert_eq!(tree.measured, set.len());
            prop_assert_eq!(brute.measured, set.len());
            // The brute-force maximum, the lowest index on ties, by a plain loop.
            let mut best: Option<(usize, f64)> = None;
            for (i, &p) in set.points().iter().enumerate() {
                let d = brute_distance(target, p);
                if best.is_none_or(|(_, b)| d > b) {
                    best = Some((i, d));
                }
            }
            match best {
                None => {
                    prop_assert_eq!((tree.distance, tree.farthest), (0.0, None));
                    prop_assert_eq!((brute.distance, brute.farthest), (0.0, None));
                }
                Some((i, d)) => {
                    prop_assert_eq!(brute.distance, d);
                    prop_assert_eq!(brute.farthest, Some(Farthest { index: i, point: set.points()[i] }));
                    prop_assert!((tree.distance - d).abs() <= 1e-12, "{} vs {}", tree.distance, d);
                    let farthest = tree.farthest.unwrap();
                    prop_assert_eq!(farthest.point, set.points()[farthest.index]);
                    prop_assert!((brute_distance(target, farthest.point) - d).abs() <= 1e-12);
                }
            }
        }
        prop_assert_eq!(h, sampled_hausdorff(&a, &b, &options.with_parallel(false)).unwrap());
    }
}
