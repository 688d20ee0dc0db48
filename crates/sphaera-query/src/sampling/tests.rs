//! Tests of both samplers against brute force.

use glam::DVec3;
use proptest::prelude::*;

use super::grid::min_distance;
use super::*;
use sphaera_mesh::shapes;

/// Brute-force distance from `p` to the triangle `a b c` (closest point by projection
/// onto the plane when inside, else the closest point on the three edges).
fn distance_to_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let n = (b - a).cross(c - a);
    let q = p - n * (p - a).dot(n) / n.length_squared();
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= 0.0);
    if inside {
        return p.distance(q);
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(u, v)| {
            let t = ((p - u).dot(v - u) / (v - u).length_squared()).clamp(0.0, 1.0);
            p.distance(u + t * (v - u))
        })
        .fold(f64::INFINITY, f64::min)
}

fn assert_on_surface(mesh: &TriMesh, samples: &[SurfaceSample]) {
    let tolerance = 1e-12 * mesh.bounding_box_diagonal();
    for (i, s) in samples.iter().enumerate() {
        let [a, b, c] = mesh.triangles()[s.triangle].map(|v| mesh.positions()[v as usize]);
        let d = distance_to_triangle(s.position, a, b, c);
        assert!(d <= tolerance, "sample {i} is {d:e} off its triangle");
        assert!(s.barycentric.iter().all(|&w| w >= 0.0), "sample {i}");
        assert!((s.barycentric.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        let normal = (b - a).cross(c - a).normalize();
        assert!(s.normal.distance(normal) < 1e-12, "sample {i} normal");
    }
}

/// Triangles of very different areas: a big and a tiny right triangle, a degenerate one,
/// and a medium one, far apart.
fn uneven_mesh() -> TriMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (i, size) in [10.0f64, 0.1, 0.0, 1.0].into_iter().enumerate() {
        let o = DVec3::new(20.0 * i as f64, 0.0, 0.0);
        let base = positions.len() as u32;
        positions.extend([o, o + DVec3::X * size.max(1.0), o + DVec3::Y * size]);
        triangles.push([base, base + 1, base + 2]);
    }
    TriMesh::new(positions, triangles).unwrap()
}

#[test]
fn random_is_deterministic_per_seed() {
    let mesh = shapes::torus(1.0, 0.3, 24).unwrap();
    let a = random(&mesh, 2000, 5).unwrap();
    assert_eq!(a, random(&mesh, 2000, 5).unwrap());
    assert_ne!(a, random(&mesh, 2000, 6).unwrap());
    // A prefix of a longer run: the stream does not depend on n.
    assert_eq!(a[..100], random(&mesh, 100, 5).unwrap()[..]);
}

#[test]
fn samples_lie_on_their_triangles() {
    for shape in &shapes::DEFAULT_SHAPES {
        let mesh = shape.build(12).unwrap();
        assert_on_surface(&mesh, &random(&mesh, 3000, 1).unwrap());
        assert_on_surface(&mesh, &poisson_disk(&mesh, 500, 1).unwrap().samples);
    }
    let mesh = uneven_mesh();
    assert_on_surface(&mesh, &random(&mesh, 3000, 2).unwrap());
}

#[test]
fn triangles_are_chosen_in_proportion_to_area() {
    let mesh = uneven_mesh();
    let areas: Vec<f64> = mesh.triangle_iter().map(|t| t.area()).collect();
    let total: f64 = areas.iter().sum();
    let n = 200_000;
    let mut counts = [0usize; 4];
    for s in random(&mesh, n, 11).unwrap() {
        counts[s.triangle] += 1;
    }
    assert_eq!(counts[2], 0, "the degenerate triangle got samples");
    // Chi-square over the triangles with positive area (2 degrees of freedom): the 0.1%
    // critical value is 13.8.
    let chi2: f64 = [0, 1, 3]
        .iter()
        .map(|&t| {
            let expected = n as f64 * areas[t] / total;
            (counts[t] as f64 - expected).powi(2) / expected
        })
        .sum();
    assert!(chi2 < 13.8, "chi-square {chi2}, counts {counts:?}");
    assert!(counts[1] > 0, "the tiny triangle got no samples");
}

#[test]
fn every_triangle_of_a_coarse_mesh_gets_its_share() {
    let mesh = shapes::cube(1.0, 3).unwrap(); // 108 equal triangles
    for samples in [
        random(&mesh, 54_000, 3).unwrap(),
        poisson_disk(&mesh, 54_000 / 4, 3).unwrap().samples,
    ] {
        let expected = samples.len() as f64 / mesh.triangle_count() as f64;
        let mut counts = vec![0usize; mesh.triangle_count()];
        for s in &samples {
            counts[s.triangle] += 1;
        }
        for (t, &c) in counts.iter().enumerate() {
            let deviation = (c as f64 - expected).abs() / expected;
            assert!(
                deviation < 0.2,
                "triangle {t}: {c} samples, expected {expected}"
            );
        }
    }
}

#[test]
fn poisson_disk_is_even_and_exact_in_count() {
    for shape in &shapes::DEFAULT_SHAPES {
        let mesh = shape.build(24).unwrap();
        for n in [1, 2, 100, 3000] {
            let set = poisson_disk(&mesh, n, 4).unwrap();
            assert_eq!(set.samples.len(), n, "{}", shape.name());
            let brute = brute_min_distance(&set.samples);
            if n == 1 {
                assert!(set.min_distance.is_infinite() && brute.is_infinite());
            } else {
                assert!((set.min_distance - brute).abs() <= 1e-12 * brute.max(1.0));
            }
            // Only meaningful once the spacing is well below the thinnest part (the thick
            // tube's wall is 0.2 thick: with 100 points the ideal spacing is 0.54).
            if n >= 3000 {
                let relative = set.relative_min_distance();
                assert!(relative > 0.6, "{} n = {n}: {relative}", shape.name());
            }
        }
    }
}

#[test]
fn poisson_disk_beats_random_and_is_deterministic() {
    let mesh = shapes::s_tube(0.3, 1.0, 32).unwrap();
    let set = poisson_disk(&mesh, 5000, 8).unwrap();
    assert_eq!(set, poisson_disk(&mesh, 5000, 8).unwrap());
    assert_ne!(set.samples, poisson_disk(&mesh, 5000, 9).unwrap().samples);
    let positions: Vec<DVec3> = random(&mesh, 5000, 8)
        .unwrap()
        .iter()
        .map(|s| s.position)
        .collect();
    let random_relative = min_distance(&positions, 0.01) / set.ideal_spacing;
    assert!(
        set.relative_min_distance() > 0.6,
        "{}",
        set.relative_min_distance()
    );
    assert!(random_relative < 0.1, "{random_relative}");
    // More oversampling is at least about as even.
    let dense = PoissonDiskOptions::default().with_oversampling(8.0);
    let better = poisson_disk_with(&mesh, 5000, 8, &dense).unwrap();
    assert!(better.relative_min_distance() > 0.6);
    let none = PoissonDiskOptions::default().with_oversampling(1.0);
    let plain = poisson_disk_with(&mesh, 5000, 8, &none).unwrap();
    assert_eq!(
        plain.samples,
        random(&mesh, 5000, 8).unwrap(),
        "oversampling 1 keeps every candidate"
    );
}

fn brute_min_distance(samples: &[SurfaceSample]) -> f64 {
    let mut best = f64::INFINITY;
    for (i, a) in samples.iter().enumerate() {
        for b in &samples[i + 1..] {
            best = best.min(a.position.distance(b.position));
        }
    }
    best
}

#[test]
fn zero_samples_and_bad_input() {
    let mesh = shapes::sphere(1.0, 8).unwrap();
    assert!(random(&mesh, 0, 1).unwrap().is_empty());
    let none = poisson_disk(&mesh, 0, 1).unwrap();
    assert!(none.samples.is_empty());
    assert!(none.min_distance.is_infinite());

    let empty = TriMesh::new(vec![DVec3::ZERO], vec![]).unwrap();
    assert!(matches!(random(&empty, 10, 1), Err(QueryError::EmptyMesh)));
    assert!(matches!(
        poisson_disk(&empty, 0, 1),
        Err(QueryError::EmptyMesh)
    ));

    let flat = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0],
        vec![[0, 1, 2]; 3],
    )
    .unwrap();
    assert!(matches!(
        random(&flat, 10, 1),
        Err(QueryError::ZeroSurfaceArea { triangle_count: 3 })
    ));
    let huge = TriMesh::new(
        vec![DVec3::ZERO, DVec3::X * 1e200, DVec3::Y * 1e200],
        vec![[0, 1, 2]],
    )
    .unwrap();
    assert!(matches!(
        random(&huge, 1, 1),
        Err(QueryError::InvalidParameter { .. })
    ));

    assert!(matches!(
        random(&mesh, MAX_SAMPLES + 1, 1),
        Err(QueryError::InvalidParameter { name: "n", .. })
    ));
    assert!(poisson_disk(&mesh, MAX_SAMPLES / 2, 1).is_err());
    for bad in [f64::NAN, 0.0, 0.99, f64::INFINITY] {
        let options = PoissonDiskOptions::default().with_oversampling(bad);
        assert!(matches!(
            poisson_disk_with(&mesh, 10, 1, &options),
            Err(QueryError::InvalidParameter {
                name: "oversampling",
                ..
            })
        ));
    }
}

#[test]
fn min_distance_matches_brute_force_at_any_guess() {
    let mesh = shapes::cone(1.0, 2.0, 10).unwrap();
    let samples = random(&mesh, 300, 2).unwrap();
    let positions: Vec<DVec3> = samples.iter().map(|s| s.position).collect();
    let brute = brute_min_distance(&samples);
    for guess in [1e-9, 1e-3, 0.1, 10.0, 1e9, f64::NAN, 0.0] {
        let d = min_distance(&positions, guess);
        assert!((d - brute).abs() <= 1e-15, "guess {guess}: {d} vs {brute}");
    }
    assert!(min_distance(&positions[..1], 1.0).is_infinite());
    assert!(min_distance(&[DVec3::ZERO, DVec3::ZERO], 1.0).abs() < f64::MIN_POSITIVE);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(sphaera_tests::cases(24)))]

    /// Random triangle soups: samples on their triangles, exact counts, brute-force
    /// minimum distance.
    #[test]
    fn random_soups(
        coords in prop::collection::vec(-10.0f64..10.0, 9..60),
        n in 1usize..200,
        seed in any::<u64>(),
    ) {
        let positions: Vec<DVec3> = coords.chunks_exact(3).map(DVec3::from_slice).collect();
        let triangles: Vec<[u32; 3]> = (0..positions.len() as u32 / 3)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        let mesh = TriMesh::new(positions, triangles).unwrap();
        let samples = random(&mesh, n, seed).unwrap();
        prop_assert_eq!(samples.len(), n);
        assert_on_surface(&mesh, &samples);
        let set = poisson_disk(&mesh, n, seed).unwrap();
        prop_assert_eq!(set.samples.len(), n);
        assert_on_surface(&mesh, &set.samples);
        let brute = brute_min_distance(&set.samples);
        if n == 1 {
            prop_assert!(set.min_distance.is_infinite());
        } else {
            prop_assert!((set.min_distance - brute).abs() <= 1e-12 * brute.max(1.0));
        }
    }
}

#[test]
fn sample_cap_keeps_the_output_allocation_modest() {
    // 2^28 samples asked for ~21 GB up front and aborted instead of returning an error.
    assert!(MAX_SAMPLES * size_of::<SurfaceSample>() <= 2 << 30);
    let mesh = shapes::cube(1.0, 1).unwrap();
    assert!(matches!(
        poisson_disk(&mesh, MAX_SAMPLES / 4, 1),
        Err(QueryError::InvalidParameter {
            name: "n × oversampling",
            ..
        })
    ));
}

#[test]
fn failed_sample_allocation_is_an_error_not_an_abort() {
    assert!(matches!(
        try_with_capacity::<SurfaceSample>("n", usize::MAX / 2),
        Err(QueryError::InvalidParameter { name: "n", .. })
    ));
    let v = try_with_capacity::<SurfaceSample>("n", 10).unwrap();
    assert!(v.capacity() >= 10 && v.is_empty());
}
